#pragma once
// The documentation the parameter catalog reads its groups and meanings from, embedded at build time
// (param_docs.cpp.in).

#include <string_view>

namespace gb {

std::string_view sharedParamsSource();  // kernels/shared_params.h
std::string_view modelDocument();       // docs/model.md

}  // namespace gb
