#pragma once
// The model's parameters: the block itself is defined once in kernels/shared/shared_params.h, shared with the
// compute shaders; this header adds what only C++ needs.

#include <span>
#include <string>
#include <vector>

#include "kernels/shared/shared_formulas.h"
#include "kernels/shared/shared_params.h"

namespace gb {

// Initial film thickness e0 (m): the paper's area weight w_e read as liquid per rest area, w_e x 100 um.
inline float initialThickness(const Params& p) { return initialThicknessOf(p.areaWeight); }

// The largest film (particlesAtFullSolution), whatever sets it: --particles, --param, a scene's [params], bench
// --sizes. 80 times the paper's largest example (25,650); 50 million ended in std::bad_alloc on a 24 GB machine
// instead of a film.
inline constexpr int kMaxParticles = 2'000'000;

// The parameters by name, for the command line (--param NAME=VALUE), scene files and validate(): each field
// of Params once, as a member pointer of its type, with its valid range (a test checks that they cover the
// whole block).
struct ParamField {
  const char* name;
  float Params::*real = nullptr;   // set for float parameters
  int Params::*integer = nullptr;  // set for int parameters
  double lo = 0, hi = 0;           // valid range, inclusive
  const char* unit = "";           // for messages, with its leading space
};
std::span<const ParamField> paramFields();

// The field of that name, or nullptr.
const ParamField* findParamField(const std::string& name);

// Sets a parameter by name. Throws std::invalid_argument naming the parameter when it is unknown, when the value is
// outside its range (checked on the value as given: as a float 1e-50 would be 0, as an int 2e9 would wrap) or when an
// int parameter gets a value that is not a whole number.
void setParameter(Params& params, const std::string& name, double value);

// A parameter out of its valid range: its name, and a message naming it, its value and the range.
struct ParamError {
  std::string name;
  std::string message;
};
// One error per parameter that is out of its valid range. Empty when the parameters are usable.
std::vector<ParamError> rangeErrors(const Params& params);
// The same errors' messages.
std::vector<std::string> validate(const Params& params);

}  // namespace gb
