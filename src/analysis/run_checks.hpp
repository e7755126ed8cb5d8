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
 * Warnings (the run goes on): a gas denser than packing fraction kDenseWarning = 0.05 without
 * `&system enskog` runs as a Boltzmann gas, whose collision rate ignores the density: at phi = 0.05 the
 * Enskog rate is chi = (1 - phi/2)/(1 - phi)^3 = 1.14 times higher (Carnahan-Starling, \ref cm_chi
 * "docs/collision-model.md"), at phi = 0.31 2.57 times. Checked by tests/cli_test.cpp (CliDsmc.DenseGasWithoutEnskogWarns).
 */
#pragma once

#include <string>
#include <vector>

#include "io/config.hpp"

namespace gdsmc::analysis {

/// Throws io::namelist::Error naming `&dsmc t_end` (or `collisions_per_particle`) where it was set
/// when the run's estimated work is beyond the caps above and allow_long_run is not set.
void check_run_cost(const io::config::Config& config);

/// Above this packing fraction a run without enskog is warned about.
inline constexpr double kDenseWarning = 0.05;
/// The warnings about an input (every sweep point), each one line naming file, line, group and variable.
std::vector<std::string> input_warnings(const io::config::Config& config);

}  // namespace gdsmc::analysis
