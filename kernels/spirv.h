#pragma once
// The embedded SPIR-V of every compute shader in this folder, one per stage of the step.

#include <cstdint>
#include <span>

namespace gb::kernels {

enum class Kernel {
  TriangleGeometry,
  VertexGeometry,
  TriangleVolume,
  TreeSum,
  FilmState,
  AirInflow,
  AirTransfer,
  Forces,
  Integrate,
  DrainageOutflow,
  DrainageGather
};
inline constexpr int kKernelCount = 11;

std::span<const uint32_t> spirv(Kernel kernel);
const char* kernelName(Kernel kernel);

}  // namespace gb::kernels
