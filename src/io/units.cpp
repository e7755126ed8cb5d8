// The units of the output file (io/units.hpp, \ref output_units "docs/output.md").
#include "io/units.hpp"

#include <map>
#include <stdexcept>

#include "io/h5md.hpp"
#include "model/observables.hpp"

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
  // Every observable has its unit in the table of observables (model/observables.hpp).
  return observables::find(name).unit;
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
