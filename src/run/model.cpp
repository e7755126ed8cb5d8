// The objects of the model built from a Config (model.hpp).
#include "run/model.hpp"

#include <limits>

#include "theory/viscosity.hpp"

namespace gdsmc::simulation {

rules::Rule make_rule(const io::config::Config& config, const species::Mixture& mix) {
  const auto beta = config.viscoelastic_beta();
  return rules::make_rule(mix, beta ? &*beta : nullptr);
}

collide::Scheme scheme(const io::config::Config& config) {
  switch (config.dsmc.scheme) {
    case io::config::Scheme::pairs: return collide::Scheme::pairs;
    case io::config::Scheme::lowrank: return collide::Scheme::lowrank;
    case io::config::Scheme::majorant: break;
  }
  return collide::Scheme::majorant;
}

particles::InitialDistribution initial_distribution(const io::config::Config& config) {
  switch (config.initial.distribution) {
    case io::config::VelocityDistribution::shell: return particles::InitialDistribution::shell;
    case io::config::VelocityDistribution::cube: return particles::InitialDistribution::cube;
    case io::config::VelocityDistribution::maxwell: break;
  }
  return particles::InitialDistribution::maxwell;
}

agg_frag::Model agg_frag_model(const io::config::Config& c) {
  agg_frag::Model m;
  m.monomer_mass = c.system.mass[0];
  m.monomer_diameter = c.system.diameter[0];
  m.monomer_density = c.system.number_density[0];
  m.restitution = c.system.restitution(0, 0);
  m.aggregation_energy = c.agg_frag.aggregation_energy.value_or(0.0);
  m.fragmentation_energy = c.agg_frag.fragmentation_energy.value_or(std::numeric_limits<double>::infinity());
  m.fragment_restitution = c.agg_frag.fragment_restitution.value_or(1.0);
  return m;
}

bool staged_blocks(const io::config::Config& config) {
  return config.dsmc.scheme != io::config::Scheme::pairs && config.dsmc.block_size > 0 &&
         config.dsmc.n_particles >= 2 * config.dsmc.block_size;
}

std::vector<std::unique_ptr<thermostat::Forcing>> make_forcings(const io::config::Config& config,
                                                               const species::Mixture& mix) {
  std::vector<std::unique_ptr<thermostat::Forcing>> forcings;
  const double shear = config.shear.rate.value_or(0.0);
  // Enskog in shear flow: the collisions do viscous work and transfer momentum (collide.hpp set_shear).
  const bool enskog_shear = shear > 0.0 && mix.enskog;
  if (config.thermostat.kind == io::config::ThermostatKind::gaussian) forcings.push_back(std::make_unique<thermostat::GaussianThermostat>(enskog_shear));
  if (config.thermostat.kind == io::config::ThermostatKind::white_noise)
    forcings.push_back(std::make_unique<thermostat::WhiteNoise>(mix, config.thermostat.noise_strength));
  if (shear > 0.0) {
    // eta_0(T) of one species (\ref eta_one_species "docs/shear-viscosity.md"), or of the elastic mixture at the same T
    // (Chapman and Cowling's first approximation; theory/viscosity.hpp).
    auto elastic_viscosity = [mix](double temperature) {
      return mix.size() == 1 ? theory::viscosity::elastic_viscosity(mix.mass[0], mix.diameter[0], temperature)
                             : theory::viscosity::elastic_mixture_viscosity(mix, temperature);
    };
    // (half the last sample time, which the sample times' spacing may leave an ulp from t_end)
    const double average_from = config.shear.average_from.value_or(0.5 * config.sample_times().back());
    forcings.push_back(std::make_unique<thermostat::ShearFlow>(shear, average_from, mix.total_density(), enskog_shear,
                                                               std::move(elastic_viscosity)));
  }
  return forcings;
}

}  // namespace gdsmc::simulation
