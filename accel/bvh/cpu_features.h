#pragma once

namespace prism {

/// Whether the CPU (and OS) support AVX2 and FMA, which the *_avx2.cpp kernels need.
bool cpu_has_avx2();

/// Whether the CPU supports AVX-512 F, VL, BW and DQ (and AVX2 + FMA), which the
/// *_avx512.cpp kernels need.
bool cpu_has_avx512();

}  // namespace prism
