#include "trajectory_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace gb {

namespace {

constexpr double kPanel = 300.0, kMargin = 40.0, kTop = 50.0;

struct Range {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  [[nodiscard]] bool empty() const { return lo > hi; }
};

// One view: which world axes go right and up, and the metres -> pixels mapping. Both hands' panels of a view
// share the scale (so their motions compare) and each is centred on its own hand.
struct View {
  int horizontal, vertical;
  const char* name;
  double scale = 1.0;
  double cx[2] = {0.0, 0.0}, cy[2] = {0.0, 0.0};
  void fit(const std::vector<const std::vector<Vec3>*> tracks[2]) {
    double span = 0.1;  // 10 cm at least
    for (int hand = 0; hand < 2; ++hand) {
      Range h, v;
      for (const auto* t : tracks[hand])
        for (const Vec3& p : *t) {
          h.add(p[horizontal]);
          v.add(p[vertical]);
        }
      if (h.empty() || v.empty()) continue;
      span = std::max({span, h.hi - h.lo, v.hi - v.lo});
      cx[hand] = 0.5 * (h.lo + h.hi);
      cy[hand] = 0.5 * (v.lo + v.hi);
    }
    scale = 0.85 * kPanel / span;
  }
  [[nodiscard]] double x(const Vec3& p, int hand, double left) const {
    return left + 0.5 * kPanel + (p[horizontal] - cx[hand]) * scale;
  }
  [[nodiscard]] double y(const Vec3& p, int hand, double top) const {
    return top + 0.5 * kPanel - (p[vertical] - cy[hand]) * scale;
  }
};

void polyline(std::ostream& out, const std::vector<Vec3>& track, const View& view, int hand, double left, double top,
              const char* colour, bool dotted) {
  std::ostringstream points;
  auto flush = [&] {
    if (points.str().empty()) return;
    out << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"" << (dotted ? 1.2 : 1.8) << "\""
        << (dotted ? " stroke-dasharray=\"1.5,2.5\"" : "") << " points=\"" << points.str() << "\"/>\n";
    points.str("");
  };
  for (const Vec3& p : track) {
    if (!p.allFinite()) {
      flush();
      continue;
    }
    char xy[48];
    std::snprintf(xy, sizeof xy, "%.1f,%.1f ", view.x(p, hand, left), view.y(p, hand, top));
    points << xy;
  }
  flush();
}

void marker(std::ostream& out, double x, double y, bool cross, const char* colour) {
  const double r = 5.0;
  out << "<path stroke=\"" << colour << "\" stroke-width=\"2\" d=\"";
  if (cross)
    out << "M" << x - r << ',' << y - r << " L" << x + r << ',' << y + r << " M" << x - r << ',' << y + r << " L"
        << x + r << ',' << y - r;
  else
    out << "M" << x - r << ',' << y << " L" << x + r << ',' << y << " M" << x << ',' << y - r << " L" << x << ','
        << y + r;
  out << "\"/>\n";
}

std::string escaped(const std::string& text) {
  std::string out;
  for (const char ch : text) {
    if (ch == '<')
      out += "&lt;";
    else if (ch == '>')
      out += "&gt;";
    else if (ch == '&')
      out += "&amp;";
    else
      out += ch;
  }
  return out;
}

}  // namespace

void writeTrajectoryPlot(const std::filesystem::path& path, const TrajectoryPlot& plot) {
  View views[2] = {{0, 1, "front (x right, y up)"}, {0, 2, "top (x right, z forward)"}};
  const std::vector<const std::vector<Vec3>*> tracks[2] = {{&plot.leftInput, &plot.leftWand},
                                                           {&plot.rightInput, &plot.rightWand}};
  for (View& v : views) v.fit(tracks);
  const double width = 2 * kPanel + 3 * kMargin, height = kTop + 2 * kPanel + 3 * kMargin;
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write the trajectory plot " + path.string());
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out << "<text x=\"" << kMargin << "\" y=\"22\" font-size=\"14\">" << escaped(plot.title) << "</text>\n";
  out << "<text x=\"" << kMargin << "\" y=\"40\">input hand: dotted   wand: solid   start: +   end: x   "
      << "(world space; both panels of a row share their scale)</text>\n";
  const struct {
    const char* name;
    const char* colour;
    const std::vector<Vec3>* input;
    const std::vector<Vec3>* wand;
  } columns[2] = {{"left wand", "#d62728", &plot.leftInput, &plot.leftWand},
                  {"right wand", "#1f77b4", &plot.rightInput, &plot.rightWand}};
  for (int row = 0; row < 2; ++row) {
    const View& view = views[row];
    for (int c = 0; c < 2; ++c) {
      const double left = kMargin + c * (kPanel + kMargin), top = kTop + kMargin + row * (kPanel + kMargin);
      out << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << kPanel << "\" height=\"" << kPanel
          << "\" fill=\"none\" stroke=\"#999\"/>\n";
      out << "<text x=\"" << left << "\" y=\"" << top - 6 << "\">" << columns[c].name << ", " << view.name
          << "</text>\n";
      // A 10 cm scale bar in the panel's corner.
      const double bar = 0.1 * view.scale;
      out << "<path stroke=\"#333\" d=\"M" << left + 8 << ',' << top + kPanel - 10 << " h" << bar << "\"/><text x=\""
          << left + 12 + bar << "\" y=\"" << top + kPanel - 6 << "\">10 cm</text>\n";
      polyline(out, *columns[c].input, view, c, left, top, columns[c].colour, true);
      polyline(out, *columns[c].wand, view, c, left, top, columns[c].colour, false);
      const std::vector<Vec3>& wand = *columns[c].wand;
      if (!wand.empty()) {
        marker(out, view.x(wand.front(), c, left), view.y(wand.front(), c, top), false, "#000");
        marker(out, view.x(wand.back(), c, left), view.y(wand.back(), c, top), true, "#000");
      }
    }
  }
  out << "</svg>\n";
  if (!out) throw std::runtime_error("cannot write the trajectory plot " + path.string());
}

}  // namespace gb
