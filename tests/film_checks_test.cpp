// The film checks of the rules between steps (cpu-reference/topology/film_checks.h): a frame on which the checks say
// that no rule acts may leave the state on the stepper's device. On the CPU, a stepper that checks the film as the
// device does plays the default performance exactly as the plain CPU stepper: no rule the checks let pass ever acts.
// On the device (lavapipe in CI), the checks reduced there are the CPU's, and the performance played with the state
// left on the device is the one played with the state read back after every step.
#include "topology/film_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "host/vulkan_stepper.h"
#include "scene/scene_file.h"
#include "simulation/simulation.h"
#include "stages/cpu_stepper.h"
#include "tests/default_performance_on_device.h"
#include "tests/vulkan_test_device.h"
#include "topology/film_growth.h"

namespace gb {
namespace {

// The CPU stepper, checking the film between steps in host memory as a device stepper checks it on its device
// (checkFilm with the device's margin).
class CheckingCpuStepper final : public Stepper, public DeviceResidency {
 public:
  [[nodiscard]] std::string name() const override { return "cpu, checking"; }
  void load(const Params& params, Film& film) override {
    params_ = params;
    film_ = &film;
    cpu_.load(params, film);
  }
  float run(std::span<const StepUniforms> substeps) override {
    const float pressure = cpu_.run(substeps);
    lastBudget_ = cpu_.lastBudget();
    return pressure;
  }
  float runStage(Stage stage, const StepUniforms& uniforms) override { return cpu_.runStage(stage, uniforms); }
  DeviceResidency* device() override { return this; }
  // The film stays in host memory: nothing to bring back or to take, no rule or search run here.
  void store(Film&) override {}
  void storePositions(Film&) override {}
  void storeParticleArrays(Film&, std::initializer_list<const void*>) override {}
  bool storeRegion(Film&, std::span<const uint32_t>, std::span<const uint32_t>) override { return false; }
  bool storeParticleArraysOf(Film&, std::span<const uint32_t>, std::initializer_list<const void*>,
                             std::span<const uint32_t>) override {
    return false;
  }
  bool findCrowdedSprings(CrowdedCandidates&) override { return false; }
  bool updateMergedRegion(const Params&, Film&, std::span<const uint32_t>, std::span<const uint32_t>) override {
    return false;
  }
  void refreshGeometry() override {}
  bool updateRegion(const Params&, Film&, std::span<const uint32_t>, size_t, std::span<const uint32_t>,
                    size_t) override {
    return false;
  }
  bool updateTopology(const Params&, Film&) override { return false; }
  void updateRestLengths(const Film&) override {}
  void updateContacts(const Film&) override {}
  bool findContacts(const Params&, float, float, Film&, const ContactHistory&) override { return false; }
  bool findContactsOnDevice(const Params&, float, float, const ContactHistory&) override { return false; }
  void storeContacts(Film&) override {}
  bool yieldStretchedSprings() override { return false; }
  bool payOutFilmAtWire() override { return false; }
  bool contractSlackSprings(float) override { return false; }
  void storeRestLengths(Film&) override {}
  [[nodiscard]] DeviceReadback readback() const override { return {}; }
  // The checks between steps; the statistics are left to the caller.
  bool probeFilm(const FilmProbe& probe, FilmSums&, FilmChecks& checks) override {
    if (probe.atPresentPositions) return false;
    checks = checkFilm(params_, *film_, probe, kFilmCheckMargin);
    return true;
  }

 private:
  CpuStepper cpu_;
  Params params_;
  Film* film_ = nullptr;
};

// The default performance's wands at frame f (Scene "default").
WandState defaultWandsAt(const Scene& scene, int f) {
  return gestureAt(Gesture::Giant, scene.run.gestureOptions, static_cast<double>(f) * scene.run.params.frameTime);
}

// The default performance, played on two simulations side by side to `frames`: after every frame their figures and
// events are the same to the last bit.
void expectTheSamePerformance(const Scene& scene, Simulation& a, Simulation& b, int frames) {
  for (int f = 1; f <= frames; ++f) {
    const WandState wands = defaultWandsAt(scene, f);
    a.advanceFrame(wands);
    b.advanceFrame(wands);
    const FrameStats x = a.stats(), y = b.stats();
    ASSERT_EQ(x.particles, y.particles) << "frame " << f;
    ASSERT_EQ(x.triangles, y.triangles) << "frame " << f;
    ASSERT_EQ(x.kineticEnergy, y.kineticEnergy) << "frame " << f;
    ASSERT_EQ(x.elasticEnergy, y.elasticEnergy) << "frame " << f;
    ASSERT_EQ(x.volume, y.volume) << "frame " << f;
    ASSERT_EQ(x.liquid, y.liquid) << "frame " << f;
    ASSERT_EQ(a.lastEvents().pinchedOff, b.lastEvents().pinchedOff) << "frame " << f;
    ASSERT_EQ(a.burst().started, b.burst().started) << "frame " << f;
  }
}

WandState defaultStart(const Scene& scene) { return defaultWandsAt(scene, 0); }

// The default performance on the Vulkan backend twice: with the state brought back after every step, and left on
// the device where the checks let a frame pass.
struct ReadBackAndKept {
  ReadBackAndKept(const std::shared_ptr<const VulkanContext>& device, const Scene& scene)
      : everyFrame(scene.run.params, WandTool{}, defaultStart(scene), onThe(device)),
        onDevice(scene.run.params, WandTool{}, defaultStart(scene), onThe(device)) {
    everyFrame.setStateStaysOnDevice(false);
  }
  static std::unique_ptr<Stepper> onThe(const std::shared_ptr<const VulkanContext>& device) {
    return std::make_unique<VulkanStepper>(device, test::everythingOnDevice());
  }
  Simulation everyFrame;
  Simulation onDevice;
};

TEST(FilmChecks, NoRuleActsWhereTheChecksLetTheFramePass) {
  // The default performance to the end of its burst on the plain CPU stepper and on the checking one: every frame's
  // figures and events are the same to the last bit, so no rule the checks let pass would have acted (a yield, a
  // contraction, a merge, a payout, a crack or a pinch skipped would change the film's energies from that frame
  // on). And the checks let frames pass: the open bag hanging before the stroke, the free bubble's calmer frames.
  const Scene scene = resolveScene("default");
  Simulation plain(scene.run.params, WandTool{}, defaultStart(scene));
  Simulation checked(scene.run.params, WandTool{}, defaultStart(scene), std::make_unique<CheckingCpuStepper>());
  constexpr int kFrames = 280;
  expectTheSamePerformance(scene, plain, checked, kFrames);
  const long passed = checked.readbackRecord().framesPassed;
  std::printf("the checks let %ld of %d frames pass without the rules\n", passed, kFrames);
  EXPECT_GT(plain.burst().started, 0.0) << "the performance's bubble burst";
  EXPECT_GT(passed, kFrames / 10);
  EXPECT_EQ(plain.readbackRecord().framesPassed, 0) << "the plain CPU stepper does not check: every rule runs";
}

// How far the device's checks may lie from the CPU's. Distances and heights are float lengths of the same floats
// (a few ulp, 1e-6 relative leaves a factor of eight); the winding number is a float sum over the triangles where
// the CPU's is in double (18,000 terms of about 1e-4 each: 1e-4 absolute); the impact number divides and squares
// float speeds (1e-5 relative).
constexpr float kDistanceTolerance = 1e-6f;
constexpr float kWindingTolerance = 1e-4f;
constexpr float kImpactTolerance = 1e-5f;

void expectSameChecks(const FilmChecks& device, const Params& p, const Film& film, const FilmProbe& probe,
                      const std::string& name) {
  const FilmChecks exact = checkFilm(p, film, probe, 0.0f), loose = checkFilm(p, film, probe, 2.0f * kFilmCheckMargin);
  std::printf(
      "%s: %zu particles, lowest %.6f m, tips %.5f and %.5f m away, winding %.5f and %.5f, thinnest %.3g m, "
      "impact %.4g; springs yielding %g, slack %g, crowded %g, rungs past growth %g of %g, wire %g m\n",
      name.c_str(), device.particles, device.lowest, device.nearestTip[0], device.nearestTip[1], device.winding[0],
      device.winding[1], device.thinnest, device.hardestImpact, device.yielding, device.slack, device.crowded,
      device.rungsPastGrowth, device.rungs, device.wireEdgeLength);
  EXPECT_EQ(device.particles, exact.particles) << name;
  EXPECT_EQ(device.unstable, exact.unstable) << name;
  EXPECT_NEAR(device.lowest, exact.lowest, kDistanceTolerance * std::abs(exact.lowest)) << name;
  EXPECT_NEAR(device.thinnest, exact.thinnest, kDistanceTolerance * exact.thinnest) << name;
  for (int w = 0; w < 2; ++w) {
    EXPECT_NEAR(device.nearestTip[w], exact.nearestTip[w], kDistanceTolerance * exact.nearestTip[w]) << name;
    // Only a closed film's winding number is read (burstOnWandTouch); an open film's tips lie on its wire, where
    // the solid angles are undefined.
    if (film.topology.isClosed()) {
      EXPECT_NEAR(device.winding[w], exact.winding[w], kWindingTolerance) << name;
    }
  }
  EXPECT_NEAR(device.hardestImpact, exact.hardestImpact, kImpactTolerance * exact.hardestImpact) << name;
  // Each count lies between the rules' own (margin 0: the device's margin never misses one) and twice the margin's.
  const auto between = [&](float d, float low, float high, const char* what) {
    EXPECT_LE(low, d) << name << ": " << what;
    EXPECT_LE(d, high) << name << ": " << what;
  };
  between(device.yielding, exact.yielding, loose.yielding, "yielding");
  between(device.slack, exact.slack, loose.slack, "slack");
  between(device.crowded, exact.crowded, loose.crowded, "crowded");
  between(device.rungsPastGrowth, exact.rungsPastGrowth, loose.rungsPastGrowth, "rungs past growth");
  // The contraction's energy sums: float over the particles on the device, double over the springs on the CPU.
  EXPECT_NEAR(device.contractionQuadratic, exact.contractionQuadratic, 1e-4f * exact.contractionQuadratic) << name;
  EXPECT_NEAR(device.contractionLinear, exact.contractionLinear, 1e-4f * exact.contractionLinear) << name;
  EXPECT_EQ(device.rungs, exact.rungs) << name;
  EXPECT_EQ(device.wireEdges, exact.wireEdges) << name;
  EXPECT_NEAR(device.rungRest, exact.rungRest, 1e-5f * exact.rungRest) << name;
  EXPECT_NEAR(device.wireEdgeLength, exact.wireEdgeLength, 1e-5f * exact.wireEdgeLength) << name;
}

TEST(DeviceFilmChecks, TheDevicesChecksAreTheCpus) {
  // The default performance on the Vulkan backend: at the bag being drawn, at its fastest and at the free bubble,
  // the checks reduced on the device against checkFilm of the state brought back; for the free bubble also with a
  // tip at its centre (winding number 1).
  GB_REQUIRE_VULKAN(device);
  test::playDefaultPerformanceOnDevice(device, [&](Simulation& played, const WandState& wands, int f) {
    if (!test::checkedFrame(f)) return;
    FilmProbe probe;
    probe.tips = {wands.leftPosition, wands.rightPosition};
    probe.frameTime = played.params().frameTime;
    probe.atPresentPositions = false;
    const std::string name = "the default performance at frame " + std::to_string(f);
    FilmSums sums;
    FilmChecks checks;
    ASSERT_TRUE(played.stepper().device()->probeFilm(probe, sums, checks));
    const Film& film = played.film();  // brought back
    expectSameChecks(checks, played.params(), film, probe, name);
    if (!film.topology.isClosed()) return;
    probe.tips[0] = centroid(film.state);
    ASSERT_TRUE(played.stepper().device()->probeFilm(probe, sums, checks));
    expectSameChecks(checks, played.params(), film, probe, name + ", a tip at its centre");
    EXPECT_NEAR(checks.winding[0], 1.0f, kWindingTolerance);
  });
}

TEST(DeviceFilmChecks, TheDeviceFindsEverySpringTheMergesTry) {
  // The default performance's free bubble (frame 110) on the Vulkan backend: what a round of merges tries, found on
  // the device (crowded_springs), against mergeCrowdedParticles's parts on the state brought back. The median spring
  // to the last bit (the root of the device's median squared length): the merges must choose exactly as the CPU's.
  // Every spring the CPU tries is listed, and none is listed that the tests loosened by twice the checks' margin
  // would not pass (the device's lengths differ from the CPU's by a few units in the last place).
  GB_REQUIRE_VULKAN(device);
  int found = 0;
  test::playDefaultPerformanceOnDevice(device, [&](Simulation& played, const WandState&, int f) {
    if (f != 110) return;
    CrowdedCandidates candidates;
    ASSERT_TRUE(played.stepper().device()->findCrowdedSprings(candidates));
    const Film& film = played.film();  // brought back
    const Params& p = played.params();
    ASSERT_TRUE(film.topology.isClosed());
    const float median = medianSpringLength(film);
    EXPECT_EQ(std::sqrt(candidates.medianSquaredLength), median);
    std::vector<CrowdedSpring> tried = crowdedSprings(p, film);
    keepTheMergeable(tried, median);
    for (const CrowdedSpring& c : tried)
      EXPECT_TRUE(std::binary_search(candidates.springs.begin(), candidates.springs.end(), c.spring))
          << "spring " << c.spring << " is tried but not listed";
    constexpr float more = 1.0f + 2.0f * kFilmCheckMargin, less = 1.0f - 2.0f * kFilmCheckMargin;
    const State& s = film.state;
    for (const uint32_t k : candidates.springs) {
      const uint32_t a = film.topology.springEnds[2 * k], b = film.topology.springEnds[2 * k + 1];
      const float length = springLength(s, a, b);
      EXPECT_TRUE(s.alive[a] && s.alive[b] && length * less < kCrowdedEdge * median * more &&
                  springCrowded(length * less, film.topology.restLength[k],
                                std::max(s.thickness[a], s.thickness[b]) * more, initialThickness(p)))
          << "spring " << k << " is listed but not crowded";
    }
    std::printf("frame 110: median spring %.6f m, %zu springs listed, %zu tried by the CPU, of %zu\n", median,
                candidates.springs.size(), tried.size(), film.topology.springCount());
    EXPECT_GT(tried.size(), 0u) << "the free bubble has crowded springs to merge";
    ++found;
  });
  EXPECT_EQ(found, 1);
}

TEST(DeviceFilmChecks, TheDeviceContractsSlackSpringsAsTheCpuDoes) {
  // A closed film whose springs are slack by 1-5% of their length or taut, thinner than the dip: the contraction on
  // the device (film_rest_lengths, the share from the device's sums) against contractSlackSprings, with the allowance
  // unbounded and with a third of what all the way needs. Rest lengths within 1e-5 relative: each is
  // rest + s (taut - rest), and the device's share s comes from float sums of the particles' halves (1e-4 of the
  // way, itself about a tenth of the rest length).
  GB_REQUIRE_VULKAN(device);
  const Params p;
  Film slack = generateSphere(p, Vec3(0.0f, 1.0f, 0.0f), 0.5f, 3);
  Topology& topo = slack.topology;
  for (size_t k = 0; k < topo.springCount(); ++k) {
    const float length =
        (slack.state.position.get(topo.springEnds[2 * k]) - slack.state.position.get(topo.springEnds[2 * k + 1]))
            .norm();
    topo.restLength[k] = (k % 2 ? 0.95f : 1.01f + 0.04f * static_cast<float>(k % 7) / 6.0f) * length;
  }
  for (float& e : slack.state.thickness) e = 0.5f * initialThickness(p);
  const ContractionEnergy energy = contractionEnergy(p, slack);
  const float allTheWay = energy.quadratic - energy.linear;
  ASSERT_GT(allTheWay, 0.0f) << "the springs must gain energy contracting for the allowance to bind";
  for (const float allowance : {std::numeric_limits<float>::infinity(), allTheWay / 3.0f}) {
    Film cpu = slack, gpu = slack;
    SpringEnergyAllowance left{allowance};
    const size_t contracted = contractSlackSprings(p, cpu, left);
    ASSERT_GT(contracted, 100u);
    VulkanStepper stepper(device, test::everythingOnDevice());
    stepper.load(p, gpu);
    FilmProbe probe;
    probe.atPresentPositions = false;
    FilmSums sums;
    FilmChecks checks;
    ASSERT_TRUE(stepper.probeFilm(probe, sums, checks));
    const float share = contractionShareOf(checks.contractionQuadratic, checks.contractionLinear, allowance);
    ASSERT_TRUE(stepper.contractSlackSprings(share));
    stepper.storeRestLengths(gpu);
    float worst = 0.0f;
    for (size_t k = 0; k < topo.springCount(); ++k)
      worst = std::max(worst,
                       std::abs(gpu.topology.restLength[k] - cpu.topology.restLength[k]) / cpu.topology.restLength[k]);
    std::printf("allowance %.3g J: %zu springs contracted, share %.6f on the device, rest lengths %.3g apart\n",
                allowance, contracted, share, worst);
    EXPECT_LT(worst, 1e-5f) << "allowance " << allowance;
  }
}

TEST(DeviceFilmChecks, TheStateStaysOnTheDeviceWhereNoRuleActs) {
  // The default performance to the free bubble on the Vulkan backend twice: with the state brought back after every
  // step, and left on the device where the checks let a frame pass. The device steps the same film either way and
  // the CPU's rules act on the same frames: the same figures at every frame, and the pinch-off at the same frame.
  // The frames that pass bring back no state: a few hundred bytes (the checks, the contact count) instead of the
  // state's 1.5 MiB.
  GB_REQUIRE_VULKAN(device);
  const Scene scene = resolveScene("default");
  ReadBackAndKept plays(device, scene);
  Simulation &everyFrame = plays.everyFrame, &onDevice = plays.onDevice;
  expectTheSamePerformance(scene, everyFrame, onDevice, 110);
  EXPECT_TRUE(onDevice.film().topology.isClosed()) << "frame 110 is the free bubble";
  const Simulation::ReadbackRecord &all = everyFrame.readbackRecord(), &some = onDevice.readbackRecord();
  std::printf(
      "state read back on %zu of %ld frames (every frame: %zu), %ld passed by the checks; %.1f KiB a frame "
      "without an event (%.1f)\n",
      some.stateReadbacks, some.frames, all.stateReadbacks, some.framesPassed,
      static_cast<double>(some.bytesWithoutEvent) / 1024.0 / static_cast<double>(some.framesWithoutEvent),
      static_cast<double>(all.bytesWithoutEvent) / 1024.0 / static_cast<double>(all.framesWithoutEvent));
  EXPECT_GE(all.stateReadbacks, 110u);
  EXPECT_LT(some.stateReadbacks, all.stateReadbacks);
  EXPECT_EQ(all.framesPassed, 0);
  // A frame held for a ring at the wire, the merges or the burst's rules alone brings back what they read; every
  // other, the state.
  size_t heldInRegion = 0;
  for (const auto& [rule, frames] : some.framesHeldByRule) {
    const auto whole = some.stateReadbacksHeldByRule.find(rule);
    const size_t readBack = whole == some.stateReadbacksHeldByRule.end() ? 0 : whole->second;
    heldInRegion += static_cast<size_t>(frames) - readBack;
    if (rule != "ring" && rule != "yield" && rule != "merge" && rule != "floor" && rule != "thinning" &&
        rule != "burst") {
      EXPECT_EQ(readBack, static_cast<size_t>(frames)) << rule;
    }
  }
  EXPECT_GT(heldInRegion, 0u) << "the rings at the wire and the merges change the film on the device";
  EXPECT_EQ(some.stateReadbacks + static_cast<size_t>(some.framesPassed) + heldInRegion, all.stateReadbacks)
      << "a frame the checks pass brings nothing back";
  // Every frame the checks held names the rule that may act on it. The free bubble's slack springs contract on the
  // device; its crowded particles hold a frame every mergeInterval frames at most.
  long held = 0;
  for (const auto& [rule, frames] : some.framesHeldByRule) {
    std::printf("held by %s: %ld frames\n", rule.c_str(), frames);
    held += frames;
  }
  EXPECT_EQ(held + some.framesPassed, some.frames);
  EXPECT_EQ(some.framesHeldByRule.count("contraction"), 0u);
  const int freeFrames = 110 - 93;  // pinched off at frame 93 (1.86 s)
  EXPECT_GT(some.framesHeldByRule.count("merge"), 0u);
  if (some.framesHeldByRule.count("merge")) {
    EXPECT_LE(some.framesHeldByRule.at("merge"), freeFrames / scene.run.params.mergeInterval);
  }
  EXPECT_TRUE(all.framesHeldByRule.empty()) << "read back every frame, the checks were not asked";
}

// Two arrays of a film's, equal to the last bit; a failure names the first index where they differ.
template <class T>
void expectSameValues(const std::vector<T>& a, const std::vector<T>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  const auto differs = std::mismatch(a.begin(), a.end(), b.begin()).first;
  EXPECT_TRUE(differs == a.end()) << what << ": first differs at " << (differs - a.begin());
}

// Every per-particle array store() brings back, the masses and alive flags, the rest lengths and the mesh of two
// films: equal to the last bit.
void expectTheSameFilm(const Film& a, const Film& b, const std::string& where) {
  ASSERT_EQ(a.state.size(), b.state.size()) << where;
  expectSameValues(a.topology.triangles, b.topology.triangles, where + ", triangles");
  expectSameValues(a.topology.springEnds, b.topology.springEnds, where + ", springs");
  expectSameValues(a.topology.restLength, b.topology.restLength, where + ", rest lengths");
  EXPECT_EQ(a.wireLiquid, b.wireLiquid) << where;
  std::vector<const void*> theirs;  // b's arrays, in the order both are visited
  forEachParticleArray(b.state, [&](const auto& array, const ParticleArrayInfo&) { theirs.push_back(&array); });
  size_t next = 0;
  forEachParticleArray(a.state, [&](const auto& array, const ParticleArrayInfo& info) {
    const auto& other = *static_cast<const std::remove_cvref_t<decltype(array)>*>(theirs[next++]);
    const void* kept[] = {&a.state.mass, &a.state.wireParam};  // the arrays the device only reads; the rest, scratch
    if (info.transfer == Transfer::UploadOnly && std::find(std::begin(kept), std::end(kept), &array) == std::end(kept))
      return;
    forEachComponent(array, [&](const auto& values, int c) {
      forEachComponent(other, [&](const auto& otherValues, int d) {
        if (c == d)
          expectSameValues(
              values, otherValues,
              where + ", binding " + std::to_string(info.binding) + " block " + std::to_string(info.block + c));
      });
    });
  });
}

TEST(DeviceFilmChecks, RingsAndMergesOnTheDeviceLeaveTheFilmOfTheWholeReadBack) {
  // The default performance to the free bubble (110 frames: the bag drawn off the wire a ring every few frames, the
  // free bubble's crowded particles merged every mergeInterval frames) on the Vulkan backend twice: with the state
  // brought back after every step, where growth and the merges run on the film in host memory and the stepper takes
  // the changed film whole (load), and left on the device, where a frame held for a ring or for the merges alone
  // brings back what they read (a region at the wire; the positions, thickness, elasticity and rest lengths, and the
  // particles merged) and the stepper takes what changed (updateRegion). After every ring and every merge: no
  // whole-state read-back, less than a third of the state's bytes, and the same film to the last bit.
  GB_REQUIRE_VULKAN(device);
  const Scene scene = resolveScene("default");
  ReadBackAndKept plays(device, scene);
  Simulation &everyFrame = plays.everyFrame, &onDevice = plays.onDevice;
  int rings = 0, merges = 0;
  for (int f = 1; f <= 110; ++f) {
    const WandState wands = defaultWandsAt(scene, f);
    everyFrame.advanceFrame(wands);
    const DeviceReadback before = onDevice.stepper().device()->readback();
    const size_t trianglesBefore = onDevice.triangleCount();
    onDevice.advanceFrame(wands);
    const DeviceReadback after = onDevice.stepper().device()->readback();
    const std::string frame = "frame " + std::to_string(f);
    ASSERT_EQ(everyFrame.lastEvents().particlesAdded, onDevice.lastEvents().particlesAdded) << frame;
    ASSERT_EQ(everyFrame.triangleCount(), onDevice.triangleCount()) << frame;
    const bool ring = onDevice.lastEvents().particlesAdded > 0;
    const bool merged = onDevice.triangleCount() < trianglesBefore && onDevice.burst().started < 0;
    if (!ring && !merged) continue;
    (ring ? rings : merges) += 1;
    const uint64_t stateBytes = onDevice.particleCount() * 128;  // 32 floats a particle come back with the state
    std::printf("%s: %s, %.1f KiB brought back (the state: %.0f KiB)\n", frame.c_str(), ring ? "a ring" : "merges",
                static_cast<double>(after.bytes - before.bytes) / 1024.0, static_cast<double>(stateBytes) / 1024.0);
    EXPECT_EQ(after.stateReadbacks, before.stateReadbacks) << frame << ": a region comes back, not the state";
    // A ring brings back its region at the wire; merges what their springs found on the device read (their ends and
    // one-rings, about a twentieth of the film at most) and the particles they merge.
    EXPECT_LT(after.bytes - before.bytes, ring ? stateBytes / 3 : stateBytes / 10) << frame;
    // The statistics refresh both films' geometry at their present positions (on the device, and in host memory as
    // each comes back), which the whole reload had made on the CPU.
    (void)everyFrame.stats();
    (void)onDevice.stats();
    expectTheSameFilm(everyFrame.film(), onDevice.film(), frame);
  }
  EXPECT_GE(rings, 3) << "the bag is drawn off the wire in rings";
  EXPECT_GE(merges, 1) << "the free bubble's crowded particles merge";
}

TEST(DeviceFilmChecks, ABurstOnTheDeviceLeavesTheFilmOfTheWholeReadBack) {
  // The default performance's bag poked at its top at frame 30 on the Vulkan backend twice: with the state brought
  // back after every step, and left on the device, where a frame of the burst brings back only what its front reads
  // (the particles it reaches, their neighbours and the corners of the triangles that die: 4 floats of each, the
  // state's 32) and the stepper takes the shrunk mesh in place (updateTopology). On every frame of the burst: no
  // whole-state read-back, less than a tenth of the state's bytes, the same film to the last bit and the same
  // droplets.
  GB_REQUIRE_VULKAN(device);
  const Scene scene = resolveScene("default");
  ReadBackAndKept plays(device, scene);
  Simulation &everyFrame = plays.everyFrame, &onDevice = plays.onDevice;
  constexpr int kPoked = 30;
  for (int f = 1; f <= kPoked; ++f) {
    everyFrame.advanceFrame(defaultWandsAt(scene, f));
    onDevice.advanceFrame(defaultWandsAt(scene, f));
  }
  const size_t top = everyFrame.topParticle();
  ASSERT_EQ(onDevice.topParticle(), top);
  everyFrame.startBurst(top);
  onDevice.startBurst(top);
  int burstFrames = 0;
  for (int f = kPoked + 1; f <= kPoked + 40 && onDevice.burst().finished < 0; ++f) {
    const WandState wands = defaultWandsAt(scene, f);
    everyFrame.advanceFrame(wands);
    const DeviceReadback before = onDevice.stepper().device()->readback();
    onDevice.advanceFrame(wands);
    const DeviceReadback after = onDevice.stepper().device()->readback();
    const std::string frame = "frame " + std::to_string(f);
    ASSERT_EQ(everyFrame.lastEvents().particlesRemoved, onDevice.lastEvents().particlesRemoved) << frame;
    ASSERT_EQ(everyFrame.lastEvents().finished, onDevice.lastEvents().finished) << frame;
    if (onDevice.lastEvents().particlesRemoved > 0) ++burstFrames;
    const uint64_t stateBytes = onDevice.particleCount() * 128;  // 32 floats a particle come back with the state
    std::printf("%s: %zu particles taken, %.1f KiB brought back (the state: %.0f KiB)\n", frame.c_str(),
                onDevice.lastEvents().particlesRemoved, static_cast<double>(after.bytes - before.bytes) / 1024.0,
                static_cast<double>(stateBytes) / 1024.0);
    EXPECT_EQ(after.stateReadbacks, before.stateReadbacks) << frame << ": the front's region comes back, not the state";
    EXPECT_LT(after.bytes - before.bytes, stateBytes / 10) << frame;
    (void)everyFrame.stats();
    (void)onDevice.stats();
    expectTheSameFilm(everyFrame.film(), onDevice.film(), frame);
    const Aerosol &a = everyFrame.aerosol(), &b = onDevice.aerosol();
    ASSERT_EQ(a.size(), b.size()) << frame;
    expectSameValues(a.mass, b.mass, frame + ", droplet masses");
    expectSameValues(a.position.x, b.position.x, frame + ", droplet positions");
    expectSameValues(a.velocity.y, b.velocity.y, frame + ", droplet velocities");
  }
  EXPECT_GE(burstFrames, 3) << "the hole opens over several frames";
  EXPECT_GT(onDevice.aerosol().size(), 0u) << "the film's liquid flies off as droplets";
}

TEST(DeviceFilmChecks, ADrawnFilmBringsBackItsPositionsAlone) {
  // The renderer drawing the stepper's buffers in place frames the film from where its particles are: on a frame
  // whose state stayed on the device, filmPositionsOnly brings back the positions alone (3 floats a particle, not a
  // state read-back), and they are the positions of the same performance read back whole after every step, to the
  // bit. 50 frames of the default performance: the bag being drawn, most frames passing the checks.
  GB_REQUIRE_VULKAN(device);
  const Scene scene = resolveScene("default");
  ReadBackAndKept plays(device, scene);
  Simulation &everyFrame = plays.everyFrame, &onDevice = plays.onDevice;
  int positionsAlone = 0;
  for (int f = 1; f <= 50; ++f) {
    const WandState wands = defaultWandsAt(scene, f);
    everyFrame.advanceFrame(wands);
    onDevice.advanceFrame(wands);
    const DeviceReadback before = onDevice.stepper().device()->readback();
    const State& drawn = onDevice.filmPositionsOnly().state;
    const DeviceReadback after = onDevice.stepper().device()->readback();
    ASSERT_EQ(after.stateReadbacks, before.stateReadbacks) << "frame " << f << ": no state read back";
    const uint64_t positionBytes = 3 * sizeof(float) * drawn.size();
    ASSERT_TRUE(after.bytes == before.bytes || after.bytes == before.bytes + positionBytes) << "frame " << f;
    if (after.bytes > before.bytes) ++positionsAlone;
    const State& whole = everyFrame.film().state;
    ASSERT_EQ(drawn.size(), whole.size()) << "frame " << f;
    for (size_t i = 0; i < whole.size(); ++i)
      ASSERT_EQ(drawn.position.get(i), whole.position.get(i)) << "frame " << f << ", particle " << i;
    const DeviceReadback again = onDevice.stepper().device()->readback();
    (void)onDevice.filmPositionsOnly();
    ASSERT_EQ(onDevice.stepper().device()->readback().bytes, again.bytes)
        << "frame " << f << ": brought back once a frame";
  }
  std::printf("positions alone brought back on %d of 50 frames\n", positionsAlone);
  EXPECT_GT(positionsAlone, 10) << "most of the bag's frames pass the checks and keep the state on the device";
}

}  // namespace
}  // namespace gb
