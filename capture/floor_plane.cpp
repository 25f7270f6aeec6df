#include "capture/floor_plane.h"

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

// The plane normal to a known up through the points near the layer: their mean height, in two rounds (the
// layer's middle is only good to a bin, 3 cm, and the floor's points must be cut a few centimetres over it).
std::optional<FloorPlane> fitHeight(const std::vector<Vec3d>& points, const Vec3d& up, double height) {
  FloorPlane floor;
  floor.up = up;
  floor.offset = height;
  for (int round = 0; round < 2; ++round) {
    double sum = 0.0;
    int n = 0;
    for (const Vec3d& p : points)
      if (const double h = up.dot(p); std::abs(h - floor.offset) < kFitTolerance) sum += h, ++n;
    if (n < 3) return std::nullopt;
    floor.offset = sum / n;
    floor.inliers = n;
  }
  return floor;
}

// Every step-th point: enough to compare tilts, whose layers hold thousands of floor points.
std::vector<Vec3d> thinned(const std::vector<Vec3d>& points, size_t step) {
  std::vector<Vec3d> out;
  out.reserve(points.size() / step + 1);
  for (size_t i = 0; i < points.size(); i += step) out.push_back(points[i]);
  return out;
}

// The tilt whose densest low layer holds the most points: pitches from 10 degrees up to 40 down and rolls of
// +-6 degrees, coarse to fine (4 then 1 degree of pitch, 6 then 3 of roll) on a quarter, then half of the
// points: a tilt a few degrees off still gathers most of the floor into its layer, so the coarse pass lands
// next to the best tilt. Its layer is then counted over all the points. A twelfth of the work of the full
// 1-degree grid's 255 histograms over every point, for the same tilts.
void searchTilts(const std::vector<Vec3d>& points, Vec3d& bestUp, Layer& best) {
  const std::vector<Vec3d> quarter = thinned(points, 4), half = thinned(points, 2);
  double bestPitch = 0.0, bestRoll = 0.0;
  int bestCount = -1;
  for (double pitch = -10.0; pitch <= 40.0; pitch += 4.0)
    for (double roll = -6.0; roll <= 6.0; roll += 6.0) {
      const Layer layer = densestLowLayer(quarter, upFromTilt(pitch, roll));
      if (layer.count > bestCount) bestCount = layer.count, bestPitch = pitch, bestRoll = roll;
    }
  const double coarsePitch = bestPitch, coarseRoll = bestRoll;
  bestCount = -1;
  for (double pitch = coarsePitch - 3.0; pitch <= coarsePitch + 3.0; pitch += 1.0)
    for (double roll = coarseRoll - 3.0; roll <= coarseRoll + 3.0; roll += 3.0) {
      if (pitch < -10.0 || pitch > 40.0 || roll < -6.0 || roll > 6.0) continue;
      const Layer layer = densestLowLayer(half, upFromTilt(pitch, roll));
      if (layer.count > bestCount) bestCount = layer.count, bestPitch = pitch, bestRoll = roll;
    }
  bestUp = upFromTilt(bestPitch, bestRoll);
  best = densestLowLayer(points, bestUp);
}

// Least-squares plane through the points near the layer: the normal is the covariance's smallest eigenvector.
// The least-squares plane through the points near the layer: their mean and the covariance's smallest
// eigenvector, turned to point along up; nothing with fewer than 3 points.
struct LayerFit {
  Vec3d mean, normal;
  int points = 0;
};
std::optional<LayerFit> fitLayer(const std::vector<Vec3d>& points, const Vec3d& up, double height) {
  LayerFit fit;
  fit.mean = Vec3d::Zero();
  for (const Vec3d& p : points)
    if (std::abs(up.dot(p) - height) < kFitTolerance) fit.mean += p, ++fit.points;
  if (fit.points < 3) return std::nullopt;
  fit.mean /= fit.points;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3d& p : points)
    if (std::abs(up.dot(p) - height) < kFitTolerance) cov += (p - fit.mean) * (p - fit.mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
  fit.normal = solver.eigenvectors().col(0);
  if (fit.normal.dot(up) < 0.0) fit.normal = -fit.normal;
  return fit;
}

std::optional<FloorPlane> fitPlane(const std::vector<Vec3d>& points, const Vec3d& up, double height) {
  const std::optional<LayerFit> fit = fitLayer(points, up, height);
  if (!fit) return std::nullopt;
  FloorPlane floor;
  floor.up = fit->normal;
  // A fit that leans far from the layer's direction caught something else (a wall's foot, a table's edge).
  if (floor.up.dot(up) < std::cos(10.0 * std::numbers::pi / 180.0)) floor.up = up;
  floor.offset = floor.up.dot(fit->mean);
  floor.inliers = fit->points;
  return floor;
}

}  // namespace

std::optional<FloorPlane> findFloor(const std::vector<Vec3d>& points, const std::optional<Vec3d>& gravityUp,
                                    double minFraction) {
  if (points.empty()) return std::nullopt;
  Vec3d bestUp = Vec3d::UnitY();
  Layer best;
  const double fewest = minFraction * static_cast<double>(points.size());
  if (gravityUp) {
    // A measured gravity is kept as the normal: only the height is fitted. With no floor along it (none in
    // view, or a reading not to be trusted) the floor is searched for as without one. (A wrong reading can
    // still gather a slanted strip of the floor: DepthHandSource checks the accelerometer against the search.)
    bestUp = gravityUp->normalized();
    best = densestLowLayer(points, bestUp);
    if (best.count >= fewest) return fitHeight(points, bestUp, best.height);
  }
  searchTilts(points, bestUp, best);
  if (best.count < fewest) return std::nullopt;
  // Two rounds of fitting: the second with the fitted normal, which the 1-degree search only approximates.
  std::optional<FloorPlane> floor = fitPlane(points, bestUp, best.height);
  if (floor) floor = fitPlane(points, floor->up, floor->offset);
  return floor;
}

}  // namespace gb
