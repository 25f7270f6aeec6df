#include "topology/bursting.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <queue>
#include <set>
#include <utility>

namespace gb {

namespace {

constexpr float kNever = std::numeric_limits<float>::infinity();

// Makes sure the per-particle arrays cover the film (it may have been made after the front).
void fitToFilm(BurstFront& front, const Film& film) {
  if (front.arrival.size() != film.state.size()) front.arrival.assign(film.state.size(), kNever);
}

// Each particle's mass is shared by the triangles it belongs to, so that the droplets carry exactly the
// mass of the particles they come from.
void countShares(BurstFront& front, const Film& film) {
  front.shares.assign(film.state.size(), 0u);
  for (uint32_t v : film.topology.triangles) ++front.shares[v];
}

// Removes the dead particles' springs and triangles from the physics mesh and rebuilds the one-ring. A spring
// stays only while a triangle of the film still holds it: a thread with no film around it is not film.
void dropDeadElements(Film& film, BurstFront& front, TopologyEvents& events) {
  State& s = film.state;
  Topology& topo = film.topology;
  std::vector<uint32_t> triangles;
  for (size_t t = 0; t < topo.triangleCount(); ++t) {
    const uint32_t* tri = &topo.triangles[3 * t];
    const bool intact = s.alive[tri[0]] && s.alive[tri[1]] && s.alive[tri[2]];
    (intact ? triangles : front.torn).insert((intact ? triangles : front.torn).end(), tri, tri + 3);
    if (!intact) ++events.trianglesRemoved;
  }
  topo.triangles = std::move(triangles);
  std::set<std::pair<uint32_t, uint32_t>> edges;
  for (size_t t = 0; t < topo.triangleCount(); ++t)
    for (int c = 0; c < 3; ++c)
      edges.insert(std::minmax(topo.triangles[3 * t + c], topo.triangles[3 * t + (c + 1) % 3]));
  std::vector<uint32_t> ends;
  std::vector<float> rest;
  for (size_t k = 0; k < topo.springCount(); ++k) {
    const uint32_t a = topo.springEnds[2 * k], b = topo.springEnds[2 * k + 1];
    if (!edges.count(std::minmax(a, b))) continue;
    ends.insert(ends.end(), {a, b});
    rest.push_back(topo.restLength[k]);
  }
  topo.springEnds = std::move(ends);
  topo.restLength = std::move(rest);
  buildAdjacency(topo);
}

// Droplets for torn triangles whose corners are now all dead. A retracting rim gathers the film's liquid and
// sheds it as droplets much larger than the film is thick (Lhuissier and Villermaux, "Bursting bubble
// aerosols", J. Fluid Mech. 696, 2012: rim instabilities, drops of tens to hundreds of microns), so the liquid
// of the triangles that die in one frame is gathered into one droplet per cell of kDropletCell (a few hundred
// to a few thousand droplets for a metre-sized film), not one per triangle. A droplet's mass is the liquid its
// triangles carried (each particle's liquid split evenly among the triangles it had when the burst began),
// times the liquid's density: the droplets together weigh what the film's liquid weighed. It flies with the
// mass-weighted velocity of its particles, never faster than the rim's Taylor-Culick speed there, the fastest
// the retracting film moves its liquid.
constexpr float kDropletCell = 0.025f;  // m

struct DropletSum {
  Vec3 momentum = Vec3::Zero();
  Vec3 moment = Vec3::Zero();  // mass times position
  float mass = 0.0f;
  float thickness = 0.0f;  // mass-weighted, for the rim speed
};

void emitDroplets(const Params& p, Film& film, BurstFront& front, Aerosol& aerosol, TopologyEvents& events) {
  const State& s = film.state;
  std::vector<uint32_t> stillTorn;
  std::map<std::array<int, 3>, DropletSum> cells;  // ordered: droplets are emitted in a defined order
  for (size_t t = 0; t < front.torn.size(); t += 3) {
    const uint32_t* tri = &front.torn[t];
    if (s.alive[tri[0]] || s.alive[tri[1]] || s.alive[tri[2]]) {
      stillTorn.insert(stillTorn.end(), tri, tri + 3);
      continue;
    }
    Vec3 centroid = Vec3::Zero();
    for (int c = 0; c < 3; ++c) centroid += s.position.get(tri[c]) / 3.0f;
    const Vec3 cell = (centroid / kDropletCell).array().floor();
    DropletSum& d = cells[{static_cast<int>(cell.x()), static_cast<int>(cell.y()), static_cast<int>(cell.z())}];
    for (int c = 0; c < 3; ++c) {
      const float m = p.liquidDensity * s.liquid[tri[c]] / static_cast<float>(std::max(1u, front.shares[tri[c]]));
      d.mass += m;
      d.moment += m * s.position.get(tri[c]);
      d.momentum += m * s.velocity.get(tri[c]);
      d.thickness += m * s.thickness[tri[c]];
    }
  }
  for (const auto& [cell, d] : cells) {
    if (d.mass <= 0.0f) continue;
    Vec3 v = d.momentum / d.mass;
    const float rim = taylorCulickSpeed(p, d.thickness / d.mass);
    if (v.norm() > rim) v *= rim / v.norm();
    aerosol.add(d.moment / d.mass, v, d.mass);
    ++events.dropletsEmitted;
    events.dropletMassEmitted += d.mass;
  }
  front.torn = std::move(stillTorn);
}

}  // namespace

void Aerosol::add(const Vec3& x, const Vec3& v, float m) {
  position.x.push_back(x.x());
  position.y.push_back(x.y());
  position.z.push_back(x.z());
  velocity.x.push_back(v.x());
  velocity.y.push_back(v.y());
  velocity.z.push_back(v.z());
  mass.push_back(m);
  age.push_back(0.0f);
}

void Aerosol::advance(const Params& p, float dt) {
  const Vec3 g(p.gravityX, p.gravityY, p.gravityZ);
  size_t kept = 0;
  for (size_t i = 0; i < size(); ++i) {
    Vec3 v = velocity.get(i);
    v += dt * (g - p.aerosolDrag * v);
    const Vec3 x = position.get(i) + dt * v;
    const float a = age[i] + dt;
    if (a > p.aerosolLifetime || x.y() < 0.0f) continue;  // faded, or landed
    position.set(kept, x);
    velocity.set(kept, v);
    mass[kept] = mass[i];
    age[kept] = a;
    ++kept;
  }
  for (Vec3Array* a : {&position, &velocity}) {
    a->x.resize(kept);
    a->y.resize(kept);
    a->z.resize(kept);
  }
  mass.resize(kept);
  age.resize(kept);
}

float taylorCulickSpeed(const Params& p, float thickness) {
  const float e = std::max(thickness, 1e-9f);  // a vanishing film still has molecules: cap the speed
  return std::sqrt(2.0f * p.surfaceTension / (p.liquidDensity * e));
}

void startCrack(BurstFront& front, const Film& film, size_t i, double t, const char* cause) {
  fitToFilm(front, film);
  if (!film.state.alive[i]) return;
  if (front.cause == nullptr) front.cause = cause;
  front.arrival[i] = std::min(front.arrival[i], static_cast<float>(t));
}

void crackWhereThin(const Params& p, double now, const Film& film, BurstFront& front) {
  fitToFilm(front, film);
  // A particle with no area left has no meaningful thickness and is left to its neighbours.
  const State& s = film.state;
  for (size_t i = 0; i < s.size(); ++i)
    if (s.alive[i] && s.voronoiArea[i] > 0 && s.thickness[i] < p.thicknessThreshold)
      startCrack(front, film, i, now, "thin");
}

namespace {

// The front: Dijkstra over the one-ring from every scheduled particle, settling in `arrival` every arrival up to
// now. Returns the particles it reached, in the order it reached them. With `readable`, the front reads only the
// particles it holds: one it needs beyond them (a particle it reaches, a neighbour it measures, a corner of a
// triangle that dies) goes into `unread`, and the front goes no further there.
std::vector<uint32_t> settleFront(const Params& p, double now, const Film& film, std::vector<float>& arrival,
                                  const std::vector<char>* readable, std::vector<uint32_t>* unread) {
  const State& s = film.state;
  const Topology& topo = film.topology;
  const auto reads = [&](uint32_t i) {
    if (readable == nullptr || (*readable)[i]) return true;
    unread->push_back(i);
    return false;
  };
  using Entry = std::pair<float, uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (uint32_t i = 0; i < s.size(); ++i)
    if (s.alive[i] && arrival[i] <= now) queue.push({arrival[i], i});
  std::vector<uint32_t> dying;
  std::vector<char> settled(s.size(), 0);
  while (!queue.empty()) {
    const auto [t, i] = queue.top();
    queue.pop();
    if (t > arrival[i] || !s.alive[i] || settled[i] || !reads(i)) continue;
    settled[i] = 1;
    dying.push_back(i);
    if (readable != nullptr)  // the droplets of its triangles read their corners
      for (uint32_t k = topo.triangleOffset[i]; k < topo.triangleOffset[i + 1]; ++k)
        for (int c = 0; c < 3; ++c) reads(topo.triangleOf(topo.triangleCorner[k])[c]);
    for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k) {
      const uint32_t j = topo.springNeighbour[k];
      if (!reads(j)) continue;
      // Paper's mode: the one-ring of this frame's dead is next frame's front. Taylor-Culick: the rim
      // reaches j after the distance over the speed in j's film.
      const float reach = p.holeOpening == 1 ? static_cast<float>(now) + p.frameTime
                                             : t + (s.position.get(j) - s.position.get(i)).norm() /
                                                       taylorCulickSpeed(p, s.thickness[j]);
      if (reach < arrival[j]) {
        arrival[j] = reach;
        if (arrival[j] <= now) queue.push({arrival[j], j});
      }
    }
  }
  return dying;
}

}  // namespace

std::vector<uint32_t> particlesTheFrontReads(const Params& p, double now, const Film& film, const BurstFront& front,
                                             const std::vector<char>& readable) {
  std::vector<uint32_t> unread;
  for (uint32_t v : front.torn)  // the torn triangles' droplets
    if (!readable[v]) unread.push_back(v);
  std::vector<float> arrival = front.arrival;  // a dry run: the front stays where it is
  if (arrival.size() != film.state.size()) arrival.assign(film.state.size(), kNever);  // as fitToFilm
  (void)settleFront(p, now, film, arrival, &readable, &unread);
  std::sort(unread.begin(), unread.end());
  unread.erase(std::unique(unread.begin(), unread.end()), unread.end());
  return unread;
}

TopologyEvents advanceBurst(const Params& p, double now, Film& film, BurstFront& front, Aerosol& aerosol) {
  crackWhereThin(p, now, film, front);  // Algorithm 3, line 1
  return advanceFront(p, now, film, front, aerosol);
}

TopologyEvents advanceFront(const Params& p, double now, Film& film, BurstFront& front, Aerosol& aerosol) {
  TopologyEvents events;
  State& s = film.state;
  fitToFilm(front, film);
  const std::vector<uint32_t> dying = settleFront(p, now, film, front.arrival, nullptr, nullptr);
  if (dying.empty()) return events;
  if (front.started < 0) {
    front.started = *std::min_element(front.arrival.begin(), front.arrival.end());
    countShares(front, film);
    events.started = true;
    events.cause = front.cause;
  }
  for (uint32_t i : dying) s.alive[i] = 0u;  // Algorithm 3, line 4
  events.particlesRemoved = dying.size();
  dropDeadElements(film, front, events);  // lines 4-6
  emitDroplets(p, film, front, aerosol, events);
  // Finished when the front has nowhere left to go: no living particle is scheduled.
  bool scheduled = false;
  double last = front.started;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s.alive[i] && std::isfinite(front.arrival[i])) scheduled = true;
    if (!s.alive[i] && std::isfinite(front.arrival[i])) last = std::max(last, static_cast<double>(front.arrival[i]));
  }
  if (!scheduled) {
    front.finished = last;
    events.finished = true;
  }
  return events;
}

}  // namespace gb
