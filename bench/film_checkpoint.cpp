#include "bench/film_checkpoint.h"

#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace gb {

namespace {

constexpr uint64_t kMagic = 0x676266696c6d3033;  // "gbfilm03": the state in device_data.h's order

template <class T>
struct IsVector : std::false_type {};
template <class T>
struct IsVector<std::vector<T>> : std::true_type {};

// Visits every field the checkpoint keeps, in file order, with the same visitor for writing and reading.
template <class Visit, class F>
void forEachField(F& c, Visit&& visit) {
  forEachParticleArray(c.film.state, [&](auto& array, const ParticleArrayInfo&) {
    forEachComponent(array, [&](auto& values, int) { visit(values); });
  });
  auto& t = c.film.topology;
  for (auto* a : {&t.triangles, &t.springEnds, &t.springOffset, &t.springIndex, &t.springNeighbour, &t.triangleOffset,
                  &t.triangleCorner, &t.boundary})
    visit(*a);
  visit(t.restLength);
  visit(t.closed);
  visit(c.film.tool);
  visit(c.film.stringLength);
  visit(c.film.loopHang);
  visit(c.film.referenceVolume);
  visit(c.film.volumeOrigin);
  visit(c.film.wireLiquid);
  visit(c.film.wireLiquidAtDip);
  visit(c.film.wireSpacing);
  visit(c.wands);
  visit(c.wandsArmed);
  visit(c.frame);
}

template <class T>
void writeValue(std::ofstream& out, const T& value) {
  if constexpr (IsVector<T>::value) {
    const uint64_t n = value.size();
    out.write(reinterpret_cast<const char*>(&n), sizeof n);
    out.write(reinterpret_cast<const char*>(value.data()), static_cast<std::streamsize>(n * sizeof(value[0])));
  } else {
    // Plain data written as its bytes: numbers, enums, flags and fixed-size Eigen vectors (floats, though Eigen's
    // own copy constructor keeps them from being trivially copyable by the standard's definition).
    out.write(reinterpret_cast<const char*>(&value), sizeof value);
  }
}

template <class T>
void readValue(std::ifstream& in, T& value) {
  if constexpr (IsVector<T>::value) {
    uint64_t n = 0;
    in.read(reinterpret_cast<char*>(&n), sizeof n);
    if (!in || n > (uint64_t{1} << 32)) throw std::runtime_error("bad array length");
    value.resize(n);
    in.read(reinterpret_cast<char*>(value.data()), static_cast<std::streamsize>(n * sizeof(value[0])));
  } else {
    in.read(reinterpret_cast<char*>(&value), sizeof value);
  }
}

}  // namespace

void writeCheckpoint(const std::string& path, const FilmCheckpoint& checkpoint) {
  std::ofstream out(path, std::ios::binary);
  writeValue(out, kMagic);
  forEachField(checkpoint, [&](const auto& field) { writeValue(out, field); });
  writeValue(out, uint64_t{checkpoint.randomWands.size()});
  out.write(checkpoint.randomWands.data(), static_cast<std::streamsize>(checkpoint.randomWands.size()));
  if (!out) throw std::runtime_error("cannot write the checkpoint " + path);
}

FilmCheckpoint readCheckpoint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  uint64_t magic = 0;
  readValue(in, magic);
  if (!in || magic != kMagic) throw std::runtime_error(path + " is not a film checkpoint of this build");
  FilmCheckpoint c;
  try {
    forEachField(c, [&](auto& field) { readValue(in, field); });
    uint64_t n = 0;
    readValue(in, n);
    if (!in || n > (uint64_t{1} << 20)) throw std::runtime_error("bad generator state");
    c.randomWands.resize(n);
    in.read(c.randomWands.data(), static_cast<std::streamsize>(n));
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  if (!in) throw std::runtime_error(path + " ends early: not a complete film checkpoint");
  return c;
}

}  // namespace gb
