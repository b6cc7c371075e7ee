#pragma once
// A small file's whole contents (settings, a run's manifest, stats.json, the viewer's scripts), read in one place.
#include <filesystem>
#include <optional>
#include <string>

namespace amos::core {

// The bytes of the file, or nullopt when it cannot be opened or is a folder (the callers say what is missing in their own terms).
std::optional<std::string> readWholeFile(const std::filesystem::path& path);

// The bytes of the file; throws core::Error(message) when it cannot be read (message names the file in the
// caller's terms, e.g. which setting gave it).
std::string readWholeFileOrThrow(const std::filesystem::path& path, const std::string& message);

}  // namespace amos::core
