#pragma once
// Where the library's log messages go. By default the library is quiet: warnings and errors to stderr (or the level
// $SPDLOG_LEVEL names: trace, debug, info, warn, error, off). A program that wants the messages in its own log sets
// a sink; the Python module sends them to the `logging` logger "amos_slam".
//
//   amos::setLogging(amos::LogLevel::kInfo, [](amos::LogLevel level, const std::string& message) {
//     my_log(amos::toString(level), message);
//   });
//
// Process-wide: the library's own threads (local mapping, segmentation, reading ahead) log too, and a message does
// not know which amos::Slam it came from, so there is one setting for the whole program, not one per Slam. The
// sink is called from any of those threads, one message at a time (calls are serialised); it must return quickly
// and must not call into the library.
#include <functional>
#include <string>

namespace amos {

// The severity of a message, from the most verbose; kOff as a level means no message at all.
enum class LogLevel { kTrace, kDebug, kInfo, kWarn, kError, kOff };
// "trace" | "debug" | "info" | "warn" | "error" | "off".
const char* toString(LogLevel level);

// Receives one message (without a trailing newline) of at least the level set.
using LogSink = std::function<void(LogLevel level, const std::string& message)>;

// Messages of at least `level` go to `sink` (an empty sink: to stderr). Replaces the setting before, including the
// default one; may be called at any time.
// Until it is called, the first amos::Slam or amos::SequenceFolder made sets the default: warnings and errors to
// stderr, or the level $SPDLOG_LEVEL names.
void setLogging(LogLevel level, LogSink sink = {});

}  // namespace amos
