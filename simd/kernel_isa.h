// ISA selection for a per-ISA kernel translation unit. The generated file
// defines QUADRA_KERNEL_ISA_<isa> and includes this (through a kernel's
// *_impl.h); it checks that the file got that ISA's compiler flags and names
// the lane architecture, a namespace private to the ISA, and the Isa value.
#pragma once

#if defined(QUADRA_KERNEL_ISA_scalar)
#define QUADRA_KERNEL_ARCH ::quadra::simd::ScalarArch
#define QUADRA_KERNEL_NAMESPACE kernel_scalar
#define QUADRA_KERNEL_SUFFIX Scalar
#elif defined(QUADRA_KERNEL_ISA_sse2)
#if !defined(__SSE2__)
#error "the sse2 kernel file must be compiled with -msse2"
#endif
#define QUADRA_KERNEL_ARCH ::xsimd::sse2
#define QUADRA_KERNEL_NAMESPACE kernel_sse2
#define QUADRA_KERNEL_SUFFIX Sse2
#elif defined(QUADRA_KERNEL_ISA_avx2)
#if !defined(__AVX2__)
#error "the avx2 kernel file must be compiled with -mavx2"
#endif
#define QUADRA_KERNEL_ARCH ::xsimd::avx2
#define QUADRA_KERNEL_NAMESPACE kernel_avx2
#define QUADRA_KERNEL_SUFFIX Avx2
#elif defined(QUADRA_KERNEL_ISA_avx512)
#if !defined(__AVX512F__) || !defined(__AVX512BW__)
#error "the avx512 kernel file must be compiled with -mavx512f -mavx512bw"
#endif
#define QUADRA_KERNEL_ARCH ::xsimd::avx512bw
#define QUADRA_KERNEL_NAMESPACE kernel_avx512
#define QUADRA_KERNEL_SUFFIX Avx512
#else
#error "define QUADRA_KERNEL_ISA_<isa> before including a kernel implementation"
#endif

#define QUADRA_KERNEL_CONCAT_(a, b) a##b
#define QUADRA_KERNEL_CONCAT(a, b) QUADRA_KERNEL_CONCAT_(a, b)
// The per-ISA entry point of a kernel table: QUADRA_KERNEL_ENTRY(tileKernels)
// is tileKernelsAvx2 in the AVX2 file.
#define QUADRA_KERNEL_ENTRY(name) QUADRA_KERNEL_CONCAT(name, QUADRA_KERNEL_SUFFIX)
#define QUADRA_KERNEL_ISA_ENUM ::quadra::Isa::QUADRA_KERNEL_SUFFIX

#include "simd/lanes.h"
