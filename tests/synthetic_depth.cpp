#include "tests/synthetic_depth.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace gb::test {

namespace {

using namespace kinect;

constexpr double kPi = std::numbers::pi;

// The camera's axes in scene space, pitched down by `pitch` degrees.
struct CameraFrame {
  Vec3d origin, ex, ey, ez;
  CameraFrame(double pitch, double height) {
    const double a = pitch * kPi / 180.0;
    origin = Vec3d(0.0, height, 0.0);
    ex = Vec3d::UnitX();
    ey = Vec3d(0.0, std::cos(a), std::sin(a));
    ez = Vec3d(0.0, -std::sin(a), std::cos(a));
  }
  [[nodiscard]] Vec3d toCamera(const Vec3d& p) const {
    const Vec3d d = p - origin;
    return {d.dot(ex), d.dot(ey), d.dot(ez)};
  }
  // Scene-space direction of pixel (u, v), scaled so that the hit's parameter is its camera depth.
  [[nodiscard]] Vec3d ray(int u, int v) const { return ex * ((u - kCx) / kFx) - ey * ((v - kCy) / kFy) + ez; }
};

struct Capsule {
  Vec3d a, b;
  double r;
};

// Nearest hit of a ray (origin o, direction d) with a capsule, Inigo Quilez's closed form; -1 for none.
double hitCapsule(const Vec3d& o, const Vec3d& d, const Capsule& c) {
  const Vec3d ba = c.b - c.a, oa = o - c.a;
  const double baba = ba.dot(ba), bard = ba.dot(d), baoa = ba.dot(oa), rdoa = d.dot(oa), oaoa = oa.dot(oa);
  const double dd = d.dot(d);
  const double a = baba * dd - bard * bard, b = baba * rdoa - baoa * bard,
               k = baba * oaoa - baoa * baoa - c.r * c.r * baba;
  if (a > 1e-12) {
    const double h = b * b - a * k;
    if (h >= 0.0) {
      const double t = (-b - std::sqrt(h)) / a;
      const double y = baoa + t * bard;
      if (y > 0.0 && y < baba) return t;
    }
  }
  // The caps: spheres at either end.
  double best = -1.0;
  for (const Vec3d& centre : {c.a, c.b}) {
    const Vec3d oc = o - centre;
    const double bb = oc.dot(d), cc = oc.dot(oc) - c.r * c.r, h = bb * bb - dd * cc;
    if (h < 0.0) continue;
    const double t = (-bb - std::sqrt(h)) / dd;
    if (t > 0.0 && (best < 0.0 || t < best)) best = t;
  }
  return best;
}

double hitBox(const Vec3d& o, const Vec3d& d, const Vec3d& lo, const Vec3d& hi) {
  double near = 0.0, far = 1e9;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (o[k] < lo[k] || o[k] > hi[k]) return -1.0;
      continue;
    }
    double t0 = (lo[k] - o[k]) / d[k], t1 = (hi[k] - o[k]) / d[k];
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0);
    far = std::min(far, t1);
  }
  return near <= far && near > 0.0 ? near : -1.0;
}

struct SceneCanvas {
  const CameraFrame& camera;
  std::vector<double> depth = std::vector<double>(kPixels, 0.0);

  // Every pixel whose ray may meet the scene-space box [lo, hi]: hit(o, d) gives the ray parameter or -1.
  template <typename Hit>
  void raster(const Vec3d& lo, const Vec3d& hi, Hit hit) {
    double u0 = kWidth, u1 = 0, v0 = kHeight, v1 = 0;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3d p((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(), (corner & 4) ? hi.z() : lo.z());
      const Vec3d c = camera.toCamera(p);
      if (c.z() < 0.05) return;  // behind the camera: not in these scenes
      const Eigen::Vector2d px = cameraToPixel(c);
      u0 = std::min(u0, px.x()), u1 = std::max(u1, px.x()), v0 = std::min(v0, px.y()), v1 = std::max(v1, px.y());
    }
    for (int v = std::max(0, static_cast<int>(v0) - 1); v <= std::min(kHeight - 1, static_cast<int>(v1) + 1); ++v)
      for (int u = std::max(0, static_cast<int>(u0) - 1); u <= std::min(kWidth - 1, static_cast<int>(u1) + 1); ++u)
        keep(u, v, hit(camera.origin, camera.ray(u, v)));
  }
  void keep(int u, int v, double t) {
    double& z = depth[static_cast<size_t>(v) * kWidth + u];
    if (t > 0.0 && (z == 0.0 || t < z)) z = t;
  }
  void capsule(const Capsule& c) {
    const Vec3d r = Vec3d::Constant(c.r);
    raster(c.a.cwiseMin(c.b) - r, c.a.cwiseMax(c.b) + r,
           [&](const Vec3d& o, const Vec3d& d) { return hitCapsule(o, d, c); });
  }
  void sphere(const Vec3d& centre, double r) { capsule({centre, centre, r}); }
  void box(const Vec3d& lo, const Vec3d& hi) {
    raster(lo, hi, [&](const Vec3d& o, const Vec3d& d) { return hitBox(o, d, lo, hi); });
  }
  // An unbounded plane n.p = offset, seen by every pixel.
  void plane(const Vec3d& n, double offset) {
    for (int v = 0; v < kHeight; ++v)
      for (int u = 0; u < kWidth; ++u) {
        const Vec3d d = camera.ray(u, v);
        const double dn = d.dot(n);
        if (std::abs(dn) > 1e-9) keep(u, v, (offset - camera.origin.dot(n)) / dn);
      }
  }
};

// The elbow of a two-link arm from shoulder s to hand h (lengths l1, l2), bent towards `hint`; h is pulled in
// to full stretch when out of reach.
Vec3d elbowOf(const Vec3d& s, Vec3d& h, double l1, double l2, const Vec3d& hint) {
  Vec3d n = h - s;
  double d = n.norm();
  n /= d;
  d = std::clamp(d, 0.05, l1 + l2 - 1e-3);
  h = s + d * n;
  const double a = (l1 * l1 - l2 * l2 + d * d) / (2.0 * d), side = std::sqrt(std::max(0.0, l1 * l1 - a * a));
  Vec3d pole = hint - hint.dot(n) * n;
  if (pole.norm() < 1e-6) pole = Vec3d(0.0, -1.0, 0.0) - n.y() * n;
  return s + a * n + side * pole.normalized();
}

// Kinect v1's IR projector sits 7.5 cm beside its camera: a surface the projector cannot see behind a nearer
// one gives no reading. Pixel u at depth z is shadowed when some q > u in its row has u_q - fx b / z_q below
// u - fx b / z.
void castProjectorShadows(std::vector<double>& z) {
  constexpr double kBaseline = 0.075;
  for (int v = 0; v < kHeight; ++v) {
    double lowest = 1e30;
    for (int u = kWidth - 1; u >= 0; --u) {
      double& d = z[static_cast<size_t>(v) * kWidth + u];
      if (d <= 0.0) continue;
      const double key = u - kFx * kBaseline / d;
      if (lowest < key - 0.5) d = 0.0;
      lowest = std::min(lowest, key);
    }
  }
}

}  // namespace

// Kinect v1 depth noise: no reading at some depth edges and at random pixels, Gaussian error growing as z^2
// (Khoshelham and Elberink 2012: sigma = 1.425 mm z^2 / m^2); the 11-bit disparity quantisation follows when
// the depth is written as raw values.
void addKinectNoise(std::vector<double>& z, unsigned seed) {
  castProjectorShadows(z);
  std::mt19937 random(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> noisy = z;
  for (int v = 1; v + 1 < kHeight; ++v)
    for (int u = 1; u + 1 < kWidth; ++u) {
      const size_t i = static_cast<size_t>(v) * kWidth + u;
      if (z[i] <= 0.0) continue;
      double jump = 0.0;
      for (const size_t j : {i - 1, i + 1, i - kWidth, i + kWidth}) jump = std::max(jump, std::abs(z[j] - z[i]));
      const bool edge = jump > 0.08 * z[i];
      if (uniform(random) < (edge ? 0.4 : 0.005)) {
        noisy[i] = 0.0;
        continue;
      }
      noisy[i] = z[i] + 1.425e-3 * z[i] * z[i] * gauss(random);
    }
  z = std::move(noisy);
}

double cameraHeightFor(double pitch, double distance) {
  constexpr double kTop = 2.2, kHalfFieldDeg = 21.5;  // Kinect v1: 43 degrees vertical field of view
  return kTop - distance * std::tan((kHalfFieldDeg - pitch) * kPi / 180.0) + 0.05;
}

SyntheticScene renderScene(const BodyPose& pose, const SceneOptions& options, double time) {
  const CameraFrame camera(options.cameraPitch, options.cameraHeight);
  SceneCanvas canvas{camera};
  const double s = pose.height / 1.75;
  const Vec3d f = pose.feet;
  auto at = [&](double x, double y, double z) { return Vec3d(f + s * Vec3d(x, y, z)); };

  // Legs, torso (two capsules side by side: wider than deep), neck and head.
  for (const double side : {1.0, -1.0}) {
    if (!options.performer) continue;
    canvas.capsule({at(0.09 * side, 0.92, 0.0), at(0.10 * side, 0.50, -0.02), 0.07 * s});
    canvas.capsule({at(0.10 * side, 0.50, -0.02), at(0.10 * side, 0.09, 0.0), 0.05 * s});
    canvas.capsule({at(0.10 * side, 0.05, 0.0), at(0.11 * side, 0.04, -0.15), 0.04 * s});
    canvas.capsule({at(0.075 * side, 0.95, 0.0), at(0.075 * side, 1.36, 0.0), 0.11 * s});
  }
  if (options.performer) {
    canvas.capsule({at(0.0, 1.40, 0.0), at(0.0, 1.52, 0.0), 0.05 * s});
    canvas.sphere(at(0.0, 1.62, 0.0), 0.10 * s);
  }

  // Arms: shoulder, elbow, hand centre; the forearm runs on to the hand.
  const Vec3d shoulders = at(0.0, 1.43, 0.0);
  Vec3d hands[2] = {shoulders + pose.leftHand, shoulders + pose.rightHand};
  const Vec3d hints[2] = {pose.leftElbowHint, pose.rightElbowHint};
  for (int side = 0; side < 2 && options.performer; ++side) {
    const Vec3d shoulder = at(side == 0 ? 0.19 : -0.19, 1.41, 0.0);
    const Vec3d elbow = elbowOf(shoulder, hands[side], 0.29 * s, 0.33 * s, hints[side]);
    canvas.capsule({shoulder, elbow, 0.045 * s});
    canvas.capsule({elbow, hands[side], 0.038 * s});
    canvas.sphere(hands[side], 0.05 * s);
  }

  if (options.furniture) {
    // A chair to the performer's right, a table to the left, both further back.
    const Vec3d chair(-1.15, 0.0, f.z() + 0.3);
    canvas.box(chair + Vec3d(-0.22, 0.42, -0.22), chair + Vec3d(0.22, 0.47, 0.22));  // seat
    canvas.box(chair + Vec3d(-0.22, 0.47, 0.18), chair + Vec3d(0.22, 0.95, 0.22));   // back
    for (const double x : {-0.2, 0.18})
      for (const double z : {-0.2, 0.18}) canvas.box(chair + Vec3d(x, 0.0, z), chair + Vec3d(x + 0.03, 0.42, z + 0.03));
    const Vec3d table(1.3, 0.0, f.z() + 0.7);
    canvas.box(table + Vec3d(-0.4, 0.0, -0.3), table + Vec3d(0.4, 0.75, 0.3));
  }
  if (options.wallDistance > 0.0) canvas.plane(Vec3d::UnitZ(), options.wallDistance);
  canvas.plane(Vec3d::UnitY(), 0.0);  // the floor

  std::vector<double>& z = canvas.depth;
  if (options.noise) addKinectNoise(z, options.seed * 7919u + static_cast<unsigned>(std::lround(time * 1000.0)));
  SyntheticScene scene;
  scene.frame.time = time;
  for (int i = 0; i < kPixels; ++i) scene.frame.raw[i] = z[i] > 0.0 ? metresToRaw(z[i]) : kNoReading;
  scene.leftHand = camera.toCamera(hands[0]);
  scene.rightHand = camera.toCamera(hands[1]);
  scene.up = Vec3d(0.0, camera.ey.y(), camera.ez.y());  // scene +y in camera axes
  scene.floorDistance = options.cameraHeight;
  return scene;
}

const std::vector<std::string>& roomLayouts() {
  static const std::vector<std::string> names = {"living-room", "office", "close-wall"};
  return names;
}

std::vector<double> renderRoom(const std::string& layout, double d, double cameraPitch, double cameraHeight) {
  const CameraFrame camera(cameraPitch, cameraHeight);
  SceneCanvas canvas{camera};
  const auto chair = [&](double x, double z) {
    const Vec3d c(x, 0.0, z);
    canvas.box(c + Vec3d(-0.22, 0.42, -0.22), c + Vec3d(0.22, 0.47, 0.22));  // seat
    canvas.box(c + Vec3d(-0.22, 0.47, 0.18), c + Vec3d(0.22, 0.95, 0.22));   // back
    for (const double dx : {-0.2, 0.18})
      for (const double dz : {-0.2, 0.18}) canvas.box(c + Vec3d(dx, 0.0, dz), c + Vec3d(dx + 0.03, 0.42, dz + 0.03));
  };
  double wall = 0.0;
  if (layout == "living-room") {
    wall = std::max(d + 1.4, 3.4);
    canvas.box(Vec3d(-1.0, 0.0, wall - 0.8), Vec3d(1.0, 0.45, wall));   // sofa seat
    canvas.box(Vec3d(-1.0, 0.45, wall - 0.25), Vec3d(1.0, 0.9, wall));  // and back
    chair(-1.2, d + 0.2);
    canvas.box(Vec3d(0.9, 0.0, d + 0.2), Vec3d(1.7, 0.75, d + 0.8));  // table
    canvas.box(Vec3d(-2.4, 0.0, 0.5), Vec3d(-2.2, 3.0, wall));        // side wall
  } else if (layout == "office") {
    wall = std::max(d + 2.0, 4.5);
    canvas.box(Vec3d(-1.6, 0.0, wall - 0.4), Vec3d(-0.4, 1.9, wall));  // shelves
    canvas.box(Vec3d(0.3, 0.0, wall - 0.4), Vec3d(1.3, 1.1, wall));    // a cupboard
    canvas.box(Vec3d(0.7, 0.72, d - 0.9), Vec3d(1.6, 0.76, d - 0.2));  // desk top
    canvas.box(Vec3d(1.5, 0.0, d - 0.9), Vec3d(1.6, 0.72, d - 0.2));   // and its side
    chair(-0.9, d + 1.0);
    chair(0.9, d + 0.9);
  } else if (layout == "close-wall") {
    wall = d + 0.5;
    canvas.box(Vec3d(-1.3, 0.0, wall - 0.1), Vec3d(-1.2, 2.1, wall));  // door frame
    canvas.box(Vec3d(-1.3, 2.0, wall - 0.1), Vec3d(-0.4, 2.1, wall));
    canvas.capsule({Vec3d(1.3, 0.0, wall - 0.3), Vec3d(1.3, 1.8, wall - 0.3), 0.03});  // coat rack
    canvas.sphere(Vec3d(1.3, 1.6, wall - 0.3), 0.25);                                  // a coat on it
  } else {
    throw std::invalid_argument("unknown room layout " + layout);
  }
  canvas.plane(Vec3d::UnitZ(), wall);
  canvas.plane(Vec3d::UnitY(), 0.0);  // the floor
  return canvas.depth;
}

BodyPose namedPose(const std::string& name) {
  BodyPose p;
  if (name == "forward") return p;
  if (name == "arms-out") {
    p.leftHand = Vec3d(0.78, 0.0, 0.0);
    p.rightHand = Vec3d(-0.78, 0.0, 0.0);
    p.leftElbowHint = Vec3d(0.0, -1.0, 0.2);
    p.rightElbowHint = Vec3d(0.0, -1.0, 0.2);
  } else if (name == "crossed") {
    // In front of the chest, each hand on the other side, the left one nearer the camera.
    p.leftHand = Vec3d(-0.17, -0.15, -0.34);
    p.rightHand = Vec3d(0.17, -0.08, -0.24);
    p.leftElbowHint = Vec3d(1.0, -0.6, -0.2);
    p.rightElbowHint = Vec3d(-1.0, -0.6, -0.2);
  } else if (name == "together") {
    // Side by side in front, 2 cm between them.
    p.leftHand = Vec3d(0.07, -0.1, -0.45);
    p.rightHand = Vec3d(-0.07, -0.1, -0.45);
  } else if (name == "overhead") {
    p.leftHand = Vec3d(0.16, 0.55, -0.05);
    p.rightHand = Vec3d(-0.16, 0.55, -0.05);
    p.leftElbowHint = Vec3d(1.0, 0.0, 0.2);
    p.rightElbowHint = Vec3d(-1.0, 0.0, 0.2);
  } else if (name == "one-arm-down") {
    p.leftHand = Vec3d(0.2, -0.05, -0.45);
    p.rightHand = Vec3d(-0.23, -0.58, 0.02);
    p.rightElbowHint = Vec3d(0.0, 0.0, 1.0);
  } else {
    throw std::invalid_argument("unknown pose '" + name + "'");
  }
  return p;
}

BodyPose blendPoses(const BodyPose& a, const BodyPose& b, double s) {
  BodyPose p = a;
  p.feet = a.feet + s * (b.feet - a.feet);
  p.leftHand = a.leftHand + s * (b.leftHand - a.leftHand);
  p.rightHand = a.rightHand + s * (b.rightHand - a.rightHand);
  p.leftElbowHint = a.leftElbowHint + s * (b.leftElbowHint - a.leftElbowHint);
  p.rightElbowHint = a.rightElbowHint + s * (b.rightElbowHint - a.rightElbowHint);
  return p;
}

const std::vector<std::string>& sequenceNames() {
  static const std::vector<std::string> names = {"forward",  "arms-out", "crossing",
                                                 "together", "overhead", "one-arm-down"};
  return names;
}

BodyPose sequencePose(const std::string& sequence, double t) {
  const double w = 2.0 * kPi;
  const double cycle = 0.5 - 0.5 * std::cos(w * t / 4.0);  // 0 -> 1 -> 0 over 4 s
  BodyPose p = namedPose("forward");
  if (sequence == "forward") {
    // Circles in front, the hands opposite each other, 12 cm across, one every 2 s.
    const Vec3d circle(0.12 * std::cos(w * t / 2.0), 0.12 * std::sin(w * t / 2.0), 0.08 * std::sin(w * t / 4.0));
    p.leftHand += circle;
    p.rightHand += Vec3d(-circle.x(), circle.y(), circle.z());
    return p;
  }
  if (sequence == "crossing") {
    BodyPose wide = p;
    wide.leftHand.x() += 0.15;
    wide.rightHand.x() -= 0.15;
    // Crossed at the middle of each 2 s half-cycle, held there briefly.
    const double s = std::clamp(1.4 * (0.5 - 0.5 * std::cos(w * t / 2.0)), 0.0, 1.0);
    return blendPoses(wide, namedPose("crossed"), s);
  }
  const BodyPose target = namedPose(sequence == "one-arm-down" ? "one-arm-down" : sequence);
  if (sequence == "one-arm-down") {
    p = target;
    p.leftHand += Vec3d(0.08 * std::sin(w * t / 2.0), 0.06 * std::cos(w * t / 2.0), 0.0);
    return p;
  }
  return blendPoses(p, target, std::clamp(1.3 * cycle, 0.0, 1.0));
}

bool presented(const std::string& sequence, Hand hand) { return !(sequence == "one-arm-down" && hand == Hand::Right); }

kinect::DepthFrame renderPerformer(const SyntheticPerformer& p, double time, uint32_t timestamp) {
  constexpr double kCameraHeight = 1.3;
  SceneOptions scene;
  scene.cameraPitch = 0.0;
  scene.cameraHeight = kCameraHeight;
  scene.furniture = false;
  scene.wallDistance = p.wallDepth;
  scene.noise = false;
  scene.performer = p.present;
  BodyPose pose;
  pose.feet = Vec3d(0.0, 0.0, p.bodyDepth);
  // A level camera: scene axes are camera axes, lifted by the camera's height.
  const Vec3d shoulders = Vec3d(0.0, 1.43 - kCameraHeight, p.bodyDepth);
  const BodyPose hanging = namedPose("one-arm-down");
  pose.leftHand = p.leftHand ? Vec3d(*p.leftHand - shoulders)
                             : Vec3d(-hanging.rightHand.x(), hanging.rightHand.y(), hanging.rightHand.z());
  pose.rightHand = p.rightHand ? Vec3d(*p.rightHand - shoulders) : hanging.rightHand;
  if (!p.leftHand) pose.leftElbowHint = Vec3d(0.0, 0.0, 1.0);
  if (!p.rightHand) pose.rightElbowHint = hanging.rightElbowHint;
  kinect::DepthFrame frame = renderScene(pose, scene, time).frame;
  frame.timestamp = timestamp;
  return frame;
}

SyntheticPerformer sessionPose(double t) {
  const double w = 2.0 * kPi;
  SyntheticPerformer p;
  p.leftHand = Vec3d(0.25 + 0.06 * std::sin(w * 0.5 * t), 0.05 + 0.10 * std::sin(w * 0.7 * t),
                     2.0 - 0.1 * std::sin(w * 0.25 * t));
  p.rightHand = Vec3d(-0.25 - 0.06 * std::sin(w * 0.5 * t), 0.0 + 0.10 * std::cos(w * 0.7 * t),
                      1.95 - 0.1 * std::sin(w * 0.25 * t));
  return p;
}

}  // namespace gb::test
