#include "performer_view.h"

#include <utility>

#include "depth_plot.h"

namespace gb {

ObservedHandSource::ObservedHandSource(std::unique_ptr<HandSource> source)
    : source_(std::move(source)), depth_(dynamic_cast<DepthHandSource*>(source_.get())) {
  if (depth_)
    depth_->onFrame([this](const kinect::DepthFrame& frame) {
      const std::lock_guard lock(mutex_);
      frame_ = frame;
      newFrame_ = true;
    });
}

std::optional<HandSample> ObservedHandSource::next() {
  std::optional<HandSample> sample = source_->next();
  const std::lock_guard lock(mutex_);
  if (sample) latest_ = *sample;
  if (newFrame_ && sample) {  // the detection is the newest frame's: the source detects right after handing it over
    detection_ = depth_->detection();
    newFrame_ = false;
    fresh_ = true;
  }
  return sample;
}

std::optional<RgbImage> ObservedHandSource::takeView(int step) {
  if (!depth_) return std::nullopt;
  std::unique_lock lock(mutex_);
  if (!fresh_) return std::nullopt;
  fresh_ = false;
  const kinect::DepthFrame frame = frame_;
  const Detection detection = detection_;
  const HandSample latest = latest_;
  lock.unlock();  // drawing takes a while: the reading thread goes on meanwhile
  return drawDepthPlot(frame, detection, latest, step);
}

std::string PerformerView::toggle() {
  if (!source_ || !source_->hasDepth()) {
    chosen_.reset();
    return "V: the performer view shows a depth camera's picture, and this input has none";
  }
  chosen_ = !shown();
  return *chosen_ ? "performer view on" : "performer view off";
}

bool PerformerView::shown() const {
  if (!source_ || !source_->hasDepth()) return false;
  return chosen_.value_or(waiting_);
}

std::optional<RgbImage> PerformerView::update() {
  const bool show = shown();
  const bool hidden = wasShown_ && !show;
  wasShown_ = show;
  if (hidden) return RgbImage{};
  if (!show) return std::nullopt;
  return source_->takeView(kStep);
}

}  // namespace gb
