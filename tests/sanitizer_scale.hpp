#pragma once
/// \file
/// Sample sizes of the longest Monte Carlo unit tests in the sanitizer build.
///
/// The unit tests run twice (README "Two commands"): in CI's optimised GCC build, where every statistical
/// test takes its full sample and has the power its comment states, and before a change lands in the clang
/// build with AddressSanitizer and UndefinedBehaviorSanitizer (scripts/clang-fuzz.sh), where the code runs 5-10
/// times slower and the run is there to catch memory errors and undefined behaviour on the same code
/// paths. There the longest Monte Carlo tests (about 240 of the sanitizer run's 490 CPU
/// seconds) take a smaller sample: the same code, the same assertions, the tolerances still in
/// measured standard errors, only a weaker test of the physics, which the optimised build's run
/// checks in full. (The factored and separable draws' tests of collide_test.cpp also leave out their
/// second reference, the one-word draw, there: they compare with the unblocked loop only.)

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace gdsmc::test {

#if defined(__SANITIZE_ADDRESS__)
/// Whether this build runs under AddressSanitizer (GCC's macro).
inline constexpr bool sanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
/// Whether this build runs under AddressSanitizer (clang's feature test).
inline constexpr bool sanitized = true;
#else
/// Whether this build runs under AddressSanitizer.
inline constexpr bool sanitized = false;
#endif
#else
/// Whether this build runs under AddressSanitizer.
inline constexpr bool sanitized = false;
#endif

/// How many times fewer independent samples a Monte Carlo integral in a unit test takes under the
/// sanitizers (its standard error grows by sqrt(8) = 2.8).
inline constexpr long sanitizer_sample_reduction = 8;

/// The number of samples of a Monte Carlo integral: `full`, or full / 8 under the sanitizers.
inline long samples(long full) { return sanitized ? full / sanitizer_sample_reduction : full; }

/// A bound on a Monte Carlo integral's relative standard error (the assertion that the check has
/// teeth) that holds for `full` samples, widened by sqrt(8) under the sanitizers with the sample.
inline double precision_bound(double full_bound) {
  return sanitized ? full_bound * std::sqrt(static_cast<double>(sanitizer_sample_reduction)) : full_bound;
}

/// The number of replicas of a blocked-against-unblocked comparison: `full`, or half of it (at least
/// 8) under the sanitizers. Those comparisons estimate each standard error from the replicas, so
/// fewer than 8 would make a 4-SE bound loose on its own scale (Student's t with few degrees of
/// freedom), not just less powerful.
inline std::size_t replicas(std::size_t full) {
  return sanitized ? std::min(full, std::max<std::size_t>(8, full / 2)) : full;
}

}  // namespace gdsmc::test
