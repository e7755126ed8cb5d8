#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "io/config.hpp"
#include "io/config_detail.hpp"

namespace gdsmc::io::config {
namespace detail {

namespace {
const Range kPositive{0.0, kInf, true, false};
const Range kUnit{0.0, 1.0, false, false};
Range at_least(double lo) { return Range{lo, kInf, false, false}; }
}  // namespace

const std::vector<Field<System>>& system_fields() {
  static const std::vector<Field<System>> fields = {
      {"n_species", &System::n_species, "", "number of species S", Range{1, 1e7}},
      {"mass", &System::mass, "mass", "m_k, one per species (or species 1 with mass_law)",
       kPositive, true},
      {"diameter", &System::diameter, "length",
       "sigma_k, one per species (or species 1 with diameter_law)", kPositive, true},
      {"number_density", &System::number_density, "1/length^3",
       "n_k, one per species (or species 1 with density_law)", kPositive, true},
      {"restitution", &System::restitution, "",
       "alpha_kj: one value for all pairs, or restitution(i,j) = ... (symmetric; required when constant)",
       kUnit, true},
      {"restitution_model", &System::restitution_model, "",
       "'constant' (alpha_kj), or 'viscoelastic' (alpha from the impact speed, Bodrova and Osinsky 2024, eqs. (5)-(8), docs/viscoelastic.md)"},
      {"visco_a_kappa", &System::visco_a_kappa, "velocity^(-1/5)",
       "beta_11 = A kappa_11^(2/5) of the viscoelastic model; other pairs by the one-material scaling "
       "of docs/viscoelastic.md", at_least(0)},
      {"enskog", &System::enskog, "",
       ".true.: Carnahan-Starling chi_ij multiplies the collision rates (Montanero and Garzo 2002, eq. (26), docs/collision-model.md)"},
      {"mass_law", &System::mass_law, "", "'list', or 'linear': m_k = k m_1"},
      {"diameter_law", &System::diameter_law, "", "'list', or 'cube_root': sigma_k = k^(1/3) sigma_1"},
      {"density_law", &System::density_law, "", "'list', or 'power': n_k = n_1 k^-theta"},
      {"density_exponent", &System::density_exponent, "", "theta of density_law = 'power'"},
      {"roughness", &System::roughness, "",
       "beta_kj, tangential restitution of rough spheres: -1 smooth (the default), +1 perfectly rough; one "
       "value for all pairs, or roughness(i,j) = ... (symmetric; docs/rough-spheres.md)",
       Range{-1, 1, false, false}},
      {"moment_of_inertia", &System::moment_of_inertia, "",
       "kappa_k = 4 I_k/(m_k sigma_k^2) of rough spheres, one per species or one for all (default 0.4, a "
       "uniform sphere)",
       Range{1e-10, 2.0 / 3.0}},  // (below: I_k so small that the spin's moments overflow and its cost has no bound)
  };
  return fields;
}

const std::vector<Field<Initial>>& initial_fields() {
  static const std::vector<Field<Initial>> fields = {
      {"temperature", &Initial::temperature, "energy",
       "T_k(0), one per species or one for all (k_B = 1)", kPositive},
      {"distribution", &Initial::distribution, "",
       "initial velocities: 'maxwell', 'shell' (equal speeds) or 'cube' (uniform in a cube)"},
      {"rotational_temperature", &Initial::rotational_temperature, "energy",
       "T_rot,k(0) = I_k <w^2>/3 of rough spheres (Maxwellian angular velocities), one per species or one "
       "for all (default: temperature; 0: no rotation)",
       Range{0, kInf, false, false}},
      {"from_file", &Initial::from_file, "",
       "start from the last particle snapshot (&output snapshot_times) of this output file instead of drawn "
       "velocities; replica r takes the file's replica r (cyclically); the species counts must match"},
  };
  return fields;
}

const std::vector<Field<Dsmc>>& dsmc_fields() {
  static const std::vector<Field<Dsmc>> fields = {
      {"scheme", &Dsmc::scheme, "",
       "'majorant' (DSMC notes, docs/schemes.md), 'pairs' (Montanero and Garzo 2002) or 'lowrank' (Bodrova and Osinsky 2024, docs/schemes.md); "
       "&agg_frag: 'lowrank' when not given"},
      {"n_particles", &Dsmc::n_particles, "", "simulated particles, split in proportion to n_k",
       Range{2, 2e9}},
      {"t_end", &Dsmc::t_end, "time", "end of the run (or give collisions_per_particle)",
       kPositive},
      {"collisions_per_particle", &Dsmc::collisions_per_particle, "",
       "end of the run in collisions per particle, 2 x events / N (or give t_end)", kPositive},
      {"replicas", &Dsmc::replicas, "", "independent realisations, averaged (standard errors over them; --compare marks need >= 4)", Range{1, 1e6}},
      {"seed", &Dsmc::seed, "", "seed of all random streams", at_least(0)},
      {"step_fraction", &Dsmc::step_fraction, "",
       "time step (bound refresh) in units of the majorant mean free time", Range{0, 100, true}},
      {"block_size", &Dsmc::block_size, "",
       "particles per cache block (majorant or lowrank up to 256 species; lowrank beyond, in blocks of at "
       "least 8 S particles while there are 16 or more, of S to 2S when species x blocks would exceed N; "
       "N >= 2 block_size; with "
       "&agg_frag, clusters per block while N >= 2 block_size); at least 64, or 0: none",
       Range{0, 2e9}},
      {"stage_step", &Dsmc::stage_step, "",
       "with &thermostat or &shear: length of one streaming/collision/thermostat stage in majorant mean free "
       "times (also at most 0.01/a); default 1 with kind = 'white_noise'",
       Range{0, 1, true}},
      {"allow_long_run", &Dsmc::allow_long_run, "",
       ".true.: run even when kinetic theory estimates more than 1e12 collision events per replica, or a "
       "cooling below 1e-40 of the initial temperature (such runs are refused by default)"},
  };
  return fields;
}

const std::vector<Field<Thermostat>>& thermostat_fields() {
  static const std::vector<Field<Thermostat>> fields = {
      {"kind", &Thermostat::kind, "",
       "'none', 'gaussian': rescale the velocities after each collision stage so that the inelastic loss "
       "is restored (homogeneous steady state, docs/shear-viscosity.md), or 'white_noise': random Gaussian "
       "kicks at each stage (docs/white-noise.md)"},
      {"noise_strength", &Thermostat::noise_strength, "velocity^2/time",
       "chi^2 of kind = 'white_noise': <dv dv> = chi^2 dt per component; one value (species 1, the others by "
       "equal forces chi^2_k = chi^2_1 (m_1/m_k)^2) or one per species",
       kPositive},
  };
  return fields;
}

const std::vector<Field<Shear>>& shear_fields() {
  static const std::vector<Field<Shear>> fields = {
      {"rate", &Shear::rate, "1/time",
       "a of the uniform shear flow u_x = a y (Lagrangian frame; V_x -> V_x - a V_y dt each stage)", at_least(0)},
      {"average_from", &Shear::average_from, "time",
       "the shear viscosity is averaged over the samples from this time on (default: t_end/2)", at_least(0)},
  };
  return fields;
}

const std::vector<Field<Output>>& output_fields() {
  static const std::vector<Field<Output>> fields = {
      {"file", &Output::file, "", "HDF5 (H5MD) output file"},
      {"author", &Output::author, "", "name in /h5md/author of the output file (default: $USER, else the login name)"},
      {"n_samples", &Output::n_samples, "",
       "sample times, t = 0 included (at most 1e5: every sample keeps every observable of every replica in memory)",
       Range{2, 1e5}},
      {"spacing", &Output::spacing, "", "'linear' or 'log' spacing of the sample times"},
      {"first_sample", &Output::first_sample, "time (or collisions per particle)",
       "first sample after 0 with spacing = 'log' (default: end / 1000)",
       Range{1e-100, 1e100}},  // (as the unit checks: log spacing from a subnormal first sample never ends)
      {"histogram_bins", &Output::histogram_bins, "", "bins of the velocity histograms",
       Range{1, 1e5}},
      {"reduced_bins", &Output::reduced_bins, "",
       "bins of the reduced speed distributions Phi_i(v*) (Montanero and Garzo 2002, eq. (22), docs/sonine.md; one or two species)",
       Range{1, 1e5}},
      {"reduced_range", &Output::reduced_range, "v0", "Phi_i(v*) covers 0 <= v* < range", kPositive},
      {"scaling_start", &Output::scaling_start, "collisions per particle",
       "Phi_i, Delta_i, G_i are accumulated over the samples from here on (the HCS after its transient)",
       at_least(0)},
      {"checkpoint_every", &Output::checkpoint_every, "s (wall clock)",
       "write the full state to <file stem>.checkpoint.h5 this often; resume with --restart (unset: never)",
       kPositive},
      {"track_displacements", &Output::track_displacements, "",
       ".true.: track every particle's displacement and write the observable msd (Bodrova and Osinsky 2024, eq. (15), docs/diffusion-msd.md)"},
      {"msd_start_time", &Output::msd_start_time, "time",
       "displacements are measured from this time (default: from t = 0)", at_least(0)},
      {"msd_start_temperature", &Output::msd_start_temperature, "energy",
       "... or from the first sample at which the total temperature is at or below this value", kPositive},
      {"histogram_range", &Output::histogram_range, "sqrt(T_k/m_k)",
       "velocity histograms cover [-range, range] in thermal units",
       Range{0, 1e6, true, false}},  // (beyond: bin edges overflow to infinity)
      {"sample_times", &Output::sample_times, "time (or collisions per particle)",
       "explicit sample points after 0, increasing; overrides n_samples and spacing (t = 0 is always "
       "sampled, and the end of the run too)",
       kPositive},
      {"snapshot_times", &Output::snapshot_times, "time",
       "times at which every particle's velocity (angular velocity, displacement) is written to /particles "
       "(H5MD), increasing, from 0 to t_end; runs with t_end only",
       Range{0, kInf, false, false}},
  };
  return fields;
}

const std::vector<Field<AggFrag>>& agg_frag_fields() {
  static const std::vector<Field<AggFrag>> fields = {
      {"aggregation_energy", &AggFrag::aggregation_energy, "energy",
       "E_agg: a colliding pair whose impact energy m_kj g^2/2 is below it sticks (docs/agg-frag.md)",
       at_least(0)},
      {"fragmentation_energy", &AggFrag::fragmentation_energy, "energy",
       "E_frag: a pair (not two monomers) whose normal energy m_kj (g.e)^2/2 is above it shatters into "
       "monomers (unset: never)",
       at_least(0)},
      {"fragment_restitution", &AggFrag::fragment_restitution, "",
       "eps_f: the fragments carry eps_f^2 of the impact energy in the centre-of-mass frame (required with "
       "fragmentation_energy)",
       kUnit},
  };
  return fields;
}

const std::vector<Field<Sweep>>& sweep_fields() {
  static const std::vector<Field<Sweep>> fields = {
      {"variable", &Sweep::variable, "",
       "the swept variables as 'group:name' or an element 'group:name(i)', 'group:name(i,j)', e.g. "
       "'system:restitution(1,2)', 'system:mass(2)' (no sweep when unset)"},
      {"values", &Sweep::values, "",
       "their values point by point (one run and one output group per point), or one list per variable: "
       "values(1,v) = ..."},
      {"grid", &Sweep::grid, "",
       ".true.: every combination of the variables' lists (values(1,v) = ...), the last variable fastest"},
  };
  return fields;
}

std::string owning_group(const std::string& name) {
  auto has = [&](const auto& fields) {
    return std::any_of(fields.begin(), fields.end(), [&](const auto& f) { return f.name == name; });
  };
  if (has(system_fields())) return "system";
  if (has(initial_fields())) return "initial";
  if (has(dsmc_fields())) return "dsmc";
  if (has(output_fields())) return "output";
  if (has(agg_frag_fields())) return "agg_frag";
  if (has(thermostat_fields())) return "thermostat";
  if (has(shear_fields())) return "shear";
  if (has(sweep_fields())) return "sweep";
  return "";
}

namespace {
/// Whether `group:name` is a string variable (a quoted sweep value of any other variable is
/// inserted without its quotes, so that an array can be swept: values = '0.01, 0.02', ...).
template <class G>
bool is_string_field(const std::vector<Field<G>>& fields, const std::string& name) {
  for (const auto& f : fields)
    if (f.name == name)
      return std::holds_alternative<std::string G::*>(f.member) || !choices(f).empty();
  return false;
}

}  // namespace

bool is_string_variable(const std::string& group, const std::string& name) {
  if (group == "system") return is_string_field(system_fields(), name);
  if (group == "initial") return is_string_field(initial_fields(), name);
  if (group == "dsmc") return is_string_field(dsmc_fields(), name);
  if (group == "output") return is_string_field(output_fields(), name);
  if (group == "agg_frag") return is_string_field(agg_frag_fields(), name);
  if (group == "thermostat") return is_string_field(thermostat_fields(), name);
  if (group == "shear") return is_string_field(shear_fields(), name);
  return false;
}

namespace {
/// Rank of variable `name` of `group`: 0 scalar, 1 list, 2 pair matrix; -1 unknown.
template <class G>
int field_rank(const std::vector<Field<G>>& fields, const std::string& name) {
  for (const auto& f : fields)
    if (f.name == name)
      return std::holds_alternative<std::vector<double> G::*>(f.member)   ? 1
             : std::holds_alternative<species::PairMatrix G::*>(f.member) ? 2
                                                                          : 0;
  return -1;
}

}  // namespace

int variable_rank(const std::string& group, const std::string& name) {
  if (group == "system") return field_rank(system_fields(), name);
  if (group == "initial") return field_rank(initial_fields(), name);
  if (group == "dsmc") return field_rank(dsmc_fields(), name);
  if (group == "output") return field_rank(output_fields(), name);
  if (group == "agg_frag") return field_rank(agg_frag_fields(), name);
  if (group == "thermostat") return field_rank(thermostat_fields(), name);
  if (group == "shear") return field_rank(shear_fields(), name);
  return -1;
}

namespace {
// ---------------------------------------------------------------------------------------------
// Writing: resolved values, template, reference
// ---------------------------------------------------------------------------------------------
template <class G>
void append_resolved(std::vector<h5md::Parameter>& out, const std::string& group, const G& target,
                     const std::vector<Field<G>>& fields) {
  for (const auto& f : fields)
    std::visit(
        [&](auto member) {
          using T = std::remove_cv_t<std::remove_reference_t<decltype(target.*member)>>;
          const auto& v = target.*member;
          if constexpr (std::is_same_v<T, std::optional<double>>) {
            if (v) out.push_back({group, f.name, *v});
          } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
            // &sweep variable: one name is a string attribute, as before several could be swept.
            if (v.size() == 1) out.push_back({group, f.name, v.front()});
            else out.push_back({group, f.name, v});
          } else if constexpr (std::is_same_v<T, SweepValues>) {
            // The points run, point after point (also for lists and grids): the value texts.
            if constexpr (std::is_same_v<G, Sweep>) {
              std::vector<std::string> flat;
              const auto table = target.table();
              for (const auto& row : table) flat.insert(flat.end(), row.begin(), row.end());
              // One variable: a list of the points' values; several: a (points, variables) table.
              const std::size_t variables = table.empty() ? 0 : table.front().size();
              if (variables > 1) out.push_back({group, f.name, flat, {table.size(), variables}});
              else out.push_back({group, f.name, flat});
            }
          } else if constexpr (Choice<T>) {
            out.push_back({group, f.name, name(v)});
          } else if constexpr (std::is_same_v<T, species::PairMatrix>) {
            // An (S, S) matrix from two species on; one species, or a uniform matrix of very many species
            // (not stored densely), as its one value (1-D, as before the matrices had their shape).
            if (!v.is_dense()) out.push_back({group, f.name, std::vector<double>{v(0, 0)}});
            else if (v.size > 1) out.push_back({group, f.name, v.values, {v.size, v.size}});
            else out.push_back({group, f.name, v.values});  // one species (or none set: roughness of a smooth gas)
          } else {
            out.push_back({group, f.name, v});
          }
        },
        f.member);
}

template <class G>
std::string default_text(const G& defaults, const Field<G>& f) {
  std::ostringstream s;
  s.precision(10);
  std::visit(
      [&](auto member) {
        using T = std::remove_cv_t<std::remove_reference_t<decltype(defaults.*member)>>;
        const auto& v = defaults.*member;
        if constexpr (std::is_same_v<T, long long> || std::is_same_v<T, double>) s << v;
        else if constexpr (std::is_same_v<T, bool>) s << (v ? ".true." : ".false.");
        else if constexpr (std::is_same_v<T, std::string>) {
          if (!v.empty()) s << "'" << v << "'";  // empty: unset, shown commented out
        }
        else if constexpr (Choice<T>) s << "'" << name(v) << "'";
        else if constexpr (std::is_same_v<T, std::vector<double>> ||
                           std::is_same_v<T, std::vector<std::string>>) {
          for (std::size_t i = 0; i < v.size(); ++i) s << (i ? ", " : "") << v[i];
        }
      },
      f.member);
  return s.str();
}

/// One group of the template: every field with its default; a field without one commented out with an
/// example value, except those in `set`, which the template sets so that it runs as printed.
template <class G>
void template_group(std::ostringstream& s, const std::string& group, const std::vector<Field<G>>& fields,
                    const std::map<std::string, std::string>& examples, const std::vector<std::string>& set = {}) {
  const G defaults{};
  s << "&" << group << "\n";
  for (const auto& f : fields) {
    std::string value = default_text(defaults, f);
    std::string prefix = "  ";
    std::string note;
    if (f.required) {
      value = examples.count(f.name) ? examples.at(f.name) : "...";
      // A help that already says when the variable is required (restitution: "required when
      // constant") is not followed by a second, unconditional "(required)".
      if (f.help.find("required") == std::string::npos) note = " (required)";
    } else if (value.empty() && std::find(set.begin(), set.end(), f.name) != set.end()) {
      value = examples.at(f.name);
      note = " (no default: set here so that this template runs as printed)";
    } else if (value.empty()) {
      prefix = "! ";
      value = examples.count(f.name) ? examples.at(f.name) : "...";
      note = " (not set by default)";
    }
    std::string line = prefix + f.name + " = " + value;
    if (line.size() < 36) line.resize(36, ' ');
    s << line << " ! " << f.help << (f.units.empty() ? "" : " [" + f.units + "]") << note << "\n";
  }
  s << "/\n\n";
}

template <class G>
void reference_group(std::ostringstream& s, const std::string& group, const std::vector<Field<G>>& fields) {
  const G defaults{};
  s << "### &" << group << "\n\n| variable | default | allowed | units | meaning |\n|---|---|---|---|---|\n";
  for (const auto& f : fields) {
    std::string allowed;
    if (const auto names = choices(f); !names.empty())
      for (const auto& c : names) allowed += (allowed.empty() ? "'" : ", '") + c + "'";
    else if (std::isfinite(f.range.lo) || std::isfinite(f.range.hi))
      allowed = f.range.text();
    std::string def = f.required ? "(required)" : default_text(defaults, f);
    if (def.empty()) def = "(unset)";
    s << "| `" << f.name << "` | " << def << " | " << allowed << " | " << f.units << " | " << f.help
      << " |\n";
  }
  s << "\n";
}
}  // namespace
}  // namespace detail

using namespace detail;  // the tables and steps of config_detail.hpp

std::vector<h5md::Parameter> Config::resolved() const {
  std::vector<h5md::Parameter> out;
  append_resolved(out, "system", system, system_fields());
  append_resolved(out, "initial", initial, initial_fields());
  if (system.roughness.size == 0)  // unset: the smooth gas, whose parameters are those of before
    std::erase_if(out, [](const h5md::Parameter& p) {
      return p.name == "roughness" || p.name == "moment_of_inertia" || p.name == "rotational_temperature";
    });
  append_resolved(out, "dsmc", dsmc, dsmc_fields());
  append_resolved(out, "output", output, output_fields());
  if (has_agg_frag) append_resolved(out, "agg_frag", agg_frag, agg_frag_fields());
  if (staged()) {
    append_resolved(out, "thermostat", thermostat, thermostat_fields());
    append_resolved(out, "shear", shear, shear_fields());
  }
  if (is_sweep()) append_resolved(out, "sweep", sweep, sweep_fields());
  std::erase_if(out, [](const h5md::Parameter& p) {  // unset (not white noise): not written
    return p.name == "noise_strength" && std::holds_alternative<std::vector<double>>(p.value) &&
           std::get<std::vector<double>>(p.value).empty();
  });
  return out;
}

std::string defaults_template() {
  std::ostringstream s;
  s << "! granular-dsmc input: every variable with its default (granular-dsmc --print-defaults).\n"
       "! Fortran namelist rules: case-insensitive names, '!' comments, 'a = 1.0, 2.0' arrays,\n"
       "! '3*1.0' repeats, .true./.false., quoted strings, a(2) = ... element assignment.\n\n";
  template_group(s, "system", system_fields(),
                 {{"mass", "1.0"}, {"diameter", "1.0"}, {"number_density", "0.01"}, {"restitution", "0.9"}});
  template_group(s, "initial", initial_fields(), {});
  template_group(s, "dsmc", dsmc_fields(), {{"t_end", "100.0"}, {"collisions_per_particle", "50.0"}},
                 {"collisions_per_particle"});
  template_group(s, "output", output_fields(), {{"first_sample", "0.1"}, {"sample_times", "1.0, 2.0, 5.0"}});
  s << "! Aggregation and fragmentation: uncomment the group to switch it on (one species = the monomer,\n"
       "! the scheme is then 'lowrank').\n";
  {
    std::ostringstream g;
    template_group(g, "agg_frag", agg_frag_fields(),
                   {{"aggregation_energy", "0.5"}, {"fragmentation_energy", "1.5"}, {"fragment_restitution", "0.5"}});
    std::istringstream lines(g.str());
    for (std::string line; std::getline(lines, line);)
      s << (line.empty() || line.rfind("!", 0) == 0 ? line : "! " + line) << "\n";
  }
  template_group(s, "thermostat", thermostat_fields(), {});
  template_group(s, "shear", shear_fields(), {{"rate", "0.05"}, {"average_from", "50.0"}});
  template_group(s, "sweep", sweep_fields(),
                 {{"variable", "'system:restitution'"}, {"values", "0.5, 0.7, 0.9"}});
  return s.str();
}

std::string reference_markdown() {
  std::ostringstream s;
  reference_group(s, "system", system_fields());
  reference_group(s, "initial", initial_fields());
  reference_group(s, "dsmc", dsmc_fields());
  reference_group(s, "output", output_fields());
  reference_group(s, "agg_frag", agg_frag_fields());
  reference_group(s, "thermostat", thermostat_fields());
  reference_group(s, "shear", shear_fields());
  reference_group(s, "sweep", sweep_fields());
  return s.str();
}

}  // namespace gdsmc::io::config
