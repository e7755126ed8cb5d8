#!/usr/bin/env bash
# Second command of README.md (and what CI runs): install what is missing, build, and run the unit
# tests and the quick validation suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
ctest --test-dir build -L "unit|quick" --output-on-failure -j "$(nproc)"
