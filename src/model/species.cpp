#include "model/species.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

namespace gdsmc::species {

PairMatrix PairMatrix::computed(std::size_t n, std::function<double(std::size_t, std::size_t)> rule) {
  PairMatrix m;
  m.size = n;
  m.rule = std::move(rule);
  return m;
}

PairMatrix PairMatrix::uniform(std::size_t n, double value) {
  PairMatrix m = computed(n, [value](std::size_t, std::size_t) { return value; });
  m.constant = value;
  return m;
}

void PairMatrix::densify() {
  if (!rule) return;
  std::vector<double> dense(size * size);
  for (std::size_t k = 0; k < size; ++k)
    for (std::size_t j = 0; j < size; ++j) dense[k * size + j] = rule(k, j);
  values = std::move(dense);
  rule = nullptr;
}

double PairMatrix::max() const {
  if (constant && size > 0) return *constant;
  if (largest && size > 0) return *largest;
  double m = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < size; ++k)
    for (std::size_t j = 0; j < size; ++j) m = std::max(m, (*this)(k, j));
  return m;
}

double PairMatrix::min() const {
  if (constant && size > 0) return *constant;
  double m = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < size; ++k)
    for (std::size_t j = 0; j < size; ++j) m = std::min(m, (*this)(k, j));
  return m;
}

double Mixture::total_density() const {
  double n = 0.0;
  for (double nk : number_density) n += nk;
  return n;
}

double Mixture::mole_fraction(std::size_t k) const { return number_density[k] / total_density(); }

double Mixture::packing_fraction() const {
  double phi = 0.0;
  for (std::size_t k = 0; k < size(); ++k)
    phi += number_density[k] * std::pow(diameter[k], 3);
  return std::numbers::pi / 6.0 * phi;
}

PairMatrix carnahan_starling(const std::vector<double>& diameter,
                             const std::vector<double>& number_density) {
  const std::size_t s = diameter.size();
  // \ref cm_chi "docs/collision-model.md": phi = (pi n/6) sum_i x_i sigma_i^3 = (pi/6) sum_i n_i sigma_i^3, likewise xi.
  double phi = 0.0, xi = 0.0;
  for (std::size_t i = 0; i < s; ++i) {
    phi += number_density[i] * std::pow(diameter[i], 3);
    xi += number_density[i] * diameter[i] * diameter[i];
  }
  phi *= std::numbers::pi / 6.0;
  xi *= std::numbers::pi / 6.0;
  const auto chi_of_diameters = [phi, xi](double a, double b) {
    const double sigma_ij = 0.5 * (a + b);
    const double s_ij = a * b / sigma_ij;  // S_ij of \ref cm_chi "docs/collision-model.md"
    const double one_minus = 1.0 - phi;
    return 1.0 / one_minus + 1.5 * xi * s_ij / (one_minus * one_minus) +
           0.5 * xi * xi * s_ij * s_ij / (one_minus * one_minus * one_minus);
  };
  PairMatrix m = PairMatrix::computed(s, [chi_of_diameters, d = diameter](std::size_t i, std::size_t j) {
    return chi_of_diameters(d[i], d[j]);
  });
  if (s <= dense_pair_limit) {
    m.densify();
    return m;
  }
  // The largest entry without the S^2 pairs (header): chi grows with S_ij and S_ij with either diameter, and
  // each floating-point operation of chi is monotone in S_ij, so an entry can pass those of the largest
  // diameters only through the round-off of S_ij, for diameters within a few ulps of the largest: the
  // largest over every pair of the distinct diameters within 1e-12 of it (one value when it is unique).
  const double widest = *std::max_element(diameter.begin(), diameter.end());
  std::vector<double> near;
  for (double d : diameter)
    if (d >= widest * (1.0 - 1e-12)) near.push_back(d);
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  double largest = -std::numeric_limits<double>::infinity();
  for (double a : near)
    for (double b : near) largest = std::max(largest, chi_of_diameters(a, b));
  m.largest = largest;
  return m;
}

Mixture make_mixture(std::vector<double> mass, std::vector<double> diameter,
                     std::vector<double> number_density, PairMatrix restitution, bool enskog) {
  Mixture mix;
  const std::size_t s = mass.size();
  mix.mass = std::move(mass);
  mix.diameter = std::move(diameter);
  mix.number_density = std::move(number_density);
  mix.restitution = std::move(restitution);
  mix.enskog = enskog;
  mix.contact_distance = PairMatrix::computed(
      s, [d = mix.diameter](std::size_t k, std::size_t j) { return 0.5 * (d[k] + d[j]); });
  mix.reduced_mass = PairMatrix::computed(
      s, [m = mix.mass](std::size_t k, std::size_t j) { return m[k] * m[j] / (m[k] + m[j]); });
  mix.pair_correlation =
      enskog ? carnahan_starling(mix.diameter, mix.number_density) : PairMatrix::uniform(s, 1.0);
  if (s <= dense_pair_limit) {
    mix.contact_distance.densify();
    mix.reduced_mass.densify();
    mix.pair_correlation.densify();
    mix.restitution.densify();
  }
  return mix;
}

std::vector<std::size_t> particle_counts(std::size_t n_particles, const Mixture& mix) {
  // Largest remainders (Hamilton's apportionment): N_k = floor(N x_k), and the N - sum_k N_k
  // particles left go one each to the species with the largest fractional parts N x_k - N_k (the
  // lower index first on a tie), so that sum_k N_k = N exactly. When rounding each N x_k to the
  // nearest integer already adds up to N, this gives the same counts.
  const std::size_t s = mix.size();
  std::vector<std::size_t> counts(s);
  std::vector<double> fraction(s);
  const double n = mix.total_density();  // once: mole_fraction(k) would sum over all species each time
  std::size_t assigned = 0;
  for (std::size_t k = 0; k < s; ++k) {
    const double share = static_cast<double>(n_particles) * mix.number_density[k] / n;
    counts[k] = static_cast<std::size_t>(std::floor(share));
    fraction[k] = share - std::floor(share);
    assigned += counts[k];
  }
  std::vector<std::size_t> order(s);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return fraction[a] > fraction[b]; });
  // Round-off may leave the floors one above N (a share a hair above an integer): take back from the
  // smallest fractional parts, which are last in `order`.
  for (std::size_t i = s; assigned > n_particles && i-- > 0;)
    if (counts[order[i]] > 0) --counts[order[i]], --assigned;
  for (std::size_t i = 0; assigned < n_particles; i = (i + 1) % s) ++counts[order[i]], ++assigned;
  return counts;
}

}  // namespace gdsmc::species
