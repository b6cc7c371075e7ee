#include "amos/core/whole_file.h"

#include <gtest/gtest.h>

#include <fstream>

#include "amos/core/error.h"
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

TEST(WholeFile, OrThrowGivesTheBytesOrTheCallersMessage) {
  const std::filesystem::path dir = testing::scratchDirForThisTest("amos_whole_file_throw_");
  std::ofstream(dir / "settings.yaml") << "Camera.fx: 500\n";
  EXPECT_EQ(readWholeFileOrThrow(dir / "settings.yaml", "unused"), "Camera.fx: 500\n");
  try {
    readWholeFileOrThrow(dir / "missing.yaml", "settings file 'missing.yaml' cannot be read");
    FAIL() << "no error for a missing file";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "settings file 'missing.yaml' cannot be read");
  }
  EXPECT_THROW(readWholeFileOrThrow(dir, "a folder"), Error);
}

}  // namespace
}  // namespace amos::core
