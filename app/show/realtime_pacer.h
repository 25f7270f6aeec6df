#pragma once
// Keeps a simulation on the wall clock (giantbubble live, run --realtime). Each loop iteration asks how many
// whole frames of h are due since the last one; when the machine cannot keep up, the solver first takes
// a smaller image (down to a floor, scaled up to the window), then fewer vertex block descent sweeps (down to a
// floor), and only then does the simulation slip: at most maxCatchUp frames are run per
// iteration and the rest of the lag is dropped (the bubble never runs in slow motion for long, it skips). Figures for
// the live window and the run summary: real-time factor (simulated seconds per wall second), simulation and render
// milliseconds.

#include <chrono>

namespace gb {

struct PacerOptions {
  double frameTime = 0.02;      // h (s)
  int sweeps = 6;               // the solver's sweeps when there is time (Params::solverSweeps' default)
  int minSweeps = 3;            // the floor: fewer sweeps leave the film visibly soft (docs/model.md)
  int maxCatchUp = 4;           // frames simulated at most per loop iteration before the lag is dropped
  double minRenderScale = 1.0;  // the smallest image, as a fraction of the window's width and height (1: fixed)
};

// The smallest render scale for a window of width x height pixels: `minRenderScale`, or less for a window so large
// that even that would draw more than kLargestFloorPixels: dynamic resolution must be able to come down to an image
// the machine can draw in time, whatever the window's size.
inline constexpr double kLargestFloorPixels = 1280.0 * 720.0;
double renderScaleFloor(double minRenderScale, int width, int height);

class RealTimePacer {
 public:
  using Clock = std::chrono::steady_clock;
  explicit RealTimePacer(const PacerOptions& options, Clock::time_point start = Clock::now());

  // Whole frames due now (0 when the simulation is ahead of the clock: sleepUntilDue waits for one). Frames
  // beyond maxCatchUp are dropped and counted.
  int framesDue(Clock::time_point now = Clock::now());
  // Forgets the time that passed (a paused show): the clock resumes from now without dropping frames.
  void resync(Clock::time_point now = Clock::now());
  // Waits until the next frame is due (run --realtime; the live window waits on the display instead).
  void sleepUntilDue();
  // One loop iteration's cost: `frames` frames simulated in simMs, and renderMs spent drawing. Adjusts the image
  // (renderScale) and then the sweeps for the next iteration: fewer sweeps when simulating and drawing took longer
  // than the frames' wall time and the image is at its floor, more again when they take under 70% of it.
  void record(int frames, double simMs, double renderMs);

  [[nodiscard]] int sweeps() const { return sweeps_; }
  // The fraction of the window's width and height to draw at: lowered while an iteration takes longer than its
  // frames, a step (0.25) at a time or, more than four times behind, at once to the scale whose pixels would take the
  // frames' time;
  // raised a step when it takes under half of them with the sweeps back at their top; at most one change per
  // kRescaleEvery iterations, since each costs the renderer new targets and pipelines.
  [[nodiscard]] double renderScale() const { return renderScale_; }
  // A new floor for the render scale (the window went full screen or back): the scale is kept within it.
  void setMinRenderScale(double floor);
  static constexpr int kRescaleEvery = 10;
  [[nodiscard]] bool atFloor() const { return sweeps_ == options_.minSweeps; }
  [[nodiscard]] long droppedFrames() const { return dropped_; }
  [[nodiscard]] long simulatedFrames() const { return simulated_; }
  // Simulated seconds per wall second since the start.
  [[nodiscard]] double realTimeFactor(Clock::time_point now = Clock::now()) const;
  // Mean simulation and render milliseconds per loop iteration over the last second (smoothed).
  [[nodiscard]] double simMs() const { return simMs_; }
  [[nodiscard]] double renderMs() const { return renderMs_; }

 private:
  PacerOptions options_;
  Clock::time_point start_;
  long due_ = 0;        // frames the wall clock has asked for since the start, dropped ones included
  long simulated_ = 0;  // frames simulated
  long dropped_ = 0;    // frames skipped because the machine could not keep up
  int sweeps_;
  double renderScale_ = 1.0;
  int sinceRescale_ = 0;  // iterations since the render scale last changed
  double simMs_ = 0, renderMs_ = 0;
};

}  // namespace gb
