// One definition, compiled as C++ (app/outputs/thickness_image.cpp) and GLSL (the renderer's diagnostic colourings),
// of the diagnostic colour maps, each from t in [0, 1] to a linear red, green, blue in [0, 1].
// Thickness (the paper's Figure 8): blue (thin) through green to red (thick).
// Air flow strength (the paper's Figure 13): dark blue (still) through magenta and orange to yellow (strong).
#ifdef __cplusplus
#pragma once
#include <algorithm>
#include <cmath>
#define GB_INLINE inline
namespace gb::colour {
using std::abs;
using std::clamp;
#else
#define GB_INLINE
#endif

GB_INLINE float thicknessRed(float t) { return clamp(2.0f * t - 0.5f, 0.0f, 1.0f); }
GB_INLINE float thicknessGreen(float t) { return 1.0f - abs(2.0f * clamp(t, 0.0f, 1.0f) - 1.0f); }
GB_INLINE float thicknessBlue(float t) { return clamp(1.5f - 2.0f * t, 0.0f, 1.0f); }

GB_INLINE float airFlowRed(float t) { return clamp(0.1f + 1.8f * t, 0.0f, 1.0f); }
GB_INLINE float airFlowGreen(float t) { return clamp(1.6f * t - 0.55f, 0.0f, 1.0f); }
GB_INLINE float airFlowBlue(float t) { return clamp(0.35f + 1.3f * t - 2.2f * t * t, 0.0f, 1.0f); }

#ifdef __cplusplus
}  // namespace gb::colour
#endif
