#include "app/show/performer_view.h"

#include <cstdio>
#include <utility>

#include "capture/depth_plot.h"
#include "host/banner_text.h"

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
    untaken_ = true;
  }
  return sample;
}

std::optional<RgbImage> ObservedHandSource::takeView(int step) {
  if (!depth_) return std::nullopt;
  std::unique_lock lock(mutex_);
  if (!fresh_) return std::nullopt;
  fresh_ = false;
  drawn_ = true;
  const kinect::DepthFrame frame = frame_;
  const Detection detection = detection_;
  const HandSample latest = latest_;
  lock.unlock();  // drawing takes a while: the reading thread goes on meanwhile
  return drawDepthPlot(frame, detection, latest, step);
}

std::optional<ObservedHandSource::Frame> ObservedHandSource::takeFrame() {
  if (!depth_) return std::nullopt;
  const std::lock_guard lock(mutex_);
  if (!untaken_) return std::nullopt;
  untaken_ = false;
  return Frame{frame_, detection_.body};
}

std::string ObservedHandSource::advice(bool withTracking) {
  if (!depth_) return {};
  const std::lock_guard lock(mutex_);
  if (!fresh_ && !drawn_) return {};  // no frame yet
  std::string advice = performerAdvice(detection_, latest_);
  if (withTracking && detection_.performerPixels > 0) {
    char sure[64];
    std::snprintf(sure, sizeof sure, "tracking: left %.0f%%, right %.0f%%", 100 * latest_.left.confidence,
                  100 * latest_.right.confidence);
    advice += (advice.empty() ? "" : "; ") + std::string(sure);
  }
  return advice;
}

std::string performerAdvice(const Detection& detection, const HandSample& hands) {
  if (detection.performerPixels == 0)
    return detection.advice.empty() ? "step in front of the camera, 1.5-3 m away" : detection.advice;
  std::string advice = detection.advice;  // "step back or tilt the camera: only part of you is in view"
  auto add = [&](const std::string& words) { advice += (advice.empty() ? "" : "; ") + words; };
  if (!hands.left.measured && !hands.right.measured)
    add("raise both hands in front of you");
  else if (!hands.left.measured || !hands.right.measured)
    add(std::string("raise your ") + (hands.left.measured ? "right" : "left") + " hand in front of you");
  return advice;
}

void drawCaption(RgbImage& image, const std::string& text) {
  const BannerImage banner = drawBanner(text, image.width, image.height);
  for (size_t p = 0; p < static_cast<size_t>(banner.width) * static_cast<size_t>(banner.height); ++p)
    for (size_t c = 0; c < 3; ++c) image.rgb[3 * p + c] = banner.rgba[4 * p + c];
}

std::string PerformerView::advice() const { return source_ ? source_->advice(false) : std::string(); }

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
  std::optional<RgbImage> plot = source_->takeView(kStep);
  const std::string advice = source_->advice(true);
  const std::string text = caption_.empty() ? advice : advice.empty() ? caption_ : advice + ". " + caption_;
  if (!plot && text == captioned_) return std::nullopt;
  if (plot) plot_ = std::move(*plot);
  if (plot_.width == 0) return std::nullopt;
  RgbImage view = plot_;
  drawCaption(view, text);
  captioned_ = text;
  return view;
}

}  // namespace gb
