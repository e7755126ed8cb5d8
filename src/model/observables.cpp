// The table of observables (observables.hpp; the docs page \ref observables_page "observables" is generated from it).
#include "model/observables.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace gdsmc::observables {

namespace {

const char* kOutput = "docs/output.md#output_observables";
const char* kSonine = "docs/sonine.md#son_reduced_distributions";
const char* kShear = "docs/shear-viscosity.md#eta_measured";
const char* kAggFrag = "docs/agg-frag.md#af_observables";
const char* kRough = "docs/rough-spheres.md#rough_observables";
const char* kSnapshots = "docs/output.md#output_snapshots";

const char* reduction_name(Reduction r) {
  switch (r) {
    case Reduction::series: return "mean +- SE over replicas, per sample";
    case Reduction::per_replica: return "one value per replica; mean +- SE over replicas";
    case Reduction::ratio: return "ratio of the replicas' sums, delta-method SE";
    case Reduction::internal: return "a replica's working sum (not written itself)";
    case Reduction::particles: return "every replica's snapshots as they are, in /particles (not averaged)";
  }
  return "";
}

}  // namespace

const std::vector<Observable>& table() {
  using R = Reduction;
  static const std::vector<Observable> list = {
      // Every run
      {"time", "time", "1", "the time of the sample (collision-driven runs: the mean over the replicas of the time each reached it)", R::series, kOutput},
      {"temperature", "energy", "species (&agg_frag: sizes)",
       "partial temperatures T_k = m_k <|v-u|^2>/3, columns = species (&agg_frag: clusters of size k = column + 1, "
       "the ratio of the replica sums (2/3) sum E_k / sum N_k; 0 where no replica has such a cluster)",
       R::series, kOutput},
      {"total_temperature", "energy", "1", "T = sum_k n_k T_k / n (&agg_frag: per cluster, sum_k N_k T_k / N; docs/agg-frag.md)", R::series, kOutput},
      {"sonine_c", "1", "species", "c_k = 2[(3/5)<v^4>/<v^2>^2 - 1] (Montanero and Garzo 2002 eq 17; docs/sonine.md)", R::series, kOutput},
      {"number", "1", "species (&agg_frag: sizes)",
       "simulated particles of each species (&agg_frag: clusters of size k = column + 1, per replica)", R::series, kOutput},
      {"collisions", "1", "1", "cumulative binary collision events of a replica, all species pairs", R::series, kOutput},
      {"collisions_pair", "1", "S(S+1)/2 pairs", "cumulative events per species pair (k <= j, row-major upper triangle)", R::series, kOutput},
      {"collisions_per_particle", "1", "1", "2 x events / N: each event is a collision for two particles", R::series, kOutput},
      {"acceptance_overshoots", "1", "1",
       "candidates whose acceptance probability exceeded 1 (a bound that was not a majorant): 0 in a correct run", R::series, kOutput},
      {"velocity_histogram", "1", "species x bins",
       "pdf of velocity components in units of sqrt(T_k/m_k), per species", R::series, kOutput},
      {"msd", "length+2", "species",
       "<|R_k|^2> per species, displacement since start_time (Bodrova and Osinsky 2024 eq 15; docs/diffusion-msd.md)", R::series,
       "docs/diffusion-msd.md#dif_displacements"},
      {"msd_start", "time", "1", "each replica's start of the displacements (-1: never started): /observables/msd/start_time",
       R::per_replica, "docs/diffusion-msd.md#dif_displacements"},
      // Rough spheres (docs/rough-spheres.md): written when &system roughness makes them rough
      {"rotational_temperature", "energy", "species", "T_rot,k = I_k <|w|^2>/3, I_k = kappa_k m_k sigma_k^2/4 (temperature stays translational)",
       R::series, kRough},
      {"cumulant_a20", "1", "species", "a20 = (3/5)<c^4>/<c^2>^2 - 1 of the peculiar velocities c (= sonine_c/2)", R::series, kRough},
      {"cumulant_a02", "1", "species", "a02 = (3/5)<w^4>/<w^2>^2 - 1 of the angular velocities w", R::series, kRough},
      {"cumulant_a11", "1", "species", "a11 = <c^2 w^2>/(<c^2><w^2>) - 1", R::series, kRough},
      {"total_energy", "energy", "1", "sum_k x_k (m_k <c^2> + I_k <w^2>)/2, the energy per particle with rotation", R::series, kRough},
      // The scaling state and the reduced distributions (docs/sonine.md)
      {"scaling_sonine_c", "1", "species", "c_k of a replica averaged over its samples past scaling_start: /observables/scaling_state/sonine_c",
       R::per_replica, kOutput},
      {"scaling_temperature_share", "1", "species",
       "T_k/T of a replica averaged over its samples past scaling_start: /observables/scaling_state/temperature_over_mean", R::per_replica,
       kOutput},
      {"temperature_over_mean", "1", "species", "T_k/T of the scaling state (sweep tables, --compare)", R::per_replica, kOutput},
      {"reduced_distribution", "1", "species x bins", "Phi_i(v*) of a replica over its scaling-state samples: /observables/reduced_distribution",
       R::per_replica, kSonine},
      {"reduced_sonine_c", "1", "species", "c_i of a replica's scaling state (Delta_i of the reduced distribution)", R::per_replica, kSonine},
      {"reduced_temperature_share", "1", "species", "T_i/T of a replica's scaling state (lambda_i of the reduced distribution)", R::per_replica,
       kSonine},
      {"reduced_cooling_rate", "1", "1", "zeta* of a replica's scaling state (G_i of the reduced distribution)", R::per_replica, kSonine},
      {"cooling_rate_reduced", "1", "1", "zeta* of the scaling state (sweep tables, --compare)", R::per_replica, kSonine},
      // &thermostat and &shear (docs/shear-viscosity.md)
      {"pressure_tensor", "energy length-3", "6: xx yy zz xy xz yz",
       "P = P^k + P^c, columns xx, yy, zz, xy, xz, yz; sampled at a stage's start, the mean of the values before and after its "
       "streaming (thermostat.hpp); dilute gas: P^c = 0",
       R::series, kShear},
      {"pressure_tensor_kinetic", "energy length-3", "6: xx yy zz xy xz yz",
       "P^k = sum_i (m_i n_i/N_i) sum (V - u)(V - u) at the middle of the stage's streaming jump", R::series, kShear},
      {"pressure_tensor_collisional", "energy length-3", "6: xx yy zz xy xz yz",
       "P^c = sum m_ij sigma_ij (1 + alpha)(g.e) e e / (V dt) since the previous sample (the Enskog gas in shear flow; else 0)", R::series,
       kShear},
      {"thermostat_zeta_dt", "1", "1", "the Gaussian thermostat's zeta dt, the mean over the stages since the previous sample", R::series,
       "docs/shear-viscosity.md#eta_thermostat"},
      {"shear_viscosity_raw", "energy length-3 time", "1", "eta = -P_xy/a, P_xy at the middle of the streaming jump", R::series, kShear},
      {"reduced_shear_rate", "1", "1", "a* = a eta_0(T)/(n T)", R::series, kShear},
      {"shear_viscosity", "1", "1",
       "eta/eta_0(T) = -P_xy/(a eta_0) with P_xy at the middle of the streaming jump (thermostat.hpp), divided by 1 - (a* eta*)^2 "
       "(finite shear rate, docs/shear-viscosity.md)",
       R::series, kShear},
      {"shear_viscosity_kinetic", "1", "1", "the kinetic part of eta/eta_0 (Enskog gas), with the same correction", R::series, kShear},
      {"shear_viscosity_average", "1", "1",
       "a replica's time average of eta/eta_0 from &shear average_from on: the attribute time_average of /observables/shear_viscosity", R::per_replica, kShear},
      {"shear_viscosity_kinetic_average", "1", "1", "the same of the kinetic part: the attribute time_average_kinetic of /observables/shear_viscosity",
       R::per_replica, kShear},
      {"shear_state_average", "1", "5: reduced_shear_rate pxx pyy pzz pxy",
       "a replica's time average from &shear average_from on of a* and P_ij/(n T), T = tr P^k/(3 n), both at the middle "
       "of the streaming jump: /observables/shear_state/value (the steady shear flow, docs/shear-viscosity.md)",
       R::per_replica, kShear},
      // &agg_frag (docs/agg-frag.md)
      {"size_energy", "energy", "sizes", "kinetic energy about the mean flow of the clusters of each size (for temperature)", R::internal, kAggFrag},
      {"kinetic_energy", "energy", "1", "kinetic energy relative to the mean flow per initial monomer", R::series, kAggFrag},
      {"dissipated_energy", "energy", "1", "energy lost in collisions so far per initial monomer, added event by event", R::series, kAggFrag},
      {"mean_size", "1", "1", "N_0/N, monomers per cluster", R::series, kAggFrag},
      {"monomer_fraction", "1", "1", "N_1/N_0", R::series, kAggFrag},
      {"aggregations", "1", "1", "cumulative collisions that stuck", R::series, kAggFrag},
      {"fragmentations", "1", "1", "cumulative collisions that shattered", R::series, kAggFrag},
      // Particle snapshots (&output snapshot_times): rows of each replica, written to /particles (io/snapshot.hpp)
      {"snapshot_time", "time", "2: time events", "a replica's snapshot: its time and collision events", R::particles,
       kSnapshots},
      {"snapshot_species", "1", "particles", "the species of each particle, from 1 (once)", R::particles, kSnapshots},
      {"snapshot_velocity", "length time-1", "3 x particles", "every particle's velocity at a snapshot", R::particles,
       kSnapshots},
      {"snapshot_angular_velocity", "time-1", "3 x particles", "every particle's angular velocity at a snapshot (rough spheres)",
       R::particles, kSnapshots},
      {"snapshot_displacement", "length", "3 x particles",
       "every particle's displacement since the start of tracking at a snapshot (track_displacements)", R::particles,
       kSnapshots},
  };
  return list;
}

const Observable& find(std::string_view name) {
  for (const Observable& o : table())
    if (name == o.name) return o;
  throw std::out_of_range("observables: '" + std::string(name) + "' is not in the table of observables");
}

/// Text for a cell of a Markdown table read by Doxygen: no bar (the cell's end), no angle bracket (a tag).
static std::string cell(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += "&#124;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else out += c;
  }
  return out;
}

std::string markdown() {
  std::ostringstream s;
  s << "| name | unit | columns | definition | replicas | defined in |\n|---|---|---|---|---|---|\n";
  for (const Observable& o : table()) {
    const std::string_view anchor = o.anchor;
    const auto hash = anchor.find('#');  // the page and its anchor: a link to the section
    s << "| `" << o.name << "` | " << o.unit << " | " << cell(o.shape) << " | " << cell(o.description) << " | "
      << reduction_name(o.reduction) << " | \\ref " << anchor.substr(hash + 1) << " \"" << anchor.substr(0, hash)
      << "\" |\n";
  }
  return s.str();
}

void Accumulator::add(std::size_t replica, const std::vector<double>& row) {
  if (values.size() <= replica) values.resize(replica + 1);
  values[replica].insert(values[replica].end(), row.begin(), row.end());
}

std::vector<double> Accumulator::mean() const {
  std::vector<double> m(values.front().size(), 0.0);
  for (const auto& r : values)
    for (std::size_t i = 0; i < m.size(); ++i) m[i] += r[i];
  for (double& x : m) x /= static_cast<double>(values.size());
  return m;
}

std::vector<double> Accumulator::standard_error() const {
  const std::size_t n = values.size();
  if (n < 2) return {};
  const std::vector<double> m = mean();
  std::vector<double> var(m.size(), 0.0);
  for (const auto& r : values)
    for (std::size_t i = 0; i < m.size(); ++i) var[i] += (r[i] - m[i]) * (r[i] - m[i]);
  for (double& v : var) v = std::sqrt(v / static_cast<double>(n - 1) / static_cast<double>(n));
  return var;
}

}  // namespace gdsmc::observables
