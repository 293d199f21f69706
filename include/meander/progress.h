// How a client follows a long job and stops it from another thread (the studio's Stop
// button, a newer request, a client that went away): the job names each stage as it
// begins and, where the stage can tell, how much of it is done; after cancel() the job
// throws Cancelled at its next check, which comes at every stage's start and every few
// thousand elements of a long loop. Functions that take a Progress* run to their end
// when given none.
#pragma once

#include "meander/error.h"

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>

namespace meander {

// A job stopped by Progress::cancel(); it left nothing behind.
class Cancelled : public Error {
public:
  using Error::Error;
};

class Progress {
public:
  // `abandoned`, if set, is asked at each stage's start and at every 64th check (from the
  // job's threads, so it must be safe to call from several at once); true cancels the
  // job. A server passes whether the client that asked for it has gone.
  explicit Progress(std::function<bool()> abandoned = {}) : abandoned_(std::move(abandoned)) {}

  // Any thread.
  void cancel();
  bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }
  struct State {
    std::string stage; // "" before the first
    double fraction = -1; // of the stage done, in [0, 1]; -1 where the stage cannot tell
  };
  State state() const;

  // For tests of clients: the job waits at its next check until cancelled, so that a
  // test holds a job in flight without making it slow.
  void hold();

  // The job's side, from any of its threads. Each throws Cancelled once cancelled.
  void begin(std::string_view stage);
  void advance(double fraction);
  void check();

private:
  std::function<bool()> abandoned_;
  std::atomic<bool> cancelled_{false};
  std::atomic<bool> held_{false};
  std::atomic<uint32_t> checks_{0};
  std::atomic<double> fraction_{-1};
  mutable std::mutex lock_; // guards stage_, and the wait of a held job
  std::condition_variable released_;
  std::string stage_;
};

// The checks of a job given an optional Progress.
inline void check_progress(Progress* progress) {
  if (progress) progress->check();
}
inline void advance_progress(Progress* progress, double fraction) {
  if (progress) progress->advance(fraction);
}

} // namespace meander
