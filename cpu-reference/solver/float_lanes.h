#pragma once
// Four floats worked on together, one per lane, and 3-vectors of them: the implicit step's sweeps solve four
// particles of one colour at once with these (implicit_euler.cpp). Every operation is the IEEE one of plain
// float code (add, subtract, multiply, divide, square root, compare; nothing fused or approximate), so a
// lane's result is the same bit for bit as the same formula in float: written once as a template on the
// float type, a formula gives the same numbers for one particle and for four. (This also needs the compiler
// not to contract a * b + c into a fused operation in either; it does not in ISO C++ mode without FMA flags,
// the project's build, and ImplicitStep.TheLanesSolveEveryParticleAsVertexBlockDescentDoes would see it.)
//
// SSE2 where the compiler targets it (every x86-64), else four plain floats.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace gb {

#if defined(__SSE2__)

struct Float4 {
  __m128 v;
  Float4() : v(_mm_setzero_ps()) {}
  Float4(float a) : v(_mm_set1_ps(a)) {}  // NOLINT(google-explicit-constructor): a constant in every lane
  explicit Float4(__m128 a) : v(a) {}
  static Float4 of(float a, float b, float c, float d) { return Float4(_mm_setr_ps(a, b, c, d)); }
  static Float4 load(const float* a) { return Float4(_mm_loadu_ps(a)); }  // a[0] .. a[3]
  void store(float* a) const { _mm_storeu_ps(a, v); }                     // into a[0] .. a[3]
  [[nodiscard]] float lane(int l) const {
    alignas(16) float out[4];
    _mm_store_ps(out, v);
    return out[l];
  }
};
struct Mask4 {
  __m128 v;  // all bits set in a true lane
  static Mask4 of(bool a, bool b, bool c, bool d) {
    return {_mm_castsi128_ps(_mm_setr_epi32(-int{a}, -int{b}, -int{c}, -int{d}))};
  }
  // The lanes l with k < count[l] (counts below 2^31).
  static Mask4 below(const uint32_t* count, uint32_t k) {
    const __m128i c = _mm_loadu_si128(reinterpret_cast<const __m128i*>(count));
    return {_mm_castsi128_ps(_mm_cmpgt_epi32(c, _mm_set1_epi32(static_cast<int>(k))))};
  }
};

inline Float4 operator+(Float4 a, Float4 b) { return Float4(_mm_add_ps(a.v, b.v)); }
inline Float4 operator-(Float4 a, Float4 b) { return Float4(_mm_sub_ps(a.v, b.v)); }
inline Float4 operator*(Float4 a, Float4 b) { return Float4(_mm_mul_ps(a.v, b.v)); }
inline Float4 operator/(Float4 a, Float4 b) { return Float4(_mm_div_ps(a.v, b.v)); }
inline Float4 sqrt(Float4 a) { return Float4(_mm_sqrt_ps(a.v)); }
// std::min(a, b) and std::max(a, b) lane by lane: b < a ? b : a, and a < b ? b : a.
inline Float4 min(Float4 a, Float4 b) { return Float4(_mm_min_ps(b.v, a.v)); }
inline Float4 max(Float4 a, Float4 b) { return Float4(_mm_max_ps(b.v, a.v)); }
inline Mask4 operator<(Float4 a, Float4 b) { return {_mm_cmplt_ps(a.v, b.v)}; }
inline Mask4 operator>(Float4 a, Float4 b) { return {_mm_cmpgt_ps(a.v, b.v)}; }
inline Mask4 operator<=(Float4 a, Float4 b) { return {_mm_cmple_ps(a.v, b.v)}; }
inline Mask4 operator&&(Mask4 a, Mask4 b) { return {_mm_and_ps(a.v, b.v)}; }
inline Mask4 operator||(Mask4 a, Mask4 b) { return {_mm_or_ps(a.v, b.v)}; }
inline bool none(Mask4 m) { return _mm_movemask_ps(m.v) == 0; }
// Bit l set where lane l is true.
inline unsigned laneBits(Mask4 m) { return static_cast<unsigned>(_mm_movemask_ps(m.v)); }
// a in the lanes of m, +0 elsewhere (whatever a holds there, infinities and NaN included).
inline Float4 masked(Mask4 m, Float4 a) { return Float4(_mm_and_ps(m.v, a.v)); }
inline Float4 select(Mask4 m, Float4 a, Float4 b) {
  return Float4(_mm_or_ps(_mm_and_ps(m.v, a.v), _mm_andnot_ps(m.v, b.v)));
}
// The sums of neighbouring lanes: (a0 + a1, a2 + a3, b0 + b1, b2 + b3).
inline Float4 pairSums(Float4 a, Float4 b) {
  return Float4(
      _mm_add_ps(_mm_shuffle_ps(a.v, b.v, _MM_SHUFFLE(2, 0, 2, 0)), _mm_shuffle_ps(a.v, b.v, _MM_SHUFFLE(3, 1, 3, 1))));
}

#else  // four plain floats, lane by lane

struct Float4 {
  std::array<float, 4> v{};
  Float4() = default;
  Float4(float a) : v{a, a, a, a} {}  // NOLINT(google-explicit-constructor): a constant in every lane
  static Float4 of(float a, float b, float c, float d) {
    Float4 r;
    r.v = {a, b, c, d};
    return r;
  }
  static Float4 load(const float* a) { return of(a[0], a[1], a[2], a[3]); }
  void store(float* a) const { std::copy(v.begin(), v.end(), a); }
  [[nodiscard]] float lane(int l) const { return v[l]; }
};
struct Mask4 {
  std::array<bool, 4> v{};
  static Mask4 of(bool a, bool b, bool c, bool d) { return {{a, b, c, d}}; }
  static Mask4 below(const uint32_t* count, uint32_t k) {
    return of(k < count[0], k < count[1], k < count[2], k < count[3]);
  }
};

template <class Op>
Float4 eachLane(Float4 a, Float4 b, Op op) {
  Float4 r;
  for (int l = 0; l < 4; ++l) r.v[l] = op(a.v[l], b.v[l]);
  return r;
}
template <class Op>
Mask4 eachLaneTest(Float4 a, Float4 b, Op op) {
  Mask4 r;
  for (int l = 0; l < 4; ++l) r.v[l] = op(a.v[l], b.v[l]);
  return r;
}
inline Float4 operator+(Float4 a, Float4 b) {
  return eachLane(a, b, [](float x, float y) { return x + y; });
}
inline Float4 operator-(Float4 a, Float4 b) {
  return eachLane(a, b, [](float x, float y) { return x - y; });
}
inline Float4 operator*(Float4 a, Float4 b) {
  return eachLane(a, b, [](float x, float y) { return x * y; });
}
inline Float4 operator/(Float4 a, Float4 b) {
  return eachLane(a, b, [](float x, float y) { return x / y; });
}
inline Float4 sqrt(Float4 a) {
  return eachLane(a, a, [](float x, float) { return std::sqrt(x); });
}
inline Float4 min(Float4 a, Float4 b) {
  return eachLane(a, b, [](float x, float y) { return std::min(x, y); });
}
inline Float4 max(Float4 a, Float4 b) {
  return eachLane(a, b, [](float x, float y) { return std::max(x, y); });
}
inline Mask4 operator<(Float4 a, Float4 b) {
  return eachLaneTest(a, b, [](float x, float y) { return x < y; });
}
inline Mask4 operator>(Float4 a, Float4 b) {
  return eachLaneTest(a, b, [](float x, float y) { return x > y; });
}
inline Mask4 operator<=(Float4 a, Float4 b) {
  return eachLaneTest(a, b, [](float x, float y) { return x <= y; });
}
inline Mask4 operator&&(Mask4 a, Mask4 b) {
  Mask4 r;
  for (int l = 0; l < 4; ++l) r.v[l] = a.v[l] && b.v[l];
  return r;
}
inline Mask4 operator||(Mask4 a, Mask4 b) {
  Mask4 r;
  for (int l = 0; l < 4; ++l) r.v[l] = a.v[l] || b.v[l];
  return r;
}
inline bool none(Mask4 m) { return !(m.v[0] || m.v[1] || m.v[2] || m.v[3]); }
inline unsigned laneBits(Mask4 m) {
  unsigned bits = 0;
  for (int l = 0; l < 4; ++l) bits |= m.v[l] ? 1u << l : 0u;
  return bits;
}
inline Float4 select(Mask4 m, Float4 a, Float4 b) {
  Float4 r;
  for (int l = 0; l < 4; ++l) r.v[l] = m.v[l] ? a.v[l] : b.v[l];
  return r;
}
inline Float4 masked(Mask4 m, Float4 a) { return select(m, a, Float4(0.0f)); }
inline Float4 pairSums(Float4 a, Float4 b) {
  return Float4::of(a.v[0] + a.v[1], a.v[2] + a.v[3], b.v[0] + b.v[1], b.v[2] + b.v[3]);
}
#endif

// The natural logarithm of a positive normal float (or four), by the same float operations for one float and in
// every lane (std::log differs between its scalar and vector forms): x = m 2^e with m in [sqrt(1/2), sqrt(2)),
// ln x = e ln 2 + 2 atanh(s), s = (m - 1) / (m + 1), |s| < 0.172, summed to s^9 (the next term is below 1e-9 of
// the result; float rounding, a few 1e-8, dominates).
template <class F>
F logFromParts(F m, F e) {
  const F s = (m - F(1.0f)) / (m + F(1.0f)), s2 = s * s;
  const F series =
      F(2.0f) * s * (F(1.0f) + s2 * (F(1.0f / 3.0f) + s2 * (F(0.2f) + s2 * (F(1.0f / 7.0f) + s2 * F(1.0f / 9.0f)))));
  return e * F(0.693147182f) + series;
}
inline float logOf(float x) {
  const auto bits = std::bit_cast<uint32_t>(x);
  int e = static_cast<int>(bits >> 23) - 127;
  float m = std::bit_cast<float>((bits & 0x007fffffu) | 0x3f800000u);  // in [1, 2)
  if (m > 1.41421356f) {
    m = 0.5f * m;
    ++e;
  }
  return logFromParts(m, static_cast<float>(e));
}
#if defined(__SSE2__)
inline Float4 logOf(Float4 x) {
  const __m128i bits = _mm_castps_si128(x.v);
  __m128i e = _mm_sub_epi32(_mm_srli_epi32(bits, 23), _mm_set1_epi32(127));
  Float4 m(_mm_castsi128_ps(
      _mm_or_si128(_mm_and_si128(bits, _mm_set1_epi32(0x007fffff)), _mm_set1_epi32(0x3f800000))));  // in [1, 2)
  const Mask4 high = Float4(1.41421356f) < m;
  m = select(high, Float4(0.5f) * m, m);
  e = _mm_sub_epi32(e, _mm_castps_si128(high.v));  // a true lane is -1
  return logFromParts(m, Float4(_mm_cvtepi32_ps(e)));
}
#else
inline Float4 logOf(Float4 x) { return Float4::of(logOf(x.v[0]), logOf(x.v[1]), logOf(x.v[2]), logOf(x.v[3])); }
#endif

// The same names for one float, so that a template on the float type reads the same for both.
inline float min(float a, float b) { return std::min(a, b); }
inline float max(float a, float b) { return std::max(a, b); }
inline bool none(bool m) { return !m; }
inline float masked(bool m, float a) { return m ? a : 0.0f; }
inline float select(bool m, float a, float b) { return m ? a : b; }

template <class F>
inline constexpr int kLanes = std::is_same_v<F, float> ? 1 : 4;
template <class F>
using MaskOf = decltype(F{} < F{});

// An F from a function of the lane number: f(0) for one float, f(0) .. f(3) for four; and a mask likewise.
template <class F, class Fn>
F fromLanes(Fn&& f) {
  if constexpr (kLanes<F> == 1)
    return f(0);
  else
    return F::of(f(0), f(1), f(2), f(3));
}
template <class F, class Fn>
MaskOf<F> maskFromLanes(Fn&& f) {
  if constexpr (kLanes<F> == 1)
    return f(0);
  else
    return MaskOf<F>::of(f(0), f(1), f(2), f(3));
}

// A 3-vector of F, with the float operations in the order Eigen's Vector3f uses (its dot product sums
// x0 y0 + (x1 y1 + x2 y2)), so that the float instance agrees with Eigen code bit for bit.
template <class F>
struct Vec3Of {
  F x, y, z;
};
template <class F>
Vec3Of<F> operator+(const Vec3Of<F>& a, const Vec3Of<F>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class F>
Vec3Of<F> operator-(const Vec3Of<F>& a, const Vec3Of<F>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class F>
Vec3Of<F> operator*(F s, const Vec3Of<F>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class F>
Vec3Of<F> operator/(const Vec3Of<F>& a, F s) {
  return {a.x / s, a.y / s, a.z / s};
}
template <class F, class M>
Vec3Of<F> masked(M m, const Vec3Of<F>& a) {
  return {masked(m, a.x), masked(m, a.y), masked(m, a.z)};
}
template <class F>
F dot(const Vec3Of<F>& a, const Vec3Of<F>& b) {
  return a.x * b.x + (a.y * b.y + a.z * b.z);
}
template <class F>
Vec3Of<F> cross(const Vec3Of<F>& a, const Vec3Of<F>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class F>
F norm(const Vec3Of<F>& a) {
  using std::sqrt;
  return sqrt(dot(a, a));
}

}  // namespace gb
