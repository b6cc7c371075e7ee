// amos::setLogging (include/amos/logging.h): the library logs through spdlog's default logger, which this replaces.
#include "amos/logging.h"

#include <spdlog/cfg/env.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <memory>

#include "amos/api/logging_default.h"
#include "amos/core/callback_log_sink.h"

namespace amos {

namespace {

spdlog::level::level_enum spdlogLevel(LogLevel level) {
  switch (level) {
    case LogLevel::kTrace: return spdlog::level::trace;
    case LogLevel::kDebug: return spdlog::level::debug;
    case LogLevel::kInfo: return spdlog::level::info;
    case LogLevel::kWarn: return spdlog::level::warn;
    case LogLevel::kError: return spdlog::level::err;
    case LogLevel::kOff: return spdlog::level::off;
  }
  return spdlog::level::warn;
}

LogLevel publicLevel(spdlog::level::level_enum level) {
  switch (level) {
    case spdlog::level::trace: return LogLevel::kTrace;
    case spdlog::level::debug: return LogLevel::kDebug;
    case spdlog::level::info: return LogLevel::kInfo;
    case spdlog::level::warn: return LogLevel::kWarn;
    case spdlog::level::err:
    case spdlog::level::critical: return LogLevel::kError;
    default: return LogLevel::kOff;
  }
}

// Whether the logging was set (by the caller or by the default). The logger it sets is process-wide (spdlog's
// default logger), so the flag that says it was set is too.
std::atomic<bool>& loggingSet() {
  static std::atomic<bool> set{false};
  return set;
}

void install(spdlog::level::level_enum level, spdlog::sink_ptr sink) {
  auto logger = std::make_shared<spdlog::logger>("amos_slam", std::move(sink));
  logger->set_level(level);
  logger->flush_on(spdlog::level::warn);
  spdlog::set_default_logger(std::move(logger));
  loggingSet() = true;
}

}  // namespace

const char* toString(LogLevel level) {
  switch (level) {
    case LogLevel::kTrace: return "trace";
    case LogLevel::kDebug: return "debug";
    case LogLevel::kInfo: return "info";
    case LogLevel::kWarn: return "warn";
    case LogLevel::kError: return "error";
    case LogLevel::kOff: return "off";
  }
  return "?";
}

void setLogging(LogLevel level, LogSink sink) {
  if (!sink) {
    auto stderr_sink = std::make_shared<spdlog::sinks::stderr_sink_mt>();
    stderr_sink->set_pattern("[amos_slam] [%l] %v");
    install(spdlogLevel(level), std::move(stderr_sink));
    return;
  }
  install(spdlogLevel(level), std::make_shared<core::CallbackLogSink>(
                                  [sink = std::move(sink)](spdlog::level::level_enum l, const std::string& message) {
                                    sink(publicLevel(l), message);
                                  }));
}

namespace api {

void useDefaultLoggingOnce() {
  if (loggingSet().exchange(true)) return;
  setLogging(LogLevel::kWarn);
  spdlog::cfg::load_env_levels();  // SPDLOG_LEVEL, when set, wins
}

}  // namespace api

}  // namespace amos
