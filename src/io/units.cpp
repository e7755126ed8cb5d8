// The units of the output file (io/units.hpp, \ref output_units "docs/output.md").
#include "io/units.hpp"

#include <map>
#include <stdexcept>

#include "io/h5md.hpp"

namespace gdsmc::io::units {

const std::vector<Symbol>& symbols() {
  static const std::vector<Symbol> list = {
      {"length", "the unit of length of the input namelist (&system diameter)"},
      {"mass", "the unit of mass of the input namelist (&system mass)"},
      {"energy", "the unit of energy of the input namelist; temperatures are energies, k_B = 1 "
                 "(&initial temperature)"},
      {"time", "the unit of time of the input namelist (&dsmc t_end), length (mass/energy)^(1/2)"},
  };
  return list;
}

std::string of_observable(const std::string& name) {
  // Every observable of run/simulation.cpp (plain, staged and &agg_frag runs) and every quantity
  // of /sweep/results (analysis/sweep_table.hpp).
  static const std::map<std::string, std::string> table = {
      // the sample times themselves (the observable `time`)
      {"time", kTime},
      // energies and temperatures
      {"temperature", kEnergy},
      {"total_temperature", kEnergy},
      {"kinetic_energy", kEnergy},     // per initial monomer (&agg_frag)
      {"dissipated_energy", kEnergy},  // per initial monomer (&agg_frag)
      // pressure (energy per volume) and viscosity (pressure times time), &thermostat and &shear
      {"pressure_tensor", "energy length-3"},
      {"pressure_tensor_kinetic", "energy length-3"},
      {"pressure_tensor_collisional", "energy length-3"},
      {"shear_viscosity_raw", "energy length-3 time"},
      // mean squared displacement
      {"msd", "length+2"},
      // dimensionless: counts, ratios, cumulants, reduced quantities
      {"sonine_c", kDimensionless},
      {"number", kDimensionless},
      {"collisions", kDimensionless},
      {"collisions_pair", kDimensionless},
      {"collisions_per_particle", kDimensionless},
      {"acceptance_overshoots", kDimensionless},
      {"velocity_histogram", kDimensionless},  // a pdf of v/sqrt(T_k/m_k)
      {"mean_size", kDimensionless},
      {"monomer_fraction", kDimensionless},
      {"aggregations", kDimensionless},
      {"fragmentations", kDimensionless},
      {"thermostat_zeta_dt", kDimensionless},
      {"shear_viscosity", kDimensionless},  // eta/eta_0
      {"shear_viscosity_kinetic", kDimensionless},
      {"reduced_shear_rate", kDimensionless},
      {"temperature_over_mean", kDimensionless},
      {"cooling_rate_reduced", kDimensionless},
  };
  const auto it = table.find(name);
  if (it == table.end()) throw std::out_of_range("io::units: no unit for the observable '" + name + "'");
  return it->second;
}

void declare(h5md::Writer& writer) {
  writer.declare_units_module(kSystem);
  std::vector<std::string> names, definitions;
  for (const Symbol& s : symbols()) {
    names.push_back(s.name);
    definitions.push_back(s.definition);
  }
  writer.write_attribute("/h5md/modules/units", "symbols", names);
  writer.write_attribute("/h5md/modules/units", "definitions", definitions);
}

}  // namespace gdsmc::io::units
