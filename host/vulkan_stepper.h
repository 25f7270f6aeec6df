#pragma once
// The Vulkan backend: the stages of cpu-reference/stages/stages.h as compute shaders (kernels/) over one storage
// buffer per attribute. A batch of substeps is recorded into one command buffer and submitted once, with a
// barrier only where a stage reads what an earlier one wrote. Topology stays on the CPU: load() takes a
// changed film, store() brings the state back; for a ring at the wire storeRegion() and updateRegion() move only the
// region film growth reads and changes, and the new ring. The self-collision contacts are found on the device
// (findContacts; kernels/contacts/contact_*.comp), where the sweeps read them.

#include <memory>
#include <optional>

#include "host/busy_interval.h"
#include "host/device_film.h"
#include "stages/stepper.h"
#include "topology/device_residency.h"

namespace gb {

class VulkanContext;

// Where a part of a frame's work between steps runs.
enum class WorkPlace {
  Automatic,  // on the device, unless the Vulkan device is a CPU driver (lavapipe), where the CPU does it faster
              // (docs/performance.md)
  Device,     // on the device
  Cpu,        // on the CPU, from the state read back, as the reference does
};

struct VulkanStepperOptions {
  // The self-collision search: on the device (findContacts), where the sweeps read the list, or the CPU's, handed
  // over (updateContacts). A CPU driver searches 13 to 36 times slower than the CPU's own search.
  WorkPlace contactSearch = WorkPlace::Automatic;
  // The frame's statistics, the film checks of the rules between steps and the yield of stretched springs: on the
  // device (probeFilm, a few floats read back; yieldStretchedSprings), or by the caller from the state read back.
  WorkPlace statistics = WorkPlace::Automatic;
  // The room the device search starts with after a load: partners of one particle, and partner entries of the whole
  // list (0: one per particle). A search that finds more grows them and runs again (DeviceContactRecord::regrown).
  uint32_t contactRowCapacity = 16;
  uint32_t contactEntryCapacity = 0;
};

// What the device contact search has done since the stepper was made: its searches, how many of them found a row or
// the whole list short of room and ran again in a larger buffer (each also reported on stderr), and its room now.
struct DeviceContactRecord {
  size_t searches = 0;
  size_t regrown = 0;
  uint32_t rowCapacity = 0;  // partners a particle has room for
  size_t entryCapacity = 0;  // partner entries the list has room for
};

class VulkanStepper final : public Stepper, public DeviceResidency {
 public:
  explicit VulkanStepper(std::shared_ptr<const VulkanContext> context, VulkanStepperOptions options = {});
  ~VulkanStepper() override;
  VulkanStepper(const VulkanStepper&) = delete;  // owns device objects
  VulkanStepper& operator=(const VulkanStepper&) = delete;

  [[nodiscard]] std::string name() const override;
  void load(const Params& params, Film& film) override;
  float run(std::span<const StepUniforms> substeps) override;
  float runStage(Stage stage, const StepUniforms& uniforms) override;
  DeviceResidency* device() override { return this; }

  // DeviceResidency:
  void store(Film& film) override;
  void storePositions(Film& film) override;
  void storeParticleArrays(Film& film, std::initializer_list<const void*> arrays) override;
  void updateContacts(const Film& film) override;
  // The search of findContacts (collision.h) on the device: cells hashed and counting-sorted, each particle gathering
  // its partners by the same pair rule; the list stays on the device for the sweeps and is read back into
  // film.topology.contacts (the CPU's impact test and the history kept across a reload read it). `history` is taken
  // to be the list the last search left when it is that list's size (Simulation keeps it so); the device then reads
  // its own copy. False when the options say the CPU searches.
  bool findContacts(const Params& params, float frameTime, float slack, Film& film,
                    const ContactHistory& history) override;
  [[nodiscard]] const DeviceContactRecord& contactRecord() const;
  bool findContactsOnDevice(const Params& params, float frameTime, float slack, const ContactHistory& history) override;
  void storeContacts(Film& film) override;
  // On the device (film_rest_lengths) where options.statistics says so.
  bool yieldStretchedSprings() override;
  bool payOutFilmAtWire() override;
  bool contractSlackSprings(float share) override;
  void storeRestLengths(Film& film) override;
  // On the device (film_statistics_terms, film_statistics_tree) where options.statistics says so.
  bool probeFilm(const FilmProbe& probe, FilmSums& sums, FilmChecks& checks) override;
  [[nodiscard]] DeviceReadback readback() const override;
  void updateRestLengths(const Film& film) override;
  bool updateTopology(const Params& params, Film& film) override;
  // The region's ranges copied into host-cached memory in one submission, and the region's changes written in
  // ranges; the per-particle buffers of a grown film laid out for the new count by copies on the device.
  bool storeRegion(Film& film, std::span<const uint32_t> particles, std::span<const uint32_t> springs) override;
  bool storeParticleArraysOf(Film& film, std::span<const uint32_t> particles, std::initializer_list<const void*> arrays,
                             std::span<const uint32_t> springs) override;
  // On the device (crowded_springs, rest_length_gather) where options.statistics says so.
  bool findCrowdedSprings(CrowdedCandidates& found) override;
  bool updateMergedRegion(const Params& params, Film& film, std::span<const uint32_t> particles,
                          std::span<const uint32_t> from) override;
  void refreshGeometry() override;
  bool updateRegion(const Params& params, Film& film, std::span<const uint32_t> particles, size_t firstNewParticle,
                    std::span<const uint32_t> springs, size_t firstNewSpring) override;

  [[nodiscard]] const VulkanContext& context() const;
  // When the device ran the last step's batch (run), on the host's clock: a batch submitted behind a frame being
  // drawn waits in the queue before it starts. Empty before a step, and on a device whose timestamps the host cannot
  // read (VulkanContext::timestampsOnHostClock).
  [[nodiscard]] std::optional<DeviceBusyInterval> lastStepOnDevice() const;
  // The film's buffers as the last batch left them, for a renderer on the same device to copy there.
  [[nodiscard]] DeviceFilm deviceFilm();
  // The device, for a renderer that copies deviceFilm() there.
  [[nodiscard]] std::shared_ptr<const VulkanContext> sharedContext() const;

 private:
  // Copies the per-particle arrays that chosen(array, info) picks of those store() brings back, of the particles listed
  // (of every particle with everyParticle), and the rest lengths of the springs listed, from the device into the film,
  // run by run.
  template <class Chosen>
  void storeRuns(Film& film, std::span<const uint32_t> particles, std::span<const uint32_t> springs, Chosen&& chosen,
                 bool everyParticle = false);

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gb
