/**
 * \file replica.hpp
 * \brief One replica of one point, in one loop: for each sample, the steps up to it (collision chunks,
 *        or stages with forcings), then its measurement; between steps an interrupt is noticed, the
 *        progress line updated and a checkpoint written when due.
 *
 * The loop is the same for every run; what steps and what is measured is the replica's engine:
 * - a free gas (collide.hpp): chunks of at most 2^20 events and about 1e5 candidates (2^24 with cache
 *   blocks, ending at blocked steps' ends), the sample's event target met exactly;
 * - a gas with forcings (the Gaussian thermostat and the uniform shear flow, dsmc/thermostat.hpp):
 *   stages of `&dsmc stage_step` majorant mean free times, at most what each forcing allows, the
 *   velocities held in a frame (collide.hpp "Frame"): per stage, the forcings' maps composed into the
 *   frame, the sample when one is due, the collisions, the forcings' ends;
 * - the cluster gas of &agg_frag (agg_frag.hpp): chunks of at most 2^19 events, or blocked steps.
 *
 * Replica r draws its initial state from stream (seed, r, initial_state) and its collisions from
 * (seed, r, collisions) (rng.hpp), so a replica's trajectory does not depend on how many replicas run
 * or in which order. Every step ends at times and events that depend only on the state a checkpoint
 * restores, so a resumed replica is the uninterrupted one bit for bit (tests/scale_out/restart.sh).
 * A checkpoint of a replica holds the Records (dsmc/state.hpp) of its engine's modules, its partial
 * result and `replica/next_sample`.
 */
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>

#include "dsmc/state.hpp"
#include "io/config.hpp"
#include "run/progress.hpp"
#include "run/results.hpp"
#include "run/simulation.hpp"

namespace gdsmc::simulation {

/// Called between steps and after each sample with a way to snapshot the replica (a checkpoint).
using SafePoint = std::function<void(const std::function<state::Record()>&)>;

/// Where a replica runs: the run's options, the rank's progress line and its slot in it, the threads its
/// cache blocks may use (collide.hpp, "Threads inside one replica"; the results do not depend on them).
struct ReplicaContext {
  const Options& options;  ///< the interrupt flag, whether progress is shown
  Progress& progress;      ///< this rank's progress line
  std::size_t slot;        ///< the unit's slot in it
  int block_threads;       ///< threads for the unit's cache blocks
  SafePoint safe_point;    ///< checkpoints
  /// Set when another unit of this rank failed: this one stops at its next step end (as on an
  /// interrupt, without a checkpoint), so that the failure is reported at once, not after the run.
  const std::atomic<bool>* abandon = nullptr;
};

/// A gas without forcing only loses energy in collisions (the rules' energy balance, \ref cm_rule
/// "docs/collision-model.md"; rough spheres with their rotation, agg/frag with the fragments' share):
/// throws std::runtime_error, naming both values and times, when the one-column row `row` of `result`
/// (an energy per particle, or a multiple of it) rose from its previous sample by more than 1e-6
/// relative (round-off: elastic gases hold it to ~1e-12). Free gases and cluster gases call it at every
/// sample, so that a physics error that heats the gas stops the run at once.
void check_energy_does_not_grow(const ReplicaResult& result, const char* row);

/// Runs replica `replica` of `config` from the start, or from `resume` (a checkpoint's record of it).
/// Throws Interrupted when the interrupt flag is set, state::StateError for a damaged record.
ReplicaResult run_replica(const io::config::Config& config, std::size_t replica, const state::Record* resume,
                          ReplicaContext& context);

}  // namespace gdsmc::simulation
