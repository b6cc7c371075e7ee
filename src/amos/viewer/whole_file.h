#pragma once
// A file's whole contents, for the small files the viewer serves and reads (three.js, a run's stats.json and
// settings file). The files of a finished run under /files/ are streamed instead (file_reply.h).
#include <filesystem>
#include <string>

namespace amos::viewer {

// Empty when the file cannot be read (the callers say what is missing in their own terms).
std::string readWholeFile(const std::filesystem::path& path);

}  // namespace amos::viewer
