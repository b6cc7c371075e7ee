#include "amos/core/whole_file.h"

#include <gtest/gtest.h>

#include <fstream>

#include "amos/testing/scratch_dir.h"

namespace amos::core {
namespace {

TEST(WholeFile, ReadsEveryByteAndTellsAnEmptyFileFromAMissingOne) {
  const std::filesystem::path dir = testing::scratchDirForThisTest("amos_whole_file_");
  const std::string bytes("line 1\r\nline 2\0binary\xff", 22);
  std::ofstream(dir / "some.bin", std::ios::binary) << bytes;
  std::ofstream(dir / "empty.txt").close();

  EXPECT_EQ(readWholeFile(dir / "some.bin"), bytes);
  EXPECT_EQ(readWholeFile(dir / "empty.txt"), std::string());
  EXPECT_EQ(readWholeFile(dir / "missing.txt"), std::nullopt);
  EXPECT_EQ(readWholeFile(dir), std::nullopt);  // a folder is not a file
}

}  // namespace
}  // namespace amos::core
