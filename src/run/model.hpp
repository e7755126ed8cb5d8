/**
 * \file model.hpp
 * \brief The objects of the model built from a validated Config (data flows one way: namelist ->
 *        Config -> model -> the DSMC steps): the initial distribution, the cluster model of &agg_frag,
 *        the forcings of &thermostat and &shear with what they need from the theory.
 *
 * This is where a new collision rule or forcing is switched on from its namelist fields
 * (\ref ext_rule "docs/extending.md"): one line per object.
 */
#pragma once

#include <memory>
#include <vector>

#include "dsmc/agg_frag.hpp"
#include "dsmc/particles.hpp"
#include "dsmc/rules.hpp"
#include "dsmc/thermostat.hpp"
#include "io/config.hpp"
#include "model/species.hpp"

namespace gdsmc::simulation {

/// The collision rule of &system (dsmc/rules.hpp): viscoelastic with `restitution_model = 'viscoelastic'`,
/// else constant alpha_kj. `mix` is the Config's mixture, which the rule refers to.
rules::Rule make_rule(const io::config::Config& config, const species::Mixture& mix);
/// The collision scheme of `&dsmc scheme` (dsmc/collide.hpp).
collide::Scheme scheme(const io::config::Config& config);
/// The initial velocity distribution of `&initial distribution`.
particles::InitialDistribution initial_distribution(const io::config::Config& config);
/// The monomer of &system and the thresholds of &agg_frag (\ref af_outcome "docs/agg-frag.md").
agg_frag::Model agg_frag_model(const io::config::Config& config);
/// Whether a run with forcings uses cache blocks (collide.hpp "Frame": frames in blocks): `majorant`
/// or `lowrank` (not `pairs`, which the Enskog gas in shear flow needs), N >= 2 block_size.
bool staged_blocks(const io::config::Config& config);
/// The forcings of &thermostat and &shear (dsmc/thermostat.hpp), in the order they act on a stage: the
/// thermostat's rescaling, then the shear's streaming. Empty without either.
std::vector<std::unique_ptr<thermostat::Forcing>> make_forcings(const io::config::Config& config,
                                                               const species::Mixture& mix);

}  // namespace gdsmc::simulation
