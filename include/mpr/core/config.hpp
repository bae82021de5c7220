#pragma once
/// \file
/// Every configuration macro of mpr, in one place (docs/conventions.md has the same table).
/// Headers include this one instead of defining macros of their own.
///
/// Settings a user may define, consistently in every translation unit (e.g. on the compiler's
/// command line):
///
/// | macro           | default                      | effect                                       |
/// |-----------------|------------------------------|----------------------------------------------|
/// | `MPR_NO_OPENMP` | undefined                    | rows go to `std::thread`s even when the      |
/// |                 |                              | program is compiled with OpenMP              |
/// | `MPR_BVH_SSE`   | 1 with SSE2 (x86-64), else 0 | 0: the BVH walks with its portable kernels   |
/// |                 |                              | only (same hits; slower)                     |
/// | `MPR_HAVE_HWY`  | 1 when <hwy/highway.h> is    | 0: the Highway kernels are left out          |
/// |                 | found, else 0                | (lightfield/kernels/, docs/simd.md)          |
/// | `MPR_HAVE_XSIMD`| 1 when <xsimd/xsimd.hpp> is  | 0: the xsimd kernel is left out              |
/// |                 | found, else 0                |                                              |
///
/// Derived from the compiler and the settings above (not to be defined by users):
///
/// | macro                 | defined as                                                      |
/// |-----------------------|-----------------------------------------------------------------|
/// | `MPR_PARALLEL_OPENMP` | 1 when compiled with OpenMP and `MPR_NO_OPENMP` is undefined,   |
/// |                       | else 0                                                          |
/// | `MPR_ADDRESS_SANITIZER` | 1 when compiled with AddressSanitizer, else 0: frame sets then |
/// |                       | copy borrowed images (`CameraFrameSet::can_share`)              |
/// | `MPR_SIMD_X86`        | 1 on x86 with GCC or Clang (kernels also built for AVX2+FMA and |
/// |                       | AVX-512, chosen at run time, core/simd.hpp); else undefined     |
/// | `MPR_TARGET_AVX2`     | `target("avx2,fma")` attribute (only with `MPR_SIMD_X86`)       |
/// | `MPR_TARGET_AVX512`   | `target("avx512f,avx512bw,avx512vl,avx512dq,fma")` attribute,   |
/// |                       | on GCC also preferring 512-bit vectors (only with MPR_SIMD_X86) |
/// | `MPR_TARGET_AVX512_VBMI` | the AVX-512 attribute plus `avx512vbmi` (byte permutes; run   |
/// |                       | at level `avx512vbmi` of core/simd.hpp, only with MPR_SIMD_X86) |
/// | `MPR_SIMD_NEON`       | 1 on AArch64 (NEON is its baseline: the portable kernels are    |
/// |                       | NEON code there, level name `neon`); else undefined             |
/// | `MPR_TARGET_AVX2_NOFMA` | `target("avx2")` attribute, no FMA: the compiler cannot fuse a  |
/// |                       | multiply-add, so results equal the SSE2 ones (BVH packet walk)  |
/// | `MPR_BVH_PACKET_AVX2` | 1 with `MPR_SIMD_X86` and `MPR_BVH_SSE`: the BVH's packet walk  |
/// |                       | has AVX2 kernels, chosen at run time; else 0                    |
/// | `MPR_BVH_PACKET_AVX512` | 1 with `MPR_SIMD_X86` and `MPR_BVH_SSE`: the BVH's packet walk |
/// |                       | has AVX-512 kernels (explicit rounding, never fused), chosen at |
/// |                       | run time; else 0                                                |
/// | `MPR_ALWAYS_INLINE`   | `inline` that always inlines (GCC/Clang), for kernel bodies     |
/// | `MPR_NOINLINE`        | never inlined (GCC/Clang): keeps code compiled without FMA out  |
/// |                       | of the AVX-512 kernels that call it                             |
/// | `MPR_INLINE_LAMBDA`   | always-inline attribute for the lambdas handed to `run_at`      |
/// | `MPR_RESTRICT`        | `__restrict__` (GCC/Clang), else nothing                        |
/// | `MPR_EXACT_FP_BEGIN`, | around code whose results must not depend on the compiler's    |
/// | `MPR_EXACT_FP_END`    | flags (the BVH walk): no multiply-add contraction in between.   |
/// |                       | GCC: `optimize("fp-contract=off")`, whatever -march or          |
/// |                       | -ffp-contract; Clang: `fp contract(off)`, honoured except under |
/// |                       | `-ffp-contract=fast` (use `fast-honor-pragmas`); else nothing   |
/// | `MPR_FLATTEN`         | `flatten` attribute (GCC/Clang): inline every call into the     |
/// |                       | marked function, recursively                                    |
///
/// The environment variable `MPR_SIMD` (`portable`, `avx2`, `avx512`, `avx512vbmi`; `neon` on
/// AArch64) lowers the kernel level chosen at run time (core/simd.hpp); it is read once, not a
/// macro.

// --- Sanitizers ----------------------------------------------------------------------------

#if defined(__SANITIZE_ADDRESS__)
#define MPR_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MPR_ADDRESS_SANITIZER 1
#endif
#endif
#if !defined(MPR_ADDRESS_SANITIZER)
#define MPR_ADDRESS_SANITIZER 0
#endif

// --- Threads -------------------------------------------------------------------------------

#if defined(_OPENMP) && !defined(MPR_NO_OPENMP)
#define MPR_PARALLEL_OPENMP 1
#else
#define MPR_PARALLEL_OPENMP 0
#endif

// --- Compiler attributes -------------------------------------------------------------------

#if defined(__GNUC__) || defined(__clang__)
#define MPR_ALWAYS_INLINE __attribute__((always_inline)) inline
/// Never inlined: a function compiled for a target without FMA keeps its values when called
/// from one with FMA (inlined, its multiply-adds could be fused there).
#define MPR_NOINLINE __attribute__((noinline))
/// For the bodies handed to `run_at`: `[&]() MPR_INLINE_LAMBDA { ... }`.
#define MPR_INLINE_LAMBDA __attribute__((always_inline))
#define MPR_RESTRICT __restrict__
/// Inlines every call, recursively, into the function it marks: used on the small loops that
/// build rays and store colours, so that no policy call is left out of line however large the
/// enclosing render function grows (the compiler's inlining budget is per function).
#define MPR_FLATTEN __attribute__((flatten))
#else
#define MPR_ALWAYS_INLINE inline
#define MPR_NOINLINE
#define MPR_INLINE_LAMBDA
#define MPR_RESTRICT
#define MPR_FLATTEN
#endif

// --- Instruction sets ----------------------------------------------------------------------

#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
/// x86 with GCC/Clang: kernels also compiled for AVX2+FMA and AVX-512, chosen at run time.
#define MPR_SIMD_X86 1
#endif

#if defined(MPR_SIMD_X86)
#define MPR_TARGET_AVX2 __attribute__((target("avx2,fma")))
// AVX2 without FMA: no contraction of a * b + c is possible, so the BVH's exact tests compute
// the same values as their SSE2 twins.
#define MPR_TARGET_AVX2_NOFMA __attribute__((target("avx2")))
#if defined(__clang__)
#define MPR_TARGET_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl,avx512dq,fma")))
#else
// GCC's generic tuning would use 256-bit vectors even here; the kernels are streaming loops
// that gain from the full width.
#define MPR_TARGET_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl,avx512dq,fma,avx2,prefer-vector-width=512")))
#endif
// AVX-512 with the byte permutes of VBMI (Ice Lake, Zen 4 and later): kernels that pick bytes
// across 128-byte windows; run at the level `SimdLevel::avx512vbmi` (core/simd.hpp).
#define MPR_TARGET_AVX512_VBMI __attribute__((target("avx512f,avx512bw,avx512vl,avx512dq,avx512vbmi,fma,avx2")))
#endif

#if defined(__aarch64__) && defined(__ARM_NEON)
/// AArch64: NEON is part of the baseline, so the portable kernels are vectorised with it.
#define MPR_SIMD_NEON 1
#endif

// SSE2 is part of x86-64, so the BVH's 4-wide float kernels need no run-time check.
#if !defined(MPR_BVH_SSE)
#if defined(__SSE2__) || defined(_M_X64)
#define MPR_BVH_SSE 1
#else
#define MPR_BVH_SSE 0
#endif
#endif

// The BVH packet walk's AVX2 kernels (bvh/kernels/packet_avx2.hpp) need the x86 target
// attributes and the SSE leaf kernels.
#if defined(MPR_SIMD_X86) && MPR_BVH_SSE
#define MPR_BVH_PACKET_AVX2 1
#else
#define MPR_BVH_PACKET_AVX2 0
#endif

// Its AVX-512 kernels (bvh/kernels/packet_avx512.hpp) likewise; they call the no-FMA
// SSE leaf kernels for their scalar steps.
#if defined(MPR_SIMD_X86) && MPR_BVH_SSE
#define MPR_BVH_PACKET_AVX512 1
#else
#define MPR_BVH_PACKET_AVX512 0
#endif

// Optional portable SIMD libraries (docs/simd.md): 1 when their headers are on the include path
// (Highway: libhwy-dev, xsimd: libxsimd-dev), else 0. lightfield/kernels/ holds the kernels
// written with them; nothing else depends on them.
#if !defined(MPR_HAVE_HWY)
#if defined(__has_include) && __has_include(<hwy/highway.h>)
#define MPR_HAVE_HWY 1
#else
#define MPR_HAVE_HWY 0
#endif
#endif
#if !defined(MPR_HAVE_XSIMD)
#if defined(__has_include) && __has_include(<xsimd/xsimd.hpp>)
#define MPR_HAVE_XSIMD 1
#else
#define MPR_HAVE_XSIMD 0
#endif
#endif

// No multiply-add contraction between MPR_EXACT_FP_BEGIN and MPR_EXACT_FP_END (namespace scope),
// whatever the translation unit's -march or -ffp-contract: the BVH walk promises the same hits
// from single rays and packets, which fused and unfused multiply-adds would break.
#if defined(__clang__)
#define MPR_EXACT_FP_BEGIN _Pragma("float_control(push)") _Pragma("clang fp contract(off)")
#define MPR_EXACT_FP_END _Pragma("float_control(pop)")
#elif defined(__GNUC__)
#define MPR_EXACT_FP_BEGIN _Pragma("GCC push_options") _Pragma("GCC optimize(\"fp-contract=off\")")
#define MPR_EXACT_FP_END _Pragma("GCC pop_options")
#else
#define MPR_EXACT_FP_BEGIN
#define MPR_EXACT_FP_END
#endif
