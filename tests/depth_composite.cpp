#include "tests/depth_composite.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "tests/synthetic_depth.h"

namespace gb::test {

namespace {

using kinect::kHeight;
using kinect::kWidth;

// The recorded people's points (camera space) of one frame: each 2 x 2 block's first reading.
std::vector<Vec3d> peopleOf(const kinect::DepthFrame& frame) {
  std::vector<Vec3d> points;
  for (int v = 0; v < kHeight; v += 2)
    for (int u = 0; u < kWidth; u += 2) {
      const double z = kinect::rawToMetres(frame.raw[static_cast<size_t>(v) * kWidth + u]);
      if (z > 0.0) points.push_back(kinect::pixelToCamera(u, v, z));
    }
  return points;
}

// Where a recording's people stand: their median depth and their floor's height (camera y of the lowest points).
struct Stance {
  double depth = 0.0, floorY = 0.0;
};

Stance stanceOf(const DepthRecording& r) {
  std::vector<double> depths, heights;
  for (size_t i = 0; i < r.frames.size(); i += 5)
    for (const Vec3d& p : peopleOf(r.frames[i])) depths.push_back(p.z()), heights.push_back(p.y());
  if (depths.empty()) return {};
  std::sort(depths.begin(), depths.end());
  std::sort(heights.begin(), heights.end());
  return {depths[depths.size() / 2], heights[heights.size() / 200]};
}

// Moves a level camera's point to where a camera at the same place, tilted down by `pitch`, sees it.
Vec3d tilted(const Vec3d& p, double pitch) {
  const double a = pitch * std::numbers::pi / 180.0;
  return {p.x(), p.y() * std::cos(a) + p.z() * std::sin(a), -p.y() * std::sin(a) + p.z() * std::cos(a)};
}

// Draws points into a depth buffer, each as large as the 2 x 2 block it was seen as at its old depth.
void splat(const std::vector<Vec3d>& points, const std::vector<double>& oldDepth, std::vector<double>& depth) {
  for (size_t k = 0; k < points.size(); ++k) {
    const Vec3d& p = points[k];
    if (p.z() < 0.4) continue;
    const Eigen::Vector2d px = kinect::cameraToPixel(p);
    const int size = std::max(2, static_cast<int>(std::ceil(2.0 * oldDepth[k] / p.z())));
    const int u0 = static_cast<int>(std::floor(px.x())), v0 = static_cast<int>(std::floor(px.y()));
    for (int v = v0; v < v0 + size; ++v)
      for (int u = u0; u < u0 + size; ++u) {
        if (u < 0 || v < 0 || u >= kWidth || v >= kHeight) continue;
        double& z = depth[static_cast<size_t>(v) * kWidth + u];
        if (z == 0.0 || p.z() < z) z = p.z();
      }
  }
}

// A frame's people moved by `shift` (camera space) and tilted, drawn over `depth`.
void drawPeople(const kinect::DepthFrame& frame, const Vec3d& shift, double pitch, std::vector<double>& depth) {
  std::vector<Vec3d> points = peopleOf(frame);
  std::vector<double> oldDepth(points.size());
  for (size_t k = 0; k < points.size(); ++k) oldDepth[k] = points[k].z(), points[k] = tilted(points[k] + shift, pitch);
  splat(points, oldDepth, depth);
}

// The true hands moved with the people; a hand the move takes out of the image is no longer measured (no one
// could find it), but keeps its place (a hand reported there is not false).
HandSample movedTruth(const HandSample& truth, const Vec3d& shift, double pitch) {
  HandSample s = truth;
  for (HandObservation* h : {&s.left, &s.right}) {
    if (!h->seen()) continue;
    h->position = tilted(h->position + shift, pitch);
    const Eigen::Vector2d px = kinect::cameraToPixel(h->position);
    if (px.x() < 0.0 || px.y() < 0.0 || px.x() >= kWidth || px.y() >= kHeight) h->measured = false;
  }
  return s;
}

}  // namespace

DepthRecording composite(const DepthRecording& performer, const CompositeOptions& o) {
  const Stance stance = stanceOf(performer);
  const Vec3d shift(0.0, 0.0, o.distance > 0.0 ? o.distance - stance.depth : 0.0);
  const double cameraHeight = -stance.floorY, feet = stance.depth + shift.z() + 0.1;
  Stance bystanderStance;
  Vec3d bystanderShift = Vec3d::Zero();
  if (o.bystander) {
    // Half in view at the right edge of the image, a little behind the performer.
    bystanderStance = stanceOf(*o.bystander);
    const double depth = std::max(bystanderStance.depth, feet + 0.4);
    const double edgeX = (kWidth - kinect::kCx) * depth / kinect::kFx;
    bystanderShift = Vec3d(edgeX, 0.0, depth - bystanderStance.depth);
  }
  DepthRecording out;
  out.name = performer.name + " (" + describe(o) + ")";
  const double dt = performer.frames.size() > 1 ? performer.frames[1].time - performer.frames[0].time : 1.0 / 30.0;
  const std::vector<double> room = renderRoom(o.room, feet, o.pitch, cameraHeight);
  const size_t frames = static_cast<size_t>(o.emptyFrames) + performer.frames.size();
  for (size_t i = 0; i < frames; ++i) {
    const bool empty = i < static_cast<size_t>(o.emptyFrames);
    const size_t k = i - (empty ? 0 : static_cast<size_t>(o.emptyFrames));
    std::vector<double> people(kinect::kPixels, 0.0);
    if (!empty) drawPeople(performer.frames[k], shift, o.pitch, people);
    if (o.bystander) drawPeople(o.bystander->frames[i % o.bystander->frames.size()], bystanderShift, o.pitch, people);
    std::vector<double> depth = room;
    addKinectNoise(depth, o.seed * 104729u + static_cast<unsigned>(i));
    kinect::DepthFrame frame;
    frame.time = static_cast<double>(i) * dt;
    frame.timestamp = static_cast<uint32_t>(i);
    for (size_t p = 0; p < depth.size(); ++p) {
      const double z = people[p] > 0.0 && (depth[p] <= 0.0 || people[p] < depth[p]) ? people[p] : depth[p];
      frame.raw[p] = z > 0.0 ? kinect::metresToRaw(z) : kinect::kNoReading;
    }
    out.frames.push_back(std::move(frame));
    HandSample truth;
    if (!empty) truth = movedTruth(performer.truth[k], shift, o.pitch);
    truth.time = static_cast<double>(i) * dt;
    out.truth.push_back(truth);
  }
  return out;
}

std::string describe(const CompositeOptions& o) {
  char text[32];
  std::string s = o.room;
  if (o.distance > 0.0) {
    std::snprintf(text, sizeof text, ", %.1f m", o.distance);
    s += text;
  }
  if (o.pitch != 0.0) {
    std::snprintf(text, sizeof text, ", tilt %.0f", o.pitch);
    s += text;
  }
  if (o.emptyFrames > 0) s += ", steps in";
  if (o.bystander) s += ", bystander";
  return s;
}

}  // namespace gb::test
