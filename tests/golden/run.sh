#!/usr/bin/env bash
# Golden runs: one short run of every path a user can take (each scheme, one species and mixtures,
# dilute and Enskog, t_end and collision targets, displacements, thermostat and shear, agg/frag,
# sweeps, 1 and 2 threads, MPI, restart, --compare, --table, granular-theory), written to OUTDIR.
# A change meant to keep the output compares two trees of these files with compare.sh (developer
# tool, not part of ctest: it needs the build of the code before the change; docs/extending.md).
#
# usage: tests/golden/run.sh BIN_DIR OUTDIR [CASE ...]   (BIN_DIR holds granular-dsmc and granular-theory)
set -euo pipefail
bin=$(cd "$1" && pwd); out=$2; shift 2
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"; out=$(cd "$out" && pwd)
mpi_flags=(--oversubscribe); [ "$(id -u)" -eq 0 ] && mpi_flags+=(--allow-run-as-root)

one="&system n_species = 1, mass = 1.0, diameter = 1.0, number_density = 0.01, restitution = 0.8 /"
binary="&system n_species = 2, mass = 1.0, 4.0, diameter = 1.0, 1.5, number_density = 0.005, 0.005, restitution = 0.8 /"
enskog="&system n_species = 2, mass = 1.0, 4.0, diameter = 1.0, 1.5, number_density = 0.0437, 0.0437, restitution = 0.8, enskog = .true. /"
many="&system n_species = 20, mass = 1.0, diameter = 1.0, number_density = 0.01, mass_law = 'linear', diameter_law = 'cube_root', density_law = 'power', density_exponent = 3.0, restitution = 0.8 /"
visco="&system n_species = 3, mass = 1.0, 2.0, 4.0, diameter = 1.0, 1.26, 1.5874, number_density = 0.01, 0.006, 0.004, restitution_model = 'viscoelastic', visco_a_kappa = 0.05 /"
visco_one="&system n_species = 1, mass = 1.0, diameter = 1.0, number_density = 0.01, restitution_model = 'viscoelastic', visco_a_kappa = 0.05 /"
enskog_one="&system n_species = 1, mass = 1.0, diameter = 1.0, number_density = 0.382, restitution = 0.9, enskog = .true. /"
monomer="&system n_species = 1, mass = 1.0, diameter = 1.0, number_density = 0.1, restitution = 0.8 /"

# case NAME SYSTEM DSMC OUTPUT [EXTRA_GROUPS]: writes NAME.nml
case_nml() {
  printf '%s\n&initial temperature = %s /\n&dsmc %s /\n&output file = '"'"'%s.h5'"'"', %s /\n%s\n' \
    "$2" "${6:-1.0}" "$3" "$1" "$4" "${5:-}" > "$out/$1.nml"
}
declare -A env_of args_of
base_cases=()
add() { local name=$1; shift; case_nml "$name" "$@"; base_cases+=("$name"); }

add one_majorant_t "$one" "scheme = 'majorant', n_particles = 100000, t_end = 400.0, replicas = 2, seed = 1, block_size = 16384" "n_samples = 12, spacing = 'log', first_sample = 1.0, scaling_start = 5.0"
add one_majorant_unblocked_events "$one" "scheme = 'majorant', n_particles = 20000, collisions_per_particle = 20.0, replicas = 2, seed = 2, block_size = 0" "n_samples = 8"
add one_lowrank_events_msd "$one" "scheme = 'lowrank', n_particles = 80000, collisions_per_particle = 15.0, replicas = 2, seed = 3, block_size = 8192" "n_samples = 10, track_displacements = .true., msd_start_temperature = 0.5"
add one_pairs_t_msd "$one" "scheme = 'pairs', n_particles = 20000, t_end = 200.0, replicas = 2, seed = 4" "n_samples = 6, track_displacements = .true., msd_start_time = 20.0"
add binary_majorant_t "$binary" "scheme = 'majorant', n_particles = 100000, t_end = 600.0, replicas = 2, seed = 5, block_size = 16384" "n_samples = 8, scaling_start = 3.0" "" "1.0, 1.0"
add binary_lowrank_events_msd "$binary" "scheme = 'lowrank', n_particles = 100000, collisions_per_particle = 10.0, replicas = 1, seed = 6, block_size = 16384" "n_samples = 6, track_displacements = .true." "" "1.0, 1.0"
add binary_pairs_t "$binary" "scheme = 'pairs', n_particles = 20000, t_end = 300.0, replicas = 2, seed = 7" "n_samples = 6" "" "1.0, 1.0"
add enskog_majorant_events "$enskog" "scheme = 'majorant', n_particles = 80000, collisions_per_particle = 8.0, replicas = 2, seed = 8, block_size = 8192" "n_samples = 6" "" "1.0, 1.0"
add enskog_lowrank_t "$enskog" "scheme = 'lowrank', n_particles = 80000, t_end = 60.0, replicas = 1, seed = 9, block_size = 8192" "n_samples = 6" "" "1.0, 1.0"
add enskog_pairs_events "$enskog" "scheme = 'pairs', n_particles = 20000, collisions_per_particle = 6.0, replicas = 2, seed = 10" "n_samples = 5" "" "1.0, 1.0"
add many_lowrank_events "$many" "scheme = 'lowrank', n_particles = 200000, collisions_per_particle = 6.0, replicas = 1, seed = 11, block_size = 16384" "n_samples = 5"
add many_majorant_unblocked_t "$many" "scheme = 'majorant', n_particles = 30000, t_end = 100.0, replicas = 1, seed = 12, block_size = 0" "n_samples = 5"
add visco_lowrank_blocks "$visco" "scheme = 'lowrank', n_particles = 60000, collisions_per_particle = 6.0, replicas = 1, seed = 13, block_size = 8192" "n_samples = 5" "" "1.0"
add visco_majorant_unblocked "$visco" "scheme = 'majorant', n_particles = 20000, t_end = 100.0, replicas = 2, seed = 14, block_size = 0" "n_samples = 5" "" "1.0"
add visco_pairs "$visco" "scheme = 'pairs', n_particles = 20000, t_end = 100.0, replicas = 1, seed = 15" "n_samples = 5" "" "1.0"
add visco_one_blocks_msd "$visco_one" "scheme = 'majorant', n_particles = 60000, t_end = 300.0, replicas = 1, seed = 16, block_size = 8192" "n_samples = 5, track_displacements = .true."
add hss_one_blocks "$one" "scheme = 'majorant', n_particles = 60000, t_end = 150.0, replicas = 2, seed = 17, block_size = 8192" "n_samples = 8, scaling_start = 2.0" "&thermostat kind = 'gaussian' /"
add hss_binary_unblocked "$binary" "scheme = 'majorant', n_particles = 20000, t_end = 150.0, replicas = 2, seed = 18, block_size = 0" "n_samples = 6" "&thermostat kind = 'gaussian' /" "1.0, 1.0"
add usf_binary_lowrank_blocks "$binary" "scheme = 'lowrank', n_particles = 60000, t_end = 200.0, replicas = 1, seed = 19, block_size = 8192" "n_samples = 11" "&thermostat kind = 'gaussian' /
&shear rate = 0.00284 /" "1.0, 1.0"
add usf_one_majorant_nothermostat "$one" "scheme = 'majorant', n_particles = 20000, t_end = 100.0, replicas = 2, seed = 20, block_size = 0" "n_samples = 6" "&shear rate = 0.005 /"
add usf_enskog_pairs "$enskog_one" "scheme = 'pairs', n_particles = 8000, t_end = 5.0, replicas = 2, seed = 21" "n_samples = 11" "&thermostat kind = 'gaussian' /
&shear rate = 0.108 /"
add usf_enskog_mixture_pairs "$enskog" "scheme = 'pairs', n_particles = 8000, t_end = 20.0, replicas = 1, seed = 22" "n_samples = 6" "&thermostat kind = 'gaussian' /
&shear rate = 0.02 /" "1.0, 1.0"
add aggfrag_blocks "$monomer" "scheme = 'lowrank', n_particles = 100000, t_end = 10.0, replicas = 2, seed = 23, block_size = 16384" "sample_times = 0.5, 1.0, 2.0, 5.0" "&agg_frag aggregation_energy = 0.5, fragmentation_energy = 1.5, fragment_restitution = 0.5 /"
add aggfrag_unblocked_events "$monomer" "scheme = 'lowrank', n_particles = 5000, collisions_per_particle = 3.0, replicas = 2, seed = 24, block_size = 0" "n_samples = 4" "&agg_frag aggregation_energy = 0.8 /"
add sweep_grid "$binary" "scheme = 'majorant', n_particles = 20000, t_end = 100.0, replicas = 2, seed = 25, block_size = 4096" "n_samples = 5" "&sweep variable = 'system:restitution', 'system:mass(2)', values(1,1) = 0.6, 0.9, values(1,2) = 2.0, 4.0, grid = .true. /" "1.0, 1.0"
add sweep_one_events "$one" "scheme = 'lowrank', n_particles = 20000, collisions_per_particle = 5.0, replicas = 1, seed = 26, block_size = 4096" "n_samples = 4" "&sweep variable = 'system:restitution', values = 0.5, 0.7, 0.95 /"

cases=("$@")
if [ ${#cases[@]} -eq 0 ]; then
  cases=("${base_cases[@]}" threads2_one threads2_binary threads2_aggfrag threads2_usf mpi_sweep restart_one restart_usf restart_aggfrag compare_one compare_binary compare_aggfrag compare_sweep compare_hss compare_usf compare_msd table_sweep theory)
fi

run() {  # run NAME ENV... -- ARGS...: one granular-dsmc run in OUTDIR
  local name=$1; shift
  (cd "$out" && env "$@")
}

for c in "${cases[@]}"; do
  start=$(date +%s.%N)
  case $c in
    threads2_one) sed "s/one_majorant_t.h5/$c.h5/; s/replicas = 2/replicas = 1/" "$out/one_majorant_t.nml" > "$out/$c.nml"
                  (cd "$out" && OMP_NUM_THREADS=2 "$bin/granular-dsmc" "$c.nml" --quiet --force) ;;
    threads2_binary) sed "s/binary_lowrank_events_msd.h5/$c.h5/" "$out/binary_lowrank_events_msd.nml" > "$out/$c.nml"
                  (cd "$out" && OMP_NUM_THREADS=2 "$bin/granular-dsmc" "$c.nml" --quiet --force) ;;
    threads2_aggfrag) sed "s/aggfrag_blocks.h5/$c.h5/; s/replicas = 2/replicas = 1/" "$out/aggfrag_blocks.nml" > "$out/$c.nml"
                  (cd "$out" && OMP_NUM_THREADS=2 "$bin/granular-dsmc" "$c.nml" --quiet --force) ;;
    threads2_usf) sed "s/usf_binary_lowrank_blocks.h5/$c.h5/" "$out/usf_binary_lowrank_blocks.nml" > "$out/$c.nml"
                  (cd "$out" && OMP_NUM_THREADS=2 "$bin/granular-dsmc" "$c.nml" --quiet --force) ;;
    mpi_sweep) sed "s/sweep_grid.h5/$c.h5/" "$out/sweep_grid.nml" > "$out/$c.nml"
               (cd "$out" && OMP_NUM_THREADS=1 mpirun "${mpi_flags[@]}" -np 2 "$bin/granular-dsmc" "$c.nml" --quiet --force) ;;
    restart_*) base=${c#restart_}
               case $base in one) src=one_majorant_t ;; usf) src=usf_binary_lowrank_blocks ;; aggfrag) src=aggfrag_blocks ;; esac
               # ten times the particles and more replicas: a few seconds, several checkpoints
               sed "s/n_particles = \([0-9]*\)/n_particles = \10/; s/replicas = [0-9]*/replicas = 3/" "$out/$src.nml" > "$out/$c.nml"
               "$here/restart.sh" "$bin/granular-dsmc" "$out/$c.nml" "$out/$c" ;;
    compare_one) (cd "$out" && "$bin/granular-dsmc" one_majorant_t.nml --quiet --force --output "$c.h5" --compare="$c.json" > "$c.txt") ;;
    compare_binary) (cd "$out" && "$bin/granular-dsmc" binary_majorant_t.nml --quiet --force --output "$c.h5" --compare="$c.json" > "$c.txt") ;;
    compare_aggfrag|compare_sweep|compare_hss|compare_usf|compare_msd)
                 case $c in compare_aggfrag) src=aggfrag_unblocked_events ;; compare_sweep) src=sweep_one_events ;;
                            compare_hss) src=hss_binary_unblocked ;; compare_usf) src=usf_enskog_mixture_pairs ;;
                            compare_msd) src=binary_lowrank_events_msd ;; esac
                 (cd "$out" && "$bin/granular-dsmc" $src.nml --quiet --force --output "$c.h5" --compare="$c.json" > "$c.txt") ;;
    table_sweep) (cd "$out" && "$bin/granular-dsmc" --table sweep_grid.h5 > "$c.csv") ;;
    theory) for n in one_majorant_t binary_majorant_t enskog_pairs_events many_lowrank_events visco_majorant_unblocked hss_binary_unblocked usf_enskog_mixture_pairs aggfrag_unblocked_events one_lowrank_events_msd sweep_grid; do
              (cd "$out" && "$bin/granular-theory" "$n.nml" > "theory_$n.json" 2> "theory_$n.err" || true)
            done ;;
    *) (cd "$out" && "$bin/granular-dsmc" "$c.nml" --quiet --force) ;;
  esac
  printf '%-32s %6.1f s\n' "$c" "$(echo "$(date +%s.%N) - $start" | bc)"
done
