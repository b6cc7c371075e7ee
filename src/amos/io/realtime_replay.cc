#include "amos/io/realtime_replay.h"

#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>

#include "amos/io/newest_frame_slot.h"

namespace amos::io {

using Clock = std::chrono::steady_clock;

struct RealtimeReplay::Impl {
  std::size_t total;
  SequenceReader reader;
  NewestFrameSlot slot;
  mutable std::mutex mutex;
  std::condition_variable wake;  // the clock thread's wait: due time or stop
  bool stop = false;
  std::optional<Clock::time_point> t0;
  std::thread clock;  // last: started when everything it uses exists

  Impl(SequenceIndex index, ReaderOptions options)
      : total(index.frames.size()), reader(std::move(index), options), clock([this] { run(); }) {}

  ~Impl() {
    cancel();
    if (clock.joinable()) clock.join();
  }

  void cancel() {
    {
      std::lock_guard<std::mutex> lock(mutex);
      stop = true;
    }
    wake.notify_all();
    slot.close();
  }

  // False when stopped before `due`.
  bool waitUntil(Clock::time_point due) {
    std::unique_lock<std::mutex> lock(mutex);
    return !wake.wait_until(lock, due, [&] { return stop; });
  }

  void run() {
    try {
      std::optional<RgbdFrame> frame = reader.next();
      if (!frame) {
        slot.close();
        return;
      }
      const double first_stamp = frame->timestamp;
      Clock::time_point start;
      {
        std::lock_guard<std::mutex> lock(mutex);
        start = Clock::now();
        t0 = start;
      }
      while (frame) {
        const auto offset = std::chrono::duration<double>(frame->timestamp - first_stamp);
        if (!waitUntil(start + std::chrono::duration_cast<Clock::duration>(offset))) break;
        if (!slot.put(std::move(*frame))) break;
        frame = reader.next();
      }
      slot.close();
    } catch (...) {
      slot.close(std::current_exception());
    }
  }
};

RealtimeReplay::RealtimeReplay(SequenceIndex index, ReaderOptions options)
    : impl_(std::make_unique<Impl>(std::move(index), options)) {}

RealtimeReplay::~RealtimeReplay() = default;

std::optional<RgbdFrame> RealtimeReplay::next() { return impl_->slot.take(); }
std::optional<RgbdFrame> RealtimeReplay::poll() { return impl_->slot.tryTake(); }
void RealtimeReplay::cancel() { impl_->cancel(); }
std::size_t RealtimeReplay::size() const { return impl_->total; }
SourceStats RealtimeReplay::stats() const {
  SourceStats stats = impl_->slot.stats();
  stats.skipped = impl_->reader.stats().skipped;
  return stats;
}

std::optional<Clock::time_point> RealtimeReplay::startTime() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->t0;
}

}  // namespace amos::io
