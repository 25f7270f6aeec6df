#pragma once
// Checks for numbers given on the command line. CLI11's Range lets NaN through (every comparison with NaN is
// false), and "nan" or "inf" parse as doubles: FiniteRange refuses both, naming the option's value.

#include <CLI/CLI.hpp>
#include <string>

namespace gb {

// The largest film --particles (and bench --sizes) accept: 2 million particles take about 2 GB and minutes to
// triangulate, 80 times the paper's largest example; beyond that a run ends in out-of-memory, not a film.
inline constexpr int kMaxParticles = 2'000'000;

// A finite number in [lo, hi].
class FiniteRange : public CLI::Validator {
 public:
  FiniteRange(double lo, double hi);
};

}  // namespace gb
