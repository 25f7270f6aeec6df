#pragma once
// The embedded SPIR-V of the renderer's shaders (host/renderer.cpp).

#include <cstdint>
#include <span>

namespace gb::kernels {

enum class RenderShader {
  FullscreenVert,  // one screen-covering triangle
  PropsVert,       // floor, wands, string
  PropsFrag,
  DropletsVert,  // aerosol point sprites
  DropletsFrag,
  FilmVert,        // the film from the simulation's buffers
  FilmFrag,        // thin-film interference or a diagnostic colouring, into the transparency targets
  CompositeFrag,   // transparency resolve over the opaque scene and the sky, display encoding
  SkyFrag,         // the environment along each pixel's view ray, for the resolve
  CameraImageFrag  // the mirror view's camera image at its own depth (host/camera_layer.h)
};

std::span<const uint32_t> renderSpirv(RenderShader shader);

}  // namespace gb::kernels
