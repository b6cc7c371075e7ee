#pragma once
// An spdlog sink that hands each message, formatted without the time and level prefix, to a function: how a
// program that embeds the library (amos::setLogging, include/amos/logging.h) receives the library's log in its own.
// spdlog's base_sink serialises the calls with its mutex, so the function sees one message at a time.
#include <spdlog/sinks/base_sink.h>

#include <functional>
#include <mutex>
#include <string>
#include <utility>

namespace amos::core {

class CallbackLogSink : public spdlog::sinks::base_sink<std::mutex> {
 public:
  using Callback = std::function<void(spdlog::level::level_enum level, const std::string& message)>;
  explicit CallbackLogSink(Callback callback) : callback_(std::move(callback)) {}

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    callback_(msg.level, std::string(msg.payload.data(), msg.payload.size()));
  }
  void flush_() override {}

 private:
  Callback callback_;
};

}  // namespace amos::core
