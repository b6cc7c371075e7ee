#pragma once
// The library's default logging (include/amos/logging.h), applied by the first amos::Slam or amos::SequenceFolder
// made unless the program called amos::setLogging before.
namespace amos::api {

// Warnings and errors to stderr, or the level $SPDLOG_LEVEL names; nothing when the logging was already set.
void useDefaultLoggingOnce();

}  // namespace amos::api
