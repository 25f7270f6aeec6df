#include "host/render_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "host/procedural_noise.h"
#include "kernels/render/render_shared.h"

namespace gb {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// `tubeRadius`: for a vertex of a tube, its radius (the vertex is the axis plus radius times the normal), so
// that props.vert can widen a tube thinner than a pixel; 0 for flat props.
void addVertex(std::vector<float>& mesh, const Vec3& p, const Vec3& n, const Vec3& albedo, int material,
               float tubeRadius = 0.0f) {
  mesh.insert(mesh.end(), {p.x(), p.y(), p.z(), n.x(), n.y(), n.z(), albedo.x(), albedo.y(), albedo.z(),
                           static_cast<float>(material), tubeRadius, 0.0f});
}

// A tube of `radius` along a polyline, six sides, flat ends left open (they are never seen end-on for long).
void addTube(std::vector<float>& mesh, const std::vector<Vec3>& path, float radius, const Vec3& albedo,
             int material = GB_MATERIAL_PLAIN) {
  constexpr int sides = 6;
  for (size_t k = 0; k + 1 < path.size(); ++k) {
    const Vec3 axis = (path[k + 1] - path[k]).normalized();
    const Vec3 side = (std::abs(axis.y()) < 0.9f ? axis.cross(Vec3::UnitY()) : axis.cross(Vec3::UnitX())).normalized();
    const Vec3 up = axis.cross(side);
    for (int s = 0; s < sides; ++s) {
      const float a0 = 2 * kPi * static_cast<float>(s) / sides, a1 = 2 * kPi * static_cast<float>(s + 1) / sides;
      const Vec3 n0 = std::cos(a0) * side + std::sin(a0) * up, n1 = std::cos(a1) * side + std::sin(a1) * up;
      const Vec3 quad[4][2] = {{path[k] + radius * n0, n0},
                               {path[k] + radius * n1, n1},
                               {path[k + 1] + radius * n1, n1},
                               {path[k + 1] + radius * n0, n0}};
      for (int corner : {0, 1, 2, 0, 2, 3}) addVertex(mesh, quad[corner][0], quad[corner][1], albedo, material, radius);
    }
  }
}

// The ground: a neutral grey square (sunlit concrete paving, groundAlbedo) 160 m across (its edge near the far
// plane). Beyond it the environment's ground shows: the default sky paints it as this floor is lit, other
// environments hide the edge in haze (EnvironmentImage::hazeDistance).
void addFloor(std::vector<float>& mesh) {
  constexpr float half = 80.0f;
  const Vec3 corners[4] = {{-half, 0, -half}, {half, 0, -half}, {half, 0, half}, {-half, 0, half}};
  for (int corner : {0, 2, 1, 0, 3, 2})
    addVertex(mesh, corners[corner], Vec3::UnitY(), groundAlbedo(), GB_MATERIAL_FLOOR);
}

// The rim of a hole: liquid the retracting film has collected (Taylor-Culick), a thread of water a few
// millimetres thick as drawn, so that the opening hole reads as a bright line racing across the film.
void addHoleRims(std::vector<float>& mesh, const Film& film) {
  const std::vector<uint32_t> rim = holeRimEdges(film);
  for (size_t k = 0; k < rim.size(); k += 2)
    addTube(mesh, {film.state.position.get(rim[k]), film.state.position.get(rim[k + 1])}, 0.003f,
            Vec3(0.9f, 0.92f, 0.95f), GB_MATERIAL_RIM);
}

// A wand: a stick from the tip down and outwards, where a hand holds it.
void addStick(std::vector<float>& mesh, const Vec3& tip, const Vec3& outward) {
  const Vec3 handle = tip + 0.5f * (0.35f * outward - Vec3::UnitY()).normalized();
  addTube(mesh, {tip, handle}, 0.012f, Vec3(0.45f, 0.3f, 0.18f));
}

}  // namespace

namespace {

// Unit, from the target towards the eye of a camera turned by `yaw` about the vertical and pitched by `pitch`.
Vec3 backOf(float yaw, float pitch) {
  return {std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch)};
}

// World -> view space of an eye at `eye` looking along the unit `forward`, y up.
Eigen::Matrix4f lookAlong(const Vec3& forward, const Vec3& eye) {
  const Vec3& f = forward;
  const Vec3 s = f.cross(Vec3::UnitY()).normalized();
  const Vec3 up = s.cross(f);
  Eigen::Matrix4f view = Eigen::Matrix4f::Identity();
  view.row(0) << s.x(), s.y(), s.z(), -s.dot(eye);
  view.row(1) << up.x(), up.y(), up.z(), -up.dot(eye);
  view.row(2) << -f.x(), -f.y(), -f.z(), f.dot(eye);
  return view;
}

// View -> Vulkan clip space (y down, depth 0 at near .. 1 at far).
Eigen::Matrix4f perspective(float fovY, float aspect) {
  const float nearPlane = 0.05f, farPlane = 100.0f;
  const float t = 1.0f / std::tan(0.5f * fovY);
  Eigen::Matrix4f proj = Eigen::Matrix4f::Zero();
  proj(0, 0) = t / aspect;
  proj(1, 1) = -t;  // Vulkan's clip space has y pointing down
  proj(2, 2) = farPlane / (nearPlane - farPlane);
  proj(2, 3) = nearPlane * farPlane / (nearPlane - farPlane);
  proj(3, 2) = -1.0f;
  return proj;
}

}  // namespace

Vec3 OrbitCamera::position() const { return target + distance * backOf(yaw, pitch); }

Eigen::Matrix4f OrbitCamera::viewProjection(float aspect) const {
  const Vec3 eye = position();
  return perspective(fovY, aspect) * lookAlong((target - eye).normalized(), eye);
}

Eigen::Matrix4f OrbitCamera::skyRays(float aspect) const {
  return (perspective(fovY, aspect) * lookAlong(-backOf(yaw, pitch), Vec3::Zero())).inverse();
}

float FilmFraming::pitchAbove(const OrbitCamera& base, const Vec3& target, float distance) const {
  const float lowest = std::clamp((options_.minEyeHeight - target.y()) / std::max(distance, 1e-3f), -1.0f, 1.0f);
  return std::max(base.pitch, std::asin(lowest));
}

float FilmFraming::framingDistance(const OrbitCamera& base, const State& s, const Vec3& centre) const {
  const Vec3 right(std::cos(base.yaw), 0.0f, -std::sin(base.yaw));  // up x back, normalised, from the yaw alone
  // Unit, towards the camera at distance d (its pitch may depend on d: pitchAbove).
  const auto backAt = [&](float d) {
    OrbitCamera probe = base;
    probe.target = centre;
    probe.pitch = pitchAbove(base, centre, d);
    probe.distance = 1.0f;
    return Vec3(probe.position() - centre);
  };
  // The outline's extent on the image at distance d, as fractions of the image's height and width: each particle
  // at (x, y) across and z towards the camera from the centre is seen at tan = x / (d - z).
  const float tanHalfY = std::tan(0.5f * base.fovY), tanHalfX = options_.aspect * tanHalfY;
  // The living particles about the centre, gathered once for the passes of the root finder below, each of them
  // over every particle. Minima and maxima are the same in any order, so the threads do not change the framing.
  std::vector<Vec3> offsets;
  offsets.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i)
    if (s.alive[i]) offsets.push_back(s.position.get(i) - centre);
  const auto count = static_cast<long>(offsets.size());
  constexpr long kParallelFrom = 16384;  // particles: below this a pass is shorter than waking the threads
  // The search starts just beyond the nearest particle, so that every particle is in front of the camera. Where
  // the pitch changes with the distance, nearest in any direction.
  const Vec3 farBack = backAt(1e4f);
  float nearest = 0.0f, radius = 0.0f;
#pragma omp parallel for reduction(max : nearest, radius) if (count >= kParallelFrom)
  for (long i = 0; i < count; ++i) {
    const Vec3& p = offsets[static_cast<size_t>(i)];
    nearest = std::max(nearest, p.dot(farBack));
    radius = std::max(radius, p.norm());
  }
  if (pitchAbove(base, centre, nearest + 0.05f) > base.pitch) nearest = radius;
  // How well the outline fits at distance d: 1 / (its largest extent as a share of what the options allow) - 1, so
  // negative where it is too large. Nearly linear in d (each particle is seen at x / (d - z)), which the root
  // finder below makes use of.
  const auto fit = [&](float d) {
    const Vec3 back = backAt(d), up = back.cross(right);
    float loX = 0, hiX = 0, loY = 0, hiY = 0;
#pragma omp parallel for reduction(min : loX, loY) reduction(max : hiX, hiY) if (count >= kParallelFrom)
    for (long i = 0; i < count; ++i) {
      const Vec3& p = offsets[static_cast<size_t>(i)];
      const float depth = d - p.dot(back);
      loX = std::min(loX, p.dot(right) / depth);
      hiX = std::max(hiX, p.dot(right) / depth);
      loY = std::min(loY, p.dot(up) / depth);
      hiY = std::max(hiY, p.dot(up) / depth);
    }
    const float share = std::max((hiY - loY) / (2.0f * tanHalfY * options_.heightFraction),
                                 (hiX - loX) / (2.0f * tanHalfX * options_.widthFraction));
    return share > 0.0f ? 1.0f / share - 1.0f : std::numeric_limits<float>::infinity();
  };
  // The extent shrinks as the camera backs away: bracket the distance between just beyond the nearest particle
  // and far enough, then close the bracket by regula falsi with the Illinois rule (the end that stays has its
  // value halved, so that both ends converge) to 0.01% of the distance: about 7 passes over the particles on the
  // default performance and on a bubble, where bisection to the same precision takes 14.
  float lo = nearest + 0.05f, hi = std::max(2.0f * lo, options_.minDistance);
  float fitLo = fit(lo), fitHi = fit(hi);
  if (fitLo >= 0.0f) return std::max(options_.minDistance, lo);  // a film that fits even there (seen end-on)
  while (fitHi < 0.0f && hi < 1e4f) {
    lo = hi, fitLo = fitHi;
    hi *= 2.0f, fitHi = fit(hi);
  }
  int kept = 0;  // the end the last step moved, +1 the far one and -1 the near one: twice the same halves the other
  for (int k = 0; k < 60 && hi - lo > 1e-4f * hi; ++k) {
    float d = std::isfinite(fitHi) ? (lo * fitHi - hi * fitLo) / (fitHi - fitLo) : 0.5f * (lo + hi);
    if (!(d > lo && d < hi)) d = 0.5f * (lo + hi);
    const float f = fit(d);
    if (f >= 0.0f) {
      hi = d, fitHi = f;
      if (kept == 1) fitLo *= 0.5f;
      kept = 1;
    } else {
      lo = d, fitLo = f;
      if (kept == -1) fitHi *= 0.5f;
      kept = -1;
    }
  }
  return std::max(options_.minDistance, hi);
}

OrbitCamera FilmFraming::update(const OrbitCamera& base, const State& s, float dt) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<float>::max()), hi = -lo;
  for (size_t i = 0; i < s.size(); ++i)
    if (s.alive[i]) {
      lo = lo.cwiseMin(s.position.get(i));
      hi = hi.cwiseMax(s.position.get(i));
    }
  OrbitCamera camera = base;
  if (lo.x() > hi.x()) {  // nothing alive: hold the last framing
    if (started_) {
      camera.target = target_;
      camera.distance = distance_;
    }
    return camera;
  }
  const Vec3 centre = 0.5f * (lo + hi);
  const float distance = framingDistance(base, s, centre);
  const float follow = started_ ? 1.0f - std::exp(-std::max(dt, 0.0f) / options_.easing) : 1.0f;
  if (started_ && dt > 0.0f) {
    Vec3 drift = (centre - lastCentre_) / dt;
    if (drift.norm() > options_.maxDrift) drift *= options_.maxDrift / drift.norm();
    velocity_ += follow * (drift - velocity_);
  }
  lastCentre_ = centre;
  // Leading the centre by velocity x easing cancels the first-order follower's lag at a steady drift.
  target_ += follow * (centre + options_.easing * velocity_ - target_);
  distance_ += follow * (distance - distance_);
  started_ = true;
  camera.target = target_;
  camera.distance = distance_;
  camera.pitch = pitchAbove(base, target_, distance_);
  return camera;
}

std::vector<uint32_t> holeRimEdges(const Film& film) {
  const std::vector<uint32_t>& wire = film.topology.boundary;
  std::vector<uint32_t> rim;
  for (const EdgeUse& e : edgeUses(wire.size(), film.topology.triangles))
    if (e.triangles == 1 && !(wire[e.lower] && wire[e.upper])) rim.insert(rim.end(), {e.lower, e.upper});
  return rim;
}

std::vector<float> buildProps(const WireFrame* frame, const Film* film) {
  std::vector<float> mesh;
  addFloor(mesh);
  if (film) addHoleRims(mesh, *film);
  if (!frame) return mesh;
  std::vector<Vec3> loop;
  constexpr int segments = 96;
  for (int k = 0; k <= segments; ++k)
    loop.push_back(wirePoint(*frame, frame->parameterEnd() * static_cast<float>(k) / segments));
  if (frame->kind == ToolKind::TwoWands) {
    addTube(mesh, loop, 0.004f, Vec3(0.85f, 0.85f, 0.8f));
    addStick(mesh, wirePoint(*frame, 0.0f), -frame->axis);
    addStick(mesh, wirePoint(*frame, 1.0f), frame->axis);
  } else {
    addTube(mesh, loop, 0.008f, Vec3(0.7f, 0.7f, 0.75f));
    const Vec3 bottom = frame->center + frame->depth * frame->down;
    addTube(mesh, {bottom, bottom + 0.45f * frame->down}, 0.015f, Vec3(0.45f, 0.3f, 0.18f));
  }
  return mesh;
}

std::vector<float> packDroplets(const Aerosol& aerosol, float lifetime) {
  std::vector<float> out;
  out.reserve(4 * aerosol.size());
  for (size_t i = 0; i < aerosol.size(); ++i) {
    const float left = 1.0f - aerosol.age[i] / std::max(lifetime, 1e-6f);
    out.insert(out.end(), {aerosol.position.x[i], aerosol.position.y[i], aerosol.position.z[i],
                           std::clamp(3.0f * left, 0.0f, 1.0f)});
  }
  return out;
}

std::array<Vec3, 2> hemisphereMeans(const EnvironmentImage& env) {
  std::array<Eigen::Vector3d, 2> sum{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  std::array<double, 2> weight{0, 0};
  for (int row = 0; row < env.height; ++row) {
    const double polar = std::numbers::pi * (row + 0.5) / env.height;
    const size_t half = polar < 0.5 * std::numbers::pi ? 0 : 1;
    const double w = std::sin(polar);  // solid angle of a texel of this row
    for (int col = 0; col < env.width; ++col) {
      const float* c = &env.rgb[3 * (static_cast<size_t>(row) * env.width + col)];
      sum[half] += w * Eigen::Vector3d(c[0], c[1], c[2]);
      weight[half] += w;
    }
  }
  return {(sum[0] / std::max(weight[0], 1e-12)).cast<float>(), (sum[1] / std::max(weight[1], 1e-12)).cast<float>()};
}

namespace {

// The direction (unit, world) of the centre of texel (row, col) of an equirectangular environment: the
// parameterisation of environment() in kernels/render/render_common.glsl, u = 0.5 + atan(x, -z) / 2 pi, v = polar / pi.
Vec3 texelDirection(const EnvironmentImage& env, int row, int col) {
  const float polar = kPi * (static_cast<float>(row) + 0.5f) / static_cast<float>(env.height);
  const float azimuth = 2 * kPi * ((static_cast<float>(col) + 0.5f) / static_cast<float>(env.width) - 0.5f);
  return {std::sin(polar) * std::sin(azimuth), std::cos(polar), -std::sin(polar) * std::cos(azimuth)};
}

// An environment of `width` x width / 2 texels whose radiance in direction d is radiance(d); the texel
// parameterisation of environment() in kernels/render/render_common.glsl: u = 0.5 + atan(x, -z) / 2 pi, v = polar / pi.
template <class Radiance>
EnvironmentImage tabulateEnvironment(int width, const Radiance& radiance) {
  EnvironmentImage env;
  env.width = width;
  env.height = width / 2;
  env.rgb.resize(static_cast<size_t>(env.width) * env.height * 3);
#pragma omp parallel for
  for (int row = 0; row < env.height; ++row) {
    for (int col = 0; col < env.width; ++col) {
      const Vec3 c = radiance(texelDirection(env, row, col));
      float* out = &env.rgb[3 * (static_cast<size_t>(row) * env.width + col)];
      out[0] = c.x();
      out[1] = c.y();
      out[2] = c.z();
    }
  }
  return env;
}

float smoothstep(float edge0, float edge1, float x) {
  const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// The outdoor sky of skyEnvironment(). Radiances are in the renderer's units (exposure 1 shows 0.8 as
// near-white): the sky 0.3-0.9, clouds about 1, the sun's disc 40 so that its reflection in a film (a few
// percent) is still a bright glint.
struct OutdoorSky {
  Vec3 sun = Vec3(0.2f, 0.55f, 0.8f).normalized();  // behind the default three-quarter camera, over its left shoulder
  Vec3 zenith = Vec3(0.13f, 0.27f, 0.62f);
  Vec3 haze = Vec3(0.72f, 0.78f, 0.86f);

  // Above the horizon; below it skyEnvironment paints the ground.
  [[nodiscard]] Vec3 operator()(const Vec3& d) const {
    const float elevation = std::asin(std::clamp(d.y(), -1.0f, 1.0f));
    if (elevation < 0.0f) return Vec3::Zero();
    const float azimuth = std::atan2(d.x(), -d.z());
    const Vec3 around(std::cos(azimuth), std::sin(azimuth), 0.0f);  // seamless in azimuth, for the woods' colour
    // Wooded hills: a ridge line of several scales, 1-6 degrees high, with a tree-scale ragged edge.
    // A sum of sines in azimuth (whole frequencies: seamless), smooth hills with a finer tree line on top;
    // lattice noise would leave flat plateaus that read as buildings.
    const float ridge = 0.045f + 0.02f * std::sin(3.0f * azimuth + 1.0f) + 0.012f * std::sin(7.0f * azimuth + 2.0f) +
                        0.006f * std::sin(17.0f * azimuth + 0.5f) + 0.002f * std::sin(83.0f * azimuth + 4.0f) +
                        0.0015f * std::sin(191.0f * azimuth);
    // The ridge's edge is blended over about a texel (0.35 degrees at 1024 wide): a hard edge would show
    // the texel rows as stair steps once the environment is magnified in the picture.
    const float hill = smoothstep(ridge + 0.003f, ridge - 0.003f, elevation);
    const float depth = std::min(elevation / ridge, 1.0f);  // distant hills are hazier at their foot
    const Vec3 woods = Vec3(0.06f, 0.09f, 0.05f) *
                       (0.8f + 0.4f * noise::fractal3(30.0f * around + Vec3(0.0f, 0.0f, 400.0f * elevation), 2, 5u));
    const Vec3 hills = woods + (haze - woods) * (0.55f - 0.25f * depth);
    const Vec3 sky = haze + (zenith - haze) * std::pow(std::clamp(d.y(), 0.0f, 1.0f), 0.45f);
    // Cumulus on a flat layer above: fractal noise over the layer's plane, thinned near the horizon.
    const Vec3 layer = Vec3(d.x(), 0.0f, d.z()) / std::max(d.y(), 0.04f);
    const float density = smoothstep(0.05f, 0.45f, noise::fractal3(0.9f * layer + Vec3(0, 0.37f, 0), 5u, 3u));
    const float cosSun = d.dot(sun);
    const Vec3 cloud = Vec3(1.05f, 1.05f, 1.08f) * (0.75f + 0.35f * std::max(cosSun, 0.0f));
    Vec3 c = sky + (cloud - sky) * (density * smoothstep(0.02f, 0.2f, d.y()));
    const float angle = std::acos(std::clamp(cosSun, -1.0f, 1.0f));
    c += Vec3(40.0f, 38.0f, 34.0f) * smoothstep(0.028f, 0.022f, angle);  // the disc
    c += Vec3(1.6f, 1.4f, 1.1f) * std::exp(-angle / 0.06f) + Vec3(0.25f, 0.22f, 0.15f) * std::exp(-angle / 0.5f);
    return c + (hills - c) * hill;
  }
};

// The edge of a wood behind the stage, where a giant-bubble performer is placed so that the audience (and the
// default camera) sees the film against dark foliage rather than sunlit ground or bright sky, as giant bubbles are
// usually photographed: a film shows its interference colour by what it reflects over what is behind it. A straight
// edge `distance` from the stage, square to the default camera's view, of broadleaf trees whose rounded crowns stand
// 14-21 m high, tapering away at the ends of its frontage. Seen from the stage (the environment is at infinity) it
// rises to about 30 degrees straight ahead and sinks towards the horizon to the sides.
struct ForestEdge {
  Vec3 facing;                // horizontal, unit: from the stage towards the wood
  float distance = 30.0f;     // m, from the stage to the edge
  float halfLength = 160.0f;  // m, half the frontage; the crowns taper over the last `taper`
  float taper = 50.0f;
  float crownSpacing = 7.0f;  // m between trees along the edge
  // Heights (m) of the shortest tree's crown, the tallest's with its leaves, and the leaves' raggedness.
  static constexpr float kShortest = 14.0f, kTallest = 21.35f, kLeaves = 0.35f;

  explicit ForestEdge(const Vec3& towards) : facing(Vec3(towards.x(), 0.0f, towards.z()).normalized()) {}

  // Height of the tree line (m) at `s` metres along the edge: the highest of the rounded crowns around s, one
  // per `crownSpacing` with its own jittered centre, radius and height, and a leafy raggedness.
  [[nodiscard]] float crownTop(float s) const {
    const auto cell = static_cast<int32_t>(std::floor(s / crownSpacing));
    float top = 0.0f;
    for (int32_t k = cell - 1; k <= cell + 1; ++k) {
      const float centre = crownSpacing * (static_cast<float>(k) + 0.2f + 0.6f * noise::latticeValue(k, 0, 0, 11u));
      const float radius = crownSpacing * (0.55f + 0.3f * noise::latticeValue(k, 1, 0, 11u));
      const float height = kShortest + (kTallest - kShortest - kLeaves) * noise::latticeValue(k, 2, 0, 11u);
      const float u = (s - centre) / radius;
      if (std::abs(u) < 1.0f) top = std::max(top, height - radius + radius * std::sqrt(1.0f - u * u));
    }
    top += kLeaves * noise::fractal3(Vec3(s / 0.8f, 0.0f, 0.0f), 2, 12u);
    return top * smoothstep(halfLength, halfLength - taper, std::abs(s));
  }

  // How much of direction d the wood covers (0-1: the tree line blended over 2.5 texels of `texel` radians, the
  // angular size of an environment texel) and the relative brightness of its foliage there (sunlit clumps, gaps in
  // shade, the understory darker towards the ground).
  struct Look {
    float cover = 0.0f;
    float brightness = 0.0f;
  };
  [[nodiscard]] Look look(const Vec3& d, float texel) const {
    const float ahead = d.dot(facing);
    if (ahead <= 1e-3f || d.y() < 0.0f) return {};
    const float range = distance / ahead;  // along d to the edge's plane
    const float height = range * d.y();
    const float along = range * d.dot(Vec3::UnitY().cross(facing));
    const float blur = 1.25f * range * texel;
    if (std::abs(along) > halfLength || height > kTallest + blur) return {};  // the sky above the tallest crown
    // The edge is blended over 2.5 texels across the outline (the height above it divided by the slope's secant):
    // a blend in height alone would leave the steep sides of the crowns hard, and a blend over a single texel is
    // magnified by the bilinear lookup into stair steps a texel wide.
    const float top = crownTop(along), step = 0.05f;
    const float slope = (crownTop(along + step) - crownTop(along - step)) / (2.0f * step);
    const float across = (height - top) / std::sqrt(1.0f + slope * slope);
    Look l;
    l.cover = smoothstep(blur, -blur, across);
    const float clumps = noise::fractal3(Vec3(along / 2.5f, height / 2.5f, 7.0f), 3, 13u);
    l.brightness = (0.75f + 0.45f * clumps) * (0.35f + 0.65f * smoothstep(0.0f, 8.0f, height));
    return l;
  }
};

// A broadleaf canopy reflects about 4% of visible light, a little more in the green: green leaves reflect 5-10%
// of it, and the crowns' own shadows and the gaps between them halve that. (Their shortwave albedo of 0.15-0.20,
// Oke, "Boundary Layer Climates", 1987, is mostly near-infrared, which the eye does not see.)
Vec3 canopyAlbedo() { return {0.032f, 0.052f, 0.026f}; }

// Radiance of a diffuse surface of `albedo` facing `normal`, lit as props.frag lights the props: the sky's and the
// ground's mean radiance blended by the normal, and the key light.
Vec3 litAsAProp(const Vec3& albedo, const Vec3& normal, const Vec3& skyMean, const Vec3& groundMean,
                const EnvironmentImage& env) {
  const float up = 0.5f + 0.5f * normal.y();
  const Vec3 ambient = groundMean + (skyMean - groundMean) * up;
  return albedo.cwiseProduct(ambient + Vec3::Constant(env.keyStrength * std::max(normal.dot(env.keyLight), 0.0f)));
}

// Paints `forest` over the upper half of `env`, its foliage lit by the open sky's mean radiance, the ground's, and
// the sun on its face.
void paintForest(EnvironmentImage& env, const ForestEdge& forest, const Vec3& groundMean) {
  const Vec3 skyMean = hemisphereMeans(env)[0];
  const Vec3 foliage = litAsAProp(canopyAlbedo(), -forest.facing, skyMean, groundMean, env);
  const float texel = 2.0f * kPi / static_cast<float>(env.width);
#pragma omp parallel for
  for (int row = 0; row < env.height / 2; ++row) {
    for (int col = 0; col < env.width; ++col) {
      const ForestEdge::Look l = forest.look(texelDirection(env, row, col), texel);
      if (l.cover <= 0.0f) continue;
      float* out = &env.rgb[3 * (static_cast<size_t>(row) * env.width + col)];
      const Vec3 c = l.brightness * foliage;
      for (int k = 0; k < 3; ++k) out[k] += l.cover * (c[k] - out[k]);
    }
  }
}

}  // namespace

Vec3 horizonRadiance(const EnvironmentImage& env) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (int row = env.height / 2; row < env.height; ++row) {
    const double below = std::numbers::pi * (row + 0.5) / env.height - 0.5 * std::numbers::pi;
    if (below > 3.0 * std::numbers::pi / 180.0) break;
    for (int col = 0; col < env.width; ++col, ++count) {
      const float* c = &env.rgb[3 * (static_cast<size_t>(row) * env.width + col)];
      sum += Eigen::Vector3d(c[0], c[1], c[2]);
    }
  }
  return count > 0 ? Vec3((sum / count).cast<float>()) : Vec3(Vec3::Zero());
}

Vec3 groundAlbedo() { return {0.30f, 0.30f, 0.29f}; }

EnvironmentImage skyEnvironment(int width) {
  const OutdoorSky sky;
  EnvironmentImage env = tabulateEnvironment(width, sky);
  env.keyLight = sky.sun;
  env.keyStrength = 1.2f;  // direct sun on a prop: brighter than the sky's mean, as outdoors
  // Clear air: meteorological visibility V = 20 km is an extinction length of V / 3.912 = 5 km (Koschmieder), so
  // the ground within the floor's 80 m keeps its contrast. A fog length of metres would lighten the ground behind
  // a film towards the horizon's haze, which real air does not do at that range.
  env.hazeDistance = 5000.0f;
  // Below the horizon: the ground as the floor prop is lit (props.frag: albedo times the sky's mean radiance and
  // the sun), so the floor meets it without a seam and a film reflects the ground it stands over. At 5 km of
  // extinction the haze over the ground is confined to a sliver under the horizon, finer than a texel.
  const auto litGround = [&] {
    const Vec3 skyMean = hemisphereMeans(env)[0];
    return litAsAProp(groundAlbedo(), Vec3::UnitY(), skyMean, skyMean, env);
  };
  // The wood behind the stage, straight ahead of the default three-quarter camera; it hides some of the sky, so the
  // ground is lit by the sky's mean with the wood in it.
  const OrbitCamera defaultCamera;
  paintForest(env, ForestEdge(defaultCamera.target - defaultCamera.position()), litGround());
  const Vec3 lit = litGround();
  for (int row = env.height / 2; row < env.height; ++row)
    for (int col = 0; col < env.width; ++col) {
      float* out = &env.rgb[3 * (static_cast<size_t>(row) * env.width + col)];
      out[0] = lit.x();
      out[1] = lit.y();
      out[2] = lit.z();
    }
  return env;
}

EnvironmentImage studioEnvironment(int width) {
  // Softboxes: direction (unit), angular half-size (radians), radiance.
  struct Light {
    Vec3 direction;
    float halfSize;
    Vec3 radiance;
  };
  const Light lights[] = {{Vec3(-0.6f, 0.5f, 0.62f).normalized(), 0.42f, Vec3(7.0f, 6.8f, 6.4f)},
                          {Vec3(0.7f, 0.3f, 0.65f).normalized(), 0.34f, Vec3(5.0f, 5.3f, 6.0f)},
                          {Vec3(0.0f, 0.95f, 0.3f).normalized(), 0.16f, Vec3(10.0f, 10.0f, 10.0f)}};
  EnvironmentImage env = tabulateEnvironment(width, [&](const Vec3& d) {
    // A dark backdrop ahead (-z), as photographers shoot bubbles, lighter walls behind the camera, a dim floor.
    const float behindCamera = std::clamp(0.5f + 0.5f * d.z(), 0.0f, 1.0f);
    const Vec3 wall = Vec3(0.05f, 0.06f, 0.08f) + behindCamera * Vec3(0.35f, 0.37f, 0.40f);
    Vec3 c = d.y() > 0 ? Vec3(wall * (0.8f + 0.4f * d.y())) : Vec3(Vec3(0.10f, 0.09f, 0.085f) * (1.0f + d.y()));
    for (const Light& l : lights) {
      const float angle = std::acos(std::clamp(d.dot(l.direction), -1.0f, 1.0f));
      c += l.radiance * std::clamp((l.halfSize - angle) / (0.15f * l.halfSize), 0.0f, 1.0f);  // soft edge
    }
    return c;
  });
  env.keyLight = lights[0].direction;
  return env;
}

}  // namespace gb
