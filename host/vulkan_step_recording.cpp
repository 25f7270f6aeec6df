// The Vulkan stepper's step: the rows of the stage table recorded into one command buffer (stepper.h), each stage
// as its kernels with the barriers between their passes.
#include <cstring>

#include "host/vulkan_stepper_impl.h"
#include "solver/coarse_correction.h"
#include "solver/implicit_euler.h"

namespace gb {

void VulkanStepper::Impl::dispatch(const vk::raii::CommandBuffer& cb, Kernel kernel, uint32_t count, uint32_t stepIndex,
                                   uint32_t flags, uint32_t first, float ruleShare) {
  dispatchGroups(cb, kernel, ceilDiv(count, workgroup), count, stepIndex, flags, first, ruleShare);
}

void VulkanStepper::Impl::dispatchTreePass(const vk::raii::CommandBuffer& cb, Kernel kernel, uint32_t n,
                                           uint32_t stepIndex, uint32_t flags, uint32_t first) {
  dispatchGroups(cb, kernel, gpu::treePassOutputs(n), n, stepIndex, flags, first);
}

void VulkanStepper::Impl::dispatchGroups(const vk::raii::CommandBuffer& cb, Kernel kernel, uint32_t groups,
                                         uint32_t count, uint32_t stepIndex, uint32_t flags, uint32_t first,
                                         float ruleShare) {
  cb.bindPipeline(vk::PipelineBindPoint::eCompute, *pipelines[static_cast<size_t>(kernel)]);
  const vk::DescriptorSet set = *sets[static_cast<size_t>(airParity)];
  cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipelineLayout, 0, set, {});
  const PushBlock push{count, particles, stepIndex, flags, triangles, first, patches, solverParticles, ruleShare};
  cb.pushConstants<PushBlock>(*pipelineLayout, vk::ShaderStageFlagBits::eCompute, 0, push);
  cb.dispatch(groups, 1, 1);
}

void VulkanStepper::Impl::recordVolume(const vk::raii::CommandBuffer& cb, uint32_t stepIndex, bool atStepStart) {
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

bool VulkanStepper::Impl::recordEnergyTreeSum(const vk::raii::CommandBuffer& cb, uint32_t stepIndex, uint32_t flags) {
  bool fromA = true;
  for (uint32_t n = particles; n > 1; n = gpu::treePassOutputs(n)) {
    dispatchTreePass(cb, Kernel::EnergyTreeSum, n, stepIndex, (fromA ? GB_REDUCE_ENERGY_IN_A : 0u) | flags, energyBase);
    computeToComputeBarrier(cb);
    fromA = !fromA;
  }
  return fromA;
}

void VulkanStepper::Impl::recordEnergyBudget(const vk::raii::CommandBuffer& cb, const StepUniforms& u,
                                             uint32_t stepIndex) {
  if (u.closed) recordVolume(cb, stepIndex, true);  // energy_terms keeps it
  dispatch(cb, Kernel::EnergyTerms, particles, stepIndex, volumeInA ? GB_REDUCE_VOLUME_IN_A : 0u, energyBase);
  computeToComputeBarrier(cb);                       // the terms are written, the volume before is kept
  if (u.closed) recordVolume(cb, stepIndex, false);  // the volume after: the gas's change, the step's pressure
  const bool fromA = recordEnergyTreeSum(cb, stepIndex, 0);
  dispatch(cb, Kernel::EnergyScale, 1, stepIndex,
           (fromA ? GB_REDUCE_ENERGY_IN_A : 0u) | (volumeInA ? GB_REDUCE_VOLUME_IN_A : 0u), energyBase);
}

void VulkanStepper::Impl::recordStage(const vk::raii::CommandBuffer& cb, Stage stage, const StepUniforms& u,
                                      uint32_t stepIndex) {
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
      const int coarseAfter = coarseSweepsBefore(*params, u);
      for (int sweep = 0; sweep < sweepsThisStep(*params, u); ++sweep) {
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

void VulkanStepper::Impl::recordStep(const vk::raii::CommandBuffer& cb, const StepUniforms& u, uint32_t stepIndex) {
  for (const StageSpec& spec : stepStages()) {
    if (!spec.runs(*params, u)) continue;
    recordStage(cb, spec.stage, u, stepIndex);
    if (spec.barrierAfter) computeToComputeBarrier(cb);
  }
}

void VulkanStepper::Impl::uploadSteps(std::span<const StepUniforms> steps) {
  ensureStepCapacity(steps.size());
  buffer(GB_BINDING_STEPS).write(steps.data(), steps.size_bytes());  // the CPU's uniforms are the kernels' block
  if (std::memcmp(&paramsOnDevice, params, sizeof(Params)) != 0) useParams(*params);
}

void VulkanStepper::Impl::useParams(const Params& live) {
  params = &live;
  paramsOnDevice = live;
  buffer(GB_BINDING_PARAMS).write(&live, sizeof(Params));
}

float VulkanStepper::run(std::span<const StepUniforms> substeps) {
  Impl& m = *impl_;
  if (m.sets.empty()) throw std::logic_error("VulkanStepper: no film loaded");
  if (substeps.empty()) return m.params->pressureCoefficient;
  m.uploadSteps(substeps);
  m.lastStep.reset();
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
        if (!spec.runs(*m.params, substeps[k])) continue;
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
    const vk::QueryPool stamps = *m.stepTimestamps;
    if (stamps) {
      cb.resetQueryPool(stamps, 0, 2);
      cb.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, stamps, 0);
    }
    for (uint32_t k = 0; k < substeps.size(); ++k) m.recordStep(cb, substeps[k], k);
    computeToHostBarrier(cb);
    if (stamps) cb.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, stamps, 1);
    cb.end();
    m.ctx->submitAndWait(cb);
    if (stamps) m.lastStep = m.ctx->busyInterval(m.stepTimestamps);
  }
  const StepUniforms& last = substeps.back();
  lastBudget_ = m.params->integrator != 0 && m.params->energyBudget != 0 ? m.readVelocityBudget() : VelocityBudget{};
  return last.closed ? boylePressure(*m.params, last.referenceVolume, m.readVolume()) : m.params->pressureCoefficient;
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

}  // namespace gb
