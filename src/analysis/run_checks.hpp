/**
 * \file run_checks.hpp
 * \brief The checks of an input that need the theory: the work of the run, refused beyond caps.
 *
 * The work of a run from kinetic theory (theory/run_cost.hpp, \ref haff_law "docs/haff-and-mixtures.md"):
 * refused unless `&dsmc allow_long_run` when it is more than 1e12 collision events per replica (a day
 * or more at 1e7 collisions per second), or a cooling below 1e-40 of the initial temperature, where
 * the thermal speeds (1e-20 of the initial ones) drown in the round-off of the conserved total
 * momentum, almost every candidate is rejected and the run never ends.
 *
 * Both programs pass check_run_cost to io::config::read_file (its RunCheck), which runs it where its
 * own checks end, on the input and on every sweep point, so that the refusal reads as any other
 * input error. Checked by tests/cli_test.cpp (CliDsmc, CliTheory: the refusals).
 *
 * The theory's memory (check_theory_memory): a mixture's theory holds O(S^2) pair tables; where they
 * would not fit in the machine's memory (70000 species: about 300 GB) granular-theory, and granular-dsmc
 * with --compare, refuse before any work, naming `&system n_species`. Checked by tests/cli_test.cpp
 * (CliTheory.TheoryBeyondTheMachinesMemoryIsRefused).
 *
 * Warnings (the run goes on): a gas denser than packing fraction kDenseWarning = 0.05 without
 * `&system enskog` runs as a Boltzmann gas, whose collision rate ignores the density: at phi = 0.05 the
 * Enskog rate is chi = (1 - phi/2)/(1 - phi)^3 = 1.14 times higher (Carnahan-Starling, \ref cm_chi
 * "docs/collision-model.md"), at phi = 0.31 2.57 times; from phi = 0.5 (species::carnahan_starling_fluid_limit,
 * where enskog is refused) the warning quotes no chi and does not suggest enskog. Checked by
 * tests/cli_test.cpp (CliDsmc.DenseGasWithoutEnskogWarns).
 */
#pragma once

#include <string>
#include <vector>

#include "io/config.hpp"

namespace gdsmc::analysis {

/// Throws io::namelist::Error naming `&dsmc t_end` (or `collisions_per_particle`) where it was set
/// when the run's estimated work is beyond the caps above and allow_long_run is not set.
void check_run_cost(const io::config::Config& config);

/// A limit on the memory this process can use.
struct MemoryLimit {
  double bytes = 0.0;  ///< its size in bytes (0 when unknown)
  std::string what;    ///< which limit it is, for messages ("this machine's memory", ...)
};
/// The memory this process can use: the machine's physical memory, or the address-space limit of
/// ulimit -v when lower.
MemoryLimit memory_limit();

/// Bytes the theory of `config` (analysis::predict: granular-theory, granular-dsmc --compare) holds at
/// its peak: a mixture's pair tables are O(S^2) (the partial-temperature ODEs' pair constants of
/// theory/maxwellian_rates.hpp, the Newton matrices of the temperature ratios), about 60 S^2 bytes above
/// 1300 species (measured, \ref perf_theory "docs/performance.md"); 0 up to 1000 species (at most 60 MB)
/// and for the cluster gas of &agg_frag.
double theory_memory_bytes(const io::config::Config& config);

/// Throws io::namelist::Error naming `&system n_species` when theory_memory_bytes is beyond
/// memory_limit(): the theory would fail with std::bad_alloc. `remedy` ends the message.
void check_theory_memory(const io::config::Config& config, const std::string& remedy);

/// Above this packing fraction a run without enskog is warned about.
inline constexpr double kDenseWarning = 0.05;
/// The warnings about an input (every sweep point), each one line naming file, line, group and variable.
std::vector<std::string> input_warnings(const io::config::Config& config);

}  // namespace gdsmc::analysis
