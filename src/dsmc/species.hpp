/**
 * \file species.hpp
 * \brief Mechanical properties of the species of a granular mixture and of each species pair.
 *
 * For S species with masses m_k, diameters sigma_k and number densities n_k the module derives the
 * pair quantities used by every collision scheme and by the theory module (notation of ERRATA):
 * - contact distance sigma_kj = (sigma_k + sigma_j)/2,
 * - reduced mass m_kj = m_k m_j / (m_k + m_j) and mass fraction mu_kj = m_k / (m_k + m_j),
 * - normal restitution alpha_kj (symmetric matrix, ERRATA §1),
 * - pair correlation at contact chi_kj: 1 for a dilute (Boltzmann) gas, Carnahan-Starling for the
 *   Enskog gas (seed 003 eq 26, corrected form ERRATA §5).
 *
 * Units: whatever the user's numbers are in (consistent units), k_B = 1, temperature is an energy.
 * Reads the namelist group `&system` through io::config. Checked by tests/species_test.cpp.
 */
#pragma once

#include <cstddef>
#include <vector>

namespace gdsmc::species {

/// Row-major symmetric S x S matrix of pair quantities.
struct PairMatrix {
  std::size_t size = 0;
  std::vector<double> values;

  PairMatrix() = default;
  explicit PairMatrix(std::size_t n, double fill = 0.0) : size(n), values(n * n, fill) {}
  double operator()(std::size_t k, std::size_t j) const { return values[k * size + j]; }
  double& operator()(std::size_t k, std::size_t j) { return values[k * size + j]; }
};

/// A mixture: per-species data and the derived pair data. Built once by make_mixture, then const.
struct Mixture {
  std::vector<double> mass;            ///< m_k
  std::vector<double> diameter;        ///< sigma_k
  std::vector<double> number_density;  ///< n_k
  PairMatrix restitution;              ///< alpha_kj
  PairMatrix contact_distance;         ///< sigma_kj = (sigma_k + sigma_j)/2
  PairMatrix reduced_mass;             ///< m_kj = m_k m_j/(m_k + m_j)
  PairMatrix pair_correlation;         ///< chi_kj (1 when not Enskog)
  bool enskog = false;

  std::size_t size() const { return mass.size(); }
  double total_density() const;                                  ///< n = sum_k n_k
  double mole_fraction(std::size_t k) const;                     ///< x_k = n_k / n
  /// mu_kj = m_k / (m_k + m_j) (ERRATA notation; mu_kj + mu_jk = 1)
  double mass_fraction(std::size_t k, std::size_t j) const { return mass[k] / (mass[k] + mass[j]); }
  double packing_fraction() const;                               ///< phi = (pi/6) sum_k n_k sigma_k^3
};

/// Carnahan-Starling chi_kj for all pairs (seed 003 eq 26; ERRATA §5).
PairMatrix carnahan_starling(const std::vector<double>& diameter,
                             const std::vector<double>& number_density);

/**
 * Builds a mixture and its pair data. `restitution` is S x S (symmetric). With `enskog` the pair
 * correlation is Carnahan-Starling, else 1. Inputs are assumed validated (io::config checks them).
 */
Mixture make_mixture(std::vector<double> mass, std::vector<double> diameter,
                     std::vector<double> number_density, PairMatrix restitution, bool enskog);

}  // namespace gdsmc::species
