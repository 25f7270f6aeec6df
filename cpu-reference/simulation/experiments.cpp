#include "simulation/experiments.h"

#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "stages/cpu_stepper.h"

namespace gb {
namespace {

constexpr double kPi = std::numbers::pi;

Params physical(Params p) {
  p.tensionModel = 1;
  p.gravityY = 0.0f;  // the experiments are about tension alone
  p.gravityX = p.gravityZ = 0.0f;
  return p;
}

// A film on a ring of the default radius around (0, 1.5, 0), and the wands that hold it there.
struct RingFilm {
  WandTool tool;
  WandState wands;
  RingFilm() {
    tool.kind = ToolKind::Ring;
    wands.rightPosition = Vec3(0, 1.5f, 0);
  }
};

void say(const std::function<void(const std::string&)>& progress, const std::string& line) {
  if (progress) progress(line);
}

// One frame, unless the caller asked the experiment to stop.
void advance(Simulation& sim, const WandState& wands, const StopRequest& stop) {
  if (stop && stop()) throw ExperimentStopped("stopped at t = " + std::to_string(sim.time()) + " s");
  sim.advanceFrame(wands);
}

void run(Simulation& sim, const WandState& wands, int frames, const StopRequest& stop) {
  for (int f = 0; f < frames; ++f) advance(sim, wands, stop);
}

Measurement flatDisc(const Params& p, const StopRequest& stop) {
  const RingFilm ring;
  Simulation sim(p, ring.tool, ring.wands);
  State& s = sim.film().state;
  const float a = ring.tool.ringRadius;
  for (size_t i = 0; i < s.size(); ++i) {  // a 3 cm bump out of the plane
    const float r2 = (s.position.get(i) - ring.wands.rightPosition).squaredNorm() / (a * a);
    if (!sim.film().topology.boundary[i]) s.position.z[i] += 0.03f * std::max(0.0f, 1.0f - r2);
  }
  sim.stepper().load(sim.params(), sim.film());
  run(sim, ring.wands, 50, stop);  // 1 s
  double worst = 0;
  for (size_t i = 0; i < s.size(); ++i)
    worst = std::max(worst, static_cast<double>(std::abs(sim.film().state.position.z[i])));
  return {"flat-disc", "largest distance from the ring's plane after 1 s (bump 3 cm)",
          "m",         worst,
          0.0,         "a film on a flat ring is flat"};
}

Measurement minimalSurface(const Params& p, const StopRequest& stop) {
  const RingFilm ring;
  Simulation sim(p, ring.tool, ring.wands);
  Film& film = sim.film();
  const float a = ring.tool.ringRadius, h = 0.3f * a;
  // The film starts as z = h (r/a)^4 cos 2 theta: it spans the bent wire smoothly but is not minimal (mean |H| a
  // about 0.6; the minimal surface is z = h (r/a)^2 cos 2 theta). A flat film with only the wire bent put a kink into
  // the triangles along the wire, which folded them instead of relaxing (docs/validation.md).
  for (size_t i = 0; i < film.state.size(); ++i) {
    const Vec3 d = film.state.position.get(i) - ring.wands.rightPosition;
    const float r2 = d.squaredNorm() / (a * a);
    film.state.position.z[i] += h * r2 * r2 * std::cos(2.0f * std::atan2(d.y(), d.x()));
    if (film.topology.boundary[i]) film.state.wireParam[i] = -1.0f;  // pinned on the bent wire
  }
  CpuStepper::refreshGeometry(p, film);
  sim.stepper().load(sim.params(), film);
  run(sim, ring.wands, 100, stop);  // 2 s
  CpuStepper::refreshGeometry(p, sim.film());
  return {"minimal-surface",
          "mean |H| x ring radius on a saddle wire after 2 s",
          "1",
          meanCurvatureTimes(sim.film(), a),
          0.0,
          "a soap film is a minimal surface: H = 0"};
}

Measurement catenoid(const Params& p, const StopRequest& stop) {
  const float R = 0.3f, d = R;
  const Vec3 c(0, 1.5f, 0);
  Simulation sim(p, generateTube(p, c, R, d, 64), WandState{});
  run(sim, WandState{}, 100, stop);  // 2 s
  Measurement m{"catenoid",
                "neck radius between rings of R = 0.3 m, d = R",
                "m",
                neckRadius(sim.film(), c),
                catenoidNeck(R, d),
                "r(z) = a cosh(z / a) through the rings: R = a cosh(d / 2a)"};
  m.xLabel = "z (m)";
  m.yLabel = "distance from the axis r (m)";
  for (size_t i = 0; i < sim.film().state.size(); ++i) {
    const Vec3 q = sim.film().state.position.get(i) - c;
    m.measuredPoints.emplace_back(q.z(), std::hypot(q.x(), q.y()));
  }
  for (int k = 0; k <= 100; ++k) {
    const double z = -0.5 * d + d * static_cast<double>(k) / 100.0;
    m.analyticCurve.emplace_back(z, m.analytic * std::cosh(z / m.analytic));
  }
  return m;
}

// The neck after `seconds` of relaxing, 0 once it has pinched to a tenth of R.
double neckAfter(const Params& p, float R, float d, double seconds, const StopRequest& stop) {
  const Vec3 c(0, 1.5f, 0);
  Simulation sim(p, generateTube(p, c, R, d, 48), WandState{});
  double neck = R;
  for (long f = 0; f < std::lround(seconds / p.frameTime) && neck > 0.1 * R; ++f) {
    advance(sim, WandState{}, stop);
    neck = neckRadius(sim.film(), c);
  }
  return neck > 0.1 * R ? neck : 0.0;
}

Measurement catenoidCritical(const Params& p, const std::function<void(const std::string&)>& progress,
                             const StopRequest& stop) {
  const float R = 0.3f;
  // Stable catenoids keep a neck above 0.55 R (0.5524 x 1.3255 R = 0.73 R at the fold); past it the film thins
  // to nothing, below 0.4 R within 3 s.
  auto collapses = [&](float d) {
    const bool c = neckAfter(p, R, d, 3.0, stop) < 0.4 * R;
    std::ostringstream line;
    line << "d = " << d / R << " R: " << (c ? "collapses into two discs" : "a stable catenoid");
    say(progress, line.str());
    return c;
  };
  if (!collapses(1.45f * R)) throw std::runtime_error("catenoid-critical: the film at 1.45 R did not collapse");
  float stable = 1.0f * R, collapsing = 1.45f * R;
  for (int it = 0; it < 4; ++it) {
    const float mid = 0.5f * (stable + collapsing);
    (collapses(mid) ? collapsing : stable) = mid;
  }
  return {"catenoid-critical",
          "critical ring separation / R (4 bisection steps in [1, 1.45])",
          "1",
          0.5 * (stable + collapsing) / R,
          1.3255,
          "d / 2a = 1.1997 where a cosh(d / 2a) = R has a double root"};
}

Measurement youngLaplace(const Params& p, const StopRequest& stop) {
  const Vec3 c(0, 1.5f, 0);
  Simulation sim(p, generateSphere(p, c, 0.4f, 3), WandState{});
  run(sim, WandState{}, 50, stop);  // 1 s
  const Film& film = sim.film();
  const Vec3 centre = centroid(film.state);
  double radius = 0, tension = 0;
  for (size_t i = 0; i < film.state.size(); ++i) {
    radius += (film.state.position.get(i) - centre).norm() / static_cast<double>(film.state.size());
    tension += film.state.elasticity[i] / static_cast<double>(film.state.size());  // 2 gamma (N/m)
  }
  std::ostringstream law;
  law << "dP = 4 gamma / R, R = " << radius << " m";
  return {"young-laplace",
          "excess pressure of a settled bubble",
          "Pa",
          sim.lastPressure() - p.pressureCoefficient,
          2.0 * tension / radius,
          law.str()};
}

Measurement waves(Params p, const StopRequest& stop) {
  p.airDrag = 0.0f;  // the drag of still air would slow the wave
  p.springDamping = 0.0f;
  p.frameTime = 0.005f;
  const RingFilm ring;
  Simulation sim(p, ring.tool, ring.wands);
  State& s = sim.film().state;
  const float a = ring.tool.ringRadius;
  size_t middle = 0;
  for (size_t i = 0; i < s.size(); ++i) {  // the fundamental mode J0(2.405 r / a), 2 mm high
    const float r = (s.position.get(i) - ring.wands.rightPosition).norm();
    if (r < (s.position.get(middle) - ring.wands.rightPosition).norm()) middle = i;
    if (!sim.film().topology.boundary[i])
      s.position.z[i] += 0.002f * std::cyl_bessel_j(0.0f, 2.405f * std::min(r / a, 1.0f));
  }
  sim.stepper().load(p, sim.film());
  std::vector<double> crossings;  // times the middle passes z = 0 going down
  std::vector<std::pair<double, double>> trace = {{0.0, sim.film().state.position.z[middle]}};
  float previous = sim.film().state.position.z[middle];
  for (int f = 1; f <= 400 && crossings.size() < 4; ++f) {
    advance(sim, ring.wands, stop);
    const float z = sim.film().state.position.z[middle];
    trace.emplace_back(static_cast<double>(p.frameTime) * f, z);
    if (previous > 0 && z <= 0)
      crossings.push_back(p.frameTime * (static_cast<double>(f - 1) + previous / (previous - z)));
    previous = z;
  }
  if (crossings.size() < 3) throw std::runtime_error("waves: the film did not oscillate");
  const double period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  Measurement m{"waves",
                "transverse wave speed on a 3.5 um film (fundamental mode of a 0.35 m ring)",
                "m/s",
                (2.0 * kPi / period) * a / 2.405,
                std::sqrt(2.0 * p.surfaceTension / (p.liquidDensity * initialThickness(p))),
                "c = sqrt(2 gamma / (rho h))"};
  m.xLabel = "time (s)";
  m.yLabel = "displacement of the middle (m)";
  m.measuredPoints = std::move(trace);
  const double omega = 2.405 * m.analytic / a, amplitude = m.measuredPoints.front().second;
  for (int k = 0; k <= 200; ++k) {
    const double t = m.measuredPoints.back().first * k / 200.0;
    m.analyticCurve.emplace_back(t, amplitude * std::cos(omega * t));
  }
  return m;
}

Measurement bubbleBurst(Params p, const StopRequest& stop) {
  p.areaWeight = 0.01f;  // initial thickness 1 um
  // A burst is the fastest event there is (the rim runs at 6.3 m/s, three edges a frame): it asks for four
  // implicit steps per frame. At one step the torn film retracts further within each step and the bubble
  // vanishes in 0.30 s instead of 0.34 s (the explicit reference: 0.36 s).
  p.implicitSubsteps = 4;
  Simulation sim(p, generateSphere(p, Vec3(0, 2.0f, 0), 1.0f, 4), WandState{});
  sim.startBurst(sim.topParticle());
  const double start = sim.time();
  double gone = -1;
  for (int f = 0; f < 200 && gone < 0; ++f) {
    advance(sim, WandState{}, stop);
    if (sim.lastEvents().finished) gone = sim.time() - start;
  }
  if (gone < 0) throw std::runtime_error("bubble-burst: the bubble did not burst completely in 4 s");
  return {"bubble-burst",
          "time for a 1 um bubble of R = 1 m to vanish after a poke",
          "s",
          gone,
          kPi * 1.0 / std::sqrt(2.0 * p.surfaceTension / (p.liquidDensity * 1e-6)),
          "t = pi R / V, V = sqrt(2 gamma / (rho h))"};
}

}  // namespace

std::vector<std::string> experimentNames() {
  return {"flat-disc", "minimal-surface", "catenoid", "catenoid-critical", "young-laplace", "waves", "bubble-burst"};
}

bool experimentSizedByParticles(const std::string& name) {
  return name == "flat-disc" || name == "minimal-surface" || name == "waves";  // the ring films
}

Measurement runExperiment(const std::string& name, Params params,
                          const std::function<void(const std::string&)>& progress, const StopRequest& stop) {
  const Params p = physical(params);
  say(progress, "experiment " + name + " (physical tension model)");
  if (name == "flat-disc") return flatDisc(p, stop);
  if (name == "minimal-surface") return minimalSurface(p, stop);
  if (name == "catenoid") return catenoid(p, stop);
  if (name == "catenoid-critical") return catenoidCritical(p, progress, stop);
  if (name == "young-laplace") return youngLaplace(p, stop);
  if (name == "waves") return waves(p, stop);
  if (name == "bubble-burst") return bubbleBurst(p, stop);
  std::string list;
  for (const std::string& n : experimentNames()) list += (list.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown experiment '" + name + "' (experiments: " + list + ")");
}

double catenoidNeck(double R, double d) {
  auto f = [&](double a) { return a * std::cosh(d / (2 * a)) - R; };
  double lo = 0.5523 * d, hi = R;  // the fold is at a = d / (2 x 1.1997): f < 0 there for d < 1.3255 R
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double neckRadius(const Film& film, const Vec3& center) {
  // On a catenoid r = a cosh(z / a) >= a, within (dz / a)^2 / 2 of a for the row nearest the middle.
  double neck = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < film.state.size(); ++i) {
    const Vec3 d = film.state.position.get(i) - center;
    neck = std::min(neck, std::hypot(static_cast<double>(d.x()), static_cast<double>(d.y())));
  }
  return neck;
}

double meanCurvatureTimes(const Film& film, float length) {
  // |grad A_i| / (2 A_i) is the discrete mean curvature: |areaTensionForce| over the tension and 2 A_i.
  double sum = 0;
  int count = 0;
  for (size_t i = 0; i < film.state.size(); ++i) {
    if (film.topology.boundary[i] || film.state.voronoiArea[i] <= 0 || film.state.elasticity[i] <= 0) continue;
    const double gradient = areaTensionForce(film.topology, film.state, i).norm() / film.state.elasticity[i];
    sum += gradient / (2.0 * film.state.voronoiArea[i]) * length;
    ++count;
  }
  // A film that burst has nothing to measure: that is a failed experiment, not a flat film.
  if (count == 0) throw std::runtime_error("the film has no interior particle left to measure its curvature on");
  return sum / count;
}

}  // namespace gb
