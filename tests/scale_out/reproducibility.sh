#!/usr/bin/env bash
# Issue 5: the same input gives the same output file, byte for byte, however it runs: one thread,
# two and three OpenMP threads, mpirun -np 1, 2 and 3, and (when given) a build without MPI and OpenMP.
# usage: reproducibility.sh GRANULAR_DSMC INPUT WORKDIR MPIEXEC [SERIAL_GRANULAR_DSMC]
set -euo pipefail
exe=$1 input=$2 work=$3 mpiexec=$4 serial=${5:-}
rm -rf "$work" && mkdir -p "$work" && cp "$input" "$work/input.nml" && cd "$work"
mpi_flags=(--oversubscribe)
if [ "$(id -u)" -eq 0 ]; then mpi_flags+=(--allow-run-as-root); fi

run() {  # run NAME command...: the output is always written as scale_out.h5, then kept as NAME.h5
  local name=$1; shift
  "$@" input.nml --quiet
  mv scale_out.h5 "$name.h5"
  echo "$(md5sum < "$name.h5" | cut -c1-32)  $name"
}
OMP_NUM_THREADS=1 run threads-1 "$exe"
OMP_NUM_THREADS=2 run threads-2 "$exe"
OMP_NUM_THREADS=3 run threads-3 "$exe"  # more threads than units: the rest go to cache blocks
if [ "$mpiexec" != "none" ]; then
  for np in 1 2 3; do OMP_NUM_THREADS=1 run "np-$np" "$mpiexec" "${mpi_flags[@]}" -np "$np" "$exe"; done
  OMP_NUM_THREADS=2 run np-2-threads-2 "$mpiexec" "${mpi_flags[@]}" -np 2 "$exe"
fi
if [ -n "$serial" ]; then run serial-build "$serial"; fi

reference=$(md5sum < threads-1.h5 | cut -c1-32)
status=0
for f in *.h5; do
  if [ "$(md5sum < "$f" | cut -c1-32)" != "$reference" ]; then
    echo "FAIL: $f differs from threads-1.h5"; status=1
    # The builds' own versions are part of the file (/h5md/creator/version): say so when they differ.
    v1=$(h5dump -a /h5md/creator/version threads-1.h5 2>/dev/null | grep -o '"[^"]*"' | head -1)
    v2=$(h5dump -a /h5md/creator/version "$f" 2>/dev/null | grep -o '"[^"]*"' | head -1)
    [ "$v1" = "$v2" ] || echo "  (built from different versions, $v1 and $v2: rebuild both from the same commit)"
  fi
done
[ $status -eq 0 ] && echo "PASS: $(ls *.h5 | wc -l) runs, one file content ($reference)"
exit $status
