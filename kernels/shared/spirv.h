#pragma once
// The embedded SPIR-V of every compute shader of kernels/ (kernel_list.h, the one list of them).

#include <cstdint>
#include <span>

namespace gb::kernels {

enum class Kernel {
#define GB_KERNEL(name, file) name,
#include "kernel_list.h"
#undef GB_KERNEL
};
inline constexpr int kKernelCount = 0
#define GB_KERNEL(name, file) +1
#include "kernel_list.h"
#undef GB_KERNEL
    ;

std::span<const uint32_t> spirv(Kernel kernel);
const char* kernelName(Kernel kernel);

}  // namespace gb::kernels
