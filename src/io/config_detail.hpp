/**
 * \file config_detail.hpp
 * \brief Inside io::config, not its interface: the field tables and the steps that config.cpp
 * (reading), config_fields.cpp (the tables and what is written from them), config_checks.cpp (the
 * checks group by group) and config_sweep.cpp (&sweep) share.
 *
 * Reading a namelist is read_point(): every group through its table (read_group), then the checks
 * of config_checks.cpp in the order of the groups, then the run check, then every &sweep point read
 * and checked the same way (check_sweep). A new variable is one line of its group's table
 * (config_fields.cpp) and, if it depends on others, a few lines of its group's check; see
 * docs/extending.md, \ref ext_rule "adding a collision rule".
 */
#pragma once

#include <cstddef>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "io/config.hpp"
#include "io/namelist.hpp"
#include "model/species.hpp"

namespace gdsmc::io::config::detail {

using namelist::Error;
inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// Where a value may lie: [lo, hi] with optionally open ends; only for numbers.
struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;
  bool contains(double x) const {
    return (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  }
  std::string text() const {
    std::ostringstream s;
    s << (lo_open ? "(" : "[") << lo << ", " << hi << (hi_open ? ")" : "]");
    return s.str();
  }
};

/// One variable of a group: declared once, used by the reader, the checks and the writers.
template <class G>
struct Field {
  using Member = std::variant<long long G::*, double G::*, bool G::*, std::string G::*,
                              std::optional<double> G::*, std::vector<double> G::*,
                              std::vector<std::string> G::*, SweepValues G::*,
                              species::PairMatrix G::*, Scheme G::*, RestitutionModel G::*,
                              MassLaw G::*, DiameterLaw G::*, DensityLaw G::*,
                              VelocityDistribution G::*, Spacing G::*, ThermostatKind G::*>;
  std::string name;
  Member member;
  std::string units;
  std::string help;
  Range range{};
  bool required = false;
};

/// Whether T is one of the choices (the enums of config.hpp, read and written by name).
template <class T>
concept Choice = std::is_enum_v<T> && requires { Choices<T>::names; };

/// The names a field may take: its choices, or none for a field that is not a choice.
template <class G>
std::vector<std::string> choices(const Field<G>& field) {
  return std::visit(
      [](auto member) {
        using T = std::remove_cv_t<std::remove_reference_t<decltype(std::declval<G&>().*member)>>;
        std::vector<std::string> names;
        if constexpr (Choice<T>)
          for (const auto name : Choices<T>::names) names.emplace_back(name);
        return names;
      },
      field.member);
}

// The tables, one per group (config_fields.cpp). Defaults are the member initialisers in
// config.hpp, nowhere else.
const std::vector<Field<System>>& system_fields();
const std::vector<Field<Initial>>& initial_fields();
const std::vector<Field<Dsmc>>& dsmc_fields();
const std::vector<Field<Thermostat>>& thermostat_fields();
const std::vector<Field<Shear>>& shear_fields();
const std::vector<Field<Output>>& output_fields();
const std::vector<Field<AggFrag>>& agg_frag_fields();
const std::vector<Field<Sweep>>& sweep_fields();

/// `s` in lower case (namelist names and choices are case-insensitive).
std::string lower(std::string s);

/// Where each variable was last assigned, and the raw element assignments of pair matrices.
struct Provenance {
  std::string file;                             ///< the namelist file (for group-level errors)
  int group_line = 0;                           ///< line of '&group' (0 if absent)
  std::map<std::string, int> line;              ///< variable -> line of its last assignment
  std::map<std::string, std::string> set_in;    ///< variable -> file (or override) of that line
  /// Pair-matrix assignments in order, each with the file (or override) it came from.
  std::map<std::string, std::vector<std::pair<const namelist::Assignment*, std::string>>>
      pair_assignments;
  /// The file where `variable` was last set; the namelist file if it was not set.
  const std::string& file_of(const std::string& variable) const {
    const auto it = set_in.find(variable);
    return it == set_in.end() ? file : it->second;
  }
};

// What the tables answer about a variable by name (config_fields.cpp).
/// The group a variable belongs to, if it belongs to another one (for "did you mean" hints).
std::string owning_group(const std::string& name);
/// Whether `group:name` is a string variable.
bool is_string_variable(const std::string& group, const std::string& name);
/// Rank of variable `name` of `group`: 0 scalar, 1 list, 2 pair matrix; -1 unknown.
int variable_rank(const std::string& group, const std::string& name);

// The checks and derivations, group by group, in the order read_point() calls them
// (config_checks.cpp). Each throws namelist::Error naming file, line, group and variable.
void check_system(System& sys, const Provenance& prov);
void check_initial(Initial& ini, std::size_t s, const Provenance& prov);
void check_dsmc(const Dsmc& d, const species::Mixture& mix, const Provenance& prov, int group_line);
void check_output(Output& out, const Dsmc& d, const Provenance& prov);
void check_agg_frag(const Config& c, std::map<std::string, Provenance>& prov);
void check_rough(Config& c, std::map<std::string, Provenance>& prov);
/// Scales the code can compute with in the input's units (\ref output_units "docs/output.md"): mass, diameter,
/// number_density and temperature of every species, T_k/m_k and the collision frequency
/// n_k sigma_k^2 sqrt(T_k/m_k) within [1e-100, 1e100] (the fourth moments (T/m)^2 of the cumulants,
/// cooled by up to 1e-40, stay within double range); one line naming the variable otherwise.
void check_scales(const Config& c, std::map<std::string, Provenance>& prov);
/// restitution_model = 'viscoelastic': the series of restitution.hpp holds up to u_max = 0.8; an input
/// whose impacts at 7 thermal relative speeds sqrt(T_k/m_k + T_i/m_i) (about 1 in 1e11 collisions) of
/// any pair reach u > 0.8 is refused naming visco_a_kappa (\ref visco_cutoff "docs/viscoelastic.md").
void check_viscoelastic_range(const Config& c, std::map<std::string, Provenance>& prov);
void check_white_noise(Config& c, std::map<std::string, Provenance>& prov);
void check_staged(const Config& c, std::map<std::string, Provenance>& prov);
void check_snapshots(Config& c, std::map<std::string, Provenance>& prov);
/// The most snapshot data (bytes) a run may hold: the replicas keep them in memory until the end and
/// MPI gathers them in one message.
inline constexpr double kSnapshotBytes = 1e9;
/// The sample grid of &output up to `end` (a time or collisions per particle).
std::vector<double> spaced(const Output& out, double end);

// &sweep (config_sweep.cpp).
/// The override that sets sweep point `value` of `variable` ("group:name", or "group:name(i,j)").
std::string sweep_override(const std::string& variable, const std::string& value);
/// &sweep checked: every variable names one of another group, the values make points, and every
/// point reads and checks as a Config of its own.
void check_sweep(const Config& c, const Provenance& prov, const namelist::Document& document,
                 const std::vector<std::string>& overrides, const RunCheck& run_check);

/// One Config from the document and overrides (config.cpp); with expand_sweep, &sweep is read and
/// every point checked too.
Config read_point(const namelist::Document& document, const std::vector<std::string>& overrides,
                  bool expand_sweep, const RunCheck& run_check);

}  // namespace gdsmc::io::config::detail
