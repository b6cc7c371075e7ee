// The program does not load OpenCV's imgcodecs (whose Debian build brings GDAL, VTK and about 110 more shared
// libraries: 0.4 s and 40 MB more for every process): its images go through io's codecs, and the libraries link
// AMOS_OPENCV_RUNTIME_LIBS. Nor Open3D (its ~80 libraries: VTK, filament...: 35 MB and 0.3 s more): the dense map
// is a module the commands that use it load (src/amos/run/dense_plugin.h). ldd lists what the loader maps,
// transitive dependencies included.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>

namespace amos::app {
namespace {

std::string lddOutput(const std::string& program) {
  const std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(("ldd '" + program + "' 2>&1").c_str(), "r"), pclose);
  std::string text;
  if (!pipe) return text;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe.get())) > 0;) text.append(buffer, n);
  return text;
}

TEST(LinkedLibraries, TheProgramDoesNotLoadOpenCvsImageCodecs) {
  const std::string libraries = lddOutput(AMOS_SLAM_EXE);
  ASSERT_NE(libraries.find("libopencv_core"), std::string::npos) << "ldd gave no list:\n" << libraries;
  EXPECT_EQ(libraries.find("libopencv_imgcodecs"), std::string::npos) << libraries;
  EXPECT_EQ(libraries.find("libopencv_ximgproc"), std::string::npos) << libraries;
}

TEST(LinkedLibraries, TheProgramDoesNotLoadOpen3D) {
  const std::string libraries = lddOutput(AMOS_SLAM_EXE);
  ASSERT_NE(libraries.find("libopencv_core"), std::string::npos) << "ldd gave no list:\n" << libraries;
  EXPECT_EQ(libraries.find("libOpen3D"), std::string::npos) << libraries;
}

}  // namespace
}  // namespace amos::app
