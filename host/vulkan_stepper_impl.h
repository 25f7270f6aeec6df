#pragma once
// The Vulkan stepper's device state (VulkanStepper::Impl) and the helpers its four source files share:
// vulkan_stepper.cpp (the device data: buffers, uploads and read-backs), vulkan_step_recording.cpp (the step's
// stages recorded into a command buffer), vulkan_contact_search.cpp (the self-collision search) and
// vulkan_film_probe.cpp (the frame's statistics, the film checks and the rest-length rules). Private to host/.

#include <array>
#include <span>
#include <vector>

#include "host/device_buffer.h"
#include "host/vulkan_context.h"
#include "host/vulkan_stepper.h"
#include "kernels/shared/shared_step.h"
#include "kernels/shared/spirv.h"
#include "topology/collision.h"

namespace gb {

using gpu::PushBlock;
using kernels::Kernel;
using enum gpu::Binding;

inline uint32_t ceilDiv(uint32_t n, uint32_t d) { return (n + d - 1) / d; }

// Makes every write of the dispatches recorded so far visible to the dispatches recorded after it: the
// one barrier kind the step needs (a stage reads what an earlier stage of this or the last step wrote).
inline void computeToComputeBarrier(const vk::raii::CommandBuffer& cb) {
  const vk::MemoryBarrier barrier(vk::AccessFlagBits::eShaderWrite,
                                  vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {}, barrier,
                     {}, {});
}

// Makes the transfers recorded so far (fills, copies, updates) visible to the dispatches recorded after it.
inline void transferToComputeBarrier(const vk::raii::CommandBuffer& cb) {
  const vk::MemoryBarrier barrier(vk::AccessFlagBits::eTransferWrite,
                                  vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, barrier, {},
                     {});
}

// Makes the last dispatches' writes visible to the host reading mapped memory after the fence.
inline void computeToHostBarrier(const vk::raii::CommandBuffer& cb) {
  const vk::MemoryBarrier barrier(vk::AccessFlagBits::eShaderWrite, vk::AccessFlagBits::eHostRead);
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eHost, {}, barrier, {}, {});
}

// Makes the last dispatches' writes visible to the copies recorded after it (a read-back into host-cached memory).
inline void computeToTransferBarrier(const vk::raii::CommandBuffer& cb) {
  const vk::MemoryBarrier barrier(vk::AccessFlagBits::eShaderWrite, vk::AccessFlagBits::eTransferRead);
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eTransfer, {}, barrier, {},
                     {});
}

// Makes the copies recorded so far visible to the copies recorded after it.
inline void transferToTransferBarrier(const vk::raii::CommandBuffer& cb) {
  const vk::MemoryBarrier barrier(vk::AccessFlagBits::eTransferWrite,
                                  vk::AccessFlagBits::eTransferRead | vk::AccessFlagBits::eTransferWrite);
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eTransfer, {}, barrier, {}, {});
}

// Makes the last copies visible to the host reading their destination after the fence.
inline void transferToHostBarrier(const vk::raii::CommandBuffer& cb) {
  const vk::MemoryBarrier barrier(vk::AccessFlagBits::eTransferWrite, vk::AccessFlagBits::eHostRead);
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eHost, {}, barrier, {}, {});
}

template <class T>
void writeVector(DeviceBuffer& buffer, const std::vector<T>& values) {
  buffer.write(values.data(), values.size() * sizeof(T));
}

// Ascending indices as runs of consecutive ones, [first, end): a region's particles lie in a few runs (a ring at the
// wire is numbered in order), each one range of a buffer.
struct IndexRun {
  uint32_t first, end;
};
std::vector<IndexRun> runsOf(std::span<const uint32_t> ascending);

// Indices the kernels read as floats from the reduce buffer (crowded_springs, rest_length_gather) are exact below this.
constexpr size_t kExactFloatIndices = size_t{1} << 24;

struct VulkanStepper::Impl {
  std::shared_ptr<const VulkanContext> ctx;
  uint32_t workgroup = 64;
  vk::raii::DescriptorSetLayout setLayout{nullptr};
  vk::raii::PipelineLayout pipelineLayout{nullptr};
  std::vector<vk::raii::ShaderModule> modules;
  std::vector<vk::raii::Pipeline> pipelines;
  vk::raii::CommandBuffer commands{nullptr};
  // The step's batch timed first and last, on a device whose clock the host reads (timestampsOnHostClock).
  vk::raii::QueryPool stepTimestamps{nullptr};
  std::optional<DeviceBusyInterval> lastStep;

  const Params* params = nullptr;  // the caller's, read at every recording (Stepper::load)
  Params paramsOnDevice;           // the block GB_BINDING_PARAMS holds, written again when the caller's changed
  uint32_t particles = 0, triangles = 0;
  uint32_t springs = 0;                                // of the mesh the device holds (writeConnectivity)
  std::array<DeviceBuffer, GB_BINDING_COUNT> buffers;  // indexed by binding; AIR_FLOW/NEXT are the two air
                                                       // buffers of descriptor set 0
  std::vector<uint32_t> colourOffset;                  // the implicit solver's colours (Topology::colourOffset)
  uint32_t patches = 0, solverParticles = 0;           // the coarse correction's P and M (kernels/step/coarse.glsl)
  uint32_t energyBase = 0;                             // where the energy budget's region of the reduce buffer starts
  size_t stepsCapacity = 0;
  vk::raii::DescriptorPool pool{nullptr};
  std::vector<vk::raii::DescriptorSet> sets;  // [0]: air A front, B back; [1]: swapped
  int airParity = 0;                          // which set is current (Jacobi swap of the air transfer)
  bool volumeInA = true;                      // where the last volume reduction left its result
  bool driftInA = true;                       // where external_drift's tree sum left the film's drift
  DeviceBuffer readback;                      // host-cached copy of the state store() brings back, and of reads
                                              // larger than kDirectReadBytes
  DeviceBuffer statisticsReadback;            // host-cached copy of the frame's statistics and checks (probeFilm)
  DeviceBuffer relayout;                      // the per-particle buffers' contents while a grown film's are laid out
  DeviceBuffer upload;                        // host memory the ranges updateRegion writes are copied from

  // The device contact search's room in the contacts buffer (shared_step.h's contact regions).
  VulkanStepperOptions options;
  bool contactsOnDevice;               // options.contactSearch resolved for this device
  bool statisticsOnDevice;             // options.statistics resolved for this device
  uint32_t contactEntryCapacity;       // C: partner entries of the list (kept as grown)
  uint32_t contactRowCapacity;         // K: partners of one particle (kept as grown: a film crumples again)
  uint32_t contactBuckets = 64;        // B
  size_t contactPreviousCapacity = 0;  // uints of the previous list's region
  size_t deviceListEntries = 0;        // uints of the list the last device search left at the start; 0: none there
  DeviceContactRecord contactRecord;
  DeviceReadback copiedToHost;  // every copy into host memory (readFrom)

  Impl(std::shared_ptr<const VulkanContext> context, VulkanStepperOptions stepperOptions);

  DeviceBuffer& buffer(int binding) { return buffers[static_cast<size_t>(binding)]; }
  // The buffer that holds the array of `binding` now: the air transfer's Jacobi swap exchanges the two air buffers.
  DeviceBuffer& holding(int binding) {
    if (airParity == 1 && binding == GB_BINDING_AIR_FLOW) return buffer(GB_BINDING_AIR_FLOW_NEXT);
    if (airParity == 1 && binding == GB_BINDING_AIR_FLOW_NEXT) return buffer(GB_BINDING_AIR_FLOW);
    return buffer(binding);
  }
  // The air buffer that currently holds the transferred air (the Jacobi front).
  DeviceBuffer& airFront() { return holding(GB_BINDING_AIR_FLOW); }

  // A buffer of `binding` with room for `bytes`. A film reloaded after merges or grown by a ring keeps its buffers
  // where they have room (allocating some 30 buffers took 3.3 ms of a 7.1 ms load on an H100): a new one has an
  // eighth more room, for the rings a growing film adds next, and one more than 4 times too large is made again.
  void ensureRoom(int binding, size_t bytes);

  void ensureStepCapacity(size_t count);

  // The mesh: the arrays that travel with it (alive flags), wire flags, triangles, rest lengths and the CSR one-ring.
  // A load writes it with the state and the contacts; a burst (updateTopology) writes only it, and the device's
  // contact list stays the next search's history.
  void writeMesh(const State& s, const Topology& t);
  // The mesh's connectivity, which only the host changes: wire flags, triangles, the CSR one-ring, the solver's lists
  // (updateRegion writes it with the region's rest lengths, keeping the device's own).
  void writeConnectivity(const Topology& t);
  // Room for the mesh's connectivity and the per-triangle and reduce buffers, for n particles.
  void ensureMeshRoom(const Topology& t, size_t n);

  // The per-particle buffers laid out for `count` particles (each holds `blocks` blocks of `particles` elements, and a
  // block's place moves with the count): copied on the device through `relayout`, old particles keeping their values.
  void layOutParticles(const std::array<int, GB_BINDING_COUNT>& blocks, uint32_t count);
  // A buffer of `binding` with room for `bytes` whose first `keptBytes` stay (copied on the device where it grows).
  void growKeeping(int binding, size_t bytes, size_t keptBytes);

  // The VelocityBudget implicit_velocity applies (ENERGY_VELOCITY_SCALE, ENERGY_CENTRE, ENERGY_SHIFT), as the energy
  // budget leaves it.
  [[nodiscard]] vk::DeviceSize velocityBudgetOffset() const {
    return (gpu::reduceEnergySlotsAt(energyBase, particles) + GB_SLOT_SCALE) * sizeof(float);
  }
  void writeVelocityBudget(const VelocityBudget& b);
  // A copy from device memory into host memory, counted in `copiedToHost`. More than a few KiB come through a copy
  // into the host-cached `readback` buffer: a discrete GPU's own memory read through its mapping (resizable BAR) is
  // uncached, about 0.5 GB/s on an H100, where reading the default film's contact list that way took 2.7 ms.
  void readFrom(const DeviceBuffer& from, void* to, vk::DeviceSize bytes, vk::DeviceSize offset = 0);
  void readThroughReadback(const DeviceBuffer& from, void* to, vk::DeviceSize bytes, vk::DeviceSize offset);
  // A range of a device buffer.
  struct DevicePart {
    const DeviceBuffer* from;
    vk::DeviceSize offset, bytes;
  };
  // Copies the parts one after the other into `readback` (grown to fit) in one submission, and waits for it.
  void copyIntoReadback(std::span<const DevicePart> parts);
  // A range of host memory and where it goes on the device.
  struct HostPart {
    const void* from;
    DeviceBuffer* to;
    vk::DeviceSize offset, bytes;
  };
  // Writes the parts through `upload` (grown to fit) in one submission, and waits for it: many small ranges cost one
  // submission, where a write to device-only memory costs one each.
  void writeThroughUpload(std::span<const HostPart> parts);
  // The parts that write every per-particle array of the particles in `runs`, and those that write the rest lengths
  // of the springs in `runs`, from the film in host memory.
  std::vector<HostPart> particleArrayParts(const State& s, std::span<const IndexRun> runs);
  void addRestLengthParts(std::vector<HostPart>& parts, const Topology& t, std::span<const IndexRun> runs);
  // The geometry and film state at the present positions (recordGeometryAtPresentPositions), submitted and waited for.
  void bringGeometryToPresentPositions();
  // A copy of `bytes` on the device, between the compute work before and after it.
  void copyOnDevice(const DeviceBuffer& from, vk::DeviceSize fromOffset, const DeviceBuffer& to,
                    vk::DeviceSize toOffset, vk::DeviceSize bytes);

  [[nodiscard]] VelocityBudget readVelocityBudget();

  // The implicit solver's colours and the coarse correction's patches (kernels/step/coarse.glsl), made with the mesh.
  void writeSolverLists(const Topology& t);

  // The self-collision contacts, found anew every frame (by the CPU here; by the device in findContacts).
  void writeContacts(const Topology& t);

  // The partner entries of a packed list for the loaded particles (Topology::contacts): N + 1 offsets, then two
  // uints an entry.
  [[nodiscard]] size_t partnerEntriesOf(const std::vector<uint32_t>& list) const {
    return list.size() > particles + size_t{1} ? (list.size() - particles) / 2 : 0;
  }
  [[nodiscard]] uint32_t contactHeader() const { return gpu::contactSearchAt(particles, contactEntryCapacity); }
  [[nodiscard]] gpu::ContactSearchLayout contactLayout() const {
    return gpu::contactSearchLayout(contactHeader(), particles, contactBuckets, contactRowCapacity);
  }
  // The contacts buffer's uints: the list, and the search's regions when the device searches.
  [[nodiscard]] size_t contactBufferUints() const {
    if (!contactsOnDevice) return contactHeader();
    return size_t{contactLayout().previous} + contactPreviousCapacity;
  }

  // Room for `entries` partner entries in the list and, searching on the device, a previous list of `previousUints`,
  // grown geometrically when short (contacts come and go). A new buffer keeps the list the device left at the start.
  void ensureContactRoom(size_t entries, size_t previousUints);

  // A copy of `uints` from `fromUint` in one contacts buffer to `toUint` in another (or the same, the two ranges
  // apart), on the device, between the searches' compute work.
  void copyContactUints(const DeviceBuffer& from, size_t fromUint, const DeviceBuffer& to, size_t toUint, size_t uints);

  void writeDescriptorSets();

  // One invocation per element of `count`.
  void dispatch(const vk::raii::CommandBuffer& cb, Kernel kernel, uint32_t count, uint32_t stepIndex,
                uint32_t flags = 0, uint32_t first = 0, float ruleShare = 0.0f);
  // One pass of a tree sum over n values: a workgroup for each 2^GB_TREE_PASS_LEVELS of them (tree_pass.glsl).
  void dispatchTreePass(const vk::raii::CommandBuffer& cb, Kernel kernel, uint32_t n, uint32_t stepIndex,
                        uint32_t flags, uint32_t first = 0);
  void dispatchGroups(const vk::raii::CommandBuffer& cb, Kernel kernel, uint32_t groups, uint32_t count,
                      uint32_t stepIndex, uint32_t flags = 0, uint32_t first = 0, float ruleShare = 0.0f);

  // Where the kernels that read the volume find it.
  [[nodiscard]] uint32_t volumeFlag() const { return volumeInA ? GB_REDUCE_VOLUME_IN_A : 0u; }

  // The volume's tree sum, at the current positions or at the step's start (the energy budget); ends with a
  // barrier, and volumeInA says which half holds the result.
  void recordVolume(const vk::raii::CommandBuffer& cb, uint32_t stepIndex, bool atStepStart);

  // The levels of treeSum over the energy terms' blocks (GB_REDUCE_DRIFT_ONLY: only the drift's first blocks); ends
  // with a barrier. Returns whether the sums are in half A.
  bool recordEnergyTreeSum(const vk::raii::CommandBuffer& cb, uint32_t stepIndex, uint32_t flags);

  // Stage energy_budget: the terms, the volumes before and after for a closed film, the terms' tree sum, the factor.
  void recordEnergyBudget(const vk::raii::CommandBuffer& cb, const StepUniforms& u, uint32_t stepIndex);

  // Records one stage. Stages of several passes record their own barriers between the passes.
  void recordStage(const vk::raii::CommandBuffer& cb, Stage stage, const StepUniforms& u, uint32_t stepIndex);

  // One step: the rows of stepStages() that run, each followed by its barrier where the table gives one.
  void recordStep(const vk::raii::CommandBuffer& cb, const StepUniforms& u, uint32_t stepIndex);
  // Reads `live` at every recording from now on (the caller's, Stepper::load) and writes it to GB_BINDING_PARAMS.
  void useParams(const Params& live);

  // The steps' uniforms into GB_BINDING_STEPS, and the parameters into GB_BINDING_PARAMS where they changed since
  // they were last written (a live change, Simulation::setFrameTime).
  void uploadSteps(std::span<const StepUniforms> steps);

  // The exclusive prefix sum of `count` uints of the contacts buffer (GB_SCAN_ROWS in flags: the partner counts, else
  // the bucket counts) in its three passes; ends with a barrier.
  void recordContactScan(const vk::raii::CommandBuffer& cb, uint32_t count, uint32_t flags);

  // The header the device search starts from (shared_step.h's GB_CONTACT_* slots).
  [[nodiscard]] std::array<uint32_t, GB_CONTACT_HEADER> contactSearchHeader(float frameTime, float slack,
                                                                            uint32_t previousParticles) const;

  // One device search (kernels/contacts/contact_*.comp) into the contacts buffer, with the previous list the history's,
  // or the device's own last list when the history is that one (copied on the device instead of uploaded).
  void searchContacts(float frameTime, float slack, const ContactHistory& history);

  // Whether the last search's rows and list had room for every partner; if not, grows them to what it found or
  // twice what they had and says so on stderr. The search has written over the list at the buffer's start: where it
  // read the device's own list as its history (history.onDevice), that list goes back there from the copy the search
  // read, on the device (the grown buffer keeps it, and the search again copies it as its history); otherwise the
  // list there is no longer the last one.
  bool contactSearchHadRoom(const ContactHistory& history);

  // The size of the list the device search left (its partner entries, the last offset): deviceListEntries.
  void countContactList();

  // The list the last search left, into `contacts` (Topology::contacts).
  void readContactList(std::vector<uint32_t>& contacts);

  // The geometry and the film state at the film's present positions (the stages geometry and film_state with the
  // uniforms u, whose dt is 0), as CpuStepper::refreshGeometry makes them in host memory; ends with a barrier.
  void recordGeometryAtPresentPositions(const vk::raii::CommandBuffer& cb, const StepUniforms& u);

  // The frame's statistics and film checks: with probe.atPresentPositions the geometry and the film state at the
  // film's present positions first (what CpuStepper::refreshGeometry does to a film in host memory: the next step's
  // first stages compute the same), then the terms and their tree, then the sums read back.
  std::array<float, GB_STATISTICS_TERMS> sumStatistics(const FilmProbe& probe);

  // A rest-length rule between steps (film_rest_lengths, GB_RULE_*) on the device, where the statistics are reduced.
  bool runSpringRule(uint32_t rule, float share = 0.0f);

  float readVolume();
};

}  // namespace gb
