#pragma once
// Checks for numbers given on the command line, one rule for every numeric option: a number is written in decimal
// ("2", "-0.5", "1e4"), finite, and in the option's range; a whole number may be written in any of those forms
// ("1e4", "6.0") and is refused when it is not whole. CLI11 alone would take hex ("0x10", and "0x1p-3" for a double),
// read "010" as octal 8, let NaN through a Range (every comparison with NaN is false) and refuse "1e4" for an integer.

#include <CLI/CLI.hpp>
#include <string>
#include <string_view>

namespace gb {

// What is wrong with `text` as a number ("'0x10' is not a number (written in decimal)", "'nan' is not a finite
// number"); empty when it is a finite decimal number, then stored in `value`.
std::string numberProblem(std::string_view text, double& value);

// A finite number in [lo, hi] (a check).
class FiniteRange : public CLI::Validator {
 public:
  FiniteRange(double lo, double hi);
};

// A whole number in [lo, hi], written in any decimal form: a transform, which hands CLI11 the number's plain digits.
class WholeNumber : public CLI::Validator {
 public:
  WholeNumber(double lo, double hi);
};

// A value that may not be empty: an option given '' is a mistake, not the option left out.
class NotEmpty : public CLI::Validator {
 public:
  NotEmpty();
};

// A UDP or TCP port, "1" to "65535" in decimal; false when `text` is none.
bool isPort(std::string_view text);

}  // namespace gb
