// STRAND_KERNEL_CLONES: an element kernel compiled twice, for any x86-64 (SSE2) and for
// x86-64-v3 (AVX2 and FMA, every x86 server CPU since 2013), the copy to run chosen once by the
// CPU at load time (GCC's target_clones, an ifunc). The kernels evaluate their Gauss points as
// arrays (architecture decision 19): SSE2 evaluates two points per instruction, AVX2 four.
// It marks only the kernels measured faster so (docs/performance.md, "Instruction sets"): the
// ALE kinds' inertia with the mass transport (4 points: a third less time) and the 2D beams' force
// and tangent (10-35 % less). The cables' 6-point kernels stay portable: AVX2 made the 2D cable's
// tangent 25 % slower and its residual no faster. With STRAND_NATIVE the whole build is for its
// own CPU and needs no clones. The two copies' results differ at round-off (FMA contracts a * b + c).
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(STRAND_NO_KERNEL_CLONES)
#define STRAND_KERNEL_CLONES [[gnu::target_clones("arch=x86-64-v3", "default")]]
#else
#define STRAND_KERNEL_CLONES
#endif
