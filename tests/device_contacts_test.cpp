// The self-collision search on the device (VulkanStepper::findContacts, kernels/contacts/contact_*.comp) against the
// CPU's findContacts (collision.h), the reference: the same pairs and the same rest distances, on the films the CPU
// search is tested on (collision_test.cpp), on a crumpled film, and on the default performance's film as it runs on the
// Vulkan backend. Runs on whatever device VulkanContext picks (lavapipe in CI); vulkan_test_device.h says when a
// missing device skips and when it fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "host/vulkan_stepper.h"
#include "scene/scene_file.h"
#include "simulation/simulation.h"
#include "tests/default_performance_on_device.h"
#include "tests/test_films.h"
#include "tests/vulkan_test_device.h"
#include "topology/collision.h"

namespace gb {
namespace {

// How far a device rest distance may lie from the CPU's, relative: each is the collision distance, a rest distance
// copied from the previous list, or a separation sqrt(dx^2 + dy^2 + dz^2), which the shader computes with the C++
// operations in their order and no fused multiply-add (precise). Vulkan lets a GPU's square root be off by a few
// ulp (lavapipe's is exact): 1e-6 is 8 ulp of a float.
constexpr float kRestTolerance = 1e-6f;

// One particle's row of a packed list (Topology::contacts for n particles): its partners and their rest distances.
struct Row {
  std::vector<uint32_t> partners;
  std::vector<float> rests;
};
Row rowOf(const std::vector<uint32_t>& list, size_t n, uint32_t i) {
  Row row;
  for (uint32_t k = list[i]; k < list[i + 1]; ++k) {
    row.partners.push_back(list[n + 1 + k]);
    row.rests.push_back(contactRestDistance(list, n, k));
  }
  return row;
}

// The two lists as sets of pairs with their rest distances: every pair of one is in the other, and its rest
// distances agree within kRestTolerance. Returns the number of pairs.
size_t expectSameContacts(const std::vector<uint32_t>& cpu, const std::vector<uint32_t>& gpu, size_t n,
                          const std::string& name) {
  EXPECT_EQ(gpu.size(), cpu.size()) << name << ": the lists' lengths";
  EXPECT_GE(cpu.size(), n + 1);
  if (cpu.size() < n + 1 || gpu.size() < n + 1) return 0;
  size_t missing = 0, extra = 0, restsApart = 0;
  float worstRest = 0;
  for (uint32_t i = 0; i < n; ++i) {
    const Row a = rowOf(cpu, n, i), b = rowOf(gpu, n, i);
    std::vector<uint32_t> onlyCpu, onlyGpu;
    std::set_difference(a.partners.begin(), a.partners.end(), b.partners.begin(), b.partners.end(),
                        std::back_inserter(onlyCpu));
    std::set_difference(b.partners.begin(), b.partners.end(), a.partners.begin(), a.partners.end(),
                        std::back_inserter(onlyGpu));
    for (uint32_t j : onlyCpu) ADD_FAILURE() << name << ": the device misses pair " << i << "-" << j;
    for (uint32_t j : onlyGpu) ADD_FAILURE() << name << ": the device lists pair " << i << "-" << j << " too";
    missing += onlyCpu.size();
    extra += onlyGpu.size();
    for (size_t k = 0; k < a.partners.size(); ++k) {
      const auto at = std::lower_bound(b.partners.begin(), b.partners.end(), a.partners[k]);
      if (at == b.partners.end() || *at != a.partners[k]) continue;
      const float gpuRest = b.rests[static_cast<size_t>(at - b.partners.begin())];
      const float apart = std::abs(gpuRest - a.rests[k]) / a.rests[k];
      worstRest = std::max(worstRest, apart);
      restsApart += apart > kRestTolerance;
    }
    if (missing + extra > 20) break;  // the first few say enough
  }
  EXPECT_EQ(restsApart, 0u) << name << ": rest distances apart by more than " << kRestTolerance << " (worst "
                            << worstRest << ")";
  const size_t pairs = cpu[n] / 2;
  std::printf("%s: %zu particles, %zu pairs, %zu missing, %zu extra, worst rest distance %.3g apart\n", name.c_str(), n,
              pairs, missing, extra, static_cast<double>(worstRest));
  return pairs;
}

// Both searches on the same film and history: the CPU's findContacts, and the device's on a stepper loaded with
// the film. Returns the number of pairs.
size_t expectTheDeviceListsWhatTheCpuLists(VulkanStepper& stepper, const Params& p, const Film& film,
                                           const ContactHistory& history, const std::string& name) {
  Film cpu = film, gpu = film;
  findContacts(p, p.frameTime, 0.005f, cpu, history);
  stepper.load(p, gpu);
  EXPECT_TRUE(stepper.findContacts(p, p.frameTime, 0.005f, gpu, history));
  return expectSameContacts(cpu.topology.contacts, gpu.topology.contacts, film.state.size(), name);
}

Params twoSheetParams() {
  Params p;
  p.particlesAtFullSolution = 600;
  p.gravityY = 0.0f;
  return p;
}

constexpr float kFoldAngle = 170.0f * 3.14159265f / 180.0f;

// The default film crumpled: every particle moved at random by up to 2 cm and given a random velocity up to
// 1 m/s, its normals recomputed: a sheet whose neighbours lie every way, as a collapsed bubble's do.
Film crumpledFilm(const Params& p, unsigned seed) {
  Film film = generateFilm(p, WandTool{}, gestureAt(Gesture::Straight, GestureOptions{}, 0.0));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (size_t i = 0; i < film.state.size(); ++i) {
    film.state.position.set(i, film.state.position.get(i) + 0.02f * Vec3(u(rng), u(rng), u(rng)));
    film.state.velocity.set(i, Vec3(u(rng), u(rng), u(rng)) / std::sqrt(3.0f));
  }
  CpuStepper::refreshGeometry(p, film);
  return film;
}

TEST(DeviceContacts, TheDeviceListsThePairsAndRestDistancesTheCpuLists) {
  GB_REQUIRE_VULKAN(device);
  VulkanStepper stepper(device, test::everythingOnDevice());
  const Params sheets = twoSheetParams();
  EXPECT_GT(expectTheDeviceListsWhatTheCpuLists(stepper, sheets, test::makeTwoSheets(sheets, 0.022f, 0.8f), {},
                                                "two sheets 2.2 cm apart, one moving"),
            100u);
  for (float angle : {0.0f, 0.7f})
    EXPECT_GT(
        expectTheDeviceListsWhatTheCpuLists(stepper, sheets, test::shiftedSheets(sheets, 0.001f, 0.00098f, angle), {},
                                            "sheets 1 mm apart, shifted 0.98 mm, turned " + std::to_string(angle)),
        500u);
  const Params film;
  EXPECT_GT(expectTheDeviceListsWhatTheCpuLists(stepper, film, test::foldedFilm(film, kFoldAngle, 1), {},
                                                "the default film folded"),
            1000u);
  EXPECT_GT(expectTheDeviceListsWhatTheCpuLists(stepper, film, crumpledFilm(film, 2), {}, "the default film crumpled"),
            1000u);
  Params still = sheets;
  still.collisionStiffness = 0.0f;  // no contact forces: no search, on either side
  EXPECT_EQ(expectTheDeviceListsWhatTheCpuLists(stepper, still, test::makeTwoSheets(still, 0.01f, 0.0f), {},
                                                "two sheets without contact forces"),
            0u);
}

void moveSecondSheet(Film& film, float dz) {
  for (size_t i = film.state.size() / 2; i < film.state.size(); ++i) film.state.position.z[i] += dz;
}

TEST(DeviceContacts, PairsKeepTheRestDistancesOfTheLastListOnTheDeviceAsOnTheCpu) {
  // As collision_test's rest-distance test: sheets listed 1 cm apart, pulled to 1.5 cm, pushed to 0.7 cm. The
  // device reads its own last list as the history (the history given is that list), or the one given when it is
  // another (a fresh stepper, or none).
  GB_REQUIRE_VULKAN(device);
  const Params p = twoSheetParams();
  Film cpu = test::makeTwoSheets(p, 0.01f, 0.0f), gpu = cpu;
  VulkanStepper stepper(device, test::everythingOnDevice());
  stepper.load(p, gpu);
  ContactHistory cpuHistory, gpuHistory;
  for (float dz : {0.0f, 0.005f, -0.008f}) {
    moveSecondSheet(cpu, dz);
    moveSecondSheet(gpu, dz);
    stepper.load(p, gpu);  // the moved positions; the history is then uploaded from gpuHistory
    findContacts(p, 0.0f, 0.01f, cpu, cpuHistory);
    ASSERT_TRUE(stepper.findContacts(p, 0.0f, 0.01f, gpu, gpuHistory));
    expectSameContacts(cpu.topology.contacts, gpu.topology.contacts, cpu.state.size(),
                       "sheets moved " + std::to_string(dz));
    cpuHistory = {cpu.topology.contacts, cpu.state.size()};
    gpuHistory = {gpu.topology.contacts, gpu.state.size()};
  }
  // Searched again where they are, with the device's own list as the history (copied on the device), and with none.
  findContacts(p, 0.0f, 0.01f, cpu, cpuHistory);
  ASSERT_TRUE(stepper.findContacts(p, 0.0f, 0.01f, gpu, gpuHistory));
  expectSameContacts(cpu.topology.contacts, gpu.topology.contacts, cpu.state.size(), "again, the device's history");
  findContacts(p, 0.0f, 0.01f, cpu);
  ASSERT_TRUE(stepper.findContacts(p, 0.0f, 0.01f, gpu, {}));
  expectSameContacts(cpu.topology.contacts, gpu.topology.contacts, cpu.state.size(), "again, no history");
}

TEST(DeviceContacts, ASearchShortOfRoomGrowsItSaysSoAndListsEveryPair) {
  // Rows of one partner, then a list of one entry: the search finds more, grows to what it found, says so on stderr,
  // and searches again; the list is the CPU's.
  GB_REQUIRE_VULKAN(device);
  const Params p;
  const Film folded = test::foldedFilm(p, kFoldAngle, 1);
  for (const auto& [rows, entries] : {std::pair{1u, 0u}, std::pair{16u, 1u}}) {
    VulkanStepperOptions options = test::everythingOnDevice();
    options.contactRowCapacity = rows;
    options.contactEntryCapacity = entries;
    VulkanStepper stepper(device, options);
    const std::string name = "room for " + std::to_string(rows) + " a row, " + std::to_string(entries) + " entries";
    EXPECT_GT(expectTheDeviceListsWhatTheCpuLists(stepper, p, folded, {}, name), 1000u);
    EXPECT_EQ(stepper.contactRecord().searches, 2u) << name;
    EXPECT_EQ(stepper.contactRecord().regrown, 1u) << name;
    // The room found is kept: the next search of the same film fits at once.
    Film again = folded;
    stepper.load(p, again);
    ASSERT_TRUE(stepper.findContacts(p, p.frameTime, 0.005f, again, {}));
    EXPECT_EQ(stepper.contactRecord().regrown, 1u) << name << ", searched again";
  }
}

// The most partners of one particle in a packed list of n particles.
uint32_t mostPartners(const std::vector<uint32_t>& list, size_t n) {
  uint32_t most = 0;
  for (size_t i = 0; i < n; ++i) most = std::max(most, list[i + 1] - list[i]);
  return most;
}

TEST(DeviceContacts, ASearchThatOutgrowsItsRowsKeepsTheHistoryItLeftOnTheDevice) {
  // The crumpled default film searched with a small margin into rows and a list that just hold it, the list left on
  // the device; then searched with a wider margin, which finds more than they hold, with its own list as
  // the history (as Simulation passes it). The history comes back from where the first search's layout put it
  // before the rows grow, on the device: the pairs' rest distances are the CPU's, which searches with the first list as
  // the history.
  GB_REQUIRE_VULKAN(device);
  const Params p;
  Film cpu = crumpledFilm(p, 3), gpu = cpu;
  findContacts(p, 0.0f, 0.002f, cpu);
  VulkanStepperOptions options = test::everythingOnDevice();
  options.contactRowCapacity = mostPartners(cpu.topology.contacts, cpu.state.size());
  options.contactEntryCapacity = cpu.topology.contacts[cpu.state.size()];
  VulkanStepper stepper(device, options);
  stepper.load(p, gpu);
  ASSERT_TRUE(stepper.findContactsOnDevice(p, 0.0f, 0.002f, {}));
  ASSERT_EQ(stepper.contactRecord().regrown, 0u) << "the first search fits its rows";
  findContacts(p, 0.0f, 0.03f, cpu, {cpu.topology.contacts, cpu.state.size()});
  const uint64_t readBefore = stepper.readback().bytes;
  ASSERT_TRUE(stepper.findContactsOnDevice(p, 0.0f, 0.03f, {{}, gpu.state.size(), true}));
  EXPECT_EQ(stepper.contactRecord().regrown, 1u) << "the wider search must outgrow the rows (room for "
                                                 << options.contactRowCapacity << ") for the test to mean something";
  // The two searches' headers and the list's size come back, a few hundred bytes; the history (1.1 MB) does not.
  EXPECT_LT(stepper.readback().bytes - readBefore, 1024u) << "the history stayed on the device";
  stepper.storeContacts(gpu);
  EXPECT_GT(expectSameContacts(cpu.topology.contacts, gpu.topology.contacts, cpu.state.size(),
                               "the crumpled film searched wider, the device's list as the history"),
            1000u);
}

TEST(DeviceContacts, TheDefaultPerformanceOnTheDeviceListsWhatTheCpuWould) {
  // The default performance on the Vulkan backend, whose frames search on the device with the last frame's list as
  // the history: after each of these frames the CPU's search on the same film and history lists the same pairs.
  // Frame 40: the bag being drawn; 80: mid-stroke, at its fastest; 110: the free bubble after the pinch-off.
  GB_REQUIRE_VULKAN(device);
  ContactHistory history;  // the list the last frame left, as Simulation keeps it
  const auto sim = test::playDefaultPerformanceOnDevice(device, [&](Simulation& played, const WandState&, int f) {
    const Params& p = played.params();
    const Film& film = played.film();
    if (test::checkedFrame(f)) {
      Film cpu = film;
      findContacts(p, p.frameTime, 0.005f, cpu, history);
      const std::string name = "the default performance at frame " + std::to_string(f);
      const size_t pairs = expectSameContacts(cpu.topology.contacts, film.topology.contacts, film.state.size(), name);
      if (f > 40) {
        EXPECT_GT(pairs, 1000u) << name;  // the bag being drawn has none yet
      }
    }
    history = {film.topology.contacts, film.state.size()};
  });
  const auto& record = dynamic_cast<const VulkanStepper&>(sim->stepper()).contactRecord();
  EXPECT_GE(record.searches, 111u);
  std::printf("%zu device searches, %zu grown, room for %u a row and %zu entries\n", record.searches, record.regrown,
              record.rowCapacity, record.entryCapacity);
}

}  // namespace
}  // namespace gb
