/**
 * \file compare.hpp
 * \brief `granular-dsmc --compare`: the DSMC results of a finished run beside the theory for the same
 *        input, as a table on stdout, the group /comparison of the output file and (optionally) JSON.
 *
 * \section compare_what What is compared
 * The theory values are those of analysis::predict (analysis/predictions.hpp), i.e. exactly what
 * `granular-theory` prints for the namelist; the DSMC values are read back from the H5MD file the run
 * wrote (mean +- standard error over replicas, sample.hpp). Per run, or per sweep point:
 * - free cooling (no &thermostat, &shear, &agg_frag): `total_temperature` T(t) and `temperature`
 *   T_k(t) (Maxwellian ODEs, \ref haff_law "docs/haff-and-mixtures.md", \ref haff_mixture_odes "docs/haff-and-mixtures.md": Haff's law for one species), `collisions_per_particle`
 *   on the sample times (time-driven runs) or the sample `time` at the collision counts
 *   (collision-driven runs);
 * - the scaling state (samples past `&output scaling_start` collisions per particle, averaged), free
 *   cooling or Gaussian thermostat without shear (the HSS has the HCS ratios and c_k, \ref eta_thermostat "docs/shear-viscosity.md"):
 *   `temperature_over_mean` T_k/T (mixtures) and `sonine_c` c_k (first Sonine, any number of species,
 *   sonine_mixture.hpp; Montanero and Garzo 2002, App. A, \ref son_binary "docs/sonine.md"), `cooling_rate_reduced` (one or two species, the
 *   reduced_distribution attributes of the file);
 * - with &output track_displacements: `msd` <R_k^2>(t) (Bodrova and Osinsky 2024, eq. (17), \ref dif_msd "docs/diffusion-msd.md") and, for mixtures,
 *   `diffusion_coefficient_ratio` D_k/D_1 as the ratio of the MSD increments over the last decade of
 *   time (as validation/diffusion_ratio; eq 17 for the theory over the same interval);
 * - &agg_frag: `number` N_k(t) (cluster populations, the sizes theory tracks), `mean_size`,
 *   `total_temperature` (Smoluchowski equations, smoluchowski.hpp, \ref af_smoluchowski "docs/agg-frag.md");
 * - &shear with the Gaussian thermostat: `shear_viscosity` eta/eta_0, its time average from
 *   average_from, against the HSS first-Sonine value (viscosity.hpp; Montanero 2003, \ref eta_one_species "docs/shear-viscosity.md", \ref eta_thermostat "docs/shear-viscosity.md").
 * Anything else (e.g. tail exponents: the file holds no measured exponent) is listed in the notes,
 * and a run with no applicable theory gives a table that says so.
 *
 * \section compare_known Known error of each approximation (docs/physics.md "Comparison with theory")
 * An independent estimate of how far the approximation is from the exact kinetic theory, as an
 * absolute error of the theory value; NaN where none exists. With eps = (3/16) max(max_ij
 * |a2(alpha_ij)|, max_k |c_k|/2) (docs/physics.md "Known limits": the Maxwellian ODEs omit first-Sonine
 * rate corrections of that relative size; a2 of van Noije and Ernst, \ref haff_sonine "docs/haff-and-mixtures.md"; in a mixture the
 * first-Sonine c_k of sonine_mixture.hpp, c = 2 a2, are larger than any a2(alpha), as in
 * validation/polydisperse) and 15 % for first Sonine's own error (\ref son_one_species "docs/sonine.md":
 * the first-Sonine cumulant is 9-14 % high):
 * - T(t), T_k(t): 1.15 eps |ln(T(0)/T(t))| relative (the rate error integrated over ln T, as the
 *   polydisperse validation); T_k(t) of mixtures adds 1.15 |tau_k^M/tau_k^FS - 1| (the Maxwellian
 *   against the first-Sonine HCS ratios);
 * - collisions per particle and the sample times of collision-driven runs: 1.15 (|a2|/16 + eps/2
 *   |ln(T(0)/T(t))|) relative (collision frequency (1 - a2/16) along a temperature off by the above;
 *   validation/collision_rate);
 * - T_k/T, first Sonine: 0.2 % for two species (\ref son_one_species "docs/sonine.md": 0.1 % from exact DSMC at mu = 10), 0.4 %
 *   for more (\ref physics_compare "docs/physics.md": independent work puts the s-species theory within 0.1-0.4 % for a ternary);
 * - T_1/T_2 of a binary (`temperature_ratio`): the 0.2 % of T_1/T carried to the ratio through the
 *   constraint x_1 T_1/T + x_2 T_2/T = 1: 0.2 % (1 + x_1 tau_1/(x_2 tau_2)) relative;
 * - c_k, first Sonine: the larger of 15 % of c_k (\ref son_scaling "docs/sonine.md": first Sonine 9-14 % high) and
 *   the size of the second-Sonine correction, max over the pairs' alpha_ij of |c^(1) - c^(2)| of one
 *   species (Brilliantov and Poeschel 2006; \ref sonine_higher "theory/sonine.hpp", nonlinear K = 2 and 3),
 *   an absolute estimate that does not vanish where c_k changes sign (alpha near 0.7); constant
 *   restitution only (viscoelastic: 15 %); cooling_rate_reduced: 0.15 |zeta*_FS - zeta*_M|;
 * - shear viscosity, HSS first Sonine: one dilute species 1.6 % (alpha >= 0.75) to 2.8 % (alpha <= 0.6)
 *   (\ref eta_mixture "docs/shear-viscosity.md" and Chapman-Cowling, validation/shear_viscosity), dilute binary 1 % for alpha >= 0.85
 *   (\ref eta_stages "docs/shear-viscosity.md"); plus 0.33 % stage-splitting bias at the default stage_step;
 * - MSD, D_k/D_1 (eq 17: \ref dif_accuracy "docs/diffusion-msd.md" gives no general bound) and the Smoluchowski closure (exact only
 *   at t = 0, \ref af_outcome "docs/agg-frag.md"): none stated (NaN).
 *
 * \section compare_marks Marks
 * d = DSMC - theory, z = d/SE, SE the standard error over the R replicas. The statistical threshold
 * z_R is Student's t quantile of R - 1 degrees of freedom at the two-sided level of 3 normal standard
 * deviations (99.73 %): the SE of a few replicas is itself uncertain (z_4 = 9.22, z_8 = 4.53,
 * z_16 = 3.59, z_64 = 3.12, tending to 3). With fewer than kMinReplicas = 4 replicas no statistical mark
 * is given (the table says so). `stat`: |d| <= z_R SE (also |d| <= 1e-12 |theory|, round-off);
 * `approx`: beyond that but |d| <= z_R SE + known error (within the approximation's known error); `off`:
 * beyond both; `?`: beyond statistics and no known error is stated, or beyond the known error without a
 * usable SE (fewer than 4 replicas). (D-T)/T % divides by |theory|, so both difference columns have the
 * sign of D - T. A trajectory is shown at its last sample, with the count of samples of each mark; the
 * file and the JSON (`mark`) hold every sample.
 *
 * \section compare_layout Output
 * `/comparison/<quantity>` (sweeps: `/comparison/point_K/<quantity>`, K from 1) with float64 datasets
 * `value`, `error` (left out when the run has one replica), `theory`, `known_error` (left out when none
 * is stated; NaN for the entries without one of a dataset that has some), each with the quantity's
 * `unit` (io/units.hpp), shaped [columns] or
 * [samples][columns] (columns = species, or cluster sizes), attributes `approximation`,
 * `known_error_source`, `label`, `mark` (strings, row-major as `value`) and `time` (float64 [samples])
 * for a trajectory; `/comparison` (or `point_K`) attributes `notes`, `replicas` and
 * `statistical_threshold` (left out below 4 replicas). The JSON holds every entry (null where not
 * given) and `mark`, shaped as `value`.
 * Checked by tests/compare_test.cpp and tests/cli_test.cpp (CliCompare.*, CliDsmc.Compare*).
 */
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/config.hpp"
#include "io/h5md.hpp"
#include "analysis/predictions.hpp"

namespace gdsmc::analysis::compare {

/// |d| <= kStatisticalZ SE counts as within statistics for a normal SE (many replicas), the level of the
/// t quantile of statistical_threshold.
inline constexpr double kStatisticalZ = 3.0;
/// Fewer replicas give no statistical mark (\ref compare_marks).
inline constexpr std::size_t kMinReplicas = 4;
/// The table shows at most this many columns of a quantity (all are in the file and the JSON).
inline constexpr std::size_t kTableColumns = 8;
/// Relative differences below this are round-off.
inline constexpr double kRoundOff = 1e-12;

/// One compared quantity of one run or sweep point.
struct Quantity {
  std::string name;                ///< key under /comparison, e.g. "total_temperature"
  std::string label;               ///< symbol for the table, e.g. "T", "T_k/T"
  std::string approximation;       ///< "maxwellian", "first_sonine", "smoluchowski_maxwellian", ...
  std::string known_error_source;  ///< where the known error comes from, or "none stated"
  std::vector<double> time;        ///< sample times of a trajectory; empty: one value per column
  std::size_t columns = 1;         ///< species or cluster sizes
  // row-major [sample][column] or [column]:
  std::vector<double> value;        ///< DSMC mean over replicas
  std::vector<double> error;        ///< its standard error (NaN without replicas)
  std::vector<double> theory;       ///< the theory value
  std::vector<double> known_error;  ///< the approximation's known error (NaN: none stated)
  std::string at{};                ///< for one value per column: over what it is taken, e.g. "scaling state"
  std::size_t label_offset = 0;    ///< column c is labelled c + 1 + label_offset
  /// Rows of value: the sample times of a trajectory, else 1.
  std::size_t samples() const { return time.empty() ? 1 : time.size(); }
};

/// The comparison of one run, or of one sweep point.
struct Point {
  std::string label;  ///< "" or the sweep assignment, e.g. "system:restitution = 0.6"
  std::size_t replicas = 0;  ///< replicas behind the SE (0: not known, the normal threshold kStatisticalZ)
  std::vector<Quantity> quantities;  ///< the compared quantities
  std::vector<std::string> notes;  ///< what is not compared, and why
};

/// The comparison of a run: one Point, or one per sweep point.
struct Comparison {
  std::vector<Point> points;  ///< the run, or every sweep point in order
  bool sweep = false;         ///< the run is a sweep
  std::string sweep_variable; ///< the swept variables, as Sweep::names()
  std::vector<std::string> sweep_values{};  ///< as written in &sweep values
};

/// What a run measured, as read from its file: observables by name (relative to the point's
/// observables group) and the scalar attributes the comparison uses ("group@name").
struct Measured {
  std::map<std::string, io::h5md::ObservableData> observables;  ///< by name
  std::map<std::string, double> attributes;                 ///< "group@name" -> value
  std::map<std::string, std::vector<double>> arrays;        ///< "group/name" -> values (e.g. scaling_state)
  /// The observable `name` was read.
  bool has(const std::string& name) const { return observables.count(name) > 0; }
};

/// Reads the observables (and attributes) under `root` ("/observables" or
/// "/sweep/point_K/observables") of `file`. Throws std::runtime_error if the file cannot be read.
Measured read_measured(const std::string& file, const std::string& root);

/// zeta* = zeta/nu_M from two samples (T_a, T_b, their standard errors, t_b - t_a) of an HCS, where
/// dT/dt = -zeta* nu_unit T^(3/2): zeta* = 2 (T_b^(-1/2) - T_a^(-1/2))/(nu_unit (t_b - t_a)), nu_unit =
/// nu_M/sqrt(T) (\ref rough_sonine "docs/rough-spheres.md"). The error takes the two temperatures' errors as
/// independent (they are positively correlated, so it is overstated). {value, standard error}.
std::pair<double, double> hcs_zeta_star(double t_a, double error_a, double t_b, double error_b, double dt, double nu_unit);

/// Within statistics, within the approximation's known error, beyond both (\ref compare_marks).
enum class Mark { statistics, approximation, beyond, beyond_no_estimate };
/// `scale` (the theory value): a difference below kRoundOff |scale| is round-off (e.g. T(0)), never a
/// deviation. NaN standard error or known error: none available. `threshold`: statistical_threshold;
/// NaN: no statistical mark (the SE is not used).
Mark classify(double difference, double standard_error, double known_error, double scale = 0.0,
              double threshold = kStatisticalZ);
/// z_R of \ref compare_marks for `replicas` replicas: Student's t quantile of replicas - 1 degrees of
/// freedom at 1 - 0.00135 (GSL gsl_cdf_tdist_Pinv); NaN below kMinReplicas; kStatisticalZ for 0 (unknown).
double statistical_threshold(std::size_t replicas);
/// The Mark's short name in tables: "stat", "approx", "off" or "?".
const char* mark_name(Mark mark);

/// Mean and standard error of samples past `start` collisions per particle (the scaling state);
/// error = mean of the samples' errors (as if fully correlated: an upper bound of the SE over
/// replicas of the time averages). `count` = 0 when no sample qualifies.
struct Average {
  double value = 0.0;    ///< mean of the samples
  double error = 0.0;    ///< mean of their standard errors
  std::size_t count = 0; ///< samples averaged
};
/// The Average of the samples `value` (errors `error`) at `collisions_per_particle` >= `start`.
Average scaling_average(const std::vector<double>& value, const std::vector<double>& error,
                        const std::vector<double>& collisions_per_particle, double start);

/// The scaling state of a point's observables: per species T_k/T (the ratio of the replica means at
/// each sample, its error propagated) and c_k averaged over the samples past `from` collisions per
/// particle (scaling_average), or, with `replica_averages` and when the file has /scaling_state, each
/// replica's own average averaged over the replicas with the SE over the replicas (docs/output.md): the
/// one computation of --compare and the sweep tables. Empty when an observable is missing.
struct ScalingState {
  std::vector<double> ratio;           ///< T_k/T, per species
  std::vector<double> ratio_error;     ///< its error
  std::vector<double> cumulant;        ///< c_k, per species
  std::vector<double> cumulant_error;  ///< its error
  std::size_t samples = 0;                       ///< samples past `from`
  bool per_replica = false;                      ///< the values are /scaling_state's
};
/// The ScalingState of `measured` (above).
std::optional<ScalingState> scaling_state(const Measured& measured, double from, bool replica_averages);

/// eps = (3/16) max(max_ij |a2(alpha_ij)|, max_k |c_k|/2) with the first-Sonine c_k when known
/// (\ref compare_known).
double sonine_rate_error(const species::Mixture& mix, const std::vector<double>& sonine_c = {});
/// The size of the second-Sonine correction to the cumulant: max over the distinct alpha_ij < 1 (at most 16,
/// spread over their range) of |c^(1) - c^(2)| of one species, nonlinear K = 2 and 3 (\ref compare_known).
double cumulant_known_error(const species::Mixture& mix);
/// Known error of the first-Sonine HSS eta/eta_0 relative to the value, NaN where none is stated.
double shear_viscosity_known_error(const species::Mixture& mix);
/// Known error of Grad's steady shear flow at restitution alpha (\ref eta_usf_steady "docs/shear-viscosity.md"):
/// |Grad - the independent program| at the table's alpha = 0.9, 0.7, 0.5 (between two points the larger; 0 at
/// alpha = 1, where no steady state exists), NaN below 0.5; `which` 0: a*, 1-4: P_xx, P_yy, P_zz, P_xy over p.
double steady_shear_known_error(double alpha, std::size_t which);

/// The comparison of one point from its Config, its theory and its measurements (pure).
Point compare_point(const io::config::Config& point, const analysis::Predictions& theory, const Measured& measured);

/// The theory of one point, or why it could not be computed.
struct PointTheory {
  std::optional<analysis::Predictions> predictions;  ///< the theory, when it could be computed
  std::string error;                               ///< else the reason
};
/// analysis::predict for every point of `config` (sweep or not). It depends on the input only, so
/// granular-dsmc computes it in a thread of its own while the run goes on. When `stop` ends a point's
/// theory (analysis::predict), its error is theory::smoluchowski::Stopped's message and the later
/// points are not computed (the same error).
std::vector<PointTheory> predict_points(const io::config::Config& config, const theory::smoluchowski::Stop& stop = {});

/// Every point of `config` (sweep or not) against the file `file` written for it; `theory` from
/// predict_points (computed here when empty).
Comparison compare_file(const io::config::Config& config, const std::string& file, std::vector<PointTheory> theory = {});

/// One table row: a quantity's column at one sample (the last of a trajectory).
struct Row {
  std::string point;     ///< sweep point label ("" without a sweep)
  std::string name;      ///< Quantity::name
  std::string quantity;  ///< column label, e.g. "T_2/T"
  std::string at;        ///< Quantity::at
  double time = 0.0;     ///< sample time (the last of a trajectory)
  bool trajectory = false;   ///< the quantity is a trajectory (counts holds its samples per Mark)
  double value = 0.0;        ///< DSMC mean
  double error = 0.0;        ///< its standard error
  double theory = 0.0;       ///< the theory value
  double known_error = 0.0;  ///< the approximation's known error
  std::string approximation; ///< Quantity::approximation
  double z = 0.0;        ///< (DSMC - theory)/SE (NaN without SE)
  double percent = 0.0;  ///< 100 (DSMC - theory)/|theory| (NaN for |theory| <= kRoundOff max(|DSMC|, SE): 0 up to round-off)
  double threshold = kStatisticalZ;  ///< z_R of the point (NaN: no statistical mark)
  Mark mark = Mark::statistics;  ///< the classification of this row
  std::size_t counts[4] = {0, 0, 0, 0};  ///< samples of a trajectory per Mark
};
/// The table rows of a comparison: every column of every quantity, at its last sample.
std::vector<Row> rows(const Comparison& comparison);

/// The table for stdout (\ref compare_marks), notes included.
std::string table(const Comparison& comparison);
/// The same numbers as JSON (NaN as null).
std::string json(const Comparison& comparison);
/// Writes /comparison (\ref compare_layout) into an open output file.
void write(io::h5md::Writer& writer, const Comparison& comparison);

}  // namespace gdsmc::analysis::compare
