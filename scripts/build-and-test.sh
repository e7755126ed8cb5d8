#!/usr/bin/env bash
# Second command of README.md (and what CI runs): install what is missing, build, run the unit
# tests and the quick validation suite, and build the docs (any Doxygen warning fails it; skipped
# when doxygen is not installed).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
ctest --test-dir build -L "unit|quick" --output-on-failure -j "$(nproc)"
if command -v doxygen > /dev/null && [ -f build/docs/Doxyfile.docs ]; then  # configured with Doxygen
  cmake --build build --target docs
else
  echo "build-and-test: doxygen not found: the docs are not built"
fi
