#pragma once
// The output folder of `amos-slam run` and the other paths a run writes, checked before anything else runs (models
// loading included), so that a wrong path is found in a second, not after the whole run, and so that a run never
// writes into its input nor removes what it did not write:
//   - no output path (--output, --record, --save-map) may be the input sequence folder or lie inside it (canonical
//     paths: symlinks resolved, also for paths that do not exist yet);
//   - the output folder is created (with its parents); a path under a regular file is an error naming that file;
//   - it is locked for the run's life (OutputFolderLock): a second run on it is refused, naming the first one's PID;
//   - a run writes a manifest (run_manifest.json: the names of everything it writes there) before its first frame.
//     A folder with a manifest holds an earlier run: refused, unless `overwrite`, which removes what the manifest
//     lists (and only that: other files in the folder stay). A folder without a manifest is never emptied: with
//     `overwrite` it must hold nothing; without, none of the names a run writes (runOutputNames()) may be there;
//   - a test file is written into it and removed; a folder that cannot be written is an error.
#include <string>
#include <vector>

namespace amos::report {

// Everything a run may leave in its output folder (run_report.h, mask_outputs.h, frame_log.h): trajectory.txt,
// keyframes.txt, map.ply, stats.json, settings_used.yaml (config/settings_writer.h), trajectory_live.txt,
// frames.tsv, masks/, overlays/, report.html (viewer/report_html.h), and with --dense mesh.ply, cloud.ply,
// removed_points.ply, occupancy.pgm, occupancy.yaml (run/dense_observer.h).
const std::vector<std::string>& runOutputNames();

// The files every run writes into its output folder, whatever its options: trajectory_live.txt, frames.tsv
// (frame_log.h), trajectory.txt, keyframes.txt, map.ply, stats.json (run_report.h), settings_used.yaml. What
// `amos-slam run` and amos::Slam::writeOutputs both write (and list in their manifest).
const std::vector<std::string>& mainOutputNames();

inline constexpr const char* kManifestFile = "run_manifest.json";

// Writes <dir>/run_manifest.json, listing `outputs` (the names written into `dir`), under a temporary name and
// renamed; throws core::Error naming it when it cannot be written. prepareOutputFolder writes it for a run.
void writeManifest(const std::string& dir, const std::vector<std::string>& outputs);
inline constexpr const char* kLockFile = ".amos-run.lock";

// The lock of an output folder, held while it lives: an flock(2) on <dir>/.amos-run.lock, which holds the PID of
// the holder. The kernel drops the lock when its process ends, however it ends; a lock file left by a process
// that is gone is taken over with a warning. The file is removed when the lock goes.
class OutputFolderLock {
 public:
  OutputFolderLock() = default;
  // Throws core::Error naming the folder and the PID of the process that holds it.
  static OutputFolderLock acquire(const std::string& dir);
  ~OutputFolderLock();
  OutputFolderLock(OutputFolderLock&& other) noexcept;
  OutputFolderLock& operator=(OutputFolderLock&& other) noexcept;
  OutputFolderLock(const OutputFolderLock&) = delete;
  OutputFolderLock& operator=(const OutputFolderLock&) = delete;
  bool held() const { return fd_ >= 0; }

 private:
  void release();
  std::string path_;
  int fd_ = -1;
};

struct OutputFolderRequest {
  std::string dir;                   // --output
  bool overwrite = false;            // --overwrite
  std::vector<std::string> outputs;  // the names this run writes into `dir` (files and folders): its manifest
  std::string input_dir;             // --sequence: `dir` must not be it or inside it ("" = none, a camera)
};

// Makes `request.dir` ready for a run's outputs as described above and returns its lock, to hold for the run's
// life. Throws core::Error with the reason and what to do.
OutputFolderLock prepareOutputFolder(const OutputFolderRequest& request);

// Throws core::Error naming `flag` when `path` is `input_dir` or lies inside it (canonical paths). Nothing when
// either is empty.
void refuseInsideInput(const std::string& path, const std::string& flag, const std::string& input_dir);

// For an output file written at the end of the run (--save-map): not a folder, in an existing folder that can be
// written (a test file is written there and removed). Throws core::Error naming `flag` and the path.
void checkOutputFile(const std::string& path, const std::string& flag);

}  // namespace amos::report
