#include "dsmc/species.hpp"

#include <cmath>
#include <numbers>

namespace gdsmc::species {

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
  // ERRATA §5: phi = (pi n/6) sum_i x_i sigma_i^3 = (pi/6) sum_i n_i sigma_i^3, likewise xi.
  double phi = 0.0, xi = 0.0;
  for (std::size_t i = 0; i < s; ++i) {
    phi += number_density[i] * std::pow(diameter[i], 3);
    xi += number_density[i] * diameter[i] * diameter[i];
  }
  phi *= std::numbers::pi / 6.0;
  xi *= std::numbers::pi / 6.0;
  PairMatrix chi(s);
  for (std::size_t i = 0; i < s; ++i)
    for (std::size_t j = 0; j < s; ++j) {
      const double sigma_ij = 0.5 * (diameter[i] + diameter[j]);
      const double s_ij = diameter[i] * diameter[j] / sigma_ij;  // S_ij of ERRATA §5
      const double one_minus = 1.0 - phi;
      chi(i, j) = 1.0 / one_minus + 1.5 * xi * s_ij / (one_minus * one_minus) +
                  0.5 * xi * xi * s_ij * s_ij / (one_minus * one_minus * one_minus);
    }
  return chi;
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
  mix.contact_distance = PairMatrix(s);
  mix.reduced_mass = PairMatrix(s);
  for (std::size_t k = 0; k < s; ++k)
    for (std::size_t j = 0; j < s; ++j) {
      mix.contact_distance(k, j) = 0.5 * (mix.diameter[k] + mix.diameter[j]);
      mix.reduced_mass(k, j) = mix.mass[k] * mix.mass[j] / (mix.mass[k] + mix.mass[j]);
    }
  mix.pair_correlation =
      enskog ? carnahan_starling(mix.diameter, mix.number_density) : PairMatrix(s, 1.0);
  return mix;
}

}  // namespace gdsmc::species
