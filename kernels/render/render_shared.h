// One definition, compiled as C++ (host/renderer.cpp) and GLSL (the render shaders), of what the renderer's
// shaders receive: the per-frame uniform block and the descriptor bindings. Matrices are column-major mat4
// (16 floats), vectors vec4: std430 and C++ agree with no hidden padding (static_asserts in host/renderer.cpp).
#ifdef __cplusplus
#pragma once
#include "shared_step.h"  // gb::gpu::vec4, uint
namespace gb::gpu {
struct alignas(16) mat4 {
  float m[16];
};
#endif

// Colourings of the film (RenderUniforms::colouring).
#define GB_COLOURING_INTERFERENCE 0
#define GB_COLOURING_THICKNESS 1
#define GB_COLOURING_AIR_FLOW 2

struct RenderUniforms {
  mat4 viewProjection;       // world -> clip (Vulkan: y down, depth 0 near .. 1 far)
  mat4 skyRays;              // clip -> a view ray's direction from the eye (OrbitCamera::skyRays), for the sky
  vec4 cameraPosition;       // world (m)
  vec4 keyLight;             // unit direction towards the key light (the sun, a softbox); w: its strength on props
  vec4 skyIrradiance;        // mean environment radiance over the upper hemisphere (props' ambient light)
  vec4 groundIrradiance;     // and over the lower hemisphere
  vec4 horizon;              // environment radiance just below the horizon (the far ground fades into it); w:
                             // the floor's fog distance (m)
  uint particles;            // stride of the x, y, z blocks of the film's vector buffers
  uint colouring;            // GB_COLOURING_*
  float thickColour;         // thickness drawn red by the thickness colouring (m)
  float airFlowColour;       // air flow strength drawn yellow by the air flow colouring (m^3/s)
  float exposure;            // scale of radiance before display encoding
  float pointScale;          // droplet sprite size: pixels per metre at distance 1 m
  float dropletRadius;       // drawn radius of a droplet (m)
  uint thicknessVariation;   // 1: the interference colouring multiplies the thickness by GB_RENDER_VARIATION
  float minTubePixels;       // tubes (string, wands, rims) are drawn at least this radius in pixels, so that
                             // a string thinner than a pixel stays a continuous anti-aliased line
  float blackFilmThickness;  // thinner film is black film: the interference colouring draws no reflection (m)
  uint pad1, pad2;
  vec4 cameraImage;  // the mirror view (host/camera_layer.h): a fragment at (X, Y) shows the camera image's
                     // pixel (x X + y, z Y + w) (DepthCameraView::imageOfPicture)
  vec4 cameraDepth;  // x, y: the depth buffer's value of camera-space distance z is x - y / z; z, w: image size
};

#ifdef __cplusplus
}  // namespace gb::gpu
#endif

// Descriptor set 0: the scene.
#define GB_RENDER_UNIFORMS 0
#define GB_RENDER_POSITION 1        // film positions, x block then y then z (as the stepper holds them)
#define GB_RENDER_NORMAL 2          // film vertex normals, same layout
#define GB_RENDER_THICKNESS 3       // film thickness per particle (m)
#define GB_RENDER_AIR_FLOW 4        // transferred air flow per particle, vector blocks (m^3/s)
#define GB_RENDER_TRIANGLES 5       // 3 particle indices per triangle; the film draw reads them as its index buffer
#define GB_RENDER_LUT 6             // thin-film reflectance by thickness and angle (kernels/render/thin_film_lut.h)
#define GB_RENDER_ENVIRONMENT 7     // equirectangular environment radiance
#define GB_RENDER_MESH 8            // opaque props: 12 floats per vertex (position, normal, albedo, material, pad)
#define GB_RENDER_DROPLETS 9        // aerosol droplets: vec4 (position, opacity)
#define GB_RENDER_VARIATION 10      // per-particle thickness factor of the film's swirls (host/film_swirls.h)
#define GB_RENDER_CAMERA_COLOUR 11  // the mirror view's camera image: packed sRGBA8 per pixel (host/camera_layer.h)
#define GB_RENDER_CAMERA_DEPTH 12   // and its camera-space distance per pixel (m; 0: nothing there)
#define GB_RENDER_SCENE_BINDINGS 13
// Descriptor set 1: the composite pass's inputs.
#define GB_COMPOSITE_OPAQUE 0
#define GB_COMPOSITE_ACCUM 1
#define GB_COMPOSITE_REVEAL 2
#define GB_COMPOSITE_SKY 3  // the environment along each pixel's view ray (sky.frag)

// Materials of the opaque props (the fourth float of a mesh vertex's albedo).
#define GB_MATERIAL_PLAIN 0
#define GB_MATERIAL_FLOOR 1  // the ground: fades into the horizon's haze with distance
#define GB_MATERIAL_RIM 2    // the rim of a bursting film's hole: water, reflecting the environment brightly
