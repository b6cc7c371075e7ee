#pragma once
// The settings for a run over a bag: the settings file's, with the camera calibration taken from the bag's
// CameraInfo when the file leaves it out. Which wins: the settings file, whenever it gives any of Camera.fx, fy, cx,
// cy (a calibration of one's own beats the driver's factory one); a CameraInfo that differs from it then gets a
// warning. Only a file with none of the four takes Camera.fx/fy/cx/cy, k1 k2 p1 p2 k3, width and height (each that
// the file leaves out) from the bag.
#include <optional>
#include <string>

#include "amos/config/settings.h"
#include "amos/core/camera.h"

namespace amos::rosbag {

// Whether the settings file gives any of Camera.fx, fy, cx, cy (then its calibration is used, whatever camera_info
// says). Throws core::Error naming a file that cannot be read.
bool settingsHaveCalibration(const std::string& path);

// The settings file's text, with the calibration keys it leaves out appended from `camera_info` when it gives none
// of Camera.fx, fy, cx, cy (the node hands this to amos::Options::settings_yaml). `camera_info_source` names the
// CameraInfo in messages ("bag 'x.bag', topic '/t'"). Throws core::Error when the file leaves the calibration out
// and there is no CameraInfo.
std::string settingsTextWithCamera(const std::string& path, const std::optional<core::CameraIntrinsics>& camera_info,
                                   const std::string& camera_info_source);

// settingsTextWithCamera's text parsed (with `added`'s sections), errors naming `path` and its lines; throws also
// as config::loadSettings does.
config::Settings settingsForBag(const std::string& path, const std::optional<core::CameraIntrinsics>& camera_info,
                                const std::string& camera_info_source, const config::SectionRegistry& added = {});

}  // namespace amos::rosbag
