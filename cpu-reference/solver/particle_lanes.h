#pragma once
// The film's 3-vectors in the lanes of float_lanes.h: a Vec3 as a Vec3Of<float> and back, four Vec3s as a
// Vec3Of<Float4>, and the particles of each lane gathered from one of State's Vec3Arrays. The lanes' stages (the
// implicit step's sweeps, the geometry stage and the volume) read the film through these.

#include "model/state.h"
#include "solver/float_lanes.h"

namespace gb {

inline Vec3Of<float> lanesOf(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
inline Vec3 eigenOf(const Vec3Of<float>& v) { return {v.x, v.y, v.z}; }
// a, b, c and d in lanes 0 to 3.
inline Vec3Of<Float4> lanesOf(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return {Float4::of(a.x(), b.x(), c.x(), d.x()), Float4::of(a.y(), b.y(), c.y(), d.y()),
          Float4::of(a.z(), b.z(), c.z(), d.z())};
}

// Element i[l] of `a` in lane l (one float: i[0]). Always inlined: called, it would return through memory, and every
// caller's sums held in vector registers (all of which a call may overwrite) would be stored and loaded around it.
template <class F, class Index>
[[gnu::always_inline]] inline Vec3Of<F> gatherVec(const Vec3Array& a, const Index& i) {
  return {fromLanes<F>([&](int l) { return a.x[i[l]]; }), fromLanes<F>([&](int l) { return a.y[i[l]]; }),
          fromLanes<F>([&](int l) { return a.z[i[l]]; })};
}

}  // namespace gb
