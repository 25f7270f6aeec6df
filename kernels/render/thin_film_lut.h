// One definition, compiled as C++ (host/thin_film.cpp builds the table) and GLSL (kernels/render/film.frag reads it),
// of the thin-film lookup texture's layout: texel columns are film thickness, rows the cosine of the view angle
// in air. Thickness is stored along sqrt(e / max) so that the first interference orders (0-600 nm, where the
// colour changes fastest) get most of the texels: 2.5 nm per texel at 200 nm, 16 nm at 8 um where the colours
// have washed out to a uniform grey-white.
#ifdef __cplusplus
#pragma once
#include <algorithm>
#include <cmath>
#define GB_INLINE inline
namespace gb::lut {
using std::clamp;
using std::sqrt;
#else
#define GB_INLINE
#endif

#define GB_LUT_THICKNESS_TEXELS 1024
#define GB_LUT_ANGLE_TEXELS 64
#define GB_LUT_MAX_THICKNESS 8.0e-6f  // m; thicker films are shown with the colour of this one
#define GB_FILM_INDEX 1.33f           // refractive index of water-soap film

// Column i of the table holds thickness (i / (columns - 1))^2 x max; row j holds cos theta = j / (rows - 1).
// The first and last texel centres are the ends of the range, so nothing is extrapolated at e = 0 or cos = 1.
GB_INLINE float lutThicknessOfColumn(float column) {
  const float u = column / float(GB_LUT_THICKNESS_TEXELS - 1);
  return u * u * GB_LUT_MAX_THICKNESS;
}
GB_INLINE float lutCosineOfRow(float row) { return row / float(GB_LUT_ANGLE_TEXELS - 1); }

// Normalised texture coordinates (what a sampler takes) of a thickness (m) and of cos theta.
GB_INLINE float lutThicknessTexture(float thickness) {
  const float u = sqrt(clamp(thickness / GB_LUT_MAX_THICKNESS, 0.0f, 1.0f));
  return (u * float(GB_LUT_THICKNESS_TEXELS - 1) + 0.5f) / float(GB_LUT_THICKNESS_TEXELS);
}
GB_INLINE float lutAngleTexture(float cosTheta) {
  return (clamp(cosTheta, 0.0f, 1.0f) * float(GB_LUT_ANGLE_TEXELS - 1) + 0.5f) / float(GB_LUT_ANGLE_TEXELS);
}

#ifdef __cplusplus
}  // namespace gb::lut
#endif
