#pragma once
// The performer view of the live window: what a depth camera sees (its depth, the floor, the body taken for the
// performer, the hands found and the hands reported), drawn as `record --depth-plot` draws it (depth_plot.h), as a
// picture-in-picture, with a caption for the performer: what to do (step in, step back, raise a hand), how sure the
// tracking is, and the show's word to them (the set-up's count). V toggles it; until then it shows while the show
// waits for a performer with a camera input (kinect, fakenect:DIR), so that whoever steps in sees where the camera
// looks. It is a layer of the window: the video stream never holds it.

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "capture/hand_sources.h"
#include "capture/kinect_depth.h"
#include "capture/png_image.h"

namespace gb {

// A hand source passed through unchanged that keeps the newest depth frame, its detection and hand sample of a depth
// camera (a DepthHandSource inside; any other source has no view). It may be read on a thread of its own
// (ThreadedHandSource) while the window takes its view: what it keeps is copied under a lock.
class ObservedHandSource : public HandSource {
 public:
  explicit ObservedHandSource(std::unique_ptr<HandSource> source);
  std::optional<HandSample> next() override;
  [[nodiscard]] std::string describe() const override { return source_->describe(); }
  [[nodiscard]] double period() const override { return source_->period(); }
  [[nodiscard]] std::optional<double> length() const override { return source_->length(); }
  std::vector<std::string> takeMessages() override { return source_->takeMessages(); }
  [[nodiscard]] std::string whyNoHands() const override { return source_->whyNoHands(); }

  [[nodiscard]] bool hasDepth() const { return depth_ != nullptr; }
  // The newest depth frame drawn at 1/step of the camera's resolution, when one arrived since the last call.
  std::optional<RgbImage> takeView(int step);
  // The newest depth frame and the performer's depth in it, when one came since the last call (the mirror view).
  struct Frame {
    kinect::DepthFrame depth;
    BodyDepth body;
  };
  std::optional<Frame> takeFrame();
  // What the performer should do now, from the newest frame (empty before the first), with how sure the tracking
  // of each hand is when asked.
  [[nodiscard]] std::string advice(bool withTracking);

 private:
  std::unique_ptr<HandSource> source_;
  DepthHandSource* depth_ = nullptr;  // source_ when it is one
  std::mutex mutex_;                  // guards what follows: the reading thread writes it, the window reads it
  kinect::DepthFrame frame_;
  Detection detection_;    // frame_'s
  bool newFrame_ = false;  // frame_ came, its detection not taken yet
  bool fresh_ = false;     // frame_ and detection_ not drawn yet
  bool untaken_ = false;   // frame_ and detection_ not taken by takeFrame yet
  bool drawn_ = false;     // a frame was drawn
  HandSample latest_;
};

// Whether the view shows, and the picture to show.
class PerformerView {
 public:
  static constexpr int kStep = 2;  // drawn at 320 x 240: the inset is a third of the window's width at most

  // The source whose frames are shown (nullptr: none, e.g. while the input is opened again).
  void attach(ObservedHandSource* source) { source_ = source; }
  // Waiting for a performer: the view shows then, unless V said otherwise.
  void setWaiting(bool waiting) { waiting_ = waiting; }
  // V: shows it if hidden and hides it if shown; says what it did.
  std::string toggle();
  [[nodiscard]] bool shown() const;
  // The show's word to the performer under the advice (the set-up's count; empty: none).
  void setCaption(const std::string& caption) { caption_ = caption; }
  // What the performer should do now (performerAdvice; empty without a depth camera).
  [[nodiscard]] std::string advice() const;
  // The picture to show when a new one is there (nothing: keep the one shown); an empty image hides it.
  std::optional<RgbImage> update();

 private:
  ObservedHandSource* source_ = nullptr;
  bool waiting_ = false;
  std::optional<bool> chosen_;  // by V
  bool wasShown_ = false;
  std::string caption_;
  RgbImage plot_;          // the newest depth plot, without its caption
  std::string captioned_;  // the text drawn over plot_ last
};

// What the performer should do, in a line: step in or back (the segmentation's advice), raise a hand not found.
std::string performerAdvice(const Detection& detection, const HandSample& hands);

// `text` drawn over the top of `image` (a banner as the window's overlay draws it, host/banner_text.h).
void drawCaption(RgbImage& image, const std::string& text);

}  // namespace gb
