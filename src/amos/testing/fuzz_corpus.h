#pragma once
// For tests only: replays a fuzz target's corpus (fuzz/corpus/<name>/ of the source tree, seeds and the reproducers
// of fixed crashes) through the target's entry function (fuzz/*_input*.h), so that every build's CTest runs what the
// fuzzer found. core::Error is an accepted outcome of an input; any other exception fails the test, naming the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "amos/core/error.h"

namespace amos::testing {

// The files of fuzz/corpus/<name>/, sorted by name.
inline std::vector<std::filesystem::path> fuzzCorpus(const std::string& name) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(AMOS_SOURCE_DIR) / "fuzz" /
                                                                "corpus" / name)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Feeds every file of fuzz/corpus/<name>/ to `entry`; returns how many inputs were replayed.
template <typename Entry>
std::size_t replayFuzzCorpus(const std::string& name, Entry entry) {
  std::size_t replayed = 0;
  for (const auto& file : fuzzCorpus(name)) {
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    try {
      entry(bytes);
    } catch (const core::Error&) {
      // the documented outcome of a malformed input
    } catch (const std::exception& e) {
      ADD_FAILURE() << file << ": unexpected exception: " << e.what();
    } catch (...) {
      ADD_FAILURE() << file << ": unexpected exception of unknown type";
    }
    ++replayed;
  }
  return replayed;
}

}  // namespace amos::testing
