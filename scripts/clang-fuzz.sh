#!/usr/bin/env bash
# Before a change lands (by hand: CI runs README's test command only, to stay near its 20 minutes):
# the clang build (the library, both programs and the unit tests) with AddressSanitizer,
# UndefinedBehaviorSanitizer and libFuzzer instrumentation; the unit tests (which run the programs
# too) under the sanitizers, and a minute of fuzzing the namelist path on the repository's namelists
# (tests/fuzz/README.md). About 15 minutes on the 2-core CI VM. Installs clang when it is missing
# (install-deps.sh --clang). Without debug information (time): to see file and line in a stack
# trace, build with -DGDSMC_FUZZ_DEBUG_INFO=ON (the default).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh && bash scripts/install-deps.sh --clang  # (the build's packages, then clang)
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
      -DGDSMC_FUZZ=ON -DGDSMC_FUZZ_DEBUG_INFO=OFF -DGDSMC_MPI=OFF
cmake --build build-fuzz -j "$(nproc)" --target namelist_fuzz granular-dsmc granular-theory unit_tests
UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 ctest --test-dir build-fuzz -L "unit|fuzz" --output-on-failure -j "$(nproc)"
