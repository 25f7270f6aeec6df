#pragma once
// Thin-film interference colour of a soap film in air (the renderer's lookup table). Pure C++, no Vulkan.
//
// A film of index n and thickness d lit at angle theta in air reflects, per wavelength and polarisation, the
// Airy sum of its two interfaces (r = Fresnel amplitude air->film, -r film->air, phase delta = 4 pi n d cos(theta_t)
// / lambda):  R = 2 r^2 (1 - cos delta) / (1 + r^4 - 2 r^2 cos delta); unpolarised light averages s and p.
// The spectrum R(lambda) under illuminant D65 is integrated against the CIE 1931 observer (5 nm, 380-780 nm) to
// XYZ, normalised so that a perfect mirror has Y = 1, and turned into linear sRGB (Belcour and Barla 2017 do the
// same spectral integration; they also filter the phase analytically, which at 5 nm sampling is not needed
// below the table's 8 um, where fringes are still 20 nm apart in wavelength).

#include <array>
#include <vector>

namespace gb {

using Rgb3 = std::array<double, 3>;

// Unpolarised reflectance of a film of index `filmIndex` and thickness `thickness` (m) in air, for light of
// wavelength `wavelength` (m) whose direction makes cos(theta) = cosIncidence with the film normal.
double airyReflectance(double filmIndex, double thickness, double wavelength, double cosIncidence);

// CIE XYZ (Y = 1 for a perfect mirror under D65) of the film's reflection, and its linear sRGB.
Rgb3 thinFilmXyz(double filmIndex, double thickness, double cosIncidence);
Rgb3 xyzToLinearSrgb(const Rgb3& xyz);
Rgb3 linearSrgbToXyz(const Rgb3& rgb);

// The lookup texture of kernels/render/thin_film_lut.h: GB_LUT_THICKNESS_TEXELS columns (thickness along
// sqrt(e / max)) by GB_LUT_ANGLE_TEXELS rows (cos theta from 0 to 1, texel centres), RGBA float, linear sRGB
// reflectance clamped to [0, 1] (the few saturated colours outside the sRGB gamut lose a little chroma),
// alpha = luminance Y (the film's opacity in the transparency blend).
struct ThinFilmLut {
  int width = 0;
  int height = 0;
  std::vector<float> rgba;  // row-major, row = angle
};
ThinFilmLut buildThinFilmLut(double filmIndex);

// What a bilinear texture sampler returns at (thickness, cos theta): the CPU twin of film.frag's lookup.
std::array<float, 4> sampleThinFilmLut(const ThinFilmLut& lut, float thickness, float cosIncidence);

}  // namespace gb
