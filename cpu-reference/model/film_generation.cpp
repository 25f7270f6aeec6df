// Film generation: wire frame -> boundary particles -> lattice interior -> CGAL constrained Delaunay.
// CGAL stays inside this file.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <queue>
#include <stdexcept>
#include <unordered_map>

#include "model/film.h"
#include "stages/stages.h"

namespace gb {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<uint32_t, Kernel>;
using FaceInfo = CGAL::Triangulation_face_base_with_info_2<int, Kernel>;  // nesting level of the face
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel, FaceInfo>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;

using Point2 = Eigen::Vector2f;

// The frame's plane coordinates of a world point.
Point2 toPlane(const WireFrame& f, const Vec3& p) { return {(p - f.center).dot(f.axis), (p - f.center).dot(f.down)}; }
Vec3 fromPlane(const WireFrame& f, const Point2& q) { return f.center + q.x() * f.axis + q.y() * f.down; }

double distanceToSegment(const Point2& p, const Point2& a, const Point2& b) {
  const Point2 ab = b - a;
  const float t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-20f), 0.0f, 1.0f);
  return (p - (a + t * ab)).norm();
}

// Interior lattice points of the polygon with their distance to the boundary.
struct InteriorPoints {
  std::vector<Point2> points;
  std::vector<float> boundaryDistance;
};

// Hexagonal lattice of the given spacing inside the polygon, keeping only points at least 0.55 spacing
// from the boundary so that no sliver triangles form there. Rows are clipped by scanline intersection and
// distances use a bucket grid of the boundary edges, so this is linear in the number of points.
InteriorPoints hexLatticeInside(const std::vector<Point2>& polygon, float spacing) {
  InteriorPoints out;
  Point2 lo = polygon[0], hi = polygon[0];
  for (const Point2& p : polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const float cell = spacing;
  const int gx = static_cast<int>((hi.x() - lo.x()) / cell) + 3, gy = static_cast<int>((hi.y() - lo.y()) / cell) + 3;
  auto cellOf = [&](const Point2& p) {
    return std::array<int, 2>{static_cast<int>((p.x() - lo.x()) / cell) + 1,
                              static_cast<int>((p.y() - lo.y()) / cell) + 1};
  };
  std::vector<std::vector<uint32_t>> buckets(static_cast<size_t>(gx) * gy);
  const size_t n = polygon.size();
  for (uint32_t e = 0; e < n; ++e) {
    const Point2 a = polygon[e], b = polygon[(e + 1) % n];
    const auto ca = cellOf(a.cwiseMin(b)), cb = cellOf(a.cwiseMax(b));
    for (int x = std::max(0, ca[0] - 1); x <= std::min(gx - 1, cb[0] + 1); ++x)
      for (int y = std::max(0, ca[1] - 1); y <= std::min(gy - 1, cb[1] + 1); ++y)
        buckets[static_cast<size_t>(y) * gx + x].push_back(e);
  }
  const float minDistance = 0.55f * spacing;
  const float rowStep = 0.5f * std::sqrt(3.0f) * spacing;
  const Point2 mid = 0.5f * (lo + hi);
  const int rowsHalf = static_cast<int>((hi.y() - lo.y()) / rowStep / 2) + 1;
  const int colsHalf = static_cast<int>((hi.x() - lo.x()) / spacing / 2) + 2;
  std::vector<float> crossings;
  for (int r = -rowsHalf; r <= rowsHalf; ++r) {
    const float y = mid.y() + static_cast<float>(r) * rowStep;
    crossings.clear();
    for (size_t e = 0; e < n; ++e) {
      const Point2 a = polygon[e], b = polygon[(e + 1) % n];
      if ((a.y() > y) != (b.y() > y)) crossings.push_back(a.x() + (y - a.y()) / (b.y() - a.y()) * (b.x() - a.x()));
    }
    std::sort(crossings.begin(), crossings.end());
    const float shift = (r & 1) ? 0.5f * spacing : 0.0f;
    for (int c = -colsHalf; c <= colsHalf; ++c) {
      const Point2 p(mid.x() + static_cast<float>(c) * spacing + shift, y);
      const auto inside = std::upper_bound(crossings.begin(), crossings.end(), p.x()) - crossings.begin();
      if (inside % 2 == 0) continue;
      double d = minDistance;  // only distances below the cut-off matter
      const auto pc = cellOf(p);
      for (uint32_t e : buckets[static_cast<size_t>(pc[1]) * gx + pc[0]])
        d = std::min(d, distanceToSegment(p, polygon[e], polygon[(e + 1) % n]));
      if (d < minDistance) continue;
      out.points.push_back(p);
      out.boundaryDistance.push_back(static_cast<float>(d));
    }
  }
  return out;
}

struct PlanarLayout {
  std::vector<float> boundaryU;
  std::vector<Point2> boundary;
  InteriorPoints interior;
  [[nodiscard]] size_t count() const { return boundary.size() + interior.points.size(); }
};

PlanarLayout layoutForSpacing(const WireFrame& f, float spacing) {
  PlanarLayout layout;
  layout.boundaryU = wireParameters(f, spacing);
  for (float u : layout.boundaryU) layout.boundary.push_back(toPlane(f, wirePoint(f, u)));
  layout.interior = hexLatticeInside(layout.boundary, spacing);
  return layout;
}

// The layout with exactly `target` points: bisection on the spacing for the smallest layout with at least
// the target, then the interior points nearest the boundary (the most crowded) are dropped.
PlanarLayout layoutWithCount(const WireFrame& f, size_t target) {
  const float nominal = std::sqrt(f.area() / static_cast<float>(target));
  float lo = 0.2f * nominal, hi = 3.0f * nominal;  // count(lo) >= target > count(hi)
  if (layoutForSpacing(f, lo).count() < target) throw std::runtime_error("film generation: frame too small");
  for (int it = 0; it < 40; ++it) {
    const float mid = 0.5f * (lo + hi);
    (layoutForSpacing(f, mid).count() >= target ? lo : hi) = mid;
  }
  PlanarLayout layout = layoutForSpacing(f, lo);
  const size_t excess = layout.count() - target;
  if (excess > layout.interior.points.size())
    throw std::invalid_argument("film generation: a film of " + std::to_string(target) +
                                " particles (particlesAtFullSolution x solution: --particles, --solution) is too few "
                                "for its wire, which alone takes " +
                                std::to_string(layout.boundary.size()) + ": give more particles or a larger solution");
  std::vector<size_t> order(layout.interior.points.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return layout.interior.boundaryDistance[a] < layout.interior.boundaryDistance[b];
  });
  std::vector<char> keep(order.size(), 1);
  for (size_t k = 0; k < excess; ++k) keep[order[k]] = 0;
  InteriorPoints kept;
  for (size_t k = 0; k < keep.size(); ++k)
    if (keep[k]) kept.points.push_back(layout.interior.points[k]);
  layout.interior = std::move(kept);
  return layout;
}

// Marks each face with its nesting level: 0 outside, 1 inside the constrained polygon (CGAL's domain marking,
// flood fill across unconstrained edges).
void markDomains(Cdt& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::queue<Cdt::Face_handle> border;
  border.push(cdt.infinite_face());
  for (int level = 0; !border.empty(); ++level) {
    std::queue<Cdt::Face_handle> next;
    while (!border.empty()) {
      std::queue<Cdt::Face_handle> fill;
      fill.push(border.front());
      border.pop();
      while (!fill.empty()) {
        const Cdt::Face_handle f = fill.front();
        fill.pop();
        if (f->info() != -1) continue;
        f->info() = level;
        for (int e = 0; e < 3; ++e) {
          const Cdt::Face_handle g = f->neighbor(e);
          if (g->info() != -1) continue;
          (cdt.is_constrained(Cdt::Edge(f, e)) ? next : fill).push(g);
        }
      }
    }
    border = std::move(next);
  }
}

// Triangles of the layout, counter-clockwise in plane coordinates, with particle indices: boundary
// particles first (in frame order), interior after.
std::vector<uint32_t> triangulate(const PlanarLayout& layout) {
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handles;
  Cdt::Face_handle hint;
  auto add = [&](const Point2& p) {
    Cdt::Vertex_handle v = cdt.insert(Kernel::Point_2(p.x(), p.y()), hint);
    v->info() = static_cast<uint32_t>(handles.size());
    hint = v->face();
    handles.push_back(v);
  };
  for (const Point2& p : layout.boundary) add(p);
  for (const Point2& p : layout.interior.points) add(p);
  if (cdt.number_of_vertices() != handles.size())
    throw std::runtime_error("film generation: two particles fell on the same point");
  const size_t nb = layout.boundary.size();
  for (size_t k = 0; k < nb; ++k) cdt.insert_constraint(handles[k], handles[(k + 1) % nb]);
  markDomains(cdt);
  std::vector<uint32_t> triangles;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (f->info() % 2 != 1) continue;
    for (int c = 0; c < 3; ++c) triangles.push_back(f->vertex(c)->info());
  }
  return triangles;
}

// The wet wire after a dip: it holds solutionReserve times the new film's liquid for growth (Section 7).
void fillWire(const Params& params, const PlanarLayout& layout, Film& film) {
  double liquid = 0;
  for (float l : film.state.liquid) liquid += l;
  film.wireLiquidAtDip = film.wireLiquid = static_cast<float>(params.solutionReserve * liquid);
  const size_t nb = layout.boundary.size();
  float perimeter = 0.0f;
  for (size_t k = 0; k < nb; ++k) perimeter += (layout.boundary[(k + 1) % nb] - layout.boundary[k]).norm();
  film.wireSpacing = perimeter / static_cast<float>(nb);
}

}  // namespace

void initialiseNewParticles(const Params& params, Film& film, size_t first) {
  computeGeometry(film.topology, film.state);
  giveNewFilmMaterial(params, film.state, first);
}

void giveNewFilmMaterial(const Params& params, State& s, size_t first) {
  const float e0 = initialThickness(params);
  for (size_t i = first; i < s.size(); ++i) {
    s.liquid[i] = e0 * s.voronoiArea[i];
    s.mass[i] = particleMass(params, s.voronoiArea[i], s.liquid[i]);
    s.lifetime[i] = 0.0f;
    s.alive[i] = 1u;
    s.velocity.set(i, Vec3::Zero());
    filmState(params, 0.0f, s, i);
  }
}

void initialiseFilmMaterial(const Params& params, Film& film) {
  for (float& l : film.topology.restLength) l *= 1.0f - params.springPrestrain;
  initialiseNewParticles(params, film, 0);
  State& s = film.state;
  for (Vec3Array* a : {&s.airFlow, &s.airFlowNext, &s.airInflow, &s.force}) a->resize(s.size());
}

Film generateFilm(const Params& params, const WandTool& tool, const WandState& wands) {
  if (const auto errors = validate(params); !errors.empty()) throw std::invalid_argument(errors.front());
  // Beyond this distance a float's steps are millimetres, and the film's particles would fall on each other: wands
  // that far away are an input in the wrong units or a broken calibration, and are named as such.
  constexpr float kFarthestWands = 1000.0f;  // m
  const float farthest = std::max(wands.leftPosition.norm(), wands.rightPosition.norm());
  if (!(farthest <= kFarthestWands)) {
    char message[200];
    std::snprintf(message, sizeof message,
                  "film generation: the wands are %.4g m from the origin, beyond %.0f m (an input in other units than "
                  "metres? a --reach or --performer far off?)",
                  farthest, kFarthestWands);
    throw std::invalid_argument(message);
  }
  Film film;
  film.tool = tool;
  const Vec3 gravity(params.gravityX, params.gravityY, params.gravityZ);
  const float halfWidth = 0.5f * (wands.rightPosition - wands.leftPosition).norm();
  film.stringLength = hangingStringLength(halfWidth, tool.loopDepth * params.solution);
  const WireFrame frame = makeWireFrame(tool, wands, film.stringLength, gravity);
  if (frame.area() <= 1e-6f) throw std::invalid_argument("film generation: the wire frame encloses no area");
  film.loopHang = frame.down;

  const auto target =
      static_cast<size_t>(std::lround(static_cast<double>(params.solution) * params.particlesAtFullSolution));
  const PlanarLayout layout = layoutWithCount(frame, std::max<size_t>(target, 16));

  State& s = film.state;
  s.resize(layout.count());
  for (size_t k = 0; k < layout.boundary.size(); ++k) {
    s.position.set(k, wirePoint(frame, layout.boundaryU[k]));
    s.wireParam[k] = layout.boundaryU[k];
  }
  for (size_t k = 0; k < layout.interior.points.size(); ++k)
    s.position.set(layout.boundary.size() + k, fromPlane(frame, layout.interior.points[k]));
  film.topology = buildTopology(s.size(), triangulate(layout), s.position);

  for (size_t k = 0; k < s.size(); ++k)
    if ((film.topology.boundary[k] != 0) != (k < layout.boundary.size()))
      throw std::runtime_error("film generation: the triangulation does not follow the wire frame");
  initialiseFilmMaterial(params, film);
  fillWire(params, layout, film);
  return film;
}

Film generateSphere(const Params& params, const Vec3& center, float radius, int subdivisions) {
  if (const auto errors = validate(params); !errors.empty()) throw std::invalid_argument(errors.front());
  if (subdivisions < 0 || subdivisions > 9) throw std::invalid_argument("sphere subdivisions must be in [0, 9]");
  // Icosahedron, counter-clockwise seen from outside, then each triangle split in four on the sphere.
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<Vec3> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& p : v) p.normalize();
  std::vector<uint32_t> tri = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                               4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                               6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto found = midpoints.find(key);
      if (found != midpoints.end()) return found->second;
      v.push_back((v[a] + v[b]).normalized());
      return midpoints[key] = static_cast<uint32_t>(v.size() - 1);
    };
    std::vector<uint32_t> finer;
    for (size_t k = 0; k < tri.size(); k += 3) {
      const uint32_t a = tri[k], b = tri[k + 1], c = tri[k + 2];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      finer.insert(finer.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    tri = std::move(finer);
  }
  Film film;
  film.state.resize(v.size());
  for (size_t k = 0; k < v.size(); ++k) film.state.position.set(k, center + radius * v[k]);
  film.topology = buildTopology(v.size(), std::move(tri), film.state.position);
  initialiseFilmMaterial(params, film);
  return film;
}

Film generateTube(const Params& params, const Vec3& center, float radius, float separation, int around) {
  if (const auto errors = validate(params); !errors.empty()) throw std::invalid_argument(errors.front());
  if (around < 6 || !(radius > 0) || !(separation > 0))
    throw std::invalid_argument("tube: needs radius, separation > 0 and 6 or more particles around");
  const float spacing = 2.0f * std::numbers::pi_v<float> * radius / static_cast<float>(around);
  const int rows = std::max(2, static_cast<int>(std::lround(separation / (0.866f * spacing))));
  Film film;
  film.tool.kind = ToolKind::Ring;  // no wand loop to pinch
  film.state.resize(static_cast<size_t>(around) * static_cast<size_t>(rows + 1));
  auto index = [&](int row, int k) { return static_cast<uint32_t>(row * around + (k % around)); };
  for (int row = 0; row <= rows; ++row)
    for (int k = 0; k < around; ++k) {
      // Alternate rows are turned half a step, so the triangles come out nearly equilateral.
      const float phi = 2.0f * std::numbers::pi_v<float> *
                        (static_cast<float>(k) + 0.5f * static_cast<float>(row % 2)) / static_cast<float>(around);
      const float z = -0.5f * separation + separation * static_cast<float>(row) / static_cast<float>(rows);
      film.state.position.set(index(row, k), center + Vec3(radius * std::cos(phi), radius * std::sin(phi), z));
    }
  std::vector<uint32_t> triangles;
  for (int row = 0; row < rows; ++row)
    for (int k = 0; k < around; ++k) {
      const bool shifted = row % 2 == 1;  // this row's point k sits between the next row's k and k + 1
      const uint32_t a = index(row, k), b = index(row, k + 1);
      const uint32_t c = index(row + 1, k), d = index(row + 1, k + 1);
      if (shifted)
        triangles.insert(triangles.end(), {a, b, d, a, d, c});
      else
        triangles.insert(triangles.end(), {a, b, c, b, d, c});
    }
  film.topology = buildTopology(film.state.size(), std::move(triangles), film.state.position);
  for (size_t i = 0; i < film.state.size(); ++i)
    if (film.topology.boundary[i]) film.state.wireParam[i] = -1.0f;
  initialiseFilmMaterial(params, film);
  // Outward: the first triangle's normal points away from the axis, or all are turned.
  computeGeometry(film.topology, film.state);
  const Vec3 p0 = film.state.position.get(film.topology.triangles[0]) - center;
  if (film.state.triangleNormal.get(0).dot(Vec3(p0.x(), p0.y(), 0.0f)) < 0) {
    for (size_t t = 0; t < film.topology.triangleCount(); ++t)
      std::swap(film.topology.triangles[3 * t + 1], film.topology.triangles[3 * t + 2]);
    buildAdjacency(film.topology);
    computeGeometry(film.topology, film.state);
  }
  return film;
}

}  // namespace gb
