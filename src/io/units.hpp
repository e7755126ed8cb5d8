/**
 * \file units.hpp
 * \brief The units of the output file: H5MD's units module with the unit system "namelist"
 *        (\ref output_units "docs/output.md").
 *
 * granular-dsmc computes in the units of its input: any consistent set, with temperatures as
 * energies (k_B = 1; \ref cm_notation "docs/collision-model.md"). The unit system "namelist" names
 * these units by four symbols:
 * - `length`: the unit in which the namelist gives lengths (`&system diameter`);
 * - `mass`: the unit of `&system mass`;
 * - `energy`: the unit of energies and temperatures (`&initial temperature`, k_B = 1);
 * - `time`: the unit of time that follows from them, `length` (`mass`/`energy`)^(1/2), in which the
 *   namelist gives times (`&dsmc t_end`, `&shear average_from`).
 * The fourth symbol is not independent: the units module allows integer powers only, and the unit
 * of time is a half-integer power of mass and energy. A dimensionless quantity (a count, a ratio,
 * a cumulant, a reduced variable) has the unit "1".
 */
#pragma once

#include <string>
#include <vector>

namespace gdsmc::io::h5md {
class Writer;
}

namespace gdsmc::io::units {

/// `/h5md/modules/units@system`: the units of the input namelist.
inline constexpr const char* kSystem = "namelist";
/// Unit of `time` datasets and of every time (the namelist's unit of time).
inline constexpr const char* kTime = "time";
/// Unit of energies and temperatures (k_B = 1).
inline constexpr const char* kEnergy = "energy";
/// Unit of a dimensionless quantity.
inline constexpr const char* kDimensionless = "1";

/// One symbol of the unit system "namelist".
struct Symbol {
  std::string name;        ///< the symbol as it appears in unit strings, e.g. "length"
  std::string definition;  ///< what it stands for
};

/// The symbols of the unit system "namelist", in the order of `/h5md/modules/units@symbols`.
const std::vector<Symbol>& symbols();

/// The unit string of the observable `name` (the last component of its path, e.g. "temperature",
/// "msd", "species_1" of velocity_histogram; also the quantities of `/sweep/results`). Throws
/// std::out_of_range for a name it does not know: every observable written has a unit.
std::string of_observable(const std::string& name);

/// Declares the units module in `writer`'s file: `/h5md/modules/units` with `version`, `system` =
/// kSystem, and the attributes `symbols` and `definitions` (string arrays, one entry per symbol).
void declare(h5md::Writer& writer);

}  // namespace gdsmc::io::units
