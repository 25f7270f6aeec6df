#include "app/commands/cli_checks.h"

#include <charconv>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "capture/untrusted.h"

namespace gb {

namespace {

// "[0 - 20]", the range as the help and the messages show it.
std::string rangeText(double lo, double hi) {
  std::ostringstream range;
  range << std::setprecision(15) << "[" << lo << " - " << hi << "]";
  return range.str();
}

std::string inQuotes(std::string_view text) { return "'" + printableNumber(text) + "'"; }

}  // namespace

std::string numberProblem(std::string_view text, double& value) {
  std::string_view digits = text;
  if (digits.starts_with('+')) digits.remove_prefix(1);  // from_chars takes a '-' only
  // std::from_chars in its general format reads decimal only ("0x10" stops at the x), and "inf" and "nan".
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  const bool whole = !digits.empty() && end == digits.data() + digits.size();
  if (error == std::errc::result_out_of_range && whole) return inQuotes(text) + " is not a finite number";
  if (error != std::errc() || !whole) return inQuotes(text) + " is not a number (written in decimal)";
  if (!std::isfinite(value)) return inQuotes(text) + " is not a finite number";
  return {};
}

namespace {

// What is wrong with `text` as a finite number in [lo, hi] (`range` in words); empty when it is one, in `value`.
std::string rangeProblem(std::string_view text, double lo, double hi, const std::string& range, double& value) {
  if (std::string problem = numberProblem(text, value); !problem.empty()) return problem;
  if (value < lo || value > hi) return inQuotes(text) + " is not in " + range;
  return {};
}

}  // namespace

FiniteRange::FiniteRange(double lo, double hi) {
  const std::string range = rangeText(lo, hi);
  description("FINITE in " + range);
  func_ = [lo, hi, range](std::string& text) {
    double value = 0;
    return rangeProblem(text, lo, hi, range, value);
  };
}

WholeNumber::WholeNumber(double lo, double hi) {
  const std::string range = rangeText(lo, hi);
  description("WHOLE in " + range);
  func_ = [lo, hi, range](std::string& text) -> std::string {
    double value = 0;
    if (std::string problem = rangeProblem(text, lo, hi, range, value); !problem.empty()) return problem;
    if (value != std::floor(value)) return inQuotes(text) + " is not a whole number";
    text = std::to_string(static_cast<long long>(value));
    return {};
  };
}

NotEmpty::NotEmpty() {
  description("NOT EMPTY");
  func_ = [](const std::string& text) -> std::string {
    return text.empty() ? "an empty value; leave the option out, or give one" : "";
  };
}

bool isPort(std::string_view text) {
  int port = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), port);
  return !text.empty() && text.size() <= 5 && error == std::errc() && end == text.data() + text.size() && port >= 1 &&
         port <= 65535;
}

}  // namespace gb
