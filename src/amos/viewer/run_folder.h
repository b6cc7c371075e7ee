#pragma once
// A finished run's outputs as the viewer shows them (`amos-slam view OUTPUT_DIR`): trajectory.txt, keyframes.txt,
// map.ply and stats.json are loaded into a LiveState, with what report.html keeps for it (the ground truth in the
// map's frame, the strip of mask overlays) and the dense products of `run --dense` (mesh.ply, cloud.ply,
// removed_points.ply: dense layers); the overlays (--save-masks) are listed for the page; and the only files the
// server hands out are those inside that folder (runFilePath).
#include <filesystem>
#include <optional>
#include <string>

#include "amos/viewer/live_state.h"

namespace amos::viewer {

// The file `request` names inside `root`, or nothing when it is not one: an empty name, an absolute path, a '..'
// or '.' component, a backslash or NUL, a path that leaves `root` through a symbolic link, or no regular file.
std::optional<std::filesystem::path> runFilePath(const std::filesystem::path& root, const std::string& request);

// Loads the run in `dir` into `state` (one update, as if the run had just ended). Throws core::Error when `dir`
// holds no run (no trajectory.txt and no stats.json) or map.ply cannot be read; a missing map.ply, keyframes.txt,
// report.html or dense product only leaves that part empty, and a dense product that cannot be read is left out
// with a warning.
void loadRunFolder(const std::filesystem::path& dir, LiveState& state);

}  // namespace amos::viewer
