/**
 * \file sample.hpp
 * \brief What is measured at each sample point, and the mean and standard error over replicas.
 *
 * For each species k, with velocities relative to the mean flow u = sum m v / sum m (zero to
 * round-off, since collisions conserve momentum and the initial state has none):
 * - partial temperature T_k = m_k <|v - u|^2> / 3 (INTERFACE.md),
 * - Sonine coefficient c_k = 2 [(3/5) <|v - u|^4> / <|v - u|^2>^2 - 1] (seed 003 eq 17, ERRATA §6:
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

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dsmc/collide.hpp"
#include "dsmc/particles.hpp"
#include "dsmc/species.hpp"

namespace gdsmc::sample {

/// Moments of one replica at one instant.
struct Moments {
  std::vector<double> temperature;  ///< T_k
  std::vector<double> sonine_c;     ///< c_k
  std::vector<double> number;       ///< N_k
  double total_temperature = 0.0;   ///< T
  double mean_flow[3] = {0.0, 0.0, 0.0};  ///< u = sum m v / sum m
};

Moments measure(const species::Mixture& mix, const particles::System& sys);

/// Velocity-component histograms of (v - u)/sqrt(T_k/m_k), S x bins, each a probability density
/// over [-range, range]; `moments` gives T_k and u.
std::vector<double> velocity_histogram(const species::Mixture& mix, const particles::System& sys,
                                       const Moments& moments, std::size_t bins, double range);

/// One observable's samples from all replicas: values[replica][sample * columns + column].
struct Accumulator {
  std::size_t columns = 1;
  std::vector<std::vector<double>> values;
  void add(std::size_t replica, const std::vector<double>& row);  ///< appends one sample row
  std::vector<double> mean() const;
  std::vector<double> standard_error() const;  ///< empty when fewer than 2 replicas
};

}  // namespace gdsmc::sample
