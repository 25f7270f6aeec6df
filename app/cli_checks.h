#pragma once
// Checks for numbers given on the command line. CLI11's Range lets NaN through (every comparison with NaN is
// false), and "nan" or "inf" parse as doubles: FiniteRange refuses both, naming the option's value.

#include <CLI/CLI.hpp>
#include <string>

namespace gb {

// The largest film --particles (and bench --sizes) accept: 80 times the paper's largest example (25,650). The
// old limit, 50 million, ended in std::bad_alloc on a 24 GB machine instead of a film.
inline constexpr int kMaxParticles = 2'000'000;

// A finite number in [lo, hi].
class FiniteRange : public CLI::Validator {
 public:
  FiniteRange(double lo, double hi);
};

}  // namespace gb
