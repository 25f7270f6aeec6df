#pragma once
// Checks for numbers given on the command line. CLI11's Range lets NaN through (every comparison with NaN is
// false), and "nan" or "inf" parse as doubles: FiniteRange refuses both, naming the option's value.

#include <CLI/CLI.hpp>
#include <string>

namespace gb {

// A finite number in [lo, hi].
class FiniteRange : public CLI::Validator {
 public:
  FiniteRange(double lo, double hi);
};

}  // namespace gb
