#include "dsmc/rules.hpp"

#include <algorithm>

namespace gdsmc::rules {

SmoothRule::SmoothRule(const species::Mixture& mix) : mix_(&mix), s_(mix.size()) {
  // The S x S table makes a pair's constants one load; with thousands of species (lowrank) the few a
  // collision needs are computed when it happens instead.
  if (s_ > species::dense_pair_limit) return;
  table_.reserve(s_ * s_);
  for (std::size_t k = 0; k < s_; ++k)
    for (std::size_t j = 0; j < s_; ++j) table_.push_back(make_pair(mix.restitution(k, j), mix.mass[k], mix.mass[j]));
}

std::optional<double> SmoothRule::largest_loss_fraction() const {
  // (1 - alpha^2)/3: one collision per particle dissipates at most this fraction of the energy
  // (\ref sch_blocks "docs/schemes.md", "Step length"). A uniform alpha (above species::dense_pair_limit
  // species: the S^2 pairs are not visited) gives the same number at once.
  if (const auto& alpha = mix_->restitution.constant) return (1.0 - *alpha * *alpha) / 3.0;
  double largest = 0.0;
  for (std::size_t k = 0; k < s_; ++k)
    for (std::size_t j = 0; j < s_; ++j) {
      const double alpha = mix_->restitution(k, j);
      largest = std::max(largest, (1.0 - alpha * alpha) / 3.0);
    }
  return largest;
}

ViscoelasticRule::ViscoelasticRule(const species::Mixture& mix, const species::PairMatrix& beta)
    : mix_(&mix), s_(mix.size()) {
  if (s_ > species::dense_pair_limit) {
    beta_ = beta;
    return;
  }
  for (std::size_t k = 0; k < s_; ++k)
    for (std::size_t j = 0; j < s_; ++j) {
      sqrt_beta_.push_back(std::sqrt(beta(k, j)));
      mass_fraction_.push_back(mix.mass[j] / (mix.mass[k] + mix.mass[j]));
    }
}

RoughRule::Pair RoughRule::make_pair(const species::Mixture& mix, std::size_t k, std::size_t j) {
  // \ref rough_rule "docs/rough-spheres.md": K_kj from the contact points' tangential mobility.
  const double mk = mix.mass[k], mj = mix.mass[j];
  const double kappa_k = mix.moment_of_inertia[k], kappa_j = mix.moment_of_inertia[j];
  const double reduced = mk * mj / (mk + mj);
  const double big_k = 1.0 / (1.0 + reduced / (kappa_k * mk) + reduced / (kappa_j * mj));
  const double alpha = mix.restitution(k, j), beta = mix.roughness(k, j);
  Pair p;
  p.alpha = alpha;
  p.tangential = (1.0 + beta) * big_k;
  p.mass_fraction = mj / (mk + mj);
  p.reduced_mass = reduced;
  p.half_a = 0.5 * mix.diameter[k];
  p.half_b = 0.5 * mix.diameter[j];
  p.spin_a = 2.0 * reduced / (kappa_k * mk * mix.diameter[k]);
  p.spin_b = 2.0 * reduced / (kappa_j * mj * mix.diameter[j]);
  p.tangential_loss = big_k * (1.0 - beta * beta);
  return p;
}

RoughRule::RoughRule(const species::Mixture& mix) : mix_(&mix), s_(mix.size()) {
  if (s_ > species::dense_pair_limit) return;
  table_.reserve(s_ * s_);
  for (std::size_t k = 0; k < s_; ++k)
    for (std::size_t j = 0; j < s_; ++j) table_.push_back(make_pair(mix, k, j));
}

std::optional<double> RoughRule::largest_loss_fraction() const {
  // Above species::dense_pair_limit species with a uniform alpha, the bound t (2 - t) <= 1 of the
  // tangential term (as the S^2 pairs are not visited): blocked steps a little shorter, never longer.
  if (s_ > species::dense_pair_limit && mix_->restitution.constant)
    return (2.0 - *mix_->restitution.constant * *mix_->restitution.constant) / 3.0;
  double largest = 0.0;
  for (std::size_t k = 0; k < s_; ++k)
    for (std::size_t j = 0; j < s_; ++j) {
      const Pair p = pair(k, j);
      largest = std::max(largest, ((1.0 - p.alpha * p.alpha) + p.tangential * (2.0 - p.tangential)) / 3.0);
    }
  return largest;
}

void RoughRule::attach(particles::System& sys) {
  if (!sys.find_array(angular_velocity)) sys.add_array<particles::Vec3>(angular_velocity);
  for (std::size_t i = 0; i < sys.extra.size(); ++i)
    if (sys.extra[i].name == angular_velocity) spin_index_ = i;
}

void RoughRule::measure(const particles::System& sys, sample::Rows& rows) const {
  // \ref rough_observables "docs/rough-spheres.md": peculiar velocities c = v - u (u the mass-weighted
  // mean flow, as sample::measure), angular velocities as they are.
  const auto& w = std::get<particles::ParticleArray<particles::Vec3>>(sys.extra[spin_index_].values);
  double u[3] = {0.0, 0.0, 0.0}, total_mass = 0.0;
  for (std::size_t k = 0; k < s_; ++k)
    for (std::size_t i = sys.first[k]; i < sys.first[k] + sys.count[k]; ++i) {
      u[0] += mix_->mass[k] * sys.v[i].x, u[1] += mix_->mass[k] * sys.v[i].y, u[2] += mix_->mass[k] * sys.v[i].z;
      total_mass += mix_->mass[k];
    }
  for (double& x : u) x /= total_mass;
  std::vector<double> t_rot(s_), a20(s_), a02(s_), a11(s_);
  double energy = 0.0;
  for (std::size_t k = 0; k < s_; ++k) {
    double c2 = 0.0, c4 = 0.0, w2 = 0.0, w4 = 0.0, c2w2 = 0.0;
    for (std::size_t i = sys.first[k]; i < sys.first[k] + sys.count[k]; ++i) {
      const double cx = sys.v[i].x - u[0], cy = sys.v[i].y - u[1], cz = sys.v[i].z - u[2];
      const double cc = cx * cx + cy * cy + cz * cz, ww = w[i].x * w[i].x + w[i].y * w[i].y + w[i].z * w[i].z;
      c2 += cc, c4 += cc * cc, w2 += ww, w4 += ww * ww, c2w2 += cc * ww;
    }
    const auto n = static_cast<double>(sys.count[k]);
    c2 /= n, c4 /= n, w2 /= n, w4 /= n, c2w2 /= n;
    t_rot[k] = mix_->inertia(k) * w2 / 3.0;
    a20[k] = c2 > 0.0 ? 0.6 * c4 / (c2 * c2) - 1.0 : 0.0;
    // (a gas without rotation, T_rot = 0: a02 and a11 undefined, written as 0, never NaN)
    a02[k] = w2 > 0.0 ? 0.6 * w4 / (w2 * w2) - 1.0 : 0.0;
    a11[k] = w2 > 0.0 && c2 > 0.0 ? c2w2 / (c2 * w2) - 1.0 : 0.0;
    energy += mix_->mole_fraction(k) * 0.5 * (mix_->mass[k] * c2 + mix_->inertia(k) * w2);
  }
  rows.add("rotational_temperature", s_, t_rot);
  rows.add("cumulant_a20", s_, a20);
  rows.add("cumulant_a02", s_, a02);
  rows.add("cumulant_a11", s_, a11);
  rows.add("total_energy", 1, {energy});
}

Rule make_rule(const species::Mixture& mix, const species::PairMatrix* viscoelastic_beta) {
  if (viscoelastic_beta) return ViscoelasticRule(mix, *viscoelastic_beta);
  if (mix.rough()) return RoughRule(mix);
  return SmoothRule(mix);
}

}  // namespace gdsmc::rules
