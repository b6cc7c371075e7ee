#pragma once
// The output folder of `amos-slam run`, checked before anything else runs (models loading included), so that a
// wrong --output is found in a second, not after the whole run:
//   - the folder is created (with its parents); a path under a regular file is an error naming that file;
//   - a test file is written into it and removed; a folder that cannot be written is an error;
//   - a folder that holds an earlier run (any of runOutputNames()) is refused, unless `overwrite`, which removes
//     that run's outputs first (only those: other files in the folder stay).
#include <string>
#include <vector>

namespace amos::report {

// What a run leaves in its output folder (run_report.h, mask_outputs.h): trajectory.txt, keyframes.txt, map.ply,
// stats.json, settings_used.yaml (config/settings_writer.h), masks/, overlays/, report.html (viewer/report_html.h).
const std::vector<std::string>& runOutputNames();

// Makes `dir` ready for a run's outputs as described above. Throws core::Error with the reason and what to do.
void prepareOutputFolder(const std::string& dir, bool overwrite);

}  // namespace amos::report
