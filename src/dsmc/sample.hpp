/**
 * \file sample.hpp
 * \brief What is measured at each sample point, and the mean and standard error over replicas.
 *
 * For each species k, with velocities relative to the mean flow u = sum m v / sum m (zero to
 * round-off, since collisions conserve momentum and the initial state has none):
 * - partial temperature T_k = m_k <|v - u|^2> / 3 (\ref output_observables "docs/output.md"),
 * - Sonine coefficient c_k = 2 [(3/5) <|v - u|^4> / <|v - u|^2>^2 - 1] (Montanero and Garzo 2002, eq. (17), \ref son_scaling "docs/sonine.md":
 *   twice the usual a2; zero for a Maxwellian),
 * - the velocity-component histogram of c = (v_alpha - u_alpha) / sqrt(T_k/m_k), all three
 *   components pooled, as a probability density (a standard normal for a Maxwellian),
 * - the simulated particle number N_k;
 * and the total temperature T = sum_k N_k T_k / N (= sum_k n_k T_k / n), the cumulative collision
 * events, in total and per species pair.
 *
 * Replica statistics: value = mean over R replicas, error = s / sqrt(R) with the unbiased sample
 * standard deviation s (only when R > 1). Checked by tests/sample_test.cpp.
 */
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "dsmc/particles.hpp"
#include "model/observables.hpp"
#include "model/species.hpp"

namespace gdsmc::sample {

/// One replica's measured rows: per observable (a name of model/observables.hpp), its column count and
/// its rows in sample order (one row for an observable of the whole replica, e.g. a time average).
struct Rows {
  std::map<std::string, std::pair<std::size_t, std::vector<double>>> rows;  ///< name -> (columns, rows)
  /// Appends one row of `columns` values to observable `name`.
  void add(const std::string& name, std::size_t columns, const std::vector<double>& row) {
    auto& entry = rows[name];
    entry.first = columns;
    entry.second.insert(entry.second.end(), row.begin(), row.end());
  }
};

/// Moments of one replica at one instant.
struct Moments {
  std::vector<double> temperature;  ///< T_k
  std::vector<double> sonine_c;     ///< c_k
  std::vector<double> number;       ///< N_k
  double total_temperature = 0.0;   ///< T
  double mean_flow[3] = {0.0, 0.0, 0.0};  ///< u = sum m v / sum m
};

/// The Moments of the particles `sys` of mixture `mix` now (velocities relative to the mean flow).
Moments measure(const species::Mixture& mix, const particles::System& sys);

/// Velocity-component histograms of (v - u)/sqrt(T_k/m_k), S x bins, each a probability density
/// over [-range, range]; `moments` gives T_k and u.
std::vector<double> velocity_histogram(const species::Mixture& mix, const particles::System& sys,
                                       const Moments& moments, std::size_t bins, double range);

/// Kinetic pressure tensor (Montanero 2003, \ref eta_pressure "docs/shear-viscosity.md"): P^k = sum_i (m_i n_i / N_i) sum_{k in i} (V - u)(V - u),
/// components xx, yy, zz, xy, xz, yz, with u = `moments.mean_flow`. Densities are the physical n_i.
std::array<double, 6> kinetic_pressure_tensor(const species::Mixture& mix, const particles::System& sys,
                                              const Moments& moments);

/// Mean-squared displacement of each species at time t >= every t_last (Bodrova and Osinsky 2024, eq. (15), \ref sch_displacements "docs/schemes.md"):
/// <|R + v (t - t_last)|^2>, the free flight since the last collision added without changing the state.
std::vector<double> mean_squared_displacement(const particles::System& sys, double t);

/// v0 = sqrt(2 T (m1 + m2)/(m1 m2)), the velocity unit of the reduced distributions of a binary
/// mixture (Montanero and Garzo 2002, sec. 2, \ref son_scaling "docs/sonine.md"); for one species m1 = m2 = m. 0 for more than two species.
double reduced_velocity_scale(const species::Mixture& mix, double total_temperature);

/// Adds the reduced speeds v* = |v - u|/v0 of each species to `counts` (S x bins over [0, range)).
void add_reduced_speeds(const species::Mixture& mix, const particles::System& sys,
                        const Moments& moments, double v0, std::size_t bins, double range,
                        std::vector<double>& counts);

/// Phi_i(v*) from speed counts gathered over `samples` sample points: the number density in
/// reduced velocity space, normalised to 1 (f_i(v) = n_i v0^-3 Phi_i(v/v0), Montanero and Garzo 2002, sec. 2, \ref son_scaling "docs/sonine.md"),
/// averaged over each spherical shell: counts / (samples N_i (4 pi/3)(e_{b+1}^3 - e_b^3)).
std::vector<double> reduced_distribution(const std::vector<double>& counts,
                                         const std::vector<double>& number, double samples,
                                         std::size_t bins, double range);

/// The Maxwellian (lambda/pi)^(3/2) exp(-lambda v*^2) averaged over the shell [a, b) (exact, with erf).
double maxwellian_shell_average(double lambda, double a, double b);

/// The HCS distributions of one point in reduced speed (Montanero and Garzo 2002, sec. 4, \ref son_reduced_distributions "docs/sonine.md"),
/// from the replicas' mean Phi_i(v*) and its standard error (S x bins, empty error: one replica), the
/// measured c_i, T_i/T and zeta*: per species the deviation Delta_i(v*) of eq 27 with lambda_i =
/// T/(T_i mu_ji), and G_i(v*) = exp(2 beta_i v*/zeta*) Phi_i of eq 30 with beta_i of eq 20 (\ref son_tails "docs/sonine.md").
/// Where the Maxwellian underflows to 0 Delta is undefined and given as 0 (never NaN); Phi itself,
/// always finite, is the quantity to read in the far tail.
/// The distributions of a point (above; model/observables.hpp ReducedDistributions).
observables::ReducedDistributions reduced_distributions(const species::Mixture& mix, const std::vector<double>& phi,
                                           const std::vector<double>& phi_error, const std::vector<double>& sonine_c,
                                           const std::vector<double>& temperature_share, double reduced_cooling_rate,
                                           std::size_t bins, double range);

/// T_k of &agg_frag clusters of size k = column + 1 at every sample from the replicas' rows of N_k
/// (`number`) and of the kinetic energy E_k (`energy`), R replicas, `samples` x `width` each: the ratio
/// estimator (2/3) sum_r E_kr / sum_r N_kr (a size most replicas lack has no per-replica temperature),
/// with the delta-method standard error (2/3) sqrt(sum_r (E_kr - rho N_kr)^2 / (R (R - 1))) / mean_r N_kr,
/// rho = sum E / sum N (\ref af_observables "docs/agg-frag.md"); 0 where no replica has such a cluster (never NaN). The
/// error is empty for one replica.
/// The temperatures of a point's clusters (above; model/observables.hpp ClusterTemperature).
observables::ClusterTemperature cluster_temperature(const std::vector<std::vector<double>>& number,
                                       const std::vector<std::vector<double>>& energy, std::size_t entries);

}  // namespace gdsmc::sample
