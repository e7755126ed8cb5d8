/**
 * \file config.hpp
 * \brief The validated input of a run: one parameter struct per namelist group, one table per group.
 *
 * Input goes through one fixed pipeline for every group, in the manner of Quantum ESPRESSO's
 * read_namelists but with each default written exactly once:
 *
 *   defaults (the member initialisers below) -> read (the group's field table assigns what the
 *   namelist gives, checking type, index and range of every value) -> check (cross-field rules,
 *   array lengths against n_species) -> derive (species laws, sample times) -> freeze (const Config).
 *
 * The field table of each group (name, type, shape, range or choices, units, help) is the only
 * place a variable is declared: it drives the reader, the checks, `--print-defaults`, the input
 * reference in docs/ and the resolved input written to `/parameters` of every output file.
 *
 * Groups (\ref input "input reference"): `&system` (required), `&initial`, `&dsmc` (required), `&output`,
 * `&agg_frag` (aggregation and fragmentation, dsmc/agg_frag.hpp), and
 * `&sweep` (variables, whole or array elements, over lists of values: jointly point by point or as a
 * grid; each point its own run and output group).
 * Every error is an io::namelist::Error: `FILE:LINE: &group: variable: message`.
 * Checked by tests/config_test.cpp.
 */
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <utility>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "model/species.hpp"
#include "io/h5md.hpp"
#include "io/namelist.hpp"

namespace gdsmc::io::config {

// The choices of the namelist's string variables: each is read from its name in the namelist
// (case-insensitive) and written back by name (name()); the names are Choices<E>::names, in the
// order of the enumerators.
/// &dsmc scheme (\ref schemes "docs/schemes.md").
enum class Scheme { majorant, pairs, lowrank };
/// &system restitution_model.
enum class RestitutionModel { constant, viscoelastic };
/// &system mass_law.
enum class MassLaw { list, linear };
/// &system diameter_law.
enum class DiameterLaw { list, cube_root };
/// &system density_law.
enum class DensityLaw { list, power };
/// &initial distribution.
enum class VelocityDistribution { maxwell, shell, cube };
/// &output spacing.
enum class Spacing { linear, log };
/// &thermostat kind.
enum class ThermostatKind { none, gaussian, white_noise };

/// The namelist names of the values of a choice E, in the order of its enumerators.
template <class E>
struct Choices;
/// \cond
template <> struct Choices<Scheme> { static constexpr std::array<std::string_view, 3> names{"majorant", "pairs", "lowrank"}; };
template <> struct Choices<RestitutionModel> { static constexpr std::array<std::string_view, 2> names{"constant", "viscoelastic"}; };
template <> struct Choices<MassLaw> { static constexpr std::array<std::string_view, 2> names{"list", "linear"}; };
template <> struct Choices<DiameterLaw> { static constexpr std::array<std::string_view, 2> names{"list", "cube_root"}; };
template <> struct Choices<DensityLaw> { static constexpr std::array<std::string_view, 2> names{"list", "power"}; };
template <> struct Choices<VelocityDistribution> { static constexpr std::array<std::string_view, 3> names{"maxwell", "shell", "cube"}; };
template <> struct Choices<Spacing> { static constexpr std::array<std::string_view, 2> names{"linear", "log"}; };
template <> struct Choices<ThermostatKind> { static constexpr std::array<std::string_view, 3> names{"none", "gaussian", "white_noise"}; };
/// \endcond

/// The namelist name of a choice: name(Scheme::pairs) = "pairs".
template <class E>
std::string name(E value) {
  return std::string(Choices<E>::names[static_cast<std::size_t>(value)]);
}

/// &system: the mixture (the "polydisperse system" of the DSMC notes, \ref haff_mixture_odes "docs/haff-and-mixtures.md"; Montanero and Garzo 2002, sec. 2, \ref son_binary "docs/sonine.md").
struct System {
  long long n_species = 1;            ///< S, the number of species
  std::vector<double> mass;            ///< m_k (required)
  std::vector<double> diameter;        ///< sigma_k (required)
  std::vector<double> number_density;  ///< n_k (required)
  species::PairMatrix restitution;     ///< alpha_kj (required with the constant model; one value fills all pairs)
  RestitutionModel restitution_model = RestitutionModel::constant;  ///< 'constant' (alpha_kj) or 'viscoelastic' (\ref visco_series "docs/viscoelastic.md")
  std::optional<double> visco_a_kappa;  ///< beta_11 = A kappa_11^(2/5) of the viscoelastic model
  bool enskog = false;                  ///< Carnahan-Starling chi_kj multiplies the rates (\ref cm_chi "docs/collision-model.md")
  MassLaw mass_law = MassLaw::list;                ///< 'list' or 'linear': m_k = k m_1
  DiameterLaw diameter_law = DiameterLaw::list;    ///< 'list' or 'cube_root': sigma_k = k^(1/3) sigma_1
  DensityLaw density_law = DensityLaw::list;       ///< 'list' or 'power': n_k = n_1 k^-theta
  double density_exponent = 0.0;        ///< theta of density_law = 'power'
  /// beta_kj, tangential restitution of rough spheres (\ref rough_rule "docs/rough-spheres.md"); unset:
  /// smooth spheres. Every beta_kj = -1 is the smooth gas (no rotation stored).
  species::PairMatrix roughness;
  std::vector<double> moment_of_inertia;  ///< kappa_k of rough spheres, one per species or one for all (unset: 0.4)
};

/// &initial: the state at t = 0.
struct Initial {
  std::vector<double> temperature{1.0};  ///< T_k(0); one value applies to every species
  VelocityDistribution distribution = VelocityDistribution::maxwell;  ///< initial velocities: 'maxwell', 'shell' (equal speeds) or 'cube'
  std::vector<double> rotational_temperature;  ///< T_rot,k(0) of rough spheres (unset: T_k(0)); one value applies to every species
  /// An output file whose last particle snapshot the run starts from (io/snapshot.hpp); temperature and
  /// rotational_temperature are then the snapshot's.
  std::string from_file;
};

/// &dsmc: the scheme and the size and length of the run.
struct Dsmc {
  Scheme scheme = Scheme::majorant;  ///< 'majorant', 'pairs' or 'lowrank' (\ref schemes "docs/schemes.md")
  long long n_particles = 20000;    ///< N, simulated particles, split in proportion to n_k
  std::optional<double> t_end;                   ///< exactly one of t_end and
  std::optional<double> collisions_per_particle; ///< collisions_per_particle (2 x events / N)
  long long replicas = 4;         ///< independent realisations, averaged (4: the fewest --compare marks)
  long long seed = 12345;         ///< seed of all random streams
  double step_fraction = 1.0;     ///< time step (bound refresh) in majorant mean free times
  long long block_size = 32768;  ///< cache blocks (collide.hpp "Blocks"); 0: none
  double stage_step = 0.125;     ///< with &thermostat or &shear: stage length in majorant mean free times
  static constexpr double white_noise_stage_step = 1.0;  ///< stage_step's default with the white noise
  bool allow_long_run = false;   ///< run even when the estimated work is beyond the caps (check_run_cost)
};

/// &output: where and when.
struct Output {
  std::string file = "run.h5";  ///< the H5MD output file
  std::string author;  ///< /h5md/author name (unset: author_name() finds one)
  long long n_samples = 100;        ///< sample times, t = 0 included
  Spacing spacing = Spacing::linear;   ///< 'linear' or 'log' spacing of the sample times
  std::optional<double> first_sample;  ///< log spacing: first sample after 0 (default end / 1000)
  long long histogram_bins = 50;   ///< bins of the velocity histograms
  double histogram_range = 5.0;    ///< the histograms cover [-range, range] in units of sqrt(T_k/m_k)
  long long reduced_bins = 100;   ///< bins of Phi_i(v*) (one or two species)
  double reduced_range = 5.0;     ///< Phi_i(v*) covers 0 <= v* < reduced_range
  double scaling_start = 10.0;    ///< collisions per particle after which the HCS is sampled
  std::optional<double> checkpoint_every;      ///< wall-clock seconds between checkpoints (unset: none)
  bool track_displacements = false;            ///< msd observable (Bodrova and Osinsky 2024, eq. (15), \ref dif_displacements "docs/diffusion-msd.md")
  std::optional<double> msd_start_time;        ///< displacements count from this time, or
  std::optional<double> msd_start_temperature; ///< from the first sample with T at or below this
  std::vector<double> sample_times;  ///< explicit sample points after 0 (time, or collisions per
                                     ///< particle in collision-driven runs); overrides n_samples/spacing
  std::vector<double> snapshot_times;  ///< every particle's velocity to /particles at these times (io/snapshot.hpp)
};

/// &agg_frag: clusters that stick and shatter (DSMC notes, eqs. (8)-(14), \ref af_outcome "docs/agg-frag.md"; dsmc/agg_frag.hpp).
/// The group's presence switches the model on (Config::has_agg_frag).
struct AggFrag {
  std::optional<double> aggregation_energy;    ///< E_agg: a pair with m_kj g^2/2 below it sticks
  std::optional<double> fragmentation_energy;  ///< E_frag: m_kj (g.e)^2/2 above it shatters (unset: never)
  std::optional<double> fragment_restitution;  ///< eps_f (required with fragmentation_energy)
};

/// &sweep values: given point by point (`values = ...`), or one list per variable (`values(1,v) = ...`).
struct SweepValues {
  std::vector<std::string> points;              ///< `values = ...`: namelist text, point after point
  std::vector<std::vector<std::string>> lists;  ///< `values(1,v) = ...`: the list of variable v (index v - 1)
  /// No values given.
  bool empty() const { return points.empty() && lists.empty(); }
};

/// &sweep: one or several variables over lists of values; every point is a run of its own (the
/// figures of Montanero and Garzo 2002 are curves against alpha, mu, ...). Absent or empty variable: no
/// sweep. (\ref output_sweeps "docs/output.md"; the points are checked when the namelist is read.)
struct Sweep {
  /// The swept variables as written, "group:name" or "group:name(i)" / "group:name(i,j)" for an
  /// element, e.g. 'system:restitution(1,2)'.
  std::vector<std::string> variable;
  /// Their values as namelist text (strings quoted); a quoted value of a non-string variable is
  /// inserted as text, so arrays sweep too: values = '0.01, 0.02', '0.02, 0.04'.
  SweepValues values;
  bool grid = false;  ///< every combination of the variables' lists (the last variable varies fastest)

  /// The points: row k = the value text of every variable at point k (checked input only).
  std::vector<std::vector<std::string>> table() const;
  /// The variables joined by ", " (one variable: its name), for attributes and messages.
  std::string names() const;
  /// A row of table() joined by ", " (one variable: the value as written).
  static std::string row_text(const std::vector<std::string>& row);
  /// "restitution(1,2) = 0.7, mass(2) = 2.0": a row's assignments, for labels.
  std::string row_label(const std::vector<std::string>& row) const;
};

/// &thermostat: a Gaussian thermostat holds the temperature of the homogeneous steady state (HSS)
/// against the inelastic loss (Montanero 2003, \ref eta_measured "docs/shear-viscosity.md"; dsmc/thermostat.hpp).
struct Thermostat {
  ThermostatKind kind = ThermostatKind::none;  ///< 'none', 'gaussian' or 'white_noise' (\ref wn_forcing "docs/white-noise.md")
  /// chi^2_k of the white noise, \<dv dv\> = chi^2_k dt per component: one value (species 1; the others by
  /// equal forces, chi^2_k = chi^2_1 (m_1/m_k)^2) or one per species; filled per species by the checks.
  std::vector<double> noise_strength;
};

/// &shear: uniform shear flow u_x = a y in the Lagrangian frame (Montanero 2003, \ref eta_enskog_shear "docs/shear-viscosity.md").
struct Shear {
  std::optional<double> rate;          ///< a (unset: no shear)
  std::optional<double> average_from;  ///< the viscosity's time average starts here (default t_end/2)
};

/// The H5MD author of the output: &output author, else $USER, else the login name of the user id, else "unknown" (docs/output.md "The H5MD file").
std::string author_name(const Output& output);

/// A checked input: the namelist groups, where each value came from, and what follows from them.
struct Config {
  System system;        ///< &system
  Initial initial;      ///< &initial
  Dsmc dsmc;            ///< &dsmc
  Output output;        ///< &output
  AggFrag agg_frag;     ///< &agg_frag (used when has_agg_frag)
  bool has_agg_frag = false;             ///< the namelist has an &agg_frag group
  Thermostat thermostat;  ///< &thermostat
  Shear shear;            ///< &shear
  /// A thermostat or a shear rate: the run advances in stages (streaming, collisions, thermostat).
  bool staged() const { return thermostat.kind != ThermostatKind::none || shear.rate.has_value(); }
  Sweep sweep;                           ///< &sweep
  std::string source_file;               ///< name of the namelist file
  std::string namelist_text;             ///< its text, verbatim
  std::vector<std::string> overrides;    ///< `--set group:variable=value`, in order
  /// Where each variable was last set: "group:variable" -> (file, line), for later error messages.
  std::map<std::string, std::pair<std::string, int>> origin;

  /// The mixture of &system with its pair data.
  species::Mixture mixture() const;
  /// Rough spheres: roughness given and some beta_kj != -1 (\ref rough_rule "docs/rough-spheres.md"); the
  /// mixture then carries beta_kj and kappa_k, and the particles an angular velocity.
  bool rough() const;
  /// beta_ki of the viscoelastic restitution (\ref visco_one_material "docs/viscoelastic.md"), empty when the model is constant.
  std::optional<species::PairMatrix> viscoelastic_beta() const;
  /// Sample times, including t = 0, when the run is time-driven (empty otherwise).
  std::vector<double> sample_times() const;
  /// Sample points in collisions per particle, including 0, when the run is collision-driven.
  std::vector<double> sample_collisions() const;
  /// The Config of every sweep point (this one's overrides plus `variable=value`), or just this
  /// Config when there is no sweep. Each was checked when the namelist was read. A point has no
  /// &sweep and no namelist_text (the text is this Config's): a long list of values stays linear.
  std::vector<Config> sweep_points() const;
  /// The namelist sweeps at least one variable over at least one value.
  bool is_sweep() const { return !sweep.variable.empty() && !sweep.values.empty(); }
  /// Every variable of every group, defaults included, for /parameters.
  std::vector<h5md::Parameter> resolved() const;
};

/// A check of a read Config that needs more than the input, given by the caller: the programs pass
/// analysis::check_run_cost (the run's work estimated by kinetic theory, which this layer does not
/// know). It runs where the reader's own checks end, on the Config and on every sweep point; it
/// throws namelist::Error, which the reader reports as its own (a sweep point's with the point).
using RunCheck = std::function<void(const Config&)>;

/// Reads, checks and derives a Config from a parsed namelist plus command-line overrides
/// (each `group:variable=value`, Fortran syntax for the value), then `run_check`. Throws namelist::Error.
Config read(const namelist::Document& document, const std::vector<std::string>& overrides = {},
            const RunCheck& run_check = {});
/// Parses and reads a namelist file.
Config read_file(const std::string& path, const std::vector<std::string>& overrides = {},
                 const RunCheck& run_check = {});
/// Rebuilds the Config of an output file from its stored namelist text and overrides.
Config read_from_output(const std::string& h5_path);

/// A commented namelist with every variable, its default, units and help (`--print-defaults`).
std::string defaults_template();
/// The input reference as Markdown tables (the page \ref input "input reference" is generated from it).
std::string reference_markdown();

}  // namespace gdsmc::io::config
