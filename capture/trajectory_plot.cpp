#include "capture/trajectory_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "capture/output_file.h"

namespace gb {

namespace {

constexpr double kPanel = 300.0, kMargin = 40.0;
constexpr double kTitleLine = 18.0;   // px between the title's lines (14 px font)
constexpr size_t kTitleColumns = 88;  // characters per title line: a 14 px sans-serif line of the plot's width

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

// The title broken into lines at spaces (or slashes, for long paths), none longer than kTitleColumns.
std::vector<std::string> titleLines(const std::string& title) {
  std::vector<std::string> lines;
  std::string rest = title;
  while (rest.size() > kTitleColumns) {
    size_t cut = rest.find_last_of(" /", kTitleColumns - 1);
    cut = cut == std::string::npos || cut == 0 ? kTitleColumns : cut + 1;
    lines.push_back(rest.substr(0, cut));
    rest = rest.substr(cut);
  }
  lines.push_back(rest);
  return lines;
}

// The scene row: both wands in one frame with the references (floor, origin, camera), front and top.
void scenePanels(std::ostream& out, const TrajectoryPlot& plot, double top);

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
  const std::vector<std::string> title = titleLines(plot.title);
  const double kTop = 32.0 + kTitleLine * static_cast<double>(title.size());
  const double width = 2 * kPanel + 3 * kMargin, height = kTop + 3 * kPanel + 4 * kMargin;
  std::ostringstream out;
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  for (size_t i = 0; i < title.size(); ++i)
    out << "<text x=\"" << kMargin << "\" y=\"" << 22 + kTitleLine * static_cast<double>(i) << "\" font-size=\"14\">"
        << escaped(title[i]) << "</text>\n";
  out << "<text x=\"" << kMargin << "\" y=\"" << kTop - 10
      << "\">input hand: dotted   wand: solid   start: +   end: x   "
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
  scenePanels(out, plot, kTop + kMargin + 2 * (kPanel + kMargin));
  out << "</svg>\n";
  writeFileAtomically(path, out.str());
}

namespace {

void scenePanels(std::ostream& out, const TrajectoryPlot& plot, double top) {
  // Both views take one scale, from everything that is drawn: the wands, the origin and the camera.
  std::vector<Vec3> references = {Vec3::Zero()};
  if (plot.camera) references.push_back(*plot.camera);
  Range axes[3];
  const std::vector<Vec3>* tracks[] = {&plot.leftWand, &plot.rightWand, &references};
  for (const std::vector<Vec3>* track : tracks)
    for (const Vec3& p : *track)
      for (int a = 0; a < 3; ++a) axes[a].add(p[a]);
  axes[1].add(0.0);  // the floor
  double span = 0.5;
  for (const Range& r : axes) span = std::max(span, r.hi - r.lo);
  const double scale = 0.85 * kPanel / span;
  const char* names[2] = {"scene, front (x right, y up)", "scene, top (x right, z forward)"};
  for (int c = 0; c < 2; ++c) {
    const int vertical = c == 0 ? 1 : 2;
    const double left = kMargin + c * (kPanel + kMargin);
    const double cx = 0.5 * (axes[0].lo + axes[0].hi), cy = 0.5 * (axes[vertical].lo + axes[vertical].hi);
    const View view{0, vertical, names[c], scale, {cx, cx}, {cy, cy}};
    auto x = [&](const Vec3& p) { return view.x(p, 0, left); };
    auto y = [&](const Vec3& p) { return view.y(p, 0, top); };
    out << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << kPanel << "\" height=\"" << kPanel
        << "\" fill=\"none\" stroke=\"#999\"/>\n<text x=\"" << left << "\" y=\"" << top - 6 << "\">" << names[c]
        << "</text>\n";
    if (c == 0) {  // the floor, y = 0, across the front view
      const double floorY = y(Vec3::Zero());
      out << "<path stroke=\"#8c6d31\" stroke-width=\"2\" d=\"M" << left << ',' << floorY << " h" << kPanel
          << "\"/><text x=\"" << left + 4 << "\" y=\"" << floorY - 4 << "\" fill=\"#8c6d31\">floor</text>\n";
    }
    polyline(out, plot.leftWand, view, 0, left, top, "#d62728", false);
    polyline(out, plot.rightWand, view, 1, left, top, "#1f77b4", false);
    marker(out, x(Vec3::Zero()), y(Vec3::Zero()), false, "#2ca02c");
    out << "<text x=\"" << x(Vec3::Zero()) + 7 << "\" y=\"" << y(Vec3::Zero()) + 14
        << "\" fill=\"#2ca02c\">origin</text>\n";
    if (plot.camera) {
      const double px = x(*plot.camera), py = y(*plot.camera);
      out << "<rect x=\"" << px - 6 << "\" y=\"" << py - 4 << "\" width=\"12\" height=\"8\" fill=\"#555\"/><text x=\""
          << px + 9 << "\" y=\"" << py + 4 << "\">camera</text>\n";
    }
    const double bar = 0.5 * scale;
    out << "<path stroke=\"#333\" d=\"M" << left + 8 << ',' << top + kPanel - 10 << " h" << bar << "\"/><text x=\""
        << left + 12 + bar << "\" y=\"" << top + kPanel - 6 << "\">50 cm</text>\n";
  }
}

}  // namespace

}  // namespace gb
