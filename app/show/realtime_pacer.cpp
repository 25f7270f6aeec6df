#include "app/show/realtime_pacer.h"

#include <algorithm>
#include <cmath>
#include <thread>

namespace gb {

RealTimePacer::RealTimePacer(const PacerOptions& options, Clock::time_point start)
    : options_(options), start_(start), sweeps_(std::max(options.sweeps, 1)) {
  options_.minSweeps = std::clamp(options_.minSweeps, 1, sweeps_);
}

int RealTimePacer::framesDue(Clock::time_point now) {
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const long wanted = static_cast<long>(std::floor(elapsed / options_.frameTime));
  const long behind = wanted - due_;
  due_ = std::max(due_, wanted);
  if (behind <= options_.maxCatchUp) return static_cast<int>(std::max(behind, 0L));
  dropped_ += behind - options_.maxCatchUp;
  return options_.maxCatchUp;
}

void RealTimePacer::resync(Clock::time_point now) {
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const long wanted = static_cast<long>(std::floor(elapsed / options_.frameTime));
  // Move the start so that the frames already simulated are exactly the ones due now.
  start_ += std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(options_.frameTime * static_cast<double>(wanted - due_)));
}

void RealTimePacer::sleepUntilDue() {
  std::this_thread::sleep_until(start_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                                             options_.frameTime * static_cast<double>(due_ + 1))));
}

void RealTimePacer::record(int frames, double simMs, double renderMs) {
  simulated_ += frames;
  constexpr double smoothing = 0.1;  // about the last ten iterations
  simMs_ += smoothing * (simMs - simMs_);
  renderMs_ += smoothing * (renderMs - renderMs_);
  if (frames == 0) return;
  const double wallMs = 1000.0 * options_.frameTime * frames;
  const double spent = simMs + renderMs;
  // The image gives way first: a softer picture costs the show less than a softer film, whose free bubble bursts
  // sooner with fewer sweeps (docs/model.md). The sweeps go down only once the image is at its floor, and come back
  // first.
  const bool imageAtFloor = renderScale_ <= options_.minRenderScale;
  const bool sweepsAtTop = sweeps_ >= options_.sweeps;
  if (spent > wallMs && imageAtFloor && sweeps_ > options_.minSweeps)
    --sweeps_;
  else if (spent < 0.7 * wallMs && !sweepsAtTop)
    ++sweeps_;
  constexpr double step = 0.25;
  if (++sinceRescale_ < kRescaleEvery) return;
  if (spent > wallMs && !imageAtFloor) {
    // Far behind (a window too large for the machine), one change goes to the scale whose pixels would take the
    // frames' time (drawing time goes with the square of the scale); near the budget, a gentle step.
    const bool farBehind = spent > 4.0 * wallMs;
    const double next = farBehind ? renderScale_ * std::sqrt(wallMs / spent) : renderScale_ - step;
    renderScale_ = std::max(next, options_.minRenderScale);
    sinceRescale_ = 0;
  } else if (spent < 0.5 * wallMs && sweepsAtTop && renderScale_ < 1.0) {
    renderScale_ = std::min(renderScale_ + step, 1.0);
    sinceRescale_ = 0;
  }
}

void RealTimePacer::setMinRenderScale(double floor) {
  options_.minRenderScale = floor;
  renderScale_ = std::max(renderScale_, floor);
}

double renderScaleFloor(double minRenderScale, int width, int height) {
  const double pixels = static_cast<double>(width) * static_cast<double>(height);
  return std::min(minRenderScale, std::sqrt(kLargestFloorPixels / std::max(pixels, 1.0)));
}

double RealTimePacer::realTimeFactor(Clock::time_point now) const {
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  return elapsed > 0 ? static_cast<double>(simulated_) * options_.frameTime / elapsed : 1.0;
}

}  // namespace gb
