#include "vulkan_stepper.h"

#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <vector>

#include "coarse_correction.h"
#include "collision.h"
#include "colouring.h"
#include "device_buffer.h"
#include "implicit_euler.h"
#include "shared_step.h"
#include "spirv.h"
#include "vulkan_context.h"

namespace gb {

using gpu::PushBlock;
using gpu::StepUniformsBlock;
using kernels::Kernel;
using enum gpu::Binding;

// The shared layouts are what the shaders expect (kernels/shared_step.h): sizes and the offsets std430
// gives the same declarations.
static_assert(sizeof(StepUniformsBlock) == 176 && offsetof(StepUniformsBlock, dt) == 128 &&
              offsetof(StepUniformsBlock, wireKind) == 156 && offsetof(StepUniformsBlock, closed) == 160);
static_assert(sizeof(PushBlock) == 36);
static_assert(alignof(Params) == 4 && sizeof(Params) % 4 == 0,
              "Params must stay a block of 4-byte scalars, whose std430 layout is the C layout");

namespace {

bool worksOnDevice(WorkPlace place, const VulkanDeviceInfo& device) {
  if (place == WorkPlace::Automatic) return device.type != "CPU";
  return place == WorkPlace::Device;
}

gpu::vec4 toVec4(const Vec3& v) { return {v.x(), v.y(), v.z(), 0.0f}; }

StepUniformsBlock toBlock(const StepUniforms& u) {
  StepUniformsBlock b{};
  b.leftPosition = toVec4(u.wands.leftPosition);
  b.leftVelocity = toVec4(u.wands.leftVelocity);
  b.rightPosition = toVec4(u.wands.rightPosition);
  b.rightVelocity = toVec4(u.wands.rightVelocity);
  b.wireCenter = toVec4(u.wireNext.center);
  b.wireAxis = toVec4(u.wireNext.axis);
  b.wireDown = toVec4(u.wireNext.down);
  b.volumeOrigin = toVec4(u.volumeOrigin);
  b.dt = u.dt;
  b.leftInflowWeight = u.leftInflowWeight;
  b.airVolume = u.airVolume;
  b.wandAlignment = u.wandAlignment;
  b.wireHalfWidth = u.wireNext.halfWidth;
  b.wireDepth = u.wireNext.depth;
  b.referenceVolume = u.referenceVolume;
  b.wireKind = static_cast<int>(u.wireNext.kind);
  b.closed = u.closed;
  b.drainageDt = u.drainageDt;
  b.wireArea = u.wireArea;
  b.frameTime = u.frameTime;
  return b;
}

uint32_t ceilDiv(uint32_t n, uint32_t d) { return (n + d - 1) / d; }

// Reads up to this size go through the buffer's mapping: a copy's submission and wait cost more than reading a few
// KiB at uncached speed.
constexpr vk::DeviceSize kDirectReadBytes = 16 * 1024;

// Makes every write of the dispatches recorded so far visible to the dispatches recorded after it: the
// one barrier kind the step needs (a stage reads what an earlier stage of this or the last step wrote).
void computeToComputeBarrier(const vk::raii::CommandBuffer& cb) {
  const vk::MemoryBarrier barrier(vk::AccessFlagBits::eShaderWrite,
                                  vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {}, barrier,
                     {}, {});
}

// Makes the transfers recorded so far (fills, copies, updates) visible to the dispatches recorded after it.
void transferToComputeBarrier(const vk::raii::CommandBuffer& cb) {
  const vk::MemoryBarrier barrier(vk::AccessFlagBits::eTransferWrite,
                                  vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, barrier, {},
                     {});
}

// Makes the last dispatches' writes visible to the host reading mapped memory after the fence.
void computeToHostBarrier(const vk::raii::CommandBuffer& cb) {
  const vk::MemoryBarrier barrier(vk::AccessFlagBits::eShaderWrite, vk::AccessFlagBits::eHostRead);
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eHost, {}, barrier, {}, {});
}

// Makes the last dispatches' writes visible to the copies recorded after it (a read-back into host-cached memory).
void computeToTransferBarrier(const vk::raii::CommandBuffer& cb) {
  const vk::MemoryBarrier barrier(vk::AccessFlagBits::eShaderWrite, vk::AccessFlagBits::eTransferRead);
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eTransfer, {}, barrier, {},
                     {});
}

// Makes the last copies visible to the host reading their destination after the fence.
void transferToHostBarrier(const vk::raii::CommandBuffer& cb) {
  const vk::MemoryBarrier barrier(vk::AccessFlagBits::eTransferWrite, vk::AccessFlagBits::eHostRead);
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eHost, {}, barrier, {}, {});
}

template <class T>
void writeVector(DeviceBuffer& buffer, const std::vector<T>& values) {
  buffer.write(values.data(), values.size() * sizeof(T));
}

// A per-particle array of State into its buffer, from its first block on (device_data.h).
template <class Array>
void writeParticleArray(DeviceBuffer& buffer, const Array& array, const ParticleArrayInfo& info, size_t particles) {
  const size_t bytes = particles * sizeof(float);  // float and uint32_t alike
  forEachComponent(array, [&](const auto& values, int c) {
    buffer.write(values.data(), bytes, static_cast<size_t>(info.block + c) * bytes);
  });
}

// The solver's list buffer: colour order, then the patch lists (kernels/coarse.glsl); at least one entry.
size_t solverListEntries(const Topology& t) {
  return std::max<size_t>(1, t.colourOrder.size() + t.patchOf.size() + t.patchOffset.size() + t.patchMembers.size() +
                                 t.patchRowOffset.size() + t.patchRow.size());
}

// The reduce buffer's regions (shared_step.h): where the energy terms start for this mesh, and the whole size.
uint32_t energyTermsAt(const Topology& t) {
  const size_t patches = t.patchOffset.empty() ? 0 : t.patchOffset.size() - 1;
  return gpu::reduceEnergyTermsAt(static_cast<uint32_t>(t.triangleCount()), static_cast<uint32_t>(t.patchRow.size()),
                                  static_cast<uint32_t>(patches));
}
size_t reduceFloats(const Topology& t, size_t particles) {
  return gpu::reduceFloatsWith(energyTermsAt(t), static_cast<uint32_t>(particles));
}
// The VelocityBudget's slots, GB_SLOT_SCALE to GB_SLOT_RELEASED.
constexpr size_t kBudgetSlots = GB_SLOT_RELEASED - GB_SLOT_SCALE + 1;

// The device contact search's buckets for n particles: twice as many as particles, a power of two, as the CPU's
// table has for a film whose cells are fewer than its particles.
uint32_t contactBucketsFor(size_t particles) {
  uint32_t buckets = 64;
  while (buckets < 2 * particles) buckets *= 2;
  return buckets;
}

}  // namespace

struct VulkanStepper::Impl {
  std::shared_ptr<const VulkanContext> ctx;
  uint32_t workgroup = 64;
  vk::raii::DescriptorSetLayout setLayout{nullptr};
  vk::raii::PipelineLayout pipelineLayout{nullptr};
  std::vector<vk::raii::ShaderModule> modules;
  std::vector<vk::raii::Pipeline> pipelines;
  vk::raii::CommandBuffer commands{nullptr};

  Params params;
  uint32_t particles = 0, triangles = 0;
  std::array<DeviceBuffer, GB_BINDING_COUNT> buffers;  // indexed by binding; AIR_FLOW/NEXT are the two air
                                                       // buffers of descriptor set 0
  std::vector<uint32_t> colourOffset;                  // the implicit solver's colours (Topology::colourOffset)
  uint32_t patches = 0, solverParticles = 0;           // the coarse correction's P and M (kernels/coarse.glsl)
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

  Impl(std::shared_ptr<const VulkanContext> context, VulkanStepperOptions stepperOptions)
      : ctx(std::move(context)),
        options(stepperOptions),
        contactsOnDevice(worksOnDevice(stepperOptions.contactSearch, ctx->info())),
        statisticsOnDevice(worksOnDevice(stepperOptions.statistics, ctx->info())),
        contactEntryCapacity(stepperOptions.contactEntryCapacity),
        contactRowCapacity(std::max(1u, stepperOptions.contactRowCapacity)) {
    const vk::raii::Device& device = ctx->device;
    workgroup = ctx->preferredWorkgroupSize();
    std::vector<vk::DescriptorSetLayoutBinding> bindings;
    for (uint32_t b = 0; b < GB_BINDING_COUNT; ++b)
      bindings.emplace_back(b, vk::DescriptorType::eStorageBuffer, 1, vk::ShaderStageFlagBits::eCompute);
    setLayout = vk::raii::DescriptorSetLayout(device, vk::DescriptorSetLayoutCreateInfo({}, bindings));
    const vk::PushConstantRange pushRange(vk::ShaderStageFlagBits::eCompute, 0, sizeof(PushBlock));
    const vk::DescriptorSetLayout layoutHandle = *setLayout;
    pipelineLayout = vk::raii::PipelineLayout(device, vk::PipelineLayoutCreateInfo({}, layoutHandle, pushRange));
    const vk::SpecializationMapEntry entry(0, 0, sizeof(uint32_t));
    const vk::SpecializationInfo specialization(1, &entry, sizeof(uint32_t), &workgroup);
    for (int k = 0; k < kernels::kKernelCount; ++k) {
      const auto code = kernels::spirv(static_cast<Kernel>(k));
      modules.emplace_back(device, vk::ShaderModuleCreateInfo({}, code.size_bytes(), code.data()));
      const vk::PipelineShaderStageCreateInfo stage({}, vk::ShaderStageFlagBits::eCompute, *modules.back(), "main",
                                                    &specialization);
      pipelines.emplace_back(device, nullptr, vk::ComputePipelineCreateInfo({}, stage, *pipelineLayout));
    }
    commands = ctx->newCommandBuffer();
  }

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
  void ensureRoom(int binding, size_t bytes) {
    DeviceBuffer& b = buffer(binding);
    if (b.size() >= bytes && b.size() <= 4 * std::max<size_t>(bytes, 16)) return;
    b = DeviceBuffer(*ctx, bytes + bytes / 8);
  }

  void ensureStepCapacity(size_t count) {
    if (count <= stepsCapacity) return;
    stepsCapacity = std::max<size_t>(count, 2 * stepsCapacity);
    buffer(GB_BINDING_STEPS) = DeviceBuffer(*ctx, stepsCapacity * sizeof(StepUniformsBlock));
    writeDescriptorSets();
  }

  // The mesh: the arrays that travel with it (alive flags), wire flags, triangles, rest lengths, the CSR one-ring and
  // the contacts. A load writes it with the state; a burst (updateTopology) writes only it.
  void writeMesh(const State& s, const Topology& t) {
    forEachParticleArray(s, [&](const auto& array, const ParticleArrayInfo& info) {
      if (info.transfer == Transfer::WithMesh) writeParticleArray(buffer(info.binding), array, info, s.size());
    });
    writeVector(buffer(GB_BINDING_BOUNDARY), t.boundary);
    writeVector(buffer(GB_BINDING_TRIANGLES), t.triangles);
    writeVector(buffer(GB_BINDING_REST_LENGTH), t.restLength);
    writeVector(buffer(GB_BINDING_SPRING_OFFSET), t.springOffset);
    writeVector(buffer(GB_BINDING_SPRING_INDEX), t.springIndex);
    writeVector(buffer(GB_BINDING_SPRING_NEIGHBOUR), t.springNeighbour);
    writeVector(buffer(GB_BINDING_TRIANGLE_OFFSET), t.triangleOffset);
    writeVector(buffer(GB_BINDING_TRIANGLE_CORNER), t.triangleCorner);
    writeSolverLists(t);
    writeContacts(t);
    energyBase = energyTermsAt(t);
    writeVelocityBudget({});  // no budget has run on this mesh yet
  }

  // The VelocityBudget implicit_velocity applies (ENERGY_VELOCITY_SCALE, ENERGY_CENTRE, ENERGY_SHIFT), as the energy
  // budget leaves it.
  [[nodiscard]] vk::DeviceSize velocityBudgetOffset() const {
    return (gpu::reduceEnergySlotsAt(energyBase, particles) + GB_SLOT_SCALE) * sizeof(float);
  }
  void writeVelocityBudget(const VelocityBudget& b) {
    std::array<float, kBudgetSlots> slots{};
    slots[GB_SLOT_SCALE - GB_SLOT_SCALE] = b.scale;
    for (int c = 0; c < 3; ++c) {
      slots[GB_SLOT_CENTRE - GB_SLOT_SCALE + c] = b.centre[c];
      slots[GB_SLOT_SHIFT - GB_SLOT_SCALE + c] = b.shift[c];
    }
    slots[GB_SLOT_RELEASED - GB_SLOT_SCALE] = b.released;
    buffer(GB_BINDING_REDUCE).write(slots.data(), sizeof slots, velocityBudgetOffset());
  }
  // A copy from device memory into host memory, counted in `copiedToHost`. More than a few KiB come through a copy
  // into the host-cached `readback` buffer: a discrete GPU's own memory read through its mapping (resizable BAR) is
  // uncached, about 0.5 GB/s on an H100, where reading the default film's contact list that way took 2.7 ms.
  void readFrom(const DeviceBuffer& from, void* to, vk::DeviceSize bytes, vk::DeviceSize offset = 0) {
    if (&from == &readback || bytes <= kDirectReadBytes)
      from.read(to, bytes, offset);
    else
      readThroughReadback(from, to, bytes, offset);
    copiedToHost.bytes += bytes;
  }
  void readThroughReadback(const DeviceBuffer& from, void* to, vk::DeviceSize bytes, vk::DeviceSize offset) {
    copyIntoReadback(std::array{DevicePart{&from, offset, bytes}});
    readback.read(to, bytes);
  }
  // A range of a device buffer.
  struct DevicePart {
    const DeviceBuffer* from;
    vk::DeviceSize offset, bytes;
  };
  // Copies the parts one after the other into `readback` (grown to fit) in one submission, and waits for it.
  void copyIntoReadback(std::span<const DevicePart> parts) {
    vk::DeviceSize total = 0;
    for (const DevicePart& part : parts) total += part.bytes;
    // Grown with room to spare: a film growing at its wire brings back a little more each time, and a new
    // allocation of host memory for each cost milliseconds at 100,000 particles.
    if (readback.size() < total) readback = DeviceBuffer(*ctx, total + total / 2, DeviceBuffer::Placement::Readback);
    const vk::raii::CommandBuffer& cb = commands;
    cb.reset();
    cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    computeToTransferBarrier(cb);
    vk::DeviceSize at = 0;
    for (const DevicePart& part : parts) {
      readback.recordCopyFrom(cb, *part.from, part.offset, part.bytes, at);
      at += part.bytes;
    }
    transferToHostBarrier(cb);
    cb.end();
    ctx->submitAndWait(cb);
  }

  [[nodiscard]] VelocityBudget readVelocityBudget() {
    std::array<float, kBudgetSlots> slots{};
    readFrom(buffer(GB_BINDING_REDUCE), slots.data(), sizeof slots, velocityBudgetOffset());
    const auto at = [&](int slot) { return slots[static_cast<size_t>(slot - GB_SLOT_SCALE)]; };
    return {at(GB_SLOT_SCALE), Vec3(at(GB_SLOT_CENTRE), at(GB_SLOT_CENTRE + 1), at(GB_SLOT_CENTRE + 2)),
            Vec3(at(GB_SLOT_SHIFT), at(GB_SLOT_SHIFT + 1), at(GB_SLOT_SHIFT + 2)), at(GB_SLOT_RELEASED)};
  }

  // The implicit solver's colours and the coarse correction's patches (kernels/coarse.glsl), made with the mesh.
  void writeSolverLists(const Topology& t) {
    std::vector<uint32_t> lists = t.colourOrder;
    for (const std::vector<uint32_t>* list :
         {&t.patchOf, &t.patchOffset, &t.patchMembers, &t.patchRowOffset, &t.patchRow})
      lists.insert(lists.end(), list->begin(), list->end());
    writeVector(buffer(GB_BINDING_COLOUR_ORDER), lists);
    colourOffset = t.colourOffset;
    patches = t.patchOffset.empty() ? 0u : static_cast<uint32_t>(t.patchOffset.size() - 1);
    solverParticles = static_cast<uint32_t>(t.colourOrder.size());
  }

  // The self-collision contacts, found anew every frame (by the CPU here; by the device in findContacts).
  void writeContacts(const Topology& t) {
    deviceListEntries = 0;  // replaced by this one
    ensureContactRoom(partnerEntriesOf(t.contacts), 0);
    writeVector(buffer(GB_BINDING_CONTACTS), t.contacts);
  }

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
  void ensureContactRoom(size_t entries, size_t previousUints) {
    if (entries > contactEntryCapacity)
      contactEntryCapacity = static_cast<uint32_t>(std::max<size_t>(entries, 2 * size_t{contactEntryCapacity}));
    contactBuckets = contactBucketsFor(particles);
    const size_t listUints = gpu::contactSearchAt(particles, contactEntryCapacity);  // what a device copy copies
    contactPreviousCapacity = std::max({contactPreviousCapacity, previousUints, listUints});
    contactRecord.rowCapacity = contactRowCapacity;
    contactRecord.entryCapacity = contactEntryCapacity;
    const size_t bytes = contactBufferUints() * sizeof(uint32_t);
    if (bytes <= buffer(GB_BINDING_CONTACTS).size()) return;
    DeviceBuffer grown(*ctx, bytes);
    copyContactUints(buffer(GB_BINDING_CONTACTS), 0, grown, 0, deviceListEntries);  // the device's list stays
    buffer(GB_BINDING_CONTACTS) = std::move(grown);
    writeDescriptorSets();
  }

  // A copy of `uints` from `fromUint` in one contacts buffer to `toUint` in another (or the same, the two ranges
  // apart), on the device, between the searches' compute work.
  void copyContactUints(const DeviceBuffer& from, size_t fromUint, const DeviceBuffer& to, size_t toUint,
                        size_t uints) {
    if (uints == 0) return;
    const vk::raii::CommandBuffer& cb = commands;
    cb.reset();
    cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    computeToTransferBarrier(cb);
    to.recordCopyFrom(cb, from, fromUint * sizeof(uint32_t), uints * sizeof(uint32_t), toUint * sizeof(uint32_t));
    transferToComputeBarrier(cb);
    cb.end();
    ctx->submitAndWait(cb);
  }

  void writeDescriptorSets() {
    if (sets.empty()) return;  // load() writes them once it has made every buffer
    std::vector<vk::DescriptorBufferInfo> infos;
    infos.reserve(2 * GB_BINDING_COUNT);
    std::vector<vk::WriteDescriptorSet> writes;
    for (int set = 0; set < 2; ++set)
      for (int b = 0; b < GB_BINDING_COUNT; ++b) {
        int source = b;  // set 1 swaps the two air buffers
        if (set == 1 && b == GB_BINDING_AIR_FLOW) source = GB_BINDING_AIR_FLOW_NEXT;
        if (set == 1 && b == GB_BINDING_AIR_FLOW_NEXT) source = GB_BINDING_AIR_FLOW;
        infos.emplace_back(buffer(source).handle(), 0, VK_WHOLE_SIZE);
        writes.emplace_back(*sets[static_cast<size_t>(set)], static_cast<uint32_t>(b), 0, 1,
                            vk::DescriptorType::eStorageBuffer, nullptr, &infos.back());
      }
    ctx->device.updateDescriptorSets(writes, nullptr);
  }

  // One invocation per element of `count`.
  void dispatch(const vk::raii::CommandBuffer& cb, Kernel kernel, uint32_t count, uint32_t stepIndex,
                uint32_t flags = 0, uint32_t first = 0, float ruleShare = 0.0f) {
    dispatchGroups(cb, kernel, ceilDiv(count, workgroup), count, stepIndex, flags, first, ruleShare);
  }
  // One pass of a tree sum over n values: a workgroup for each 2^GB_TREE_PASS_LEVELS of them (tree_pass.glsl).
  void dispatchTreePass(const vk::raii::CommandBuffer& cb, Kernel kernel, uint32_t n, uint32_t stepIndex,
                        uint32_t flags, uint32_t first = 0) {
    dispatchGroups(cb, kernel, gpu::treePassOutputs(n), n, stepIndex, flags, first);
  }
  void dispatchGroups(const vk::raii::CommandBuffer& cb, Kernel kernel, uint32_t groups, uint32_t count,
                      uint32_t stepIndex, uint32_t flags = 0, uint32_t first = 0, float ruleShare = 0.0f) {
    cb.bindPipeline(vk::PipelineBindPoint::eCompute, *pipelines[static_cast<size_t>(kernel)]);
    const vk::DescriptorSet set = *sets[static_cast<size_t>(airParity)];
    cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipelineLayout, 0, set, {});
    const PushBlock push{count, particles, stepIndex, flags, triangles, first, patches, solverParticles, ruleShare};
    cb.pushConstants<PushBlock>(*pipelineLayout, vk::ShaderStageFlagBits::eCompute, 0, push);
    cb.dispatch(groups, 1, 1);
  }

  // Where the kernels that read the volume find it.
  [[nodiscard]] uint32_t volumeFlag() const { return volumeInA ? GB_REDUCE_VOLUME_IN_A : 0u; }

  // The volume's tree sum, at the current positions or at the step's start (the energy budget); ends with a
  // barrier, and volumeInA says which half holds the result.
  void recordVolume(const vk::raii::CommandBuffer& cb, uint32_t stepIndex, bool atStepStart) {
    dispatch(cb, Kernel::TriangleVolume, triangles, stepIndex, atStepStart ? GB_REDUCE_AT_STEP_START : 0u);
    computeToComputeBarrier(cb);
    bool fromA = true;
    for (uint32_t n = triangles; n > 1; n = gpu::treePassOutputs(n)) {  // the passes of treeSum
      dispatchTreePass(cb, Kernel::TreeSum, n, stepIndex, fromA ? GB_REDUCE_VOLUME_IN_A : 0u);
      computeToComputeBarrier(cb);
      fromA = !fromA;
    }
    volumeInA = fromA;
  }

  // The levels of treeSum over the energy terms' blocks (GB_REDUCE_DRIFT_ONLY: only the drift's first blocks); ends
  // with a barrier. Returns whether the sums are in half A.
  bool recordEnergyTreeSum(const vk::raii::CommandBuffer& cb, uint32_t stepIndex, uint32_t flags) {
    bool fromA = true;
    for (uint32_t n = particles; n > 1; n = gpu::treePassOutputs(n)) {
      dispatchTreePass(cb, Kernel::EnergyTreeSum, n, stepIndex, (fromA ? GB_REDUCE_ENERGY_IN_A : 0u) | flags,
                       energyBase);
      computeToComputeBarrier(cb);
      fromA = !fromA;
    }
    return fromA;
  }

  // Stage energy_budget: the terms, the volumes before and after for a closed film, the terms' tree sum, the factor.
  void recordEnergyBudget(const vk::raii::CommandBuffer& cb, const StepUniforms& u, uint32_t stepIndex) {
    if (u.closed) recordVolume(cb, stepIndex, true);  // energy_terms keeps it
    dispatch(cb, Kernel::EnergyTerms, particles, stepIndex, volumeInA ? GB_REDUCE_VOLUME_IN_A : 0u, energyBase);
    computeToComputeBarrier(cb);                       // the terms are written, the volume before is kept
    if (u.closed) recordVolume(cb, stepIndex, false);  // the volume after: the gas's change, the step's pressure
    const bool fromA = recordEnergyTreeSum(cb, stepIndex, 0);
    dispatch(cb, Kernel::EnergyScale, 1, stepIndex,
             (fromA ? GB_REDUCE_ENERGY_IN_A : 0u) | (volumeInA ? GB_REDUCE_VOLUME_IN_A : 0u), energyBase);
  }

  // Records one stage. Stages of several passes record their own barriers between the passes.
  void recordStage(const vk::raii::CommandBuffer& cb, Stage stage, const StepUniforms& u, uint32_t stepIndex) {
    switch (stage) {
      case Stage::Geometry:
        dispatch(cb, Kernel::TriangleGeometry, triangles, stepIndex);
        computeToComputeBarrier(cb);  // every triangle is done before any particle gathers
        dispatch(cb, Kernel::VertexGeometry, particles, stepIndex);
        break;
      case Stage::Volume:
        recordVolume(cb, stepIndex, false);
        break;
      case Stage::FilmState:
        dispatch(cb, Kernel::FilmState, particles, stepIndex);
        break;
      case Stage::AirInflow:
        dispatch(cb, Kernel::AirInflow, particles, stepIndex);
        break;
      case Stage::AirTransfer:
        dispatch(cb, Kernel::AirTransfer, particles, stepIndex);
        airParity = 1 - airParity;  // later dispatches see the new air as the front buffer
        break;
      case Stage::Forces:
        dispatch(cb, Kernel::Forces, particles, stepIndex, volumeFlag());
        break;
      case Stage::Integrate:
        dispatch(cb, Kernel::Integrate, particles, stepIndex);
        break;
      case Stage::ExternalForces:
        dispatch(cb, Kernel::ExternalForces, particles, stepIndex, volumeFlag());
        break;
      case Stage::ExternalDrift:
        dispatch(cb, Kernel::ExternalDrift, particles, stepIndex, 0, energyBase);
        computeToComputeBarrier(cb);  // every term is written before the sum reads it
        driftInA = recordEnergyTreeSum(cb, stepIndex, GB_REDUCE_DRIFT_ONLY);
        break;
      case Stage::ImplicitPredict:
        dispatch(cb, Kernel::ImplicitPredict, particles, stepIndex, driftInA ? GB_REDUCE_ENERGY_IN_A : 0u, energyBase);
        break;
      case Stage::VertexBlockDescent: {
        const int coarseAfter = coarseSweepsBefore(params, u);
        for (int sweep = 0; sweep < sweepsThisStep(params, u); ++sweep) {
          if (sweep > 0) computeToComputeBarrier(cb);  // the volume and the next colours read the last positions
          if (sweep == coarseAfter) {
            recordStage(cb, Stage::CoarseCorrection, u, stepIndex);
            computeToComputeBarrier(cb);  // the sweeps read the corrected positions
          }
          if (u.closed) recordStage(cb, Stage::Volume, u, stepIndex);  // this iterate's volume; ends with a barrier
          for (size_t c = 0; c + 1 < colourOffset.size(); ++c) {
            if (c > 0) computeToComputeBarrier(cb);  // the next colour reads this one's positions
            const uint32_t first = colourOffset[c];
            dispatch(cb, Kernel::VertexBlockDescent, colourOffset[c + 1] - first, stepIndex, volumeFlag(), first);
          }
        }
        break;
      }
      case Stage::CoarseCorrection:
        if (patches == 0) break;  // the correction is off (no patches were made), or there is nothing to solve
        if (u.closed) recordStage(cb, Stage::Volume, u, stepIndex);  // this iterate's volume; ends with a barrier
        dispatch(cb, Kernel::CoarseAssemble, patches, stepIndex, volumeFlag());
        computeToComputeBarrier(cb);                      // the solve reads every patch's row
        dispatch(cb, Kernel::CoarseSolve, 1, stepIndex);  // one workgroup: its invocations share the patches
        computeToComputeBarrier(cb);                      // every particle reads its patch's solution
        dispatch(cb, Kernel::CoarseApply, particles, stepIndex);
        break;
      case Stage::EnergyBudget:
        recordEnergyBudget(cb, u, stepIndex);
        break;
      case Stage::ImplicitVelocity:
        dispatch(cb, Kernel::ImplicitVelocity, particles, stepIndex, 0, energyBase);
        break;
      case Stage::Drainage:
        dispatch(cb, Kernel::DrainageOutflow, particles, stepIndex);
        computeToComputeBarrier(cb);  // every outflow is written before anyone gathers
        dispatch(cb, Kernel::DrainageGather, particles, stepIndex);
        break;
      case Stage::FilmFlow:
        dispatch(cb, Kernel::FilmFlowVelocity, particles, stepIndex);
        computeToComputeBarrier(cb);  // every new velocity is written before the limits read their edges
        dispatch(cb, Kernel::FilmFlowLimit, particles, stepIndex);
        computeToComputeBarrier(cb);  // every limit and kept surfactant is written before anyone gathers
        dispatch(cb, Kernel::FilmFlowGather, particles, stepIndex);
        break;
      case Stage::Count:
        break;
    }
  }

  // One step: the rows of stepStages() that run, each followed by its barrier where the table gives one.
  void recordStep(const vk::raii::CommandBuffer& cb, const StepUniforms& u, uint32_t stepIndex) {
    for (const StageSpec& spec : stepStages()) {
      if (!spec.runs(params, u)) continue;
      recordStage(cb, spec.stage, u, stepIndex);
      if (spec.barrierAfter) computeToComputeBarrier(cb);
    }
  }

  void uploadSteps(std::span<const StepUniforms> steps) {
    ensureStepCapacity(steps.size());
    std::vector<StepUniformsBlock> blocks;
    blocks.reserve(steps.size());
    for (const StepUniforms& u : steps) blocks.push_back(toBlock(u));
    writeVector(buffer(GB_BINDING_STEPS), blocks);
  }

  // The exclusive prefix sum of `count` uints of the contacts buffer (GB_SCAN_ROWS in flags: the partner counts, else
  // the bucket counts) in its three passes; ends with a barrier.
  void recordContactScan(const vk::raii::CommandBuffer& cb, uint32_t count, uint32_t flags) {
    const uint32_t header = contactHeader();
    dispatchGroups(cb, Kernel::ContactScanBlocks, ceilDiv(count, workgroup * GB_SCAN_RUN), count, 0, flags, header);
    computeToComputeBarrier(cb);  // every block's sum is written before they are scanned
    dispatchGroups(cb, Kernel::ContactScanTotals, 1, count, 0, flags, header);  // one workgroup over the sums
    computeToComputeBarrier(cb);  // the sums are scanned before any block adds its own
    dispatch(cb, Kernel::ContactScanAdd, count, 0, flags, header);
    computeToComputeBarrier(cb);  // the scan is done before anyone reads it
  }

  // The header the device search starts from (shared_step.h's GB_CONTACT_* slots).
  [[nodiscard]] std::array<uint32_t, GB_CONTACT_HEADER> contactSearchHeader(float frameTime, float slack,
                                                                            uint32_t previousParticles) const {
    std::array<uint32_t, GB_CONTACT_HEADER> h{};
    h[GB_CONTACT_PREVIOUS_PARTICLES] = previousParticles;
    h[GB_CONTACT_ROW_CAPACITY] = contactRowCapacity;
    h[GB_CONTACT_ENTRY_CAPACITY] = contactEntryCapacity;
    h[GB_CONTACT_BUCKETS] = contactBuckets;
    h[GB_CONTACT_FRAME_TIME] = std::bit_cast<uint32_t>(frameTime);
    h[GB_CONTACT_SLACK] = std::bit_cast<uint32_t>(slack);
    return h;
  }

  // One device search (kernels/contact_*.comp) into the contacts buffer, with the previous list the history's, or
  // the device's own last list when the history is that one (copied on the device instead of uploaded).
  void searchContacts(float frameTime, float slack, const ContactHistory& history) {
    ensureContactRoom(0, history.contacts.size());
    const gpu::ContactSearchLayout l = contactLayout();
    DeviceBuffer& contacts = buffer(GB_BINDING_CONTACTS);
    const bool historyOnDevice = deviceListEntries > 0 && history.particles == particles &&
                                 (history.onDevice || history.contacts.size() == deviceListEntries);
    uint32_t previousParticles = static_cast<uint32_t>(particles);
    if (!historyOnDevice) {
      const bool listed = !history.contacts.empty() && history.contacts.size() >= history.particles + 1;
      previousParticles = listed ? static_cast<uint32_t>(history.particles) : 0u;
      if (listed)
        contacts.write(history.contacts.data(), history.contacts.size() * sizeof(uint32_t),
                       size_t{l.previous} * sizeof(uint32_t));
    }
    const vk::raii::CommandBuffer& cb = commands;
    cb.reset();
    cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    cb.updateBuffer<uint32_t>(contacts.handle(), vk::DeviceSize{l.header} * sizeof(uint32_t),
                              contactSearchHeader(frameTime, slack, previousParticles));
    cb.fillBuffer(contacts.handle(), vk::DeviceSize{l.bucketStart} * sizeof(uint32_t),
                  (vk::DeviceSize{contactBuckets} + 1) * sizeof(uint32_t), 0u);
    if (historyOnDevice)
      cb.copyBuffer(
          contacts.handle(), contacts.handle(),
          vk::BufferCopy(0, vk::DeviceSize{l.previous} * sizeof(uint32_t), deviceListEntries * sizeof(uint32_t)));
    transferToComputeBarrier(cb);  // the header, the zeroed counts and the previous list are in place
    const uint32_t header = l.header;
    const uint32_t runs = gpu::contactReachGroups(particles, workgroup);
    dispatchGroups(cb, Kernel::ContactReach, runs, particles, 0, 0, header);  // each run's velocity sum
    computeToComputeBarrier(cb);
    dispatchGroups(cb, Kernel::ContactReach, runs, particles, 0, GB_REACH_FASTEST, header);  // about the mean
    computeToComputeBarrier(cb);
    dispatchGroups(cb, Kernel::ContactReach, 1, particles, 0, GB_REACH_FINAL, header);  // the largest: the reach
    computeToComputeBarrier(cb);                                                        // the reach sizes the cells
    dispatch(cb, Kernel::ContactCells, particles, 0, 0, header);
    computeToComputeBarrier(cb);  // every particle is counted before the counts are scanned
    recordContactScan(cb, contactBuckets + 1, 0);
    dispatch(cb, Kernel::ContactSort, particles, 0, 0, header);
    computeToComputeBarrier(cb);  // every bucket is filled before anyone reads it
    dispatch(cb, Kernel::ContactSheets, contactBuckets, 0, 0, header);
    computeToComputeBarrier(cb);  // every bucket's sheet is summarised before the pairs read them
    dispatch(cb, Kernel::ContactPairs, particles, 0, 0, header);
    computeToComputeBarrier(cb);  // every row is counted before the counts are scanned
    recordContactScan(cb, particles + 1, GB_SCAN_ROWS);
    dispatch(cb, Kernel::ContactWrite, particles, 0, 0, header);
    computeToHostBarrier(cb);
    cb.end();
    ctx->submitAndWait(cb);
    ++contactRecord.searches;
  }

  // Whether the last search's rows and list had room for every partner; if not, grows them to what it found or
  // twice what they had and says so on stderr. The search has written over the list at the buffer's start: where it
  // read the device's own list as its history (history.onDevice), that list goes back there from the copy the search
  // read, on the device (the grown buffer keeps it, and the search again copies it as its history); otherwise the
  // list there is no longer the last one.
  bool contactSearchHadRoom(const ContactHistory& history) {
    std::array<uint32_t, GB_CONTACT_HEADER> h{};
    readFrom(buffer(GB_BINDING_CONTACTS), h.data(), sizeof h, vk::DeviceSize{contactHeader()} * sizeof(uint32_t));
    const uint32_t most = h[GB_CONTACT_MOST_PARTNERS], entries = h[GB_CONTACT_PARTNER_ENTRIES];
    if (most <= contactRowCapacity && entries <= contactEntryCapacity) return true;
    std::fprintf(stderr,
                 "vulkan: the contact search found %u partners of one particle and %u in all, with room for %u and "
                 "%u: searching again with more room\n",
                 most, entries, contactRowCapacity, contactEntryCapacity);
    if (history.onDevice && deviceListEntries > 0)  // from where the search's layout put it: the old room's
      copyContactUints(buffer(GB_BINDING_CONTACTS), contactLayout().previous, buffer(GB_BINDING_CONTACTS), 0,
                       deviceListEntries);
    else
      deviceListEntries = 0;
    if (most > contactRowCapacity) contactRowCapacity = std::max(most, 2 * contactRowCapacity);  // a film crumples on
    ensureContactRoom(entries, 0);
    ++contactRecord.regrown;
    return false;
  }

  // The size of the list the device search left (its partner entries, the last offset): deviceListEntries.
  void countContactList() {
    uint32_t entries = 0;
    readFrom(buffer(GB_BINDING_CONTACTS), &entries, sizeof entries, vk::DeviceSize{particles} * sizeof(uint32_t));
    deviceListEntries = particles + size_t{1} + 2 * size_t{entries};
  }

  // The list the last search left, into `contacts` (Topology::contacts).
  void readContactList(std::vector<uint32_t>& contacts) {
    contacts.resize(deviceListEntries);
    readFrom(buffer(GB_BINDING_CONTACTS), contacts.data(), contacts.size() * sizeof(uint32_t));
  }

  // The frame's statistics and film checks: with probe.atPresentPositions the geometry and the film state at the
  // film's present positions first (what CpuStepper::refreshGeometry does to a film in host memory: the next step's
  // first stages compute the same), then the terms and their tree, then the sums read back.
  std::array<float, GB_STATISTICS_TERMS> sumStatistics(const FilmProbe& probe) {
    StepUniforms u;
    u.dt = 0.0f;  // the film state without ageing it
    u.volumeOrigin = probe.origin;
    u.wands.leftPosition = probe.tips[0];
    u.wands.rightPosition = probe.tips[1];
    u.frameTime = probe.frameTime;
    uploadSteps(std::span(&u, 1));
    const uint32_t at = gpu::reduceStatisticsAt(energyBase, particles);
    const vk::raii::CommandBuffer& cb = commands;
    cb.reset();
    cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    if (probe.atPresentPositions) {
      recordStage(cb, Stage::Geometry, u, 0);
      computeToComputeBarrier(cb);
      recordStage(cb, Stage::FilmState, u, 0);
      computeToComputeBarrier(cb);
    }
    dispatch(cb, Kernel::FilmStatisticsTerms, particles, 0, 0, at);
    computeToComputeBarrier(cb);
    bool inA = true;
    for (uint32_t n = particles; n > 1; n = gpu::treePassOutputs(n)) {  // the passes of the tree
      dispatchTreePass(cb, Kernel::FilmStatisticsTree, n, 0, inA ? GB_REDUCE_STATISTICS_IN_A : 0u, at);
      computeToComputeBarrier(cb);
      inA = !inA;
    }
    // Each term's sum is the first float of its block: the terms copied side by side into host-cached memory.
    std::array<float, GB_STATISTICS_TERMS> sums{};
    if (statisticsReadback.size() < sizeof sums)
      statisticsReadback = DeviceBuffer(*ctx, sizeof sums, DeviceBuffer::Placement::Readback);
    computeToTransferBarrier(cb);
    const size_t half = inA ? 0 : size_t{GB_STATISTICS_TERMS} * particles;
    for (size_t c = 0; c < sums.size(); ++c)
      statisticsReadback.recordCopyFrom(cb, buffer(GB_BINDING_REDUCE), (at + half + c * particles) * sizeof(float),
                                        sizeof(float), c * sizeof(float));
    transferToHostBarrier(cb);
    cb.end();
    ctx->submitAndWait(cb);
    readFrom(statisticsReadback, sums.data(), sizeof sums);
    return sums;
  }

  // A rest-length rule between steps (film_rest_lengths, GB_RULE_*) on the device, where the statistics are reduced.
  bool runSpringRule(uint32_t rule, float share = 0.0f) {
    if (!statisticsOnDevice) return false;
    if (sets.empty()) throw std::logic_error("VulkanStepper: no film loaded");
    const vk::raii::CommandBuffer& cb = commands;
    cb.reset();
    cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    computeToComputeBarrier(cb);
    dispatch(cb, Kernel::FilmRestLengths, particles, 0, rule, 0, share);
    computeToHostBarrier(cb);  // storeRestLengths reads them through the buffer's mapping
    cb.end();
    ctx->submitAndWait(cb);
    return true;
  }

  float readVolume() {
    float volume = 0.0f;
    readFrom(buffer(GB_BINDING_REDUCE), &volume, sizeof volume,
             volumeInA ? 0 : gpu::reduceHalfB(triangles) * sizeof(float));
    return volume;
  }
};

VulkanStepper::VulkanStepper(std::shared_ptr<const VulkanContext> context, VulkanStepperOptions options)
    : impl_(std::make_unique<Impl>(std::move(context), options)) {}
VulkanStepper::~VulkanStepper() = default;

const VulkanContext& VulkanStepper::context() const { return *impl_->ctx; }

std::string VulkanStepper::name() const {
  return "vulkan (" + impl_->ctx->info().name + ", " + impl_->ctx->info().type + ")";
}

void VulkanStepper::load(const Params& params, Film& film) {
  Impl& m = *impl_;
  ensureColouring(film.state.alive, film.topology);
  if (params.coarseIterations > 0) ensurePatches(film.state.alive, params.coarsePatchRings, film.topology);
  const State& s = film.state;
  const Topology& t = film.topology;
  m.params = params;
  m.particles = static_cast<uint32_t>(s.size());
  m.triangles = static_cast<uint32_t>(t.triangleCount());
  const size_t n = s.size();
  auto make = [&](int binding, size_t bytes) { m.ensureRoom(binding, bytes); };
  make(GB_BINDING_PARAMS, sizeof(Params));
  // The per-particle buffers: as many blocks of n elements as the arrays of device_data.h they hold.
  std::array<int, GB_BINDING_COUNT> blocks{};
  forEachParticleArray(s, [&](const auto&, const ParticleArrayInfo& a) {
    int& held = blocks[static_cast<size_t>(a.binding)];
    held = std::max(held, a.block + a.components);
  });
  for (int b = 0; b < GB_BINDING_COUNT; ++b)
    if (blocks[static_cast<size_t>(b)] > 0)
      make(b, static_cast<size_t>(blocks[static_cast<size_t>(b)]) * n * sizeof(float));
  make(GB_BINDING_BOUNDARY, t.boundary.size() * sizeof(uint32_t));
  make(GB_BINDING_COLOUR_ORDER, solverListEntries(t) * sizeof(uint32_t));
  make(GB_BINDING_TRIANGLES, t.triangles.size() * sizeof(uint32_t));
  make(GB_BINDING_REST_LENGTH, t.restLength.size() * sizeof(float));
  make(GB_BINDING_SPRING_OFFSET, t.springOffset.size() * sizeof(uint32_t));
  make(GB_BINDING_SPRING_INDEX, t.springIndex.size() * sizeof(uint32_t));
  make(GB_BINDING_SPRING_NEIGHBOUR, t.springNeighbour.size() * sizeof(uint32_t));
  make(GB_BINDING_TRIANGLE_OFFSET, t.triangleOffset.size() * sizeof(uint32_t));
  make(GB_BINDING_TRIANGLE_CORNER, t.triangleCorner.size() * sizeof(uint32_t));
  m.contactPreviousCapacity = 0;  // the contacts buffer is kept as grown, and grown for these particles below
  m.deviceListEntries = 0;        // the old film's list: the film's own is written below
  const size_t startingEntries = m.contactEntryCapacity > 0 ? 0 : n;  // the room grown for an earlier film is kept
  m.ensureContactRoom(std::max(startingEntries, m.partnerEntriesOf(t.contacts)), 0);
  make(GB_BINDING_TRIANGLE_NORMAL, 3 * t.triangleCount() * sizeof(float));
  make(GB_BINDING_CORNER_AREA, 3 * t.triangleCount() * sizeof(float));
  make(GB_BINDING_REDUCE, reduceFloats(t, n) * sizeof(float));

  m.buffer(GB_BINDING_PARAMS).write(&params, sizeof(Params));
  m.airParity = 0;  // each air array into its own buffer
  forEachParticleArray(s, [&](const auto& array, const ParticleArrayInfo& info) {
    if (info.transfer != Transfer::WithMesh) writeParticleArray(m.buffer(info.binding), array, info, n);
  });
  m.writeMesh(s, t);

  m.sets.clear();
  const vk::DescriptorPoolSize poolSize(vk::DescriptorType::eStorageBuffer, 2 * GB_BINDING_COUNT);
  m.pool = vk::raii::DescriptorPool(
      m.ctx->device, vk::DescriptorPoolCreateInfo(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, 2, poolSize));
  const std::array<vk::DescriptorSetLayout, 2> layouts = {*m.setLayout, *m.setLayout};
  vk::raii::DescriptorSets sets(m.ctx->device, vk::DescriptorSetAllocateInfo(*m.pool, layouts));
  for (auto& set : sets) m.sets.push_back(std::move(set));
  m.airParity = 0;
  m.volumeInA = true;
  m.driftInA = true;
  m.ensureStepCapacity(1);
  m.writeDescriptorSets();
}

float VulkanStepper::run(std::span<const StepUniforms> substeps) {
  Impl& m = *impl_;
  if (m.sets.empty()) throw std::logic_error("VulkanStepper: no film loaded");
  if (substeps.empty()) return m.params.pressureCoefficient;
  m.uploadSteps(substeps);
  const vk::raii::CommandBuffer& cb = m.commands;
  cb.reset();
  cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  if (timing_) {
    // Timing: every stage alone between barriers and timestamps, so each gets its own duration.
    std::vector<Stage> order;
    const uint32_t queries = static_cast<uint32_t>(substeps.size()) * kStageCount + 1;
    vk::raii::QueryPool pool(m.ctx->device, vk::QueryPoolCreateInfo({}, vk::QueryType::eTimestamp, queries));
    cb.resetQueryPool(*pool, 0, queries);
    uint32_t q = 0;
    cb.writeTimestamp(vk::PipelineStageFlagBits::eComputeShader, *pool, q++);
    for (uint32_t k = 0; k < substeps.size(); ++k)
      for (const StageSpec& spec : stepStages()) {
        if (!spec.runs(m.params, substeps[k])) continue;
        m.recordStage(cb, spec.stage, substeps[k], k);
        computeToComputeBarrier(cb);
        cb.writeTimestamp(vk::PipelineStageFlagBits::eComputeShader, *pool, q++);
        order.push_back(spec.stage);
      }
    computeToHostBarrier(cb);
    cb.end();
    m.ctx->submitAndWait(cb);
    const auto [result, ticks] = pool.getResults<uint64_t>(
        0, q, q * sizeof(uint64_t), sizeof(uint64_t), vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
    for (size_t k = 0; k < order.size(); ++k)
      times_[static_cast<int>(order[k])] +=
          static_cast<double>(ticks[k + 1] - ticks[k]) * m.ctx->timestampPeriodNs() * 1e-6;
  } else {
    for (uint32_t k = 0; k < substeps.size(); ++k) m.recordStep(cb, substeps[k], k);
    computeToHostBarrier(cb);
    cb.end();
    m.ctx->submitAndWait(cb);
  }
  const StepUniforms& last = substeps.back();
  lastBudget_ = m.params.integrator != 0 && m.params.energyBudget != 0 ? m.readVelocityBudget() : VelocityBudget{};
  return last.closed ? boylePressure(m.params, last.referenceVolume, m.readVolume()) : m.params.pressureCoefficient;
}

float VulkanStepper::runStage(Stage stage, const StepUniforms& uniforms) {
  Impl& m = *impl_;
  if (m.sets.empty()) throw std::logic_error("VulkanStepper: no film loaded");
  m.uploadSteps(std::span(&uniforms, 1));
  const vk::raii::CommandBuffer& cb = m.commands;
  cb.reset();
  cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  m.recordStage(cb, stage, uniforms, 0);
  computeToHostBarrier(cb);
  cb.end();
  m.ctx->submitAndWait(cb);
  if (stage == Stage::Volume) return m.readVolume();
  return stage == Stage::EnergyBudget ? m.readVelocityBudget().scale : 0.0f;
}

void VulkanStepper::updateContacts(const Film& film) { impl_->writeContacts(film.topology); }

bool VulkanStepper::findContacts(const Params& params, float frameTime, float slack, Film& film,
                                 const ContactHistory& history) {
  if (film.state.size() != impl_->particles) throw std::logic_error("VulkanStepper::findContacts: not the loaded film");
  if (!findContactsOnDevice(params, frameTime, slack, history)) return false;
  storeContacts(film);
  return true;
}

bool VulkanStepper::findContactsOnDevice(const Params& params, float frameTime, float slack,
                                         const ContactHistory& history) {
  Impl& m = *impl_;
  if (!m.contactsOnDevice) return false;
  if (m.sets.empty()) throw std::logic_error("VulkanStepper: no film loaded");
  if (params.collisionDistance != m.params.collisionDistance ||
      params.collisionStiffness != m.params.collisionStiffness)
    throw std::logic_error("VulkanStepper::findContacts: not the loaded film");
  // A search short of room lists nothing reliable: it runs once more with the room it found it needed.
  m.searchContacts(frameTime, slack, history);
  if (!m.contactSearchHadRoom(history)) {
    m.searchContacts(frameTime, slack, history);
    if (!m.contactSearchHadRoom(history)) throw std::logic_error("VulkanStepper::findContacts: no room after growing");
  }
  m.countContactList();
  return true;
}

void VulkanStepper::storeContacts(Film& film) {
  Impl& m = *impl_;
  if (m.deviceListEntries == 0) return;  // the list the CPU gave (updateContacts, load) is the one there
  if (film.state.size() != m.particles) throw std::logic_error("VulkanStepper::storeContacts: not the loaded film");
  m.readContactList(film.topology.contacts);
}

const DeviceContactRecord& VulkanStepper::contactRecord() const { return impl_->contactRecord; }

void VulkanStepper::updateTopology(const Params& params, Film& film) {
  Impl& m = *impl_;
  ensureColouring(film.state.alive, film.topology);
  if (params.coarseIterations > 0) ensurePatches(film.state.alive, params.coarsePatchRings, film.topology);
  const Topology& t = film.topology;
  auto fits = [&](int binding, size_t count, size_t elementBytes) {
    return count * elementBytes <= m.buffer(binding).size();
  };
  const bool fitsBuffers = film.state.size() == m.particles && t.triangleCount() <= m.triangles &&
                           fits(GB_BINDING_TRIANGLES, t.triangles.size(), sizeof(uint32_t)) &&
                           fits(GB_BINDING_REST_LENGTH, t.restLength.size(), sizeof(float)) &&
                           fits(GB_BINDING_SPRING_INDEX, t.springIndex.size(), sizeof(uint32_t)) &&
                           fits(GB_BINDING_SPRING_NEIGHBOUR, t.springNeighbour.size(), sizeof(uint32_t)) &&
                           fits(GB_BINDING_TRIANGLE_CORNER, t.triangleCorner.size(), sizeof(uint32_t)) &&
                           fits(GB_BINDING_CONTACTS, t.contacts.size(), sizeof(uint32_t)) &&
                           fits(GB_BINDING_COLOUR_ORDER, solverListEntries(t), sizeof(uint32_t)) &&
                           fits(GB_BINDING_REDUCE, reduceFloats(t, film.state.size()), sizeof(float));
  if (!fitsBuffers) {
    load(params, film);
    return;
  }
  // A burst only shrinks the mesh: the buffers keep their size, the counts say how much of them is used.
  m.triangles = static_cast<uint32_t>(t.triangleCount());
  m.writeMesh(film.state, t);
}

void VulkanStepper::updateRestLengths(const Film& film) {
  Impl& m = *impl_;
  if (film.topology.restLength.size() * sizeof(float) > m.buffer(GB_BINDING_REST_LENGTH).size())
    throw std::logic_error("VulkanStepper::updateRestLengths: not the loaded film");
  writeVector(m.buffer(GB_BINDING_REST_LENGTH), film.topology.restLength);
}

// The state is copied in one submission into host-cached memory and read from there: on a discrete GPU the
// CPU reads the device's own memory through a mapping (resizable BAR) at uncached speed, which made this the
// slowest part of a frame on an H100 (docs/performance.md).
void VulkanStepper::store(Film& film) {
  storeArrays(film, [](const void*, const ParticleArrayInfo& info) { return info.transfer == Transfer::ReadBack; });
  ++impl_->copiedToHost.stateReadbacks;
}

void VulkanStepper::storePositions(Film& film) {
  const void* position = &film.state.position;
  storeArrays(film, [&](const void* array, const ParticleArrayInfo&) { return array == position; });
}

template <class Chosen>
void VulkanStepper::storeArrays(Film& film, Chosen&& chosen) {
  Impl& m = *impl_;
  State& s = film.state;
  if (s.size() != m.particles) throw std::logic_error("VulkanStepper::store: not the loaded film");
  // The arrays to bring back: where each lies on the device, in the table's order (device_data.h), one after the
  // other in the host-cached copy.
  const vk::DeviceSize blockBytes = s.size() * sizeof(float);
  std::vector<Impl::DevicePart> parts;
  forEachParticleArray(s, [&](const auto& array, const ParticleArrayInfo& info) {
    if (chosen(&array, info))
      parts.push_back({&m.holding(info.binding), static_cast<vk::DeviceSize>(info.block) * blockBytes,
                       static_cast<vk::DeviceSize>(info.components) * blockBytes});
  });
  m.copyIntoReadback(parts);
  // The same arrays in the same order, out of the copy.
  vk::DeviceSize at = 0;
  forEachParticleArray(s, [&](auto& array, const ParticleArrayInfo& info) {
    if (!chosen(&array, info)) return;
    forEachComponent(array, [&](auto& values, int) {
      m.readFrom(m.readback, values.data(), blockBytes, at);
      at += blockBytes;
    });
  });
}

bool VulkanStepper::probeFilm(const FilmProbe& probe, FilmSums& sums, FilmChecks& checks) {
  Impl& m = *impl_;
  if (!m.statisticsOnDevice) return false;
  if (m.sets.empty()) throw std::logic_error("VulkanStepper: no film loaded");
  sums = {};
  checks = {};
  if (m.particles == 0) return true;
  const std::array<float, GB_STATISTICS_TERMS> t = m.sumStatistics(probe);
  sums.particles = static_cast<size_t>(std::lround(t[GB_STAT_PARTICLES]));
  sums.kinetic = t[GB_STAT_KINETIC];
  sums.potential = t[GB_STAT_POTENTIAL];
  sums.liquid = t[GB_STAT_LIQUID];
  sums.thickness = t[GB_STAT_THICKNESS];
  sums.airFlow = t[GB_STAT_AIR_FLOW];
  sums.elastic = t[GB_STAT_ELASTIC];
  sums.area = t[GB_STAT_AREA];
  sums.volume = t[GB_STAT_VOLUME];
  sums.maxSpeed = t[GB_STAT_SPEED];
  checks.particles = sums.particles;
  if (sums.particles == 0) return true;  // the largest-kept terms hold no particle's value
  checks.unstable = t[GB_STAT_UNSTABLE] > 0.0f;
  checks.lowest = -t[GB_STAT_DEPTH];
  checks.nearestTip = {-t[GB_STAT_NEAR_LEFT], -t[GB_STAT_NEAR_RIGHT]};
  checks.winding = {t[GB_STAT_WINDING_LEFT], t[GB_STAT_WINDING_RIGHT]};
  if (t[GB_STAT_THIN] > -1e38f) checks.thinnest = -t[GB_STAT_THIN];  // else no particle has area
  checks.hardestImpact = t[GB_STAT_IMPACT];
  checks.yielding = t[GB_STAT_YIELDING];
  checks.slack = t[GB_STAT_SLACK];
  checks.crowded = t[GB_STAT_CROWDED];
  checks.contractionQuadratic = t[GB_STAT_CONTRACTION_QUADRATIC];
  checks.contractionLinear = t[GB_STAT_CONTRACTION_LINEAR];
  checks.rungsPastGrowth = t[GB_STAT_RUNGS_PAST_GROWTH];
  checks.rungs = t[GB_STAT_RUNG_COUNT];
  checks.rungRest = t[GB_STAT_RUNG_REST];
  checks.wireEdges = t[GB_STAT_WIRE_EDGE_COUNT];
  checks.wireEdgeLength = t[GB_STAT_WIRE_EDGES];
  return true;
}

bool VulkanStepper::yieldStretchedSprings() { return impl_->runSpringRule(GB_RULE_YIELD); }

bool VulkanStepper::payOutFilmAtWire() { return impl_->runSpringRule(GB_RULE_PAYOUT); }

bool VulkanStepper::contractSlackSprings(float share) { return impl_->runSpringRule(GB_RULE_CONTRACT, share); }

void VulkanStepper::storeRestLengths(Film& film) {
  Impl& m = *impl_;
  std::vector<float>& rest = film.topology.restLength;
  if (rest.size() * sizeof(float) > m.buffer(GB_BINDING_REST_LENGTH).size())
    throw std::logic_error("VulkanStepper::storeRestLengths: not the loaded film");
  m.readFrom(m.buffer(GB_BINDING_REST_LENGTH), rest.data(), rest.size() * sizeof(float));
}

DeviceReadback VulkanStepper::readback() const { return impl_->copiedToHost; }

std::shared_ptr<const VulkanContext> VulkanStepper::sharedContext() const { return impl_->ctx; }

DeviceFilm VulkanStepper::deviceFilm() {
  Impl& m = *impl_;
  return {m.buffer(GB_BINDING_POSITION).handle(),
          m.buffer(GB_BINDING_NORMAL).handle(),
          m.buffer(GB_BINDING_THICKNESS).handle(),
          m.airFront().handle(),
          m.buffer(GB_BINDING_TRIANGLES).handle(),
          m.particles,
          m.triangles};
}

}  // namespace gb
