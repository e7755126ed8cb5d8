#!/usr/bin/env bash
# Ctrl-C on every path: an endless run (t_end = 1e30) of each kind is sent SIGINT (or SIGTERM) once it
# is well under way and must end within a second (the standard: "every loop notices Ctrl-C within a
# second, by time, whatever the step size"), with exit status 130 and no output file, temporary or
# checkpoint left behind. The kinds: every scheme, one species, a mixture and 1e5 species, Enskog, step_fraction
# from 1e-300 to 100 (the documented range is (0, 100]), blocks and no blocks, threads inside a
# replica and replicas on threads, the Gaussian and white-noise thermostats, shear flow, rough
# spheres, aggregation/fragmentation, a sweep (and one while its output is written), --compare's
# theory (during and after the run) and granular-theory alone (Smoluchowski, and 3000 species), and with
# MPIEXEC two MPI ranks.
# usage: interrupt.sh GRANULAR_DSMC WORKDIR [MPIEXEC]
set -uo pipefail
exe=$1 work=$2 mpiexec=${3:-none}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1

limit=1.0  # seconds from the signal to the end of the process
failures=0 cases=0

base() {  # one species, 1e5 particles (blocks of 32768), an endless run, one replica
  cat <<EOF
&system
  n_species = 1, mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 0.9
/
&initial
  temperature = 1.0
/
&dsmc
  n_particles = 100000, t_end = 1e30, allow_long_run = .true., replicas = 1, seed = 3
/
&output
  file = 'out.h5', n_samples = 3
/
EOF
}
mixture=(--set system:n_species=2 --set "system:mass=1.0,2.0" --set "system:diameter=1.0,1.2"
         --set "system:number_density=0.005,0.005" --set "initial:temperature=1.0,1.0")

# run_case NAME SIGNAL EXTRA_GROUPS [LAUNCHER...] -- [--set ...]
run_case() {
  local name=$1 signal=$2 extra=$3
  shift 3
  local launcher=()
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do launcher+=("$1"); shift; done
  shift
  cases=$((cases + 1))
  rm -rf "case-$name" && mkdir "case-$name" && cd "case-$name" || exit 1
  { base; printf '%s\n' "$extra"; } > in.nml
  local command=("${launcher[@]}")
  [ "${launcher[0]:-}" = "mpi" ] && command=("${launcher[@]:1}")
  # The input by its absolute path: the ranks are found by their command line, and other tests running
  # at the same time (ctest -j) also run "granular-dsmc in.nml"; they must neither be signalled nor waited for.
  local input=$PWD/in.nml
  "${command[@]}" "$exe" "$input" --quiet "$@" > stdout 2> stderr &
  local pid=$!
  sleep "${setup_seconds:-1.2}"  # past the set-up, inside the loops
  if ! kill -0 $pid 2>/dev/null; then
    echo "FAIL $name: ended before the signal: $(tail -1 stderr)"; failures=$((failures + 1)); cd ..; return
  fi
  local sent=$(date +%s.%N)
  if [ "${launcher[0]:-}" = "mpi" ]; then
    # Open MPI's mpirun passes a signal on to the ranks only after odls_base_sigkill_timeout (1-2 s,
    # its own delay); a batch system (scancel) and a terminal's Ctrl-C signal the ranks themselves.
    pkill --signal "$signal" -f "^$exe $input "
  else
    kill -s "$signal" $pid
  fi
  local waited=0
  if [ "${launcher[0]:-}" = "mpi" ]; then  # the ranks' end (mpirun's own teardown takes ~1 s more)
    while pgrep -f "^$exe $input " > /dev/null && [ $waited -lt 100 ]; do sleep 0.02; waited=$((waited + 1)); done
    local ended=$(date +%s.%N)
    for _ in $(seq 100); do kill -0 $pid 2>/dev/null || break; sleep 0.05; done
  else
    while kill -0 $pid 2>/dev/null && [ $waited -lt 100 ]; do sleep 0.02; waited=$((waited + 1)); done
    local ended=$(date +%s.%N)
  fi
  if kill -0 $pid 2>/dev/null; then
    pkill -9 -f "^$exe $input " ; kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
    echo "FAIL $name: still running 2 s after SIG$signal"; failures=$((failures + 1)); cd ..; return
  fi
  wait $pid
  local status=$? seconds
  seconds=$(awk -v a="$sent" -v b="$ended" 'BEGIN { printf "%.3f", b - a }')
  local left
  left=$(ls | grep -v -x -e in.nml -e stdout -e stderr | tr '\n' ' ')
  if [ $status -ne 130 ] || awk -v s="$seconds" -v l="$limit" 'BEGIN { exit !(s > l) }' || [ -n "$left" ]; then
    echo "FAIL $name: SIG$signal -> exit $status after $seconds s (limit $limit s); left: ${left:-nothing}; $(tail -1 stderr)"
    failures=$((failures + 1))
  else
    echo "ok   $name: SIG$signal -> exit 130 after $seconds s"
  fi
  cd ..
}

for sf in 1e-300 1e-6 1 100; do
  for scheme in majorant lowrank pairs; do
    run_case "$scheme-$sf" INT "" -- --set "dsmc:scheme='$scheme'" --set "dsmc:step_fraction=$sf"
  done
  run_case "mixture-lowrank-$sf" INT "" -- "${mixture[@]}" --set "dsmc:scheme='lowrank'" --set "dsmc:step_fraction=$sf"
done
# Without &output checkpoint_every the one line says how to make a run resumable.
cases=$((cases + 1))
hint="granular-dsmc: interrupted: no output written (with &output checkpoint_every = SECONDS an interrupted run leaves a checkpoint to resume)"
if [ "$(cat case-majorant-1/stderr)" = "$hint" ]; then echo "ok   the message without a checkpoint names checkpoint_every"
else echo "FAIL the message without a checkpoint: $(cat case-majorant-1/stderr)"; failures=$((failures + 1)); fi
# 1e5 species in cache blocks (the separable draw): a candidate costs several times one species', so the
# blocks look at the signal every 2^16 candidates, and a pass visits no block after it.
# Its set-up (4e6 particles of 1e5 species) takes 0.6 s on an idle machine and up to 2.4 s beside three busy
# processes on 2 cores, and looks at the signal too (dsmc/particles.hpp, SetUpCheck): signalled at 0.6 s
# (inside the set-up, or on a fast machine just past it; the handler is installed after about 0.1 s, and a
# script's background job ignores a SIGINT that comes before it) and at 3 s (in the loops).
species=(--set system:n_species=100000 --set "system:mass_law='linear'" --set "system:diameter_law='cube_root'"
         --set "system:density_law='power'" --set system:density_exponent=0 --set "dsmc:scheme='lowrank'"
         --set dsmc:n_particles=4000000)
setup_seconds=0.6 run_case "lowrank-100000-species-set-up" INT "" -- "${species[@]}"
setup_seconds=3.0 run_case "lowrank-100000-species" INT "" -- "${species[@]}"
run_case "majorant-no-blocks-1e-300" INT "" -- --set dsmc:block_size=0 --set dsmc:step_fraction=1e-300
run_case "mixture-majorant-no-blocks-1e-300" INT "" -- "${mixture[@]}" --set dsmc:block_size=0 --set dsmc:step_fraction=1e-300
run_case "mixture-pairs-1e-300" INT "" -- "${mixture[@]}" --set "dsmc:scheme='pairs'" --set dsmc:step_fraction=1e-300
run_case "enskog-pairs-1e-300" INT "" -- --set system:enskog=.true. --set system:number_density=0.2 \
  --set "dsmc:scheme='pairs'" --set dsmc:step_fraction=1e-300
run_case "rough-1e-300" INT "" -- --set system:roughness=0.5 --set dsmc:step_fraction=1e-300
run_case "gaussian-1e-300" INT $'&thermostat\n  kind = \'gaussian\'\n/' -- --set dsmc:step_fraction=1e-300
run_case "white-noise-1e-300" INT $'&thermostat\n  kind = \'white_noise\', noise_strength = 0.01\n/' -- \
  --set dsmc:step_fraction=1e-300
run_case "shear-gaussian-1e-300" INT $'&thermostat\n  kind = \'gaussian\'\n/\n&shear\n  rate = 0.003\n/' -- \
  --set dsmc:step_fraction=1e-300
agg=$'&agg_frag\n  aggregation_energy = 0.5, fragmentation_energy = 1.5, fragment_restitution = 0.5\n/'
for sf in 1e-300 1 100; do
  run_case "agg-frag-blocks-$sf" INT "$agg" -- --set dsmc:step_fraction=$sf --set dsmc:n_particles=1000000
  run_case "agg-frag-no-blocks-$sf" INT "$agg" -- --set dsmc:step_fraction=$sf --set dsmc:block_size=0 \
    --set dsmc:n_particles=1000000
done
run_case "sweep-1e-300" INT $'&sweep\n  variable = \'system:restitution\'\n  values = 0.9, 0.7\n/' -- \
  --set dsmc:step_fraction=1e-300
# While the output is written: a sweep of 1000 points of 10 particles computes in milliseconds and writes
# for seconds (the writing looks at the signal between points; io/file_guard.hpp ends a write it cannot see).
seeds=$(seq -s, 1 1000)
run_case "writing-a-sweep" INT $'&sweep\n  variable = \'dsmc:seed\'\n  values = '"$seeds"$'\n/' -- \
  --set dsmc:n_particles=10 --set dsmc:t_end=0.001 --set dsmc:replicas=2
run_case "block-threads-1e-300" INT "" env OMP_NUM_THREADS=2 -- --set dsmc:step_fraction=1e-300
run_case "replica-threads-1e-300" INT "" env OMP_NUM_THREADS=2 -- --set dsmc:replicas=2 --set dsmc:step_fraction=1e-300
run_case "sigterm-pairs-1e-300" TERM "" -- --set "dsmc:scheme='pairs'" --set dsmc:step_fraction=1e-300
run_case "sigterm-agg-frag-1e-300" TERM "$agg" -- --set dsmc:step_fraction=1e-300 --set dsmc:block_size=0
# --compare of a sticking gas: the Smoluchowski theory takes far longer than the run (the run takes
# 0.3 s, the theory would take hours); interrupted while the theory runs beside the run (2 threads),
# and after the run while only the theory is left (t_end = 1000).
sticky=(--compare --set agg_frag:aggregation_energy=100)
run_case "compare-agg-frag-during-run" INT "$agg" env OMP_NUM_THREADS=2 -- "${sticky[@]}" --set dsmc:n_particles=1000000
run_case "compare-agg-frag-theory-after-run" INT "$agg" -- "${sticky[@]}" --set dsmc:t_end=1000
run_case "compare-agg-frag-theory-one-thread" INT "$agg" env OMP_NUM_THREADS=1 -- "${sticky[@]}" --set dsmc:t_end=1000
# granular-theory alone: on the same input (the Smoluchowski equations, which stop at their next
# right-hand side), and on 3000 species (the partial-temperature equations, more than 8 s on the 2-core VM:
# their dense Newton steps have no place to stop, so the program ends while they run)
theory_exe=$(dirname "$exe")/granular-theory
theory_case() {  # theory_case NAME NAMELIST [--set ...]: SIGINT 1.2 s after the start
  local name=$1 input=$2
  shift 2
  cases=$((cases + 1))
  "$theory_exe" "$input" "$@" > "theory-$name.json" 2> "theory-$name.err" &
  local pid=$!
  sleep 1.2
  local sent ended waited=0 status seconds
  if ! kill -0 $pid 2>/dev/null; then
    wait $pid; echo "FAIL granular-theory $name: ended before the signal (exit $?): the case needs a longer theory"
    failures=$((failures + 1))
    return
  fi
  sent=$(date +%s.%N)
  kill -INT $pid
  while kill -0 $pid 2>/dev/null && [ $waited -lt 100 ]; do sleep 0.02; waited=$((waited + 1)); done
  ended=$(date +%s.%N)
  if kill -0 $pid 2>/dev/null; then
    kill -9 $pid; wait $pid; echo "FAIL granular-theory $name: still running 2 s after SIGINT"; failures=$((failures + 1))
    return
  fi
  wait $pid
  status=$?
  seconds=$(awk -v a="$sent" -v b="$ended" 'BEGIN { printf "%.3f", b - a }')
  if [ $status -ne 130 ] || [ -s "theory-$name.json" ] || awk -v s="$seconds" -v l="$limit" 'BEGIN { exit !(s > l) }'; then
    echo "FAIL granular-theory $name: SIGINT -> exit $status after $seconds s, $(wc -c < "theory-$name.json") bytes printed; $(cat "theory-$name.err")"
    failures=$((failures + 1))
  else
    echo "ok   granular-theory $name: SIGINT -> exit 130 after $seconds s, nothing printed"
  fi
}
if [ -x "$theory_exe" ]; then
  theory_case agg-frag case-compare-agg-frag-theory-after-run/in.nml --set agg_frag:aggregation_energy=100 \
    --set dsmc:t_end=1000
  cat > theory-many.nml <<EOF
&system
  n_species = 3000, mass = 1.0, mass_law = 'linear', diameter = 1.0, diameter_law = 'cube_root',
  number_density = 0.0001, density_law = 'power', density_exponent = 1.0, restitution = 0.8
/
&initial
  temperature = 1.0
/
&dsmc
  scheme = 'lowrank', n_particles = 100000, t_end = 2000.0, replicas = 1, seed = 5
/
EOF
  theory_case many-species theory-many.nml
fi
if [ "$mpiexec" != "none" ]; then
  mpi=("$mpiexec" --oversubscribe -np 2)
  if [ "$(id -u)" -eq 0 ]; then mpi+=(--allow-run-as-root); fi
  # Three times: which rank leaves MPI_Finalize first is a race, and a rank that exits non-zero while
  # another is still inside it made that one wait out Open MPI's 2 s timeout (parallel.hpp, finish).
  for attempt in 1 2 3; do
    run_case "mpi-2-ranks-1e-300-$attempt" INT "" mpi env OMP_NUM_THREADS=1 "${mpi[@]}" -- --set dsmc:replicas=2 \
      --set "dsmc:scheme='pairs'" --set dsmc:step_fraction=1e-300
  done
fi

echo "$((cases - failures)) of $cases runs (44 kinds, the MPI one three times) stopped within $limit s of the signal"
[ $failures -eq 0 ]
