// A test program for scratch_dir_test.cc: each case makes a scratch folder, writes a file in it and prints the
// folder on stdout; the test runs one case and looks at what the process left behind when it ended.
#include <gtest/gtest.h>

#include <fstream>
#include <iostream>

#include "amos/testing/scratch_dir.h"

namespace {

std::filesystem::path writeScratchFile() {
  const std::filesystem::path dir = amos::testing::scratchDir("probe");
  std::ofstream(dir / "output.txt") << "what a run wrote\n";
  std::cout << dir.string() << std::endl;
  return dir;
}

TEST(ScratchDirProbe, Passes) { writeScratchFile(); }

TEST(ScratchDirProbe, Fails) {
  writeScratchFile();
  ADD_FAILURE() << "failed on purpose";
}

}  // namespace
