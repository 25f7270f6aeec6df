#include "app/outputs/thickness_image.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include "capture/png_image.h"
#include "kernels/render/colour_maps.h"

namespace gb {

namespace {

using Rgb = std::array<float, 3>;

// Blue (thin) through green to red (thick): the colour map of kernels/render/colour_maps.h, shared with the renderer.
Rgb thicknessColour(float e, const ImageView& v) {
  const float t = std::clamp((e - v.thinColour) / (v.thickColour - v.thinColour), 0.0f, 1.0f);
  return {colour::thicknessRed(t), colour::thicknessGreen(t), colour::thicknessBlue(t)};
}

}  // namespace

ImageView ImageFraming::frame(const Film& film) {
  const State& s = film.state;
  for (size_t i = 0; i < s.size(); ++i)
    if (s.alive[i]) box_.extend(Eigen::Vector2f(s.position.x[i], s.position.y[i]));
  if (box_.isEmpty()) return view_;
  const Eigen::Vector2f size = box_.sizes(), centre = box_.center();
  const float aspect = static_cast<float>(view_.width) / static_cast<float>(view_.height);
  view_.center = Vec3(centre.x(), centre.y(), 0.0f);
  view_.metresAcross = std::max({size.x(), size.y() * aspect, kSmallest}) * (1.0f + 2.0f * kMargin);
  return view_;
}

void writeThicknessImage(const std::filesystem::path& path, const Film& film, const Aerosol& aerosol,
                         const ImageView& v) {
  const float scale = static_cast<float>(v.width) / v.metresAcross;
  auto toPixel = [&](const Vec3& x) {
    return Eigen::Vector2f(static_cast<float>(v.width) / 2 + (x.x() - v.center.x()) * scale,
                           static_cast<float>(v.height) / 2 - (x.y() - v.center.y()) * scale);
  };
  std::vector<uint8_t> rgb(static_cast<size_t>(v.width) * v.height * 3, 24);  // dark grey studio
  std::vector<float> depth(static_cast<size_t>(v.width) * v.height, -std::numeric_limits<float>::infinity());
  const State& s = film.state;
  const Topology& topo = film.topology;
  for (size_t t = 0; t < topo.triangleCount(); ++t) {
    const uint32_t* tri = &topo.triangles[3 * t];
    const Eigen::Vector2f p[3] = {toPixel(s.position.get(tri[0])), toPixel(s.position.get(tri[1])),
                                  toPixel(s.position.get(tri[2]))};
    const float area = (p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x();
    if (std::abs(area) < 1e-9f) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].x(), p[1].x(), p[2].x()}))));
    const int x1 = std::min(v.width - 1, static_cast<int>(std::ceil(std::max({p[0].x(), p[1].x(), p[2].x()}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].y(), p[1].y(), p[2].y()}))));
    const int y1 = std::min(v.height - 1, static_cast<int>(std::ceil(std::max({p[0].y(), p[1].y(), p[2].y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2f q(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
        float w[3];
        for (int c = 0; c < 3; ++c) {
          const Eigen::Vector2f a = p[(c + 1) % 3], b = p[(c + 2) % 3];
          w[c] = ((b - a).x() * (q - a).y() - (b - a).y() * (q - a).x()) / area;
        }
        if (w[0] < 0 || w[1] < 0 || w[2] < 0) continue;
        const float z = w[0] * s.position.z[tri[0]] + w[1] * s.position.z[tri[1]] + w[2] * s.position.z[tri[2]];
        const size_t at = static_cast<size_t>(y) * v.width + x;
        if (z <= depth[at]) continue;
        depth[at] = z;
        const float e = w[0] * s.thickness[tri[0]] + w[1] * s.thickness[tri[1]] + w[2] * s.thickness[tri[2]];
        const Rgb c = thicknessColour(e, v);
        for (int k = 0; k < 3; ++k) rgb[3 * at + k] = static_cast<uint8_t>(255.0f * c[k]);
      }
  }
  for (size_t i = 0; i < aerosol.size(); ++i) {
    const Eigen::Vector2f q = toPixel(aerosol.position.get(i));
    const int x = static_cast<int>(q.x()), y = static_cast<int>(q.y());
    if (x < 0 || y < 0 || x >= v.width || y >= v.height) continue;
    for (int k = 0; k < 3; ++k) rgb[3 * (static_cast<size_t>(y) * v.width + x) + k] = 235;
  }
  writePng(path, v.width, v.height, rgb);
}

}  // namespace gb
