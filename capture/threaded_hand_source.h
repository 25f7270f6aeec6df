#pragma once
// A hand source read on a thread of its own: a camera's capture, segmentation and hand finding run beside the frame
// loop instead of inside it. The thread reads the source as fast as it delivers (a camera's 30 frames a second, a
// fakenect recording at its own pace) and queues the samples; the frame loop takes what has arrived and never waits
// for the next frame unless it asks to (next()). Each sample keeps the steady-clock time it arrived at, so that a
// frame knows how old the newest hands are.

#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "capture/hand_source.h"

namespace gb {

class ThreadedHandSource : public HandSource {
 public:
  using Clock = std::chrono::steady_clock;

  // Starts reading `source` at once. The source is only touched by the thread from here on (its describe(),
  // period() and length() are read before it starts).
  explicit ThreadedHandSource(std::unique_ptr<HandSource> source);
  ~ThreadedHandSource() override;  // stops the thread (after the source's current read) and joins it
  ThreadedHandSource(const ThreadedHandSource&) = delete;  // owns a running thread
  ThreadedHandSource& operator=(const ThreadedHandSource&) = delete;

  // The next sample in order, waiting for it when none has arrived; nothing at the end. Rethrows the source's
  // HandSourceLost (or any other failure) once the samples before it are taken.
  std::optional<HandSample> next() override;
  // Whether next() would return at once: a sample is queued, or the source has ended or failed.
  [[nodiscard]] bool ready() const override;
  [[nodiscard]] std::string describe() const override { return describe_; }
  [[nodiscard]] double period() const override { return period_; }
  [[nodiscard]] std::optional<double> length() const override { return length_; }
  std::vector<std::string> takeMessages() override;
  [[nodiscard]] std::string whyNoHands() const override;
  // When the newest sample next() returned arrived from the thread (steady clock).
  [[nodiscard]] std::optional<Clock::time_point> arrivedAt() const override { return lastArrival_; }

  // At most this many samples wait in the queue (10 s at 30 Hz): a consumer that stops taking them (a long pause)
  // loses the oldest, not memory.
  static constexpr size_t kMaxQueued = 300;

 private:
  struct Arrival {
    HandSample sample;
    Clock::time_point at;
  };
  void read();  // the thread

  std::unique_ptr<HandSource> source_;
  std::string describe_;
  double period_;
  std::optional<double> length_;
  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::deque<Arrival> queue_;
  std::vector<std::string> messages_;
  std::string whyNoHands_;
  bool ended_ = false;
  bool stop_ = false;
  std::exception_ptr failure_;
  std::optional<Clock::time_point> lastArrival_;
  std::thread thread_;  // last: started once everything it reads exists
};

}  // namespace gb
