#include "floor_plane.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gb {

namespace {

constexpr double kBin = 0.03;           // m: height histogram bin
constexpr double kLowest = -4.0;        // m: lowest floor considered below the camera
constexpr double kHighest = -0.2;       // m: the floor is at least this far below the camera
constexpr double kFitTolerance = 0.04;  // m: points this close to the layer take part in the plane fit
constexpr double kMaxUnder = 0.02;      // fraction of the points allowed under the floor (noise, reflections)
constexpr int kBins = static_cast<int>((kHighest - kLowest) / kBin);

struct Layer {
  double height = 0.0;  // up . p of the layer's middle
  int count = 0;
};

// The most populated two-bin layer of up . p below the camera with almost nothing under it: for the true up,
// the floor's points collapse into it; for a wrong one they spread over many bins, and a tilted "floor"
// through a wall or a body has much of the scene under it.
Layer densestLowLayer(const std::vector<Vec3d>& points, const Vec3d& up) {
  std::vector<int> bins(kBins, 0);
  int under = 0;  // below the lowest bin
  for (const Vec3d& p : points) {
    const int b = static_cast<int>(std::floor((up.dot(p) - kLowest) / kBin));
    if (b < 0) ++under;
    if (b >= 0 && b < kBins) ++bins[b];
  }
  const double allowedUnder = kMaxUnder * static_cast<double>(points.size());
  Layer best;
  for (int b = 0; b + 1 < kBins; ++b) {
    if (under > allowedUnder) break;
    if (bins[b] + bins[b + 1] > best.count) best = {kLowest + (b + 1) * kBin, bins[b] + bins[b + 1]};
    under += b > 0 ? bins[b - 1] : 0;  // the bin two below the next layer: clearly under it
  }
  return best;
}

Vec3d upFromTilt(double pitchDeg, double rollDeg) {
  const double p = pitchDeg * std::numbers::pi / 180.0, r = rollDeg * std::numbers::pi / 180.0;
  // A camera pitched down by p sees the up direction tilted towards -z; a roll turns it about z.
  return Vec3d(std::sin(r) * std::cos(p), std::cos(r) * std::cos(p), -std::sin(p)).normalized();
}

// Least-squares plane through the points near the layer: the normal is the covariance's smallest eigenvector.
std::optional<FloorPlane> fitPlane(const std::vector<Vec3d>& points, const Vec3d& up, double height) {
  Vec3d mean = Vec3d::Zero();
  int n = 0;
  for (const Vec3d& p : points)
    if (std::abs(up.dot(p) - height) < kFitTolerance) mean += p, ++n;
  if (n < 3) return std::nullopt;
  mean /= n;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3d& p : points)
    if (std::abs(up.dot(p) - height) < kFitTolerance) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
  Vec3d normal = solver.eigenvectors().col(0);
  if (normal.dot(up) < 0.0) normal = -normal;
  // A fit that leans far from the layer's direction caught something else (a wall's foot, a table's edge).
  if (normal.dot(up) < std::cos(10.0 * std::numbers::pi / 180.0)) normal = up;
  FloorPlane floor;
  floor.up = normal;
  floor.offset = normal.dot(mean);
  floor.inliers = n;
  return floor;
}

}  // namespace

std::optional<FloorPlane> findFloor(const std::vector<Vec3d>& points, const std::optional<Vec3d>& gravityUp,
                                    double minFraction) {
  if (points.empty()) return std::nullopt;
  Vec3d bestUp = Vec3d::UnitY();
  Layer best;
  if (gravityUp) {
    bestUp = gravityUp->normalized();
    best = densestLowLayer(points, bestUp);
  } else {
    for (double pitch = -10.0; pitch <= 40.0; pitch += 1.0)
      for (double roll = -6.0; roll <= 6.0; roll += 3.0) {
        const Vec3d up = upFromTilt(pitch, roll);
        const Layer layer = densestLowLayer(points, up);
        if (layer.count > best.count) best = layer, bestUp = up;
      }
  }
  if (best.count < minFraction * static_cast<double>(points.size())) return std::nullopt;
  // Two rounds of fitting: the second with the fitted normal, which the 1-degree search only approximates. A
  // measured gravity is kept as the normal: only the height is fitted.
  std::optional<FloorPlane> floor = fitPlane(points, bestUp, best.height);
  if (floor) floor = fitPlane(points, floor->up, floor->offset);
  if (floor && gravityUp) {
    floor->up = bestUp;
    floor->offset = best.height;
  }
  return floor;
}

}  // namespace gb
