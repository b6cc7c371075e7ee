#include "amos/camera/openni2_source.h"

#include <gtest/gtest.h>

#include <OpenNI.h>

#include <string>

#include "amos/core/error.h"

namespace amos::camera {
namespace {

int devicesPresent() {
  if (openni::OpenNI::initialize() != openni::STATUS_OK) return 0;
  openni::Array<openni::DeviceInfo> list;
  openni::OpenNI::enumerateDevices(&list);
  const int n = list.getSize();
  openni::OpenNI::shutdown();
  return n;
}

// Without a camera, opening fails with what OpenNI2 said and how many devices it found, and nothing crashes.
TEST(OpenNI2Source, WithoutADeviceOpeningAnyFailsWithOpenNIsReason) {
  if (devicesPresent() > 0) GTEST_SKIP() << "a device is connected";
  try {
    OpenNI2Source source(OpenNI2Options{});
    FAIL() << "expected a core::Error";
  } catch (const core::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("OpenNI2 could not open a device"), std::string::npos) << what;
    EXPECT_NE(what.find("no devices found"), std::string::npos) << what;  // OpenNI2's extended error
    EXPECT_NE(what.find("OpenNI2 found 0 devices"), std::string::npos) << what;
    EXPECT_EQ(what.find('\t'), std::string::npos) << what;
  }
}

TEST(OpenNI2Source, UnknownUriNamesTheUri) {
  if (devicesPresent() > 0) GTEST_SKIP() << "a device is connected";
  OpenNI2Options options;
  options.uri = "no-such-device/0@1";
  for (int attempt = 0; attempt < 2; ++attempt) {  // OpenNI2 is initialised and shut down each time
    try {
      OpenNI2Source source(options);
      FAIL() << "expected a core::Error";
    } catch (const core::Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("device 'no-such-device/0@1'"), std::string::npos) << what;
      EXPECT_NE(what.find("Couldn't open device"), std::string::npos) << what;
      EXPECT_NE(what.find("found 0 devices"), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace amos::camera
