#pragma once
// For tests only: where the real test data (TUM and Bonn slices, reference trajectories, person photographs) and
// the segmentation models live, outside the repository. One setting each, an environment variable at run time or
// else the build's compile definition of the same name (CMake cache variables, see CMakeLists.txt):
//   AMOS_DATA_DIR    the data folder; default ../shared/data beside the checkout
//   AMOS_MODELS_DIR  the models folder; default the repository's bundled ./models when it holds the models, else
//                    ../shared/models (the default folders of segmentation::locateModelDir, in its order)
// Deprecated: the environment variable AMOS_SHARED_DIR (a folder holding data/ and models/) is still read when the
// variable of the setting is not set.
//
// A test that needs a part of the data starts with AMOS_REQUIRE_DATA("tum_fr2_desk_first50") (AMOS_REQUIRE_MODELS
// for a model file): when that path is absent (a clone without ../shared) the test is skipped with a message
// saying what is missing and how to get it, so CTest lists it as skipped, not failed. With
// AMOS_REQUIRE_SHARED_DATA=1 in the environment (CI, which has the data) a missing path fails the test instead,
// so that no real-data test is skipped unnoticed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace amos::testing {
namespace detail {

inline std::optional<std::string> environment(const char* name) {
  const char* value = std::getenv(name);
  if (value == nullptr || *value == '\0') return std::nullopt;
  return std::string(value);
}

// $variable, else $AMOS_SHARED_DIR/<shared_sub> (deprecated), else the build's default.
inline std::string setting(const char* variable, const char* shared_sub, const char* build_default) {
  if (auto value = environment(variable)) return *value;
  if (auto shared = environment("AMOS_SHARED_DIR")) return (std::filesystem::path(*shared) / shared_sub).string();
  return build_default;
}

inline std::optional<std::string> missing(const std::string& path, const std::string& relative,
                                          const std::string& what, const char* variable, const std::string& dir,
                                          const std::string& how_to_get) {
  if (std::filesystem::exists(path)) return std::nullopt;
  return what + " '" + relative + "' is missing: " + path + " is absent (" + variable + " = " + dir + "). " +
         how_to_get;
}

}  // namespace detail

// The folder of the real test data: $AMOS_DATA_DIR, else the build's AMOS_DATA_DIR (default ../shared/data).
inline std::string dataDir() { return detail::setting("AMOS_DATA_DIR", "data", AMOS_DATA_DIR); }

// The folder of the segmentation models: $AMOS_MODELS_DIR, else the build's AMOS_MODELS_DIR (default ./models of
// the repository when it has them, else ../shared/models).
inline std::string modelsDir() { return detail::setting("AMOS_MODELS_DIR", "models", AMOS_MODELS_DIR); }

// <data>/<relative>, e.g. dataPath("bonn_crowd_dev").
inline std::string dataPath(const std::string& relative) {
  return (std::filesystem::path(dataDir()) / relative).string();
}

// <models>/<relative>, e.g. modelPath("nanodet_m_320.onnx").
inline std::string modelPath(const std::string& relative) {
  return (std::filesystem::path(modelsDir()) / relative).string();
}

// Why a test that needs <data>/<relative> cannot run, or nullopt when the path is there.
inline std::optional<std::string> missingData(const std::string& relative) {
  return detail::missing(
      dataPath(relative), relative, "test data", "AMOS_DATA_DIR", dataDir(),
      "Point the environment variable AMOS_DATA_DIR (or the CMake cache variable of that name) at the folder of the "
      "shared test data, or put it beside the checkout as ../shared/data. scripts/fetch_data.sh NAME downloads "
      "the full TUM RGB-D and Bonn sequences (--list names them) in the reader's layout; the test slices are cut "
      "from them");
}

// Why a test that needs <models>/<relative> cannot run, or nullopt when the path is there.
inline std::optional<std::string> missingModels(const std::string& relative) {
  return detail::missing(
      modelPath(relative), relative, "segmentation model", "AMOS_MODELS_DIR", modelsDir(),
      "Point the environment variable AMOS_MODELS_DIR (or the CMake cache variable of that name) at a folder of "
      "the ONNX models: the repository's ./models (see models/README.md) or ../shared/models");
}

inline bool sharedDataRequired() {
  const auto flag = detail::environment("AMOS_REQUIRE_SHARED_DATA");
  return flag && *flag == "1";
}

}  // namespace amos::testing

// Skips the current test (or fails it under AMOS_REQUIRE_SHARED_DATA=1) when `missing` names a reason.
#define AMOS_REQUIRE_PRESENT_(missing)                                                                \
  do {                                                                                                \
    if (const auto amos_missing_ = (missing)) {                                                       \
      if (::amos::testing::sharedDataRequired()) FAIL() << *amos_missing_;                            \
      GTEST_SKIP() << *amos_missing_;                                                                 \
    }                                                                                                 \
  } while (false)

// Skips (or fails, see above) when <data>/<relative> is absent. Use in a test body or a fixture's SetUp().
#define AMOS_REQUIRE_DATA(relative) AMOS_REQUIRE_PRESENT_(::amos::testing::missingData(relative))
// Skips (or fails, see above) when <models>/<relative> is absent, e.g. AMOS_REQUIRE_MODELS("nanodet_m_320.onnx").
#define AMOS_REQUIRE_MODELS(relative) AMOS_REQUIRE_PRESENT_(::amos::testing::missingModels(relative))
