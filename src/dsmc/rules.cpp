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
  // (\ref sch_blocks "docs/schemes.md", "Step length").
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

Rule make_rule(const species::Mixture& mix, const species::PairMatrix* viscoelastic_beta) {
  if (viscoelastic_beta) return ViscoelasticRule(mix, *viscoelastic_beta);
  return SmoothRule(mix);
}

}  // namespace gdsmc::rules
