// The frame's statistics summed on the device (VulkanStepper::probeFilm, kernels/statistics/film_statistics_*.comp)
// against the CPU's sums in double (Simulation::stats on a CPU stepper), the reference: on the default performance's
// film as it runs on the Vulkan backend (the bag being drawn, at its fastest, the free bubble), and on a bubble of the
// physical tension model. Runs on whatever device VulkanContext picks (lavapipe in CI); vulkan_test_device.h says when
// a missing device skips and when it fails.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "host/vulkan_stepper.h"
#include "simulation/simulation.h"
#include "tests/default_performance_on_device.h"
#include "tests/test_films.h"
#include "tests/vulkan_test_device.h"

namespace gb {
namespace {

// How far the device's figures may lie from the CPU's, relative. The device adds floats in a tree (at most
// log2(n) = 14 roundings of 2^-24 on these films) where the CPU adds doubles; each term also rounds a few times in
// float: 1e-5 leaves a factor of five for a GPU's fused multiply-adds and square roots a few ulp off.
constexpr double kSumTolerance = 1e-5;
// A spring's energy is its stiffness times its stretch squared, and the stretch is a float length less the rest
// length: a stretch of 1% of a 2 cm spring carries the float length's rounding (1e-9 m) as 1e-5 of itself, doubled
// in its square.
constexpr double kElasticTolerance = 1e-4;

void expectNear(double device, double cpu, double tolerance, double scale, const std::string& what) {
  const double apart = device == cpu ? 0.0 : std::abs(device - cpu) / scale;  // both 0: a film in still air
  std::printf("  %-18s device %.9g, cpu %.9g, apart %.2e of %.3g\n", what.c_str(), device, cpu, apart, scale);
  EXPECT_LE(apart, tolerance) << what;
}

// The statistics of a simulation on the device against those the CPU sums for the same film and wands.
void expectSameStatistics(const Simulation& onDevice, const FrameStats& device, const WandState& wands,
                          const std::string& name) {
  Simulation cpu(onDevice.params(), onDevice.film(), wands);  // a copy of the film, on the CPU stepper
  const FrameStats reference = cpu.stats();
  std::printf("%s: %zu particles\n", name.c_str(), reference.particles);
  EXPECT_EQ(device.particles, reference.particles) << name;
  expectNear(device.area, reference.area, kSumTolerance, reference.area, name + " area");
  // The volume's terms have either sign (an open film's swept volume, a closed film's cones about a centroid):
  // its rounding is that of its terms' magnitudes, about the film's area times its size.
  const double size = std::sqrt(reference.area);
  expectNear(device.volume, reference.volume, kSumTolerance, reference.area * size, name + " volume");
  expectNear(device.kineticEnergy, reference.kineticEnergy, kSumTolerance, reference.kineticEnergy, name + " kinetic");
  expectNear(device.potentialEnergy, reference.potentialEnergy, kSumTolerance, std::abs(reference.potentialEnergy),
             name + " potential");
  expectNear(device.elasticEnergy, reference.elasticEnergy, kElasticTolerance, reference.elasticEnergy,
             name + " elastic");
  expectNear(device.liquid, reference.liquid, kSumTolerance, reference.liquid, name + " liquid");
  expectNear(device.meanThickness, reference.meanThickness, kSumTolerance, reference.meanThickness,
             name + " mean thickness");
  expectNear(device.meanAirFlow, reference.meanAirFlow, kSumTolerance, reference.meanAirFlow, name + " mean air");
  expectNear(device.maxSpeed, reference.maxSpeed, kSumTolerance, reference.maxSpeed, name + " max speed");
}

TEST(DeviceStatistics, TheDefaultPerformancesFiguresAreTheCpusFromTheDevice) {
  // The default performance on the Vulkan backend with its statistics summed on the device. Frame 40: the bag
  // being drawn (an open film: the volume is the cone to the frame's centre); 80: mid-stroke, at its fastest; 110:
  // the free bubble after the pinch-off (closed: the device takes the bubble's fixed origin, the CPU its centroid).
  GB_REQUIRE_VULKAN(device);
  const auto sim = test::playDefaultPerformanceOnDevice(device, [&](Simulation& played, const WandState& wands, int f) {
    if (!test::checkedFrame(f)) return;
    const auto& stepper = dynamic_cast<const VulkanStepper&>(played.stepper());
    const uint64_t before = stepper.readback().bytes;
    const FrameStats onDevice = played.stats();
    EXPECT_EQ(stepper.readback().bytes - before, GB_STATISTICS_TERMS * sizeof(float)) << "the sums alone come back";
    expectSameStatistics(played, onDevice, wands, "the default performance at frame " + std::to_string(f));
  });
  EXPECT_TRUE(sim->film().topology.isClosed()) << "frame 110 is the free bubble";
}

TEST(DeviceStatistics, APhysicalTensionBubblesFiguresAreTheCpusFromTheDevice) {
  // The physical tension model's energy (filmTensionEnergy per particle, in float on the device) on a bubble
  // falling for half a second.
  GB_REQUIRE_VULKAN(device);
  Params p;
  p.tensionModel = 1;
  Simulation sim(p, generateSphere(p, Vec3(0, 1.5f, 0), 0.4f, 3), WandState{},
                 std::make_unique<VulkanStepper>(device, test::everythingOnDevice()));
  for (int f = 0; f < 25; ++f) sim.advanceFrame(WandState{});
  expectSameStatistics(sim, sim.stats(), WandState{}, "a physical-tension bubble after 0.5 s");
}

}  // namespace
}  // namespace gb
