// The thin-film lookup table (host/thin_film.cpp) against an independent spectral computation written here:
// complex Airy amplitudes per polarisation (not the closed-form intensity of the module), the Wyman, Sloan and
// Shirley (2013) analytic multi-lobe fit of the CIE 1931 observer (not the typed 5 nm table), 1 nm steps (not
// 5 nm), compared in CIELAB. Also the colour sequence a physicist expects from Newton's series, checked on the
// table the renderer uses, and the typed observer table itself.
#include "host/thin_film.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>

#include "host/spectral_tables.h"
#include "kernels/render/thin_film_lut.h"

namespace gb {
namespace {

constexpr double kFilmIndex = GB_FILM_INDEX;

// Wyman, Sloan, Shirley, "Simple Analytic Approximations to the CIE XYZ Color Matching Functions", JCGT 2(2),
// 2013: the multi-lobe piecewise Gaussian fit.
double lobe(double nm, double mu, double sigmaBelow, double sigmaAbove) {
  const double t = (nm - mu) / (nm < mu ? sigmaBelow : sigmaAbove);
  return std::exp(-0.5 * t * t);
}
Rgb3 wymanCmf(double nm) {
  return {
      1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7) - 0.065 * lobe(nm, 501.1, 20.4, 26.2),
      0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1),
      1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8)};
}

// Reflectance from the complex Airy sum r = (r12 + r23 e^{i delta}) / (1 + r12 r23 e^{i delta}), s and p.
double airyComplex(double thickness, double nm, double cosIncidence) {
  const double ci = cosIncidence, n = kFilmIndex;
  const double ct = std::sqrt(1.0 - (1.0 - ci * ci) / (n * n));
  const std::complex<double> phase = std::polar(1.0, 4.0 * std::numbers::pi * n * thickness * ct / (nm * 1e-9));
  const double rs12 = (ci - n * ct) / (ci + n * ct), rp12 = (n * ci - ct) / (n * ci + ct);
  // Leaving the film: the film->air amplitudes (from the film side) are the negatives.
  const double rs23 = (n * ct - ci) / (n * ct + ci), rp23 = (ct - n * ci) / (ct + n * ci);
  const double rs = std::norm((rs12 + rs23 * phase) / (1.0 + rs12 * rs23 * phase));
  const double rp = std::norm((rp12 + rp23 * phase) / (1.0 + rp12 * rp23 * phase));
  return 0.5 * (rs + rp);
}

Rgb3 independentXyz(double thickness, double cosIncidence) {
  Rgb3 xyz{0, 0, 0};
  double white = 0;
  for (double nm = 380; nm <= 780; nm += 1.0) {
    const Rgb3 cmf = wymanCmf(nm);
    const double light = spectral::d65(nm), r = airyComplex(thickness, nm, cosIncidence);
    for (size_t c = 0; c < 3; ++c) xyz[c] += r * light * cmf[c];
    white += light * cmf[1];
  }
  for (double& v : xyz) v /= white;
  return xyz;
}

struct Lab {
  double L, a, b;
  [[nodiscard]] double chroma() const { return std::hypot(a, b); }
  [[nodiscard]] double hueDegrees() const {
    const double h = std::atan2(b, a) * 180.0 / std::numbers::pi;
    return h < 0 ? h + 360.0 : h;
  }
};

// CIELAB with the film's brightest possible reflection as reference white: the eye adapts to the bubble, whose
// reflectance never exceeds 4 r^2 / (1 + r^2)^2 (7.7% at normal incidence), not to a white sheet of paper.
Lab toLab(const Rgb3& xyz) {
  const double r = (1.0 - kFilmIndex) / (1.0 + kFilmIndex);
  const double brightest = 4 * r * r / ((1 + r * r) * (1 + r * r));
  const Rgb3 white{0.95047 * brightest, brightest, 1.08883 * brightest};
  auto f = [](double t) { return t > 216.0 / 24389.0 ? std::cbrt(t) : (24389.0 / 27.0 * t + 16.0) / 116.0; };
  const double fx = f(xyz[0] / white[0]), fy = f(xyz[1] / white[1]), fz = f(xyz[2] / white[2]);
  return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

double deltaE(const Lab& p, const Lab& q) {
  return std::sqrt((p.L - q.L) * (p.L - q.L) + (p.a - q.a) * (p.a - q.a) + (p.b - q.b) * (p.b - q.b));
}

// The independent colour as the table must store it: linear sRGB, negative (out-of-gamut) channels clamped.
Lab independentStoredLab(double thickness, double cosIncidence) {
  Rgb3 rgb = xyzToLinearSrgb(independentXyz(thickness, cosIncidence));
  for (double& c : rgb) c = std::max(c, 0.0);
  return toLab(linearSrgbToXyz(rgb));
}

Lab lutLab(const ThinFilmLut& lut, double thickness, double cosIncidence) {
  const auto t = sampleThinFilmLut(lut, static_cast<float>(thickness), static_cast<float>(cosIncidence));
  return toLab(linearSrgbToXyz({t[0], t[1], t[2]}));
}

const ThinFilmLut& table() {
  static const ThinFilmLut lut = buildThinFilmLut(kFilmIndex);
  return lut;
}

TEST(ThinFilm, ObserverTableMatchesTheStandardAndAnAnalyticFit) {
  // Spot values of CIE 015 Table T.4, exactly as published.
  auto at = [](int nm) { return spectral::kCie1931[static_cast<size_t>((nm - 380) / 5)]; };
  EXPECT_EQ(at(555)[1], 1.0);
  EXPECT_EQ(at(600)[0], 1.0622);
  EXPECT_EQ(at(450)[2], 1.77211);
  // Equal-energy white has chromaticity (1/3, 1/3): a mistyped entry of 0.01 moves it by more than 5e-5.
  Rgb3 sum{0, 0, 0};
  for (const auto& row : spectral::kCie1931)
    for (size_t c = 0; c < 3; ++c) sum[c] += row[c];
  const double total = sum[0] + sum[1] + sum[2];
  EXPECT_NEAR(sum[0] / total, 1.0 / 3.0, 2e-4);
  EXPECT_NEAR(sum[1] / total, 1.0 / 3.0, 2e-4);
  // Every entry within 0.03 of the analytic fit plus 5% of the value: the fit's own error (its authors quote
  // under 1% of the peak in the mean, a few % at worst); a digit typed wrong in the first two places fails.
  for (int i = 0; i < spectral::kCmfCount; ++i) {
    const double nm = 380.0 + 5.0 * i;
    const Rgb3 fit = wymanCmf(nm);
    for (size_t c = 0; c < 3; ++c) {
      const double v = spectral::kCie1931[static_cast<size_t>(i)][c];
      EXPECT_NEAR(v, fit[c], 0.03 + 0.05 * v) << "channel " << c << " at " << nm << " nm";
    }
  }
}

TEST(ThinFilm, ClosedFormAiryEqualsComplexAmplitudeSum) {
  // Two formulations of one physical quantity; only rounding separates them (1e-12 absolute).
  for (double e : {0.0, 50e-9, 210e-9, 1.3e-6})
    for (double c : {1.0, 0.7, 0.2})
      for (double nm : {400.0, 550.0, 700.0})
        EXPECT_NEAR(airyReflectance(kFilmIndex, e, nm * 1e-9, c), airyComplex(e, nm, c), 1e-12);
}

TEST(ThinFilm, LookupTableMatchesIndependentSpectralComputation) {
  // Tolerance: CIELAB Delta E 3.0 (Delta E 2.3 is a just-noticeable difference). What separates the two
  // paths is the analytic observer fit against the table (about Delta E 1-2 on saturated colours) and the
  // bilinear lookup between texels; a wrong formula, table, illuminant or texel mapping gives tens.
  const double thicknessesNm[] = {10, 30, 60, 100, 150, 200, 250, 300, 350, 400, 500, 650, 800, 1200, 3000, 6000};
  for (double cosTheta : {1.0, 0.5}) {
    double worst = 0;
    for (double nm : thicknessesNm) {
      const double e = nm * 1e-9;
      const double d = deltaE(lutLab(table(), e, cosTheta), independentStoredLab(e, cosTheta));
      worst = std::max(worst, d);
      EXPECT_LT(d, 3.0) << "thickness " << nm << " nm, cos theta " << cosTheta;
    }
    std::printf("cos theta %.1f: worst Delta E %.2f over %zu thicknesses\n", cosTheta, worst, std::size(thicknessesNm));
  }
}

TEST(ThinFilm, NewtonSeriesOfColours) {
  // The reflected colours of a soap film (Newton's series, n = 1.33, looking straight on), read from the table
  // the renderer samples. Lightness is relative to the brightest a film can be (toLab).
  auto lab = [](double nm) { return lutLab(table(), nm * 1e-9, 1.0); };
  // Black films (below about 30 nm) reflect under a tenth of the first-order white: L* under 40.
  for (double nm : {5.0, 10.0, 20.0}) EXPECT_LT(lab(nm).L, 40.0) << nm << " nm: black film";
  EXPECT_LT(lab(5).L, lab(20).L);
  // First-order white-silver near a quarter wave (550 / 4 / 1.33 = 103 nm): bright, nearly neutral.
  EXPECT_GT(lab(100).L, 85.0);
  EXPECT_LT(lab(100).chroma(), 20.0);
  // First-order magenta near a half wave (207 nm): green cancelled, red and blue kept.
  EXPECT_GT(lab(200).a, 20.0);
  EXPECT_LT(lab(200).b, 0.0);
  // Second order: blue, then green, then yellow as the cancelled band moves to the red.
  EXPECT_LT(lab(240).b, -20.0);
  EXPECT_LT(lab(300).a, -15.0);
  EXPECT_GT(lab(330).b, 20.0);
  // Second-order magenta near a full wave (414 nm) and the third order's green after it.
  EXPECT_GT(lab(400).a, 20.0);
  EXPECT_LT(lab(480).a, -10.0);
  // Several micrometres: the fringes are closer than the eye resolves in wavelength: near-white grey.
  for (double nm : {3000.0, 6000.0}) {
    EXPECT_LT(lab(nm).chroma(), 8.0) << nm << " nm";
    EXPECT_GT(lab(nm).L, 60.0) << nm << " nm";
  }
  // Print the series for the reader of the log (docs/rendering.md quotes it).
  for (double nm : {10.0, 30.0, 100.0, 150.0, 200.0, 240.0, 300.0, 330.0, 400.0, 480.0, 3000.0, 6000.0}) {
    const Lab c = lab(nm);
    std::printf("%6.0f nm: L %5.1f a %6.1f b %6.1f  C %5.1f h %5.1f\n", nm, c.L, c.a, c.b, c.chroma(), c.hueDegrees());
  }
}

TEST(ThinFilm, GrazingLightReflectsMore) {
  // Fresnel: at grazing incidence the film becomes a mirror. Luminance (alpha) at cos 0.05 far above normal.
  const auto normal = sampleThinFilmLut(table(), 3e-6f, 1.0f), grazing = sampleThinFilmLut(table(), 3e-6f, 0.05f);
  EXPECT_GT(grazing[3], 5.0f * normal[3]);
  EXPECT_LE(grazing[3], 1.0f);
}

}  // namespace
}  // namespace gb
