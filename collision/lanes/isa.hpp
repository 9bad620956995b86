#pragma once
/// Host code built twice: for the build's own target (-march, x86-64-v3 by default) and for
/// x86-64-v4 (AVX-512), the second chosen at run time where the CPU has it. Only the exact
/// stage's two hottest functions are (collision/exact.cpp: posing an organ, testing two posed
/// organs): on a Zen 5 machine their x86-64-v4 code makes the exact stage faster (bench_detect:
/// about 7 %), while the whole library built for x86-64-v4 makes the leaf and organ pass slower.
/// Both builds do the same operations in the same order (-ffp-contract=off, no
/// approximate instructions), so their answers are the same bit for bit:
/// tests/collision/test_exact_isa.cpp compares them. Host only: nvcc never reads this file.

namespace canopy {

/// Which build of a twice-built function to run.
enum class Isa { build_target, x86_64_v4 };

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
/// Marks a function definition as built for x86-64-v4.
#define CANOPY_TARGET_V4 __attribute__((target("arch=x86-64-v4")))
/// Whether this CPU runs x86-64-v4 code (AVX-512 F, BW, CD, DQ, VL), asked once.
inline bool cpu_has_x86_64_v4() {
  static const bool yes = __builtin_cpu_supports("x86-64-v4");
  return yes;
}
#else
// Elsewhere the "x86-64-v4" build is the build target's: the same code twice.
#define CANOPY_TARGET_V4
inline bool cpu_has_x86_64_v4() { return false; }
#endif

/// The build to run here: x86-64-v4 where the CPU has it.
inline Isa fastest_isa() { return cpu_has_x86_64_v4() ? Isa::x86_64_v4 : Isa::build_target; }

}  // namespace canopy
