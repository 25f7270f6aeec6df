#include "host/vulkan_stepper.h"

#include <cstdio>

#include "host/vulkan_stepper_impl.h"
#include "solver/coarse_correction.h"
#include "solver/colouring.h"

namespace gb {

// The shared layouts are what the shaders expect (kernels/shared/shared_step.h): sizes and the offsets std430
// gives the same declarations.
static_assert(sizeof(StepUniforms) == 192 && offsetof(StepUniforms, dt) == 128 &&
              offsetof(StepUniforms, wireKind) == 156 && offsetof(StepUniforms, closed) == 160 &&
              offsetof(StepUniforms, solverSweeps) == 176);
static_assert(sizeof(PushBlock) == 36);
static_assert(alignof(Params) == 4 && sizeof(Params) % 4 == 0,
              "Params must stay a block of 4-byte scalars, whose std430 layout is the C layout");

namespace {

bool worksOnDevice(WorkPlace place, const VulkanDeviceInfo& device) {
  if (place == WorkPlace::Automatic) return device.type != "CPU";
  return place == WorkPlace::Device;
}

// Reads up to this size go through the buffer's mapping: a copy's submission and wait cost more than reading a few
// KiB at uncached speed.
constexpr vk::DeviceSize kDirectReadBytes = 16 * 1024;

// A per-particle array of State into its buffer, from its first block on (device_data.h).
template <class Array>
void writeParticleArray(DeviceBuffer& buffer, const Array& array, const ParticleArrayInfo& info, size_t particles) {
  const size_t bytes = particles * sizeof(float);  // float and uint32_t alike
  forEachComponent(array, [&](const auto& values, int c) {
    buffer.write(values.data(), bytes, static_cast<size_t>(info.block + c) * bytes);
  });
}

// The solver's list buffer: colour order, then the patch lists (kernels/step/coarse.glsl); at least one entry.
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

// The blocks of `particles` elements each per-particle buffer holds: as many as the arrays of device_data.h in it.
std::array<int, GB_BINDING_COUNT> particleBlocks(const State& s) {
  std::array<int, GB_BINDING_COUNT> blocks{};
  forEachParticleArray(s, [&](const auto&, const ParticleArrayInfo& a) {
    int& held = blocks[static_cast<size_t>(a.binding)];
    held = std::max(held, a.block + a.components);
  });
  return blocks;
}

}  // namespace

std::vector<IndexRun> runsOf(std::span<const uint32_t> ascending) {
  std::vector<IndexRun> runs;
  for (const uint32_t i : ascending) {
    if (!runs.empty() && runs.back().end == i)
      ++runs.back().end;
    else
      runs.push_back({i, i + 1});
  }
  return runs;
}

VulkanStepper::Impl::Impl(std::shared_ptr<const VulkanContext> context, VulkanStepperOptions stepperOptions)
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
  if (ctx->timestampsOnHostClock())
    stepTimestamps = vk::raii::QueryPool(device, vk::QueryPoolCreateInfo({}, vk::QueryType::eTimestamp, 2));
}

void VulkanStepper::Impl::ensureRoom(int binding, size_t bytes) {
  DeviceBuffer& b = buffer(binding);
  if (b.size() >= bytes && b.size() <= 4 * std::max<size_t>(bytes, 16)) return;
  b = DeviceBuffer(*ctx, bytes + bytes / 8);
}

void VulkanStepper::Impl::ensureStepCapacity(size_t count) {
  if (count <= stepsCapacity) return;
  stepsCapacity = std::max<size_t>(count, 2 * stepsCapacity);
  buffer(GB_BINDING_STEPS) = DeviceBuffer(*ctx, stepsCapacity * sizeof(StepUniforms));
  writeDescriptorSets();
}

void VulkanStepper::Impl::writeMesh(const State& s, const Topology& t) {
  forEachParticleArray(s, [&](const auto& array, const ParticleArrayInfo& info) {
    if (info.transfer == Transfer::WithMesh) writeParticleArray(buffer(info.binding), array, info, s.size());
  });
  writeVector(buffer(GB_BINDING_REST_LENGTH), t.restLength);
  writeConnectivity(t);
}

void VulkanStepper::Impl::writeConnectivity(const Topology& t) {
  writeVector(buffer(GB_BINDING_BOUNDARY), t.boundary);
  writeVector(buffer(GB_BINDING_TRIANGLES), t.triangles);
  writeVector(buffer(GB_BINDING_SPRING_OFFSET), t.springOffset);
  writeVector(buffer(GB_BINDING_SPRING_INDEX), t.springIndex);
  writeVector(buffer(GB_BINDING_SPRING_NEIGHBOUR), t.springNeighbour);
  writeVector(buffer(GB_BINDING_TRIANGLE_OFFSET), t.triangleOffset);
  writeVector(buffer(GB_BINDING_TRIANGLE_CORNER), t.triangleCorner);
  writeSolverLists(t);
  springs = static_cast<uint32_t>(t.springCount());
  energyBase = energyTermsAt(t);
  writeVelocityBudget({});  // no budget has run on this mesh yet
}

void VulkanStepper::Impl::ensureMeshRoom(const Topology& t, size_t n) {
  ensureRoom(GB_BINDING_BOUNDARY, t.boundary.size() * sizeof(uint32_t));
  ensureRoom(GB_BINDING_COLOUR_ORDER, solverListEntries(t) * sizeof(uint32_t));
  ensureRoom(GB_BINDING_TRIANGLES, t.triangles.size() * sizeof(uint32_t));
  ensureRoom(GB_BINDING_SPRING_OFFSET, t.springOffset.size() * sizeof(uint32_t));
  ensureRoom(GB_BINDING_SPRING_INDEX, t.springIndex.size() * sizeof(uint32_t));
  ensureRoom(GB_BINDING_SPRING_NEIGHBOUR, t.springNeighbour.size() * sizeof(uint32_t));
  ensureRoom(GB_BINDING_TRIANGLE_OFFSET, t.triangleOffset.size() * sizeof(uint32_t));
  ensureRoom(GB_BINDING_TRIANGLE_CORNER, t.triangleCorner.size() * sizeof(uint32_t));
  ensureRoom(GB_BINDING_TRIANGLE_NORMAL, 3 * t.triangleCount() * sizeof(float));
  ensureRoom(GB_BINDING_CORNER_AREA, 3 * t.triangleCount() * sizeof(float));
  ensureRoom(GB_BINDING_REDUCE, reduceFloats(t, n) * sizeof(float));
}

void VulkanStepper::Impl::layOutParticles(const std::array<int, GB_BINDING_COUNT>& blocks, uint32_t count) {
  const vk::DeviceSize oldBlock = vk::DeviceSize{particles} * sizeof(float),
                       newBlock = vk::DeviceSize{count} * sizeof(float);
  vk::DeviceSize total = 0;
  for (const int held : blocks) total += static_cast<vk::DeviceSize>(held) * oldBlock;
  if (relayout.size() < total) relayout = DeviceBuffer(*ctx, total + total / 8);
  const vk::raii::CommandBuffer& cb = commands;
  if (total > 0) {  // the old film's blocks, one after the other
    cb.reset();
    cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    computeToTransferBarrier(cb);
    vk::DeviceSize at = 0;
    for (int b = 0; b < GB_BINDING_COUNT; ++b)
      if (const vk::DeviceSize bytes = static_cast<vk::DeviceSize>(blocks[static_cast<size_t>(b)]) * oldBlock;
          bytes > 0) {
        relayout.recordCopyFrom(cb, buffer(b), 0, bytes, at);
        at += bytes;
      }
    cb.end();
    ctx->submitAndWait(cb);
  }
  for (int b = 0; b < GB_BINDING_COUNT; ++b)
    if (const int held = blocks[static_cast<size_t>(b)]; held > 0) ensureRoom(b, static_cast<size_t>(held) * newBlock);
  cb.reset();
  cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  transferToTransferBarrier(cb);  // the copy above is done
  vk::DeviceSize at = 0;
  for (int b = 0; b < GB_BINDING_COUNT; ++b)
    for (int k = 0; k < blocks[static_cast<size_t>(b)] && oldBlock > 0; ++k) {  // each block at its new place
      buffer(b).recordCopyFrom(cb, relayout, at, oldBlock, static_cast<vk::DeviceSize>(k) * newBlock);
      at += oldBlock;
    }
  transferToComputeBarrier(cb);
  cb.end();
  ctx->submitAndWait(cb);
  particles = count;
}

void VulkanStepper::Impl::growKeeping(int binding, size_t bytes, size_t keptBytes) {
  if (buffer(binding).size() >= bytes) return;
  DeviceBuffer grown(*ctx, bytes + bytes / 8);  // an eighth more room, as ensureRoom gives
  copyOnDevice(buffer(binding), 0, grown, 0, keptBytes);
  buffer(binding) = std::move(grown);
}

void VulkanStepper::Impl::copyOnDevice(const DeviceBuffer& from, vk::DeviceSize fromOffset, const DeviceBuffer& to,
                                       vk::DeviceSize toOffset, vk::DeviceSize bytes) {
  if (bytes == 0) return;
  const vk::raii::CommandBuffer& cb = commands;
  cb.reset();
  cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  computeToTransferBarrier(cb);
  to.recordCopyFrom(cb, from, fromOffset, bytes, toOffset);
  transferToComputeBarrier(cb);
  cb.end();
  ctx->submitAndWait(cb);
}

void VulkanStepper::Impl::writeThroughUpload(std::span<const HostPart> parts) {
  vk::DeviceSize total = 0;
  for (const HostPart& part : parts) total += part.bytes;
  if (total == 0) return;
  if (upload.size() < total) upload = DeviceBuffer(*ctx, total + total / 2, DeviceBuffer::Placement::Host);
  vk::DeviceSize at = 0;
  for (const HostPart& part : parts) {
    upload.write(part.from, part.bytes, at);
    at += part.bytes;
  }
  const vk::raii::CommandBuffer& cb = commands;
  cb.reset();
  cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  computeToTransferBarrier(cb);
  at = 0;
  for (const HostPart& part : parts) {
    part.to->recordCopyFrom(cb, upload, at, part.bytes, part.offset);
    at += part.bytes;
  }
  transferToComputeBarrier(cb);
  cb.end();
  ctx->submitAndWait(cb);
}

void VulkanStepper::Impl::writeVelocityBudget(const VelocityBudget& b) {
  std::array<float, kBudgetSlots> slots{};
  slots[GB_SLOT_SCALE - GB_SLOT_SCALE] = b.scale;
  for (int c = 0; c < 3; ++c) {
    slots[GB_SLOT_CENTRE - GB_SLOT_SCALE + c] = b.centre[c];
    slots[GB_SLOT_SHIFT - GB_SLOT_SCALE + c] = b.shift[c];
  }
  slots[GB_SLOT_RELEASED - GB_SLOT_SCALE] = b.released;
  buffer(GB_BINDING_REDUCE).write(slots.data(), sizeof slots, velocityBudgetOffset());
}

void VulkanStepper::Impl::readFrom(const DeviceBuffer& from, void* to, vk::DeviceSize bytes, vk::DeviceSize offset) {
  if (&from == &readback || bytes <= kDirectReadBytes)
    from.read(to, bytes, offset);
  else
    readThroughReadback(from, to, bytes, offset);
  copiedToHost.bytes += bytes;
}

void VulkanStepper::Impl::readThroughReadback(const DeviceBuffer& from, void* to, vk::DeviceSize bytes,
                                              vk::DeviceSize offset) {
  copyIntoReadback(std::array{DevicePart{&from, offset, bytes}});
  readback.read(to, bytes);
}

void VulkanStepper::Impl::copyIntoReadback(std::span<const DevicePart> parts) {
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

VelocityBudget VulkanStepper::Impl::readVelocityBudget() {
  std::array<float, kBudgetSlots> slots{};
  readFrom(buffer(GB_BINDING_REDUCE), slots.data(), sizeof slots, velocityBudgetOffset());
  const auto at = [&](int slot) { return slots[static_cast<size_t>(slot - GB_SLOT_SCALE)]; };
  return {at(GB_SLOT_SCALE), Vec3(at(GB_SLOT_CENTRE), at(GB_SLOT_CENTRE + 1), at(GB_SLOT_CENTRE + 2)),
          Vec3(at(GB_SLOT_SHIFT), at(GB_SLOT_SHIFT + 1), at(GB_SLOT_SHIFT + 2)), at(GB_SLOT_RELEASED)};
}

void VulkanStepper::Impl::writeSolverLists(const Topology& t) {
  std::vector<uint32_t> lists = t.colourOrder;
  for (const std::vector<uint32_t>* list :
       {&t.patchOf, &t.patchOffset, &t.patchMembers, &t.patchRowOffset, &t.patchRow})
    lists.insert(lists.end(), list->begin(), list->end());
  writeVector(buffer(GB_BINDING_COLOUR_ORDER), lists);
  colourOffset = t.colourOffset;
  patches = t.patchOffset.empty() ? 0u : static_cast<uint32_t>(t.patchOffset.size() - 1);
  solverParticles = static_cast<uint32_t>(t.colourOrder.size());
}

void VulkanStepper::Impl::writeDescriptorSets() {
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

float VulkanStepper::Impl::readVolume() {
  float volume = 0.0f;
  readFrom(buffer(GB_BINDING_REDUCE), &volume, sizeof volume,
           volumeInA ? 0 : gpu::reduceHalfB(triangles) * sizeof(float));
  return volume;
}

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
  m.particles = static_cast<uint32_t>(s.size());
  m.triangles = static_cast<uint32_t>(t.triangleCount());
  const size_t n = s.size();
  auto make = [&](int binding, size_t bytes) { m.ensureRoom(binding, bytes); };
  make(GB_BINDING_PARAMS, sizeof(Params));
  // The per-particle buffers: as many blocks of n elements as the arrays of device_data.h they hold.
  const std::array<int, GB_BINDING_COUNT> blocks = particleBlocks(s);
  for (int b = 0; b < GB_BINDING_COUNT; ++b)
    if (blocks[static_cast<size_t>(b)] > 0)
      make(b, static_cast<size_t>(blocks[static_cast<size_t>(b)]) * n * sizeof(float));
  make(GB_BINDING_REST_LENGTH, t.restLength.size() * sizeof(float));
  m.ensureMeshRoom(t, n);
  m.contactPreviousCapacity = 0;  // the contacts buffer is kept as grown, and grown for these particles below
  m.deviceListEntries = 0;        // the old film's list: the film's own is written below
  const size_t startingEntries = m.contactEntryCapacity > 0 ? 0 : n;  // the room grown for an earlier film is kept
  m.ensureContactRoom(std::max(startingEntries, m.partnerEntriesOf(t.contacts)), 0);

  m.useParams(params);
  m.airParity = 0;  // each air array into its own buffer
  forEachParticleArray(s, [&](const auto& array, const ParticleArrayInfo& info) {
    if (info.transfer != Transfer::WithMesh) writeParticleArray(m.buffer(info.binding), array, info, n);
  });
  m.writeMesh(s, t);
  m.writeContacts(t);

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

bool VulkanStepper::updateTopology(const Params& params, Film& film) {
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
                           fits(GB_BINDING_COLOUR_ORDER, solverListEntries(t), sizeof(uint32_t)) &&
                           fits(GB_BINDING_REDUCE, reduceFloats(t, film.state.size()), sizeof(float));
  if (!fitsBuffers) return false;
  // A burst only shrinks the mesh: the buffers keep their size, the counts say how much of them is used.
  m.triangles = static_cast<uint32_t>(t.triangleCount());
  m.writeMesh(film.state, t);
  return true;
}

void VulkanStepper::updateRestLengths(const Film& film) {
  Impl& m = *impl_;
  if (film.topology.restLength.size() * sizeof(float) > m.buffer(GB_BINDING_REST_LENGTH).size())
    throw std::logic_error("VulkanStepper::updateRestLengths: not the loaded film");
  writeVector(m.buffer(GB_BINDING_REST_LENGTH), film.topology.restLength);
}

bool VulkanStepper::storeRegion(Film& film, std::span<const uint32_t> particles, std::span<const uint32_t> springs) {
  storeRuns(film, particles, springs, [](const void*, const ParticleArrayInfo&) { return true; });
  return true;
}

bool VulkanStepper::storeParticleArraysOf(Film& film, std::span<const uint32_t> particles,
                                          std::initializer_list<const void*> arrays,
                                          std::span<const uint32_t> springs) {
  storeRuns(film, particles, springs, [&](const void* array, const ParticleArrayInfo&) {
    return std::find(arrays.begin(), arrays.end(), array) != arrays.end();
  });
  return true;
}

template <class Chosen>
void VulkanStepper::storeRuns(Film& film, std::span<const uint32_t> particles, std::span<const uint32_t> springs,
                              Chosen&& chosen, bool everyParticle) {
  Impl& m = *impl_;
  State& s = film.state;
  if (s.size() != m.particles) throw std::logic_error("VulkanStepper: not the loaded film");
  const std::vector<IndexRun> particleRuns =
      everyParticle ? std::vector<IndexRun>{{0, static_cast<uint32_t>(s.size())}} : runsOf(particles);
  const std::vector<IndexRun> springRuns = runsOf(springs);
  const vk::DeviceSize blockBytes = s.size() * sizeof(float);
  const auto picked = [&](const void* array, const ParticleArrayInfo& info) {
    return info.transfer == Transfer::ReadBack && chosen(array, info);
  };
  // The arrays picked of those store() brings back, each run of each, then the springs' runs, one after the other in
  // the copy.
  std::vector<Impl::DevicePart> parts;
  forEachParticleArray(s, [&](const auto& array, const ParticleArrayInfo& info) {
    if (!picked(&array, info)) return;
    forEachComponent(array, [&](const auto&, int c) {
      for (const IndexRun& run : particleRuns)
        parts.push_back({&m.holding(info.binding),
                         static_cast<vk::DeviceSize>(info.block + c) * blockBytes + run.first * sizeof(float),
                         (run.end - run.first) * sizeof(float)});
    });
  });
  for (const IndexRun& run : springRuns)
    parts.push_back(
        {&m.buffer(GB_BINDING_REST_LENGTH), run.first * sizeof(float), (run.end - run.first) * sizeof(float)});
  if (parts.empty()) return;
  m.copyIntoReadback(parts);
  // The same runs in the same order, out of the copy.
  vk::DeviceSize at = 0;
  const auto readRuns = [&](auto* values, const std::vector<IndexRun>& runs) {
    for (const IndexRun& run : runs) {
      const vk::DeviceSize bytes = (run.end - run.first) * sizeof(float);
      m.readFrom(m.readback, values + run.first, bytes, at);
      at += bytes;
    }
  };
  forEachParticleArray(s, [&](auto& array, const ParticleArrayInfo& info) {
    if (!picked(&array, info)) return;
    forEachComponent(array, [&](auto& values, int) { readRuns(values.data(), particleRuns); });
  });
  readRuns(film.topology.restLength.data(), springRuns);
}

bool VulkanStepper::updateRegion(const Params& params, Film& film, std::span<const uint32_t> particles,
                                 size_t firstNewParticle, std::span<const uint32_t> springs, size_t firstNewSpring) {
  Impl& m = *impl_;
  if (m.sets.empty()) return false;
  if (firstNewParticle != m.particles) throw std::logic_error("VulkanStepper::updateRegion: not the loaded film");
  ensureColouring(film.state.alive, film.topology);
  if (params.coarseIterations > 0) ensurePatches(film.state.alive, params.coarsePatchRings, film.topology);
  const State& s = film.state;
  const Topology& t = film.topology;
  m.useParams(params);
  const auto n = static_cast<uint32_t>(s.size());
  if (n != m.particles) m.layOutParticles(particleBlocks(s), n);
  m.triangles = static_cast<uint32_t>(t.triangleCount());
  m.growKeeping(GB_BINDING_REST_LENGTH, t.restLength.size() * sizeof(float), firstNewSpring * sizeof(float));
  m.ensureMeshRoom(t, n);
  m.ensureContactRoom(0, 0);  // the list the device holds stays, the history of the next search
  // The region's particles and the new ones, every array; the region's springs and the new ones.
  std::vector<IndexRun> particleRuns = runsOf(particles), springRuns = runsOf(springs);
  if (firstNewParticle < n) particleRuns.push_back({static_cast<uint32_t>(firstNewParticle), n});
  if (firstNewSpring < t.restLength.size())
    springRuns.push_back({static_cast<uint32_t>(firstNewSpring), static_cast<uint32_t>(t.restLength.size())});
  std::vector<Impl::HostPart> parts = m.particleArrayParts(s, particleRuns);
  m.addRestLengthParts(parts, t, springRuns);
  m.writeThroughUpload(parts);
  m.writeConnectivity(t);
  m.volumeInA = true;  // as a load leaves them
  m.driftInA = true;
  m.writeDescriptorSets();
  // The geometry and film state everywhere at the present positions, as a reloaded film has them: the contact search
  // reads the normals before the next step makes them anew.
  m.bringGeometryToPresentPositions();
  return true;
}

bool VulkanStepper::updateMergedRegion(const Params& params, Film& film, std::span<const uint32_t> particles,
                                       std::span<const uint32_t> from) {
  Impl& m = *impl_;
  if (m.sets.empty()) return false;
  const State& s = film.state;
  const Topology& t = film.topology;
  const size_t before = m.springs, after = t.springCount();
  if (s.size() != m.particles || from.size() != after || std::max(before, after) >= kExactFloatIndices)
    throw std::logic_error("VulkanStepper::updateMergedRegion: not the loaded film, or more springs than it takes");
  ensureColouring(s.alive, film.topology);
  if (params.coarseIterations > 0) ensurePatches(s.alive, params.coarsePatchRings, film.topology);
  m.useParams(params);
  m.triangles = static_cast<uint32_t>(t.triangleCount());
  m.growKeeping(GB_BINDING_REST_LENGTH, std::max(before, after) * sizeof(float), before * sizeof(float));
  m.ensureMeshRoom(t, s.size());
  // The gather's region: where each spring comes from, then the rest lengths before (rest_length_gather.comp).
  const uint32_t at = gpu::reduceStatisticsAt(energyTermsAt(t), m.particles);
  m.ensureRoom(GB_BINDING_REDUCE, std::max(reduceFloats(t, s.size()), at + after + before) * sizeof(float));
  m.writeDescriptorSets();
  m.copyOnDevice(m.buffer(GB_BINDING_REST_LENGTH), 0, m.buffer(GB_BINDING_REDUCE), (at + after) * sizeof(float),
                 before * sizeof(float));
  std::vector<float> source(after);
  std::vector<uint32_t> made;
  for (size_t k = 0; k < after; ++k) {
    source[k] = from[k] == kMadeSpring ? -1.0f : static_cast<float>(from[k]);
    if (from[k] == kMadeSpring) made.push_back(static_cast<uint32_t>(k));
  }
  std::vector<Impl::HostPart> parts = m.particleArrayParts(s, runsOf(particles));
  m.addRestLengthParts(parts, t, runsOf(made));  // the gather leaves them
  parts.push_back({source.data(), &m.buffer(GB_BINDING_REDUCE), at * sizeof(float), after * sizeof(float)});
  m.writeThroughUpload(parts);
  m.writeConnectivity(t);
  m.volumeInA = true;  // as a load leaves them
  m.driftInA = true;
  const vk::raii::CommandBuffer& cb = m.commands;
  cb.reset();
  cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  m.dispatch(cb, Kernel::RestLengthGather, static_cast<uint32_t>(after), 0, 0, at);
  computeToComputeBarrier(cb);
  cb.end();
  m.ctx->submitAndWait(cb);
  return true;
}

void VulkanStepper::refreshGeometry() { impl_->bringGeometryToPresentPositions(); }

std::vector<VulkanStepper::Impl::HostPart> VulkanStepper::Impl::particleArrayParts(const State& s,
                                                                                   std::span<const IndexRun> runs) {
  const vk::DeviceSize blockBytes = vk::DeviceSize{s.size()} * sizeof(float);
  std::vector<HostPart> parts;
  forEachParticleArray(s, [&](const auto& array, const ParticleArrayInfo& info) {
    forEachComponent(array, [&](const auto& values, int c) {
      for (const IndexRun& run : runs)
        parts.push_back({values.data() + run.first, &holding(info.binding),
                         static_cast<vk::DeviceSize>(info.block + c) * blockBytes + run.first * sizeof(float),
                         (run.end - run.first) * sizeof(float)});
    });
  });
  return parts;
}

void VulkanStepper::Impl::addRestLengthParts(std::vector<HostPart>& parts, const Topology& t,
                                             std::span<const IndexRun> runs) {
  for (const IndexRun& run : runs)
    parts.push_back({t.restLength.data() + run.first, &buffer(GB_BINDING_REST_LENGTH), run.first * sizeof(float),
                     (run.end - run.first) * sizeof(float)});
}

void VulkanStepper::Impl::bringGeometryToPresentPositions() {
  StepUniforms u;
  u.dt = 0.0f;
  uploadSteps(std::span(&u, 1));
  const vk::raii::CommandBuffer& cb = commands;
  cb.reset();
  cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  recordGeometryAtPresentPositions(cb, u);
  cb.end();
  ctx->submitAndWait(cb);
}

// The state is copied in one submission into host-cached memory and read from there: on a discrete GPU the
// CPU reads the device's own memory through a mapping (resizable BAR) at uncached speed, which made this the
// slowest part of a frame on an H100 (docs/performance.md).
void VulkanStepper::store(Film& film) {
  storeRuns(
      film, {}, {}, [](const void*, const ParticleArrayInfo&) { return true; }, true);
  ++impl_->copiedToHost.stateReadbacks;
}

void VulkanStepper::storePositions(Film& film) {
  const void* position = &film.state.position;
  storeRuns(
      film, {}, {}, [&](const void* array, const ParticleArrayInfo&) { return array == position; }, true);
}

void VulkanStepper::storeParticleArrays(Film& film, std::initializer_list<const void*> arrays) {
  storeRuns(
      film, {}, {},
      [&](const void* array, const ParticleArrayInfo&) {
        return std::find(arrays.begin(), arrays.end(), array) != arrays.end();
      },
      true);
}

DeviceReadback VulkanStepper::readback() const { return impl_->copiedToHost; }

std::shared_ptr<const VulkanContext> VulkanStepper::sharedContext() const { return impl_->ctx; }

std::optional<DeviceBusyInterval> VulkanStepper::lastStepOnDevice() const { return impl_->lastStep; }

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
