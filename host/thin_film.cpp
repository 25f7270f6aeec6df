#include "host/thin_film.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "host/spectral_tables.h"
#include "kernels/render/thin_film_lut.h"

namespace gb {

namespace {

// Film-air Fresnel amplitudes (s, p) for light arriving from air at cos(theta_i) = ci and refracted into the
// film at cos(theta_t) = ct.
std::array<double, 2> fresnelAmplitudes(double n, double ci, double ct) {
  return {(ci - n * ct) / (ci + n * ct), (n * ci - ct) / (n * ci + ct)};
}

}  // namespace

double airyReflectance(double filmIndex, double thickness, double wavelength, double cosIncidence) {
  const double ci = std::clamp(cosIncidence, 0.0, 1.0);
  const double sinT = std::sqrt(1.0 - ci * ci) / filmIndex;  // Snell
  const double ct = std::sqrt(1.0 - sinT * sinT);
  const double cosDelta = std::cos(4.0 * std::numbers::pi * filmIndex * thickness * ct / wavelength);
  double sum = 0.0;
  for (const double r : fresnelAmplitudes(filmIndex, ci, ct)) {
    const double r2 = r * r;
    sum += 2.0 * r2 * (1.0 - cosDelta) / (1.0 + r2 * r2 - 2.0 * r2 * cosDelta);
  }
  return 0.5 * sum;
}

Rgb3 thinFilmXyz(double filmIndex, double thickness, double cosIncidence) {
  Rgb3 xyz{0, 0, 0};
  double white = 0;
  for (int i = 0; i < spectral::kCmfCount; ++i) {
    const double nm = spectral::kCmfFirstNm + spectral::kCmfStepNm * i;
    const double light = spectral::d65(nm);
    const double r = airyReflectance(filmIndex, thickness, nm * 1e-9, cosIncidence);
    for (int c = 0; c < 3; ++c)
      xyz[static_cast<size_t>(c)] += r * light * spectral::kCie1931[static_cast<size_t>(i)][static_cast<size_t>(c)];
    white += light * spectral::kCie1931[static_cast<size_t>(i)][1];
  }
  for (double& v : xyz) v /= white;
  return xyz;
}

// IEC 61966-2-1 (sRGB, D65 white) matrices.
Rgb3 xyzToLinearSrgb(const Rgb3& v) {
  return {3.2404542 * v[0] - 1.5371385 * v[1] - 0.4985314 * v[2],
          -0.9692660 * v[0] + 1.8760108 * v[1] + 0.0415560 * v[2],
          0.0556434 * v[0] - 0.2040259 * v[1] + 1.0572252 * v[2]};
}

Rgb3 linearSrgbToXyz(const Rgb3& c) {
  return {0.4124564 * c[0] + 0.3575761 * c[1] + 0.1804375 * c[2],
          0.2126729 * c[0] + 0.7151522 * c[1] + 0.0721750 * c[2],
          0.0193339 * c[0] + 0.1191920 * c[1] + 0.9503041 * c[2]};
}

ThinFilmLut buildThinFilmLut(double filmIndex) {
  ThinFilmLut lut;
  lut.width = GB_LUT_THICKNESS_TEXELS;
  lut.height = GB_LUT_ANGLE_TEXELS;
  lut.rgba.resize(static_cast<size_t>(lut.width) * lut.height * 4);
#pragma omp parallel for
  for (int row = 0; row < lut.height; ++row) {
    const double cosTheta = lut::lutCosineOfRow(static_cast<float>(row));
    for (int col = 0; col < lut.width; ++col) {
      const double e = lut::lutThicknessOfColumn(static_cast<float>(col));
      const Rgb3 xyz = thinFilmXyz(filmIndex, e, cosTheta);
      const Rgb3 rgb = xyzToLinearSrgb(xyz);
      float* texel = &lut.rgba[4 * (static_cast<size_t>(row) * lut.width + col)];
      for (int c = 0; c < 3; ++c) texel[c] = static_cast<float>(std::clamp(rgb[static_cast<size_t>(c)], 0.0, 1.0));
      texel[3] = static_cast<float>(xyz[1]);
    }
  }
  return lut;
}

std::array<float, 4> sampleThinFilmLut(const ThinFilmLut& lut, float thickness, float cosIncidence) {
  // Texel centres sit at (i + 0.5) / size; clamp-to-edge addressing.
  const float x = lut::lutThicknessTexture(thickness) * static_cast<float>(lut.width) - 0.5f;
  const float y = lut::lutAngleTexture(cosIncidence) * static_cast<float>(lut.height) - 0.5f;
  const auto texel = [&](int i, int j) {
    i = std::clamp(i, 0, lut.width - 1);
    j = std::clamp(j, 0, lut.height - 1);
    return &lut.rgba[4 * (static_cast<size_t>(j) * lut.width + i)];
  };
  const int i = static_cast<int>(std::floor(x)), j = static_cast<int>(std::floor(y));
  const float fx = x - static_cast<float>(i), fy = y - static_cast<float>(j);
  std::array<float, 4> out{};
  for (size_t c = 0; c < 4; ++c)
    out[c] = (1 - fy) * ((1 - fx) * texel(i, j)[c] + fx * texel(i + 1, j)[c]) +
             fy * ((1 - fx) * texel(i, j + 1)[c] + fx * texel(i + 1, j + 1)[c]);
  return out;
}

}  // namespace gb
