// prt/core/kernel_path.h — which implementation of a relighting kernel runs: the diffuse SH
// kernel (prt/diffuse/relighter.h) and the glossy kernels (prt/glossy/kernel.h,
// prt/glossy/cpca_kernel.h) share it. Every path of a kernel gives identical bits; the choice
// is for tests and benchmarks. Compiles as C++17.
#pragma once

namespace prt {

// Which implementation of the kernel runs.
enum class KernelPath {
  Auto,      // AVX2+F16C+FMA when the CPU has them, else Portable
  Portable,  // plain C++ (auto-vectorised, software binary16)
  Avx2,      // x86-64 with AVX2, F16C and FMA only; an error elsewhere
  // The CPCA kernel only (CpcaKernel, prt/glossy/cpca_kernel.h): its AVX2 code with a 512-bit
  // accumulation, x86-64 with AVX-512F as well; Auto picks it there. An error elsewhere and in
  // the other kernels (they have no AVX-512 code; their Auto stays AVX2).
  Avx512,
};

}  // namespace prt
