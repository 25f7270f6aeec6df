#include "capture/threaded_hand_source.h"

#include <utility>

namespace gb {

ThreadedHandSource::ThreadedHandSource(std::unique_ptr<HandSource> source)
    : source_(std::move(source)),
      describe_(source_->describe()),
      period_(source_->period()),
      length_(source_->length()),
      whyNoHands_(source_->whyNoHands()),
      thread_([this] { read(); }) {}

ThreadedHandSource::~ThreadedHandSource() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  thread_.join();  // a camera's read returns within its frame timeout (DepthHandSource), a recording's at once
}

void ThreadedHandSource::read() {
  for (;;) {
    {
      const std::lock_guard lock(mutex_);
      if (stop_) return;
    }
    std::optional<HandSample> sample;
    std::exception_ptr failure;
    try {
      sample = source_->next();
    } catch (...) {
      failure = std::current_exception();
    }
    std::vector<std::string> messages = source_->takeMessages();
    std::string why = source_->whyNoHands();
    {
      const std::lock_guard lock(mutex_);
      for (std::string& m : messages) messages_.push_back(std::move(m));
      whyNoHands_ = std::move(why);
      if (sample) {
        if (queue_.size() >= kMaxQueued) queue_.pop_front();
        queue_.push_back({*sample, Clock::now()});
      } else {
        failure_ = failure;
        ended_ = true;
      }
    }
    arrived_.notify_all();
    if (!sample) return;
  }
}

std::optional<HandSample> ThreadedHandSource::next() {
  std::unique_lock lock(mutex_);
  arrived_.wait(lock, [this] { return !queue_.empty() || ended_; });
  if (queue_.empty()) {
    if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
    return std::nullopt;
  }
  Arrival a = std::move(queue_.front());
  queue_.pop_front();
  lastArrival_ = a.at;
  return a.sample;
}

bool ThreadedHandSource::ready() const {
  const std::lock_guard lock(mutex_);
  return !queue_.empty() || ended_;
}

std::vector<std::string> ThreadedHandSource::takeMessages() {
  const std::lock_guard lock(mutex_);
  return std::exchange(messages_, {});
}

std::string ThreadedHandSource::whyNoHands() const {
  const std::lock_guard lock(mutex_);
  return whyNoHands_;
}

}  // namespace gb
