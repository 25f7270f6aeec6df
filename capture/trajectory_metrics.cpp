#include "capture/trajectory_metrics.h"

#include <cmath>
#include <limits>

namespace gb {

double jitter(const std::vector<Vec3d>& p) {
  if (p.size() < 3) return 0.0;
  double sum = 0.0;
  for (size_t i = 1; i + 1 < p.size(); ++i) sum += (p[i + 1] - 2.0 * p[i] + p[i - 1]).squaredNorm();
  return std::sqrt(sum / static_cast<double>(p.size() - 2));
}

double lag(const std::vector<Vec3d>& leader, const std::vector<Vec3d>& follower, double dt, double maxLag,
           double* rmsError) {
  const size_t n = std::min(leader.size(), follower.size());
  const int steps = static_cast<int>(std::ceil(maxLag / dt * 20.0));
  const size_t first = static_cast<size_t>(std::ceil(maxLag / dt)) + 1;  // the same samples for every shift
  double best = 0.0, bestError = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= steps; ++k) {
    const double shift = k * dt / 20.0, samples = shift / dt;
    const size_t whole = static_cast<size_t>(samples);
    const double fraction = samples - static_cast<double>(whole);
    double sum = 0.0;
    size_t count = 0;
    for (size_t i = first; i < n; ++i) {
      const Vec3d earlier = (1.0 - fraction) * leader[i - whole] + fraction * leader[i - whole - 1];
      sum += (follower[i] - earlier).squaredNorm();
      ++count;
    }
    if (count == 0) break;
    const double error = std::sqrt(sum / static_cast<double>(count));
    if (error < bestError) {
      bestError = error;
      best = shift;
    }
  }
  if (rmsError) *rmsError = bestError;
  return best;
}

}  // namespace gb
