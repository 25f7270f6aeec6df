#pragma once
// Smooth pseudo-random fields for the renderer's procedural content (the sky's clouds and hills, the film's
// thickness swirls): lattice value noise with a quintic fade, summed over octaves. Deterministic (an integer
// hash of the lattice point, no global state), so frames and tests reproduce exactly. Pure C++ and Eigen.

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>

namespace gb::noise {

// A value in [0, 1) for an integer lattice point and a seed (a 32-bit integer hash, "lowbias32" by C. Wellons).
inline float latticeValue(int32_t x, int32_t y, int32_t z, uint32_t seed) {
  uint32_t h = seed ^ (static_cast<uint32_t>(x) * 0x8da6b343u) ^ (static_cast<uint32_t>(y) * 0xd8163841u) ^
               (static_cast<uint32_t>(z) * 0xcb1ab31fu);
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return static_cast<float>(h >> 8) * (1.0f / 16777216.0f);
}

// Value noise in [-1, 1] at p (lattice spacing 1), C2-smooth between lattice points.
inline float value3(const Eigen::Vector3f& p, uint32_t seed) {
  const Eigen::Vector3f f = p.array().floor();
  const Eigen::Vector3f t = p - f;
  const auto fade = [](float u) { return u * u * u * (u * (u * 6.0f - 15.0f) + 10.0f); };
  const float wx = fade(t.x()), wy = fade(t.y()), wz = fade(t.z());
  const auto x = static_cast<int32_t>(f.x()), y = static_cast<int32_t>(f.y()), z = static_cast<int32_t>(f.z());
  float c[2][2];
  for (int dy = 0; dy < 2; ++dy)
    for (int dz = 0; dz < 2; ++dz) {
      const float a = latticeValue(x, y + dy, z + dz, seed), b = latticeValue(x + 1, y + dy, z + dz, seed);
      c[dy][dz] = a + wx * (b - a);
    }
  const float near = c[0][0] + wy * (c[1][0] - c[0][0]), far = c[0][1] + wy * (c[1][1] - c[0][1]);
  return 2.0f * (near + wz * (far - near)) - 1.0f;
}

// Fractal sum of `octaves` octaves (each twice the frequency and `gain` the amplitude of the last), scaled so
// that its range stays within [-1, 1].
inline float fractal3(const Eigen::Vector3f& p, int octaves, uint32_t seed, float gain = 0.5f) {
  float sum = 0.0f, amplitude = 1.0f, total = 0.0f, frequency = 1.0f;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * value3(frequency * p, seed + 101u * static_cast<uint32_t>(o));
    total += amplitude;
    amplitude *= gain;
    frequency *= 2.0f;
  }
  return sum / total;
}

}  // namespace gb::noise
