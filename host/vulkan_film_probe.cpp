// The Vulkan stepper's film probe: the frame's statistics and the film checks of the rules between steps summed on
// the device (kernels/statistics/film_statistics_*.comp), and the rest-length rules run there (film_rest_lengths.comp).
#include <algorithm>
#include <cmath>

#include "host/vulkan_stepper_impl.h"

namespace gb {

void VulkanStepper::Impl::recordGeometryAtPresentPositions(const vk::raii::CommandBuffer& cb, const StepUniforms& u) {
  recordStage(cb, Stage::Geometry, u, 0);
  computeToComputeBarrier(cb);
  recordStage(cb, Stage::FilmState, u, 0);
  computeToComputeBarrier(cb);
}

std::array<float, GB_STATISTICS_TERMS> VulkanStepper::Impl::sumStatistics(const FilmProbe& probe) {
  StepUniforms u;
  u.dt = 0.0f;  // the film state without ageing it
  u.volumeOrigin = toVec4(probe.origin);
  u.leftPosition = toVec4(probe.tips[0]);
  u.rightPosition = toVec4(probe.tips[1]);
  u.frameTime = probe.frameTime;
  uploadSteps(std::span(&u, 1));
  const uint32_t at = gpu::reduceStatisticsAt(energyBase, particles);
  const vk::raii::CommandBuffer& cb = commands;
  cb.reset();
  cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  if (probe.atPresentPositions) recordGeometryAtPresentPositions(cb, u);
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

bool VulkanStepper::Impl::runSpringRule(uint32_t rule, float share) {
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

bool VulkanStepper::findCrowdedSprings(CrowdedCandidates& found) {
  Impl& m = *impl_;
  if (!m.statisticsOnDevice || m.springs >= kExactFloatIndices) return false;
  if (m.sets.empty()) throw std::logic_error("VulkanStepper: no film loaded");
  found = {};
  if (m.particles == 0) return true;
  const uint32_t at = gpu::reduceStatisticsAt(m.energyBase, m.particles);
  const vk::raii::CommandBuffer& cb = m.commands;
  cb.reset();
  cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  computeToComputeBarrier(cb);
  m.dispatchGroups(cb, Kernel::CrowdedSprings, 1, m.particles, 0, 0, at);
  computeToHostBarrier(cb);
  cb.end();
  m.ctx->submitAndWait(cb);
  std::array<float, GB_CROWDED_LIST> head{};
  m.readFrom(m.buffer(GB_BINDING_REDUCE), head.data(), sizeof head, at * sizeof(float));
  const auto listed = static_cast<size_t>(head[GB_CROWDED_LISTED]);
  if (listed > size_t{2} * GB_STATISTICS_TERMS * m.particles - GB_CROWDED_LIST) return false;  // the list overflowed
  found.medianSquaredLength = head[GB_CROWDED_MEDIAN];
  std::vector<float> list(listed);
  m.readFrom(m.buffer(GB_BINDING_REDUCE), list.data(), listed * sizeof(float), (at + GB_CROWDED_LIST) * sizeof(float));
  found.springs.reserve(listed);
  for (const float spring : list) found.springs.push_back(static_cast<uint32_t>(spring));
  std::sort(found.springs.begin(), found.springs.end());  // listed as the invocations came
  return true;
}

void VulkanStepper::storeRestLengths(Film& film) {
  Impl& m = *impl_;
  std::vector<float>& rest = film.topology.restLength;
  if (rest.size() * sizeof(float) > m.buffer(GB_BINDING_REST_LENGTH).size())
    throw std::logic_error("VulkanStepper::storeRestLengths: not the loaded film");
  m.readFrom(m.buffer(GB_BINDING_REST_LENGTH), rest.data(), rest.size() * sizeof(float));
}

}  // namespace gb
