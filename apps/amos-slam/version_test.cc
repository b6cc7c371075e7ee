// `amos-slam --version` prints the version written once in the top-level CMakeLists.txt.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <string>

#include "child_process.h"

namespace amos::app {
namespace {

TEST(Version, PrintsTheProjectVersionAndExitsZero) {
  const auto out = testOutputDir("version", "stdout");
  const Finished f = runChild({"--version"}, out.string() + ".txt");
  ASSERT_TRUE(WIFEXITED(f.status)) << f.err;
  EXPECT_EQ(WEXITSTATUS(f.status), 0) << f.err;
  EXPECT_EQ(f.out, std::string("amos-slam ") + AMOS_VERSION + "\n");
}

}  // namespace
}  // namespace amos::app
