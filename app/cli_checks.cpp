#include "cli_checks.h"

#include <cmath>
#include <sstream>

namespace gb {

FiniteRange::FiniteRange(double lo, double hi) {
  std::ostringstream range;
  range << "[" << lo << " - " << hi << "]";
  description("FINITE in " + range.str());
  func_ = [lo, hi, range = range.str()](std::string& text) -> std::string {
    double value = 0;
    if (!CLI::detail::lexical_cast(text, value)) return "'" + text + "' is not a number";
    if (!std::isfinite(value)) return "'" + text + "' is not a finite number";
    if (value < lo || value > hi) return "'" + text + "' is not in " + range;
    return {};
  };
}

}  // namespace gb
