#include "render_spirv.h"

#include "spirv/camera_image_frag.h"
#include "spirv/composite_frag.h"
#include "spirv/droplets_frag.h"
#include "spirv/droplets_vert.h"
#include "spirv/film_frag.h"
#include "spirv/film_vert.h"
#include "spirv/fullscreen_vert.h"
#include "spirv/props_frag.h"
#include "spirv/props_vert.h"
#include "spirv/sky_frag.h"

namespace gb::kernels {

std::span<const uint32_t> renderSpirv(RenderShader shader) {
  switch (shader) {
    case RenderShader::FullscreenVert:
      return fullscreen_vert_spv;
    case RenderShader::PropsVert:
      return props_vert_spv;
    case RenderShader::PropsFrag:
      return props_frag_spv;
    case RenderShader::DropletsVert:
      return droplets_vert_spv;
    case RenderShader::DropletsFrag:
      return droplets_frag_spv;
    case RenderShader::FilmVert:
      return film_vert_spv;
    case RenderShader::FilmFrag:
      return film_frag_spv;
    case RenderShader::CompositeFrag:
      return composite_frag_spv;
    case RenderShader::SkyFrag:
      return sky_frag_spv;
    case RenderShader::CameraImageFrag:
      return camera_image_frag_spv;
  }
  return {};
}

}  // namespace gb::kernels
