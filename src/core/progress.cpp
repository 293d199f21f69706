#include "meander/progress.h"

#include <chrono>

namespace meander {

void Progress::cancel() {
  std::lock_guard guard(lock_);
  cancelled_.store(true);
  released_.notify_all();
}

Progress::State Progress::state() const {
  std::lock_guard guard(lock_);
  return {stage_, fraction_.load(std::memory_order_relaxed)};
}

void Progress::hold() { held_.store(true); }

void Progress::begin(std::string_view stage) {
  {
    std::lock_guard guard(lock_);
    stage_ = stage;
    fraction_.store(-1, std::memory_order_relaxed);
  }
  if (abandoned_ && abandoned_()) cancel();
  check();
}

void Progress::advance(double fraction) {
  check();
  fraction_.store(fraction, std::memory_order_relaxed);
}

void Progress::check() {
  if (held_.load(std::memory_order_relaxed)) {
    // Asking now and then whether the client has gone, as a job at work would.
    std::unique_lock guard(lock_);
    while (!released_.wait_for(guard, std::chrono::milliseconds(50), [this] { return cancelled_.load(); }))
      if (abandoned_ && abandoned_()) cancelled_.store(true);
  }
  if (abandoned_ && checks_.fetch_add(1, std::memory_order_relaxed) % 64 == 63 && abandoned_()) cancel();
  if (cancelled()) throw Cancelled("cancelled");
}

} // namespace meander
