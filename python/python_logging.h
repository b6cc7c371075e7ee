#pragma once
// The library's log in Python's `logging` (logger "amos_slam"), installed when the module is imported.
//
// The library's threads (local mapping, segmentation, the folder's reader) log too, so a message may come from a
// thread that does not hold the GIL: the sink takes it. Every call of the module that waits for those threads
// (track, finish, destroying a Slam...) releases the GIL first, so the sink never waits for a thread that waits for
// it. At interpreter exit (atexit) the log goes back to stderr, so a thread that logs while Python shuts down does
// not touch the interpreter.
#include <pybind11/pybind11.h>

namespace amos::python {

namespace py = pybind11;

// Sends the library's messages of at least `level` (a `logging` level: logging.DEBUG, INFO, WARNING...) to the
// logger "amos_slam".
void setPythonLogLevel(int level);

// Installs the sink (level: $SPDLOG_LEVEL when set, else WARNING) and the atexit hook; defines
// amos_slam.set_log_level.
void bindLogging(py::module_& m);

}  // namespace amos::python
