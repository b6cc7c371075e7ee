#pragma once
// Where an installed Amos-SLAM keeps its data (the segmentation models and the ORB vocabulary): the folder
// share/amos-slam/models of its install prefix. The prefix is found at run time from the file that holds this code
// (the amos-slam program in <prefix>/bin, the Python module in <prefix>/lib/python3/dist-packages), so an install
// moved to another prefix still finds its data; a program linked with the installed library is given the folder
// by the CMake package instead (AMOS_SLAM_DATA_DIR, see include/amos/slam.h).
#include <string>

namespace amos::api {

// The models folder of the install this code was loaded from, or "" when it is not an install (a build tree).
std::string installedModelsDir();

// The folder to look in first for the models: `given` when not empty; else, when neither the settings
// (Segmentation.modelsDir) nor the environment (AMOS_MODELS) name one, `installed` when it holds the models;
// else "" (the usual search: segmentation/model_locator.h).
std::string modelsFolder(const std::string& given, const std::string& settings_dir, const std::string& installed);

}  // namespace amos::api
