#include "python_logging.h"

#include <atomic>
#include <cstdlib>
#include <string>

#include "amos/logging.h"

namespace amos::python {

namespace {

// Python's logging levels.
constexpr int kDebug = 10, kInfo = 20, kWarning = 30, kError = 40, kCritical = 50;

int pythonLevel(LogLevel level) {
  switch (level) {
    case LogLevel::kTrace:
    case LogLevel::kDebug: return kDebug;
    case LogLevel::kInfo: return kInfo;
    case LogLevel::kWarn: return kWarning;
    case LogLevel::kError: return kError;
    case LogLevel::kOff: return kCritical;
  }
  return kWarning;
}

LogLevel libraryLevel(int level) {
  if (level <= kDebug) return LogLevel::kDebug;
  if (level <= kInfo) return LogLevel::kInfo;
  if (level <= kWarning) return LogLevel::kWarn;
  if (level <= kCritical) return LogLevel::kError;
  return LogLevel::kOff;
}

// $SPDLOG_LEVEL as a logging level, or WARNING.
int startLevel() {
  const char* env = std::getenv("SPDLOG_LEVEL");
  const std::string name = env == nullptr ? "" : env;
  if (name == "trace" || name == "debug") return kDebug;
  if (name == "info") return kInfo;
  if (name == "err" || name == "error") return kError;
  if (name == "critical") return kCritical;
  if (name == "off") return kCritical + 10;
  return kWarning;
}

// Set by the atexit hook: from then on the messages go to stderr.
std::atomic<bool>& interpreterExiting() {
  static std::atomic<bool> exiting{false};
  return exiting;
}

// The level set last (a logging level), kept for the switch to stderr at exit.
std::atomic<int>& currentLevel() {
  static std::atomic<int> level{kWarning};
  return level;
}

void toPython(LogLevel level, const std::string& message) {
  if (interpreterExiting() || !Py_IsInitialized()) return;
  py::gil_scoped_acquire gil;
  try {
    py::module_::import("logging").attr("getLogger")("amos_slam").attr("log")(pythonLevel(level), message);
  } catch (py::error_already_set& e) {
    e.discard_as_unraisable("amos_slam log message");
  }
}

}  // namespace

void setPythonLogLevel(int level) {
  currentLevel() = level;
  const LogLevel library = libraryLevel(level);
  if (interpreterExiting())
    setLogging(library);
  else
    setLogging(library, toPython);
}

void bindLogging(py::module_& m) {
  setPythonLogLevel(startLevel());
  m.def("set_log_level", &setPythonLogLevel, py::arg("level"),
        "Sets the least severe of the library's messages that reach the `logging` logger \"amos_slam\" (a logging "
        "level: logging.DEBUG, logging.INFO, logging.WARNING...; default WARNING, or $SPDLOG_LEVEL). The library "
        "logs through the logger \"amos_slam\", so its handlers and level apply too.");
  py::module_::import("atexit").attr("register")(py::cpp_function([] {
    interpreterExiting() = true;
    setLogging(libraryLevel(currentLevel()));  // stderr from now on: the library's threads may outlive the interpreter
  }));
}

}  // namespace amos::python
