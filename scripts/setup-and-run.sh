#!/usr/bin/env bash
# First command of README.md: install what is missing, build, run the default input (monodisperse
# Haff cooling, examples/haff.nml) and compare its result with the theory.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
mkdir -p runs
build/bin/granular-dsmc examples/haff.nml --output runs/haff.h5
build/bin/granular-theory examples/haff.nml > runs/haff.theory.json
echo "theory: runs/haff.theory.json; comparison of runs/haff.h5 with Haff's law:"
build/bin/validation/validate_haff examples/haff.nml --output runs/haff.h5 --reuse
