#!/usr/bin/env bash
# One golden restart case: the run of INPUT killed after its first checkpoint, then resumed, with
# checkpoints every 0.2 s. Leaves WORK.checkpoint.h5 (the checkpoint it resumed from) and WORK.h5.
# With RESUME_EXE, the checkpoint is written by EXE and resumed by RESUME_EXE (a checkpoint of the
# code before a change, read by the code after it).
# usage: restart.sh EXE INPUT WORK [RESUME_EXE]
set -euo pipefail
exe=$1 input=$2 work=$3 resume=${4:-$1}
dir=$(dirname "$work") name=$(basename "$work")
cd "$dir"
nml=$name.run.nml
sed "s/file = '[^']*'/file = '$name.h5'/" "$input" > "$nml"
set_cp=(--set output:checkpoint_every=0.2)
rm -f "$name.h5" "$name.checkpoint.h5" "$name.run.checkpoint.h5"
"$exe" "$nml" --quiet "${set_cp[@]}" &
pid=$! waited=0
while [ ! -e "$name.checkpoint.h5" ]; do
  sleep 0.05; waited=$((waited + 1))
  kill -0 $pid 2>/dev/null || { echo "restart.sh: $name ended before its first checkpoint" >&2; exit 1; }
  [ $waited -lt 1200 ] || { kill -9 $pid; echo "restart.sh: no checkpoint" >&2; exit 1; }
done
sleep 0.1
kill -9 $pid 2>/dev/null || { echo "restart.sh: $name ended before it could be killed" >&2; exit 1; }
wait $pid 2>/dev/null || true
rm -f "$name.h5".tmp.*
cp "$name.checkpoint.h5" "$name.resumed-from.checkpoint.h5"
"$resume" "$nml" --quiet "${set_cp[@]}" --restart "$name.resumed-from.checkpoint.h5"
