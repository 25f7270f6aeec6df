#pragma once
// The model's parameters: the block itself is defined once in kernels/shared_params.h, shared with the
// compute shaders; this header adds what only C++ needs.

#include <string>
#include <vector>

#include "shared_params.h"

namespace gb {

// Initial film thickness e0 (m): the paper's area weight w_e read as liquid per rest area, w_e x 100 um.
inline float initialThickness(const Params& p) { return p.areaWeight * 100e-6f; }

// One message per parameter that is out of its valid range, each naming the parameter, its value and the
// range. Empty when the parameters are usable.
std::vector<std::string> validate(const Params& params);

}  // namespace gb
