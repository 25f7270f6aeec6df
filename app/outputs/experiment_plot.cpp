#include "app/outputs/experiment_plot.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "capture/output_file.h"

namespace gb {
namespace {

struct Range {
  double lo = 1e300, hi = -1e300;
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  [[nodiscard]] double span() const { return hi > lo ? hi - lo : 1.0; }
};

// Maps data to the plot area of an 640 x 400 image with 70 px margins left and bottom.
struct Frame {
  Range x, y;
  static constexpr double left = 70, right = 620, top = 40, bottom = 340;
  [[nodiscard]] double px(double v) const { return left + (v - x.lo) / x.span() * (right - left); }
  [[nodiscard]] double py(double v) const { return bottom - (v - y.lo) / y.span() * (bottom - top); }
};

void axes(std::ostream& svg, const Frame& f, const Measurement& m) {
  svg << "<rect x='" << Frame::left << "' y='" << Frame::top << "' width='" << Frame::right - Frame::left
      << "' height='" << Frame::bottom - Frame::top << "' fill='none' stroke='#444'/>\n";
  for (int k = 0; k <= 4; ++k) {  // five ticks per axis, labelled with their values
    // A tick a rounding error away from zero is zero.
    auto tick = [](const Range& r, int i) {
      const double v = r.lo + r.span() * i / 4;
      return std::abs(v) < 1e-6 * r.span() ? 0.0 : v;
    };
    const double xv = tick(f.x, k), yv = tick(f.y, k);
    svg << "<text x='" << f.px(xv) << "' y='" << Frame::bottom + 18 << "' font-size='11' text-anchor='middle'>" << xv
        << "</text>\n<text x='" << Frame::left - 6 << "' y='" << f.py(yv) + 4 << "' font-size='11' text-anchor='end'>"
        << yv << "</text>\n";
  }
  svg << "<text x='" << (Frame::left + Frame::right) / 2 << "' y='" << Frame::bottom + 40
      << "' font-size='13' text-anchor='middle'>" << m.xLabel << "</text>\n<text x='16' y='"
      << (Frame::top + Frame::bottom) / 2 << "' font-size='13' text-anchor='middle' transform='rotate(-90 16 "
      << (Frame::top + Frame::bottom) / 2 << ")'>" << m.yLabel << "</text>\n<text x='" << Frame::left << "' y='24'"
      << " font-size='14'>" << m.experiment << ": the film (dots) and the analytic curve (line)</text>\n";
}

}  // namespace

void writeExperimentPlot(const std::filesystem::path& path, const Measurement& m) {
  if (m.measuredPoints.empty()) return;
  Frame f;
  for (const auto& [x, y] : m.measuredPoints) f.x.add(x), f.y.add(y);
  for (const auto& [x, y] : m.analyticCurve) f.x.add(x), f.y.add(y);
  std::ostringstream svg;
  svg.precision(4);
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='640' height='400' font-family='sans-serif'>\n"
      << "<rect width='640' height='400' fill='white'/>\n";
  axes(svg, f, m);
  svg << "<polyline fill='none' stroke='#c03' stroke-width='2' points='";
  for (const auto& [x, y] : m.analyticCurve) svg << f.px(x) << ',' << f.py(y) << ' ';
  svg << "'/>\n";
  for (const auto& [x, y] : m.measuredPoints)
    svg << "<circle cx='" << f.px(x) << "' cy='" << f.py(y) << "' r='1.6' fill='#036'/>\n";
  svg << "</svg>\n";
  writeFileAtomically(path, svg.str());
}

}  // namespace gb
