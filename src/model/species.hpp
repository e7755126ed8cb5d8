/**
 * \file species.hpp
 * \brief Mechanical properties of the species of a granular mixture and of each species pair.
 *
 * For S species with masses m_k, diameters sigma_k and number densities n_k the module derives the
 * pair quantities used by every collision scheme and by the theory module (notation of \ref cm_notation "docs/collision-model.md"):
 * - contact distance sigma_kj = (sigma_k + sigma_j)/2,
 * - reduced mass m_kj = m_k m_j / (m_k + m_j) and mass fraction mu_kj = m_k / (m_k + m_j),
 * - normal restitution alpha_kj (symmetric matrix, \ref cm_rule "docs/collision-model.md"),
 * - pair correlation at contact chi_kj: 1 for a dilute (Boltzmann) gas, Carnahan-Starling for the
 *   Enskog gas (Montanero and Garzo 2002, eq. (26), corrected form \ref cm_chi "docs/collision-model.md").
 *
 * Units: whatever the user's numbers are in (consistent units), k_B = 1, temperature is an energy.
 * Reads the namelist group `&system` through io::config. Checked by tests/species_test.cpp.
 */
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

namespace gdsmc::species {

/// S x S matrix of pair quantities: stored row-major (dense), or computed entry by entry from
/// per-species data (`rule`), so that mixtures of thousands of species need no S^2 storage.
struct PairMatrix {
  std::size_t size = 0;        ///< S
  std::vector<double> values;  ///< dense storage, row-major; empty when `rule` computes the entries
  std::function<double(std::size_t, std::size_t)> rule;  ///< entry (k, j) on access; empty when dense
  /// Set by uniform() (kept by densify(), dropped by a write access): every entry is this value, so
  /// that max() and min() take O(1), not O(S^2), and the block kernels read no S x S table.
  std::optional<double> constant;
  /// Set by a builder that knows the largest entry without visiting the S^2 (carnahan_starling: at the
  /// largest diameters), so that max() takes O(1); dropped by a write access.
  std::optional<double> largest;

  PairMatrix() = default;
  /// A dense n x n matrix with every entry `fill`.
  explicit PairMatrix(std::size_t n, double fill = 0.0) : size(n), values(n * n, fill) {}
  /// A matrix whose entry (k, j) is rule(k, j), evaluated on access.
  static PairMatrix computed(std::size_t n, std::function<double(std::size_t, std::size_t)> rule);
  /// Every entry equal to `value`, stored as one number.
  static PairMatrix uniform(std::size_t n, double value);

  /// The entries are stored (no rule).
  bool is_dense() const { return !rule; }
  /// Entry (k, j).
  double operator()(std::size_t k, std::size_t j) const {
    return rule ? rule(k, j) : values[k * size + j];
  }
  /// Write access: a computed matrix is first stored densely.
  double& operator()(std::size_t k, std::size_t j) {
    if (rule) densify();
    constant.reset(), largest.reset();  // (the entry may be written)
    return values[k * size + j];
  }
  /// Stores every entry of a computed matrix and drops the rule (S^2 doubles).
  void densify();
  double max() const;  ///< largest entry (O(S^2) for a computed matrix other than uniform() and one with `largest`)
  double min() const;  ///< smallest entry
};

/// Mixtures with more species than this keep their pair data computed, not stored (S^2 doubles).
inline constexpr std::size_t dense_pair_limit = 512;

/// Packing fractions from here on are beyond the Carnahan-Starling fluid (\ref cm_chi "docs/collision-model.md"):
/// enskog refuses them (io/config_checks.cpp), and the dilute gas's warning quotes no chi there.
inline constexpr double carnahan_starling_fluid_limit = 0.5;

/// A mixture: per-species data and the derived pair data. Built once by make_mixture, then const.
struct Mixture {
  std::vector<double> mass;            ///< m_k
  std::vector<double> diameter;        ///< sigma_k
  std::vector<double> number_density;  ///< n_k
  PairMatrix restitution;              ///< alpha_kj
  PairMatrix contact_distance;         ///< sigma_kj = (sigma_k + sigma_j)/2
  PairMatrix reduced_mass;             ///< m_kj = m_k m_j/(m_k + m_j)
  PairMatrix pair_correlation;         ///< chi_kj (1 when not Enskog)
  bool enskog = false;                 ///< chi_kj from Carnahan-Starling (else 1)
  /// beta_kj, the tangential restitution of rough spheres (\ref rough_rule "docs/rough-spheres.md"):
  /// -1 smooth, +1 perfectly rough; empty (size 0) for smooth spheres, which have no rotation.
  PairMatrix roughness;
  /// kappa_k = 4 I_k/(m_k sigma_k^2), the reduced moment of inertia (2/5 for a uniform sphere);
  /// empty for smooth spheres.
  std::vector<double> moment_of_inertia;

  /// S, the number of species.
  std::size_t size() const { return mass.size(); }
  double total_density() const;                                  ///< n = sum_k n_k
  double mole_fraction(std::size_t k) const;                     ///< x_k = n_k / n
  /// mu_kj = m_k / (m_k + m_j) (\ref cm_notation "docs/collision-model.md"; mu_kj + mu_jk = 1)
  double mass_fraction(std::size_t k, std::size_t j) const { return mass[k] / (mass[k] + mass[j]); }
  double packing_fraction() const;                               ///< phi = (pi/6) sum_k n_k sigma_k^3
  /// The spheres are rough (roughness and moment_of_inertia given): particles carry an angular velocity.
  bool rough() const { return roughness.size != 0; }
  /// I_k = kappa_k m_k sigma_k^2 / 4 of rough spheres.
  double inertia(std::size_t k) const { return 0.25 * moment_of_inertia[k] * mass[k] * diameter[k] * diameter[k]; }
};

/// Carnahan-Starling chi_kj for all pairs (Montanero and Garzo 2002, eq. (26); \ref cm_chi "docs/collision-model.md").
/// Computed on access above dense_pair_limit species, with its largest entry known: chi_kj grows with
/// S_kj = sigma_k sigma_j/sigma_kj, which grows with either diameter, so the largest entry is among the pairs
/// of the largest diameters (those within 1e-12 of the largest, each distinct value once: O(S) with a few
/// of them, O(D^2) for D distinct diameters that close, D at most some thousands).
PairMatrix carnahan_starling(const std::vector<double>& diameter,
                             const std::vector<double>& number_density);

/**
 * Builds a mixture and its pair data. `restitution` is S x S (symmetric). With `enskog` the pair
 * correlation is Carnahan-Starling, else 1. Inputs are assumed validated (io::config checks them).
 * Above dense_pair_limit species the pair data are computed on access instead of stored.
 */
Mixture make_mixture(std::vector<double> mass, std::vector<double> diameter,
                     std::vector<double> number_density, PairMatrix restitution, bool enskog);

/// The simulated particles of each species for N in all: N_k ~ N x_k, adding up to N exactly (largest
/// remainders; the caller checks N_k >= 2; Montanero and Garzo 2002, eq. (22), \ref cm_initial "docs/collision-model.md").
std::vector<std::size_t> particle_counts(std::size_t n_particles, const Mixture& mix);

}  // namespace gdsmc::species
