#include "spirv.h"

#include <cstdint>

#include "spirv/air_inflow.h"
#include "spirv/air_transfer.h"
#include "spirv/drainage_gather.h"
#include "spirv/drainage_outflow.h"
#include "spirv/film_state.h"
#include "spirv/forces.h"
#include "spirv/integrate.h"
#include "spirv/tree_sum.h"
#include "spirv/triangle_geometry.h"
#include "spirv/triangle_volume.h"
#include "spirv/vertex_geometry.h"

namespace gb::kernels {

std::span<const uint32_t> spirv(Kernel kernel) {
  switch (kernel) {
    case Kernel::TriangleGeometry: return triangle_geometry_spv;
    case Kernel::VertexGeometry: return vertex_geometry_spv;
    case Kernel::TriangleVolume: return triangle_volume_spv;
    case Kernel::TreeSum: return tree_sum_spv;
    case Kernel::FilmState: return film_state_spv;
    case Kernel::AirInflow: return air_inflow_spv;
    case Kernel::AirTransfer: return air_transfer_spv;
    case Kernel::Forces: return forces_spv;
    case Kernel::Integrate: return integrate_spv;
    case Kernel::DrainageOutflow: return drainage_outflow_spv;
    case Kernel::DrainageGather: return drainage_gather_spv;
  }
  return {};
}

const char* kernelName(Kernel kernel) {
  static constexpr const char* names[] = {"triangle_geometry", "vertex_geometry", "triangle_volume", "tree_sum", "film_state",
                                          "air_inflow", "air_transfer", "forces", "integrate",
                                          "drainage_outflow", "drainage_gather"};
  return names[static_cast<int>(kernel)];
}

}  // namespace gb::kernels
