#!/usr/bin/env bash
# Refusals under MPI end every rank, at once, with rank 0's status (parallel.hpp Session::finish): a check
# that only rank 0 makes (the --compare JSON's folder) once left the other ranks waiting in the run's first
# collective for ever; a bad input is reported once, not once per rank, and so is a run's failure that
# every rank has (parallel::AgreedFailure: each rank's replica of a sticking gas aggregated into one cluster)
# or one rank has (a two-point sweep whose second point, run by rank 1, sticks).
# usage: mpi_refusals.sh GRANULAR_DSMC WORKDIR MPIEXEC   (MPIEXEC none: skipped, exit 77)
set -uo pipefail
exe=$1 work=$2 mpiexec=${3:-none}
[ "$mpiexec" = "none" ] && { echo "no MPI launcher: skipped"; exit 77; }
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
mpi=("$mpiexec" --oversubscribe -np 2)
if [ "$(id -u)" -eq 0 ]; then mpi+=(--allow-run-as-root); fi
cat > in.nml <<'NML'
&system
  n_species = 1, mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 0.9
/
&dsmc
  n_particles = 2000, t_end = 5.0, replicas = 2, seed = 3
/
&output
  file = 'out.h5', n_samples = 3
/
NML
cat > sticky.nml <<'NML'
&system
  n_species = 1, mass = 1.0, diameter = 1.0, number_density = 0.1, restitution = 1.0
/
&dsmc
  scheme = 'lowrank', n_particles = 200, collisions_per_particle = 50, replicas = 2, seed = 1
/
&output
  file = 'sticky.h5', n_samples = 3
/
&agg_frag
  aggregation_energy = 100.0, fragmentation_energy = 1000.0, fragment_restitution = 0.5
/
NML
{ sed 's/sticky.h5/sticky2.h5/; s/replicas = 2/replicas = 1/' sticky.nml
  printf '%s\n' "&sweep" "  variable = 'agg_frag:aggregation_energy', values = 1e-9, 100.0" "/"; } > sticky2.nml
failures=0
# expect NAME STATUS MESSAGE -- ARGS...: the exit status, the message (if any) exactly once, within 15 s
expect() {
  local name=$1 want=$2 message=$3
  shift 4
  local start=$SECONDS
  timeout -s KILL 15 "${mpi[@]}" "$exe" "$@" > stdout 2> stderr
  local status=$? took=$((SECONDS - start)) count
  if [ -n "$message" ]; then count=$(grep -c -F -- "$message" stderr); else count=1; fi
  if [ $status -ne "$want" ] || [ "$count" -ne 1 ]; then
    echo "FAIL $name: exit $status (want $want) after $took s, the message $count times: $(head -3 stderr)"
    failures=$((failures + 1))
  else
    echo "ok   $name: exit $status after $took s, the message once"
  fi
}
expect "compare-json-folder-missing" 2 "cannot write the JSON file" -- in.nml --quiet --compare="$PWD/no-such-folder/x.json"
expect "bad-input" 2 "n_particles = -3 is outside" -- in.nml --quiet --set dsmc:n_particles=-3
expect "a-failure-of-every-rank" 1 "aggregated into one cluster" -- sticky.nml --quiet
[ -e sticky.h5 ] && { echo "FAIL a-failure-of-every-rank: sticky.h5 written"; failures=$((failures + 1)); }
expect "a-failure-of-rank-1" 1 "aggregated into one cluster" -- sticky2.nml --quiet
[ -e sticky2.h5 ] && { echo "FAIL a-failure-of-rank-1: sticky2.h5 written"; failures=$((failures + 1)); }
expect "a-run" 0 "" -- in.nml --quiet --force
[ -f out.h5 ] || { echo "FAIL a-run: no out.h5"; failures=$((failures + 1)); }
[ $failures -eq 0 ]
