#!/usr/bin/env bash
# CI, after build-and-test.sh: the clang build (the library, both programs and the unit tests) with
# AddressSanitizer, UndefinedBehaviorSanitizer and libFuzzer instrumentation; the unit tests (which run
# the programs too) under the sanitizers, and a minute of fuzzing the namelist path on the repository's
# namelists (tests/fuzz/README.md). Skipped where clang is not installed. Without debug information (CI
# time): to see file and line in a stack trace, build with -DGDSMC_FUZZ_DEBUG_INFO=ON (the default).
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v clang++ >/dev/null; then
  echo "clang++ not found: clang build and fuzzing skipped"
  exit 0
fi
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
      -DGDSMC_FUZZ=ON -DGDSMC_FUZZ_DEBUG_INFO=OFF -DGDSMC_MPI=OFF
cmake --build build-fuzz -j "$(nproc)" --target namelist_fuzz granular-dsmc granular-theory unit_tests
UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 ctest --test-dir build-fuzz -L "unit|fuzz" --output-on-failure -j "$(nproc)"
