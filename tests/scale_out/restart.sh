#!/usr/bin/env bash
# Issue 5: a run killed with SIGKILL and resumed with --restart writes the same file, byte for byte,
# as the same run left alone. Kills it twice (the second time after a restart), on 1 and then 2 threads.
# With MPIEXEC, also under mpirun -np 2 (one checkpoint file per rank).
# usage: restart.sh GRANULAR_DSMC INPUT WORKDIR [MPIEXEC]
set -euo pipefail
exe=$1 input=$2 work=$3 mpiexec=${4:-none}
# A name of its own, so that killing "$exe $nml" can never hit another test running beside this one.
nml=run-$$.nml
rm -rf "$work" && mkdir -p "$work" && cp "$input" "$work/$nml" && cd "$work"

OMP_NUM_THREADS=2 "$exe" "$nml" --quiet
mv restart.h5 uninterrupted.h5
[ ! -e restart.checkpoint.h5 ] || { echo "FAIL: a completed run left its checkpoint behind"; exit 1; }

# Starts the command in the background, waits for a fresh checkpoint, kills -9 while it still runs.
kill_after_checkpoint() {
  rm -f restart.checkpoint.h5
  "$@" &
  local pid=$! waited=0
  while [ ! -e restart.checkpoint.h5 ]; do
    sleep 0.1; waited=$((waited + 1))
    if ! kill -0 $pid 2>/dev/null; then echo "FAIL: the run ended before its first checkpoint"; exit 1; fi
    [ $waited -lt 600 ] || { echo "FAIL: no checkpoint after 60 s"; kill -9 $pid; exit 1; }
  done
  # The checkpoint is renamed into place whole, so the run can be killed at once: waiting longer only
  # lets a fast or idle machine finish the run first (CI once saw that with 2 threads).
  sleep 0.05
  kill -9 $pid 2>/dev/null || { echo "FAIL: the run ended before it could be killed"; exit 1; }
  wait $pid 2>/dev/null || true
  [ ! -e restart.h5 ] || { echo "FAIL: a killed run left an output file"; exit 1; }
  echo "killed $* after a checkpoint ($(stat -c %s restart.checkpoint.h5) bytes)"
}
# Killed on 1 thread, resumed on 2 and killed again, resumed on 1 to the end: both thread counts, and a
# checkpoint taken on one resumed on the other (one pass, not one per thread count: CI time).
OMP_NUM_THREADS=1 kill_after_checkpoint "$exe" "$nml" --quiet
cp restart.checkpoint.h5 first.checkpoint.h5
OMP_NUM_THREADS=2 kill_after_checkpoint "$exe" "$nml" --quiet --restart first.checkpoint.h5
OMP_NUM_THREADS=1 "$exe" "$nml" --quiet --restart restart.checkpoint.h5
rm -f restart.h5.tmp.*  # left by the killed runs: a killed process cannot remove its temporary file
if cmp -s restart.h5 uninterrupted.h5; then
  echo "PASS (1, 2, 1 threads): killed twice, resumed twice: identical to the uninterrupted run (2 threads)"
else
  echo "FAIL (1, 2, 1 threads): the resumed run differs from the uninterrupted run"; exit 1
fi
[ ! -e restart.checkpoint.h5 ] || { echo "FAIL: the completed run left its checkpoint behind"; exit 1; }
rm restart.h5

if [ "$mpiexec" != "none" ]; then
  mpi=("$mpiexec" --oversubscribe -np 2)
  if [ "$(id -u)" -eq 0 ]; then mpi+=(--allow-run-as-root); fi
  export OMP_NUM_THREADS=1
  rm -f restart.checkpoint*.h5
  "${mpi[@]}" "$exe" "$nml" --quiet &
  pid=$! waited=0
  until [ -e restart.checkpoint.h5 ] && [ -e restart.checkpoint.rank1.h5 ]; do
    sleep 0.1; waited=$((waited + 1))
    kill -0 $pid 2>/dev/null || { echo "FAIL: the MPI run ended before both ranks wrote a checkpoint"; exit 1; }
    [ $waited -lt 600 ] || { echo "FAIL: no MPI checkpoints after 60 s"; exit 1; }
  done
  # (each checkpoint file is renamed into place whole and each rank resumes its own replicas, so any pair
  # of files is a state to resume from: kill at once, as above, before a fast machine ends the run)
  sleep 0.05
  pkill -9 -f "^$exe $nml " || true  # the ranks (this run's input name only), then their launcher
  kill -9 $pid 2>/dev/null || true
  wait $pid 2>/dev/null || true
  rm -f restart.h5.tmp.*
  [ ! -e restart.h5 ] || { echo "FAIL: a killed MPI run left an output file"; exit 1; }
  "${mpi[@]}" "$exe" "$nml" --quiet --restart restart.checkpoint.h5
  if cmp -s restart.h5 uninterrupted.h5; then
    echo "PASS (mpirun -np 2): killed, resumed from 2 checkpoint files: identical to the uninterrupted run"
  else
    echo "FAIL (mpirun -np 2): the resumed run differs from the uninterrupted run"; exit 1
  fi
  ls restart.checkpoint*.h5 >/dev/null 2>&1 && { echo "FAIL: the completed MPI run left checkpoints"; exit 1; }
  rm restart.h5
fi

# A damaged checkpoint (a velocity made NaN, as a flipped bit could) is refused with a message (its
# checksum, or the checks of every field on restore), no crash and no output file (issue 12).
if /usr/bin/python3 -c "import h5py" 2>/dev/null; then
  cp first.checkpoint.h5 damaged.checkpoint.h5
  /usr/bin/python3 - <<'PY'
import h5py
with h5py.File("damaged.checkpoint.h5", "r+") as f:
    found = []
    f["checkpoint"].visititems(lambda name, obj: found.append(obj) if name.endswith("velocity") else None)
    found[0][0] = float("nan")
PY
  set +e
  rm -f restart.h5
  "$exe" "$nml" --quiet --restart damaged.checkpoint.h5 2> damaged.txt
  status=$?
  set -e
  if [ $status -ne 0 ] && [ $status -lt 128 ] && grep -q "is damaged" damaged.txt && [ ! -e restart.h5 ]; then
    echo "PASS: a damaged checkpoint is refused (status $status): $(cat damaged.txt)"
  else
    echo "FAIL: damaged checkpoint: status $status, message: $(cat damaged.txt)"; exit 1
  fi
fi

# A checkpoint of another input is refused with exit status 2 and a message.
sed 's/seed = [0-9]*/seed = 12345/' "$nml" > other.nml
set +e
"$exe" other.nml --quiet --output other.h5 --restart first.checkpoint.h5 2> refused.txt
status=$?
set -e
if [ $status -eq 2 ] && grep -q "different input" refused.txt && [ ! -e other.h5 ]; then
  echo "PASS: a checkpoint of another input is refused: $(cat refused.txt)"
else
  echo "FAIL: status $status, message: $(cat refused.txt)"; exit 1
fi
