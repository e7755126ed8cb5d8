/**
 * \file input_checks.hpp
 * \brief Internal: what the theory modules share (namespace gdsmc::theory::detail): argument checks and the
 *        pair sum s_kj of the Maxwellian pair kernels.
 */
#pragma once

#include <cmath>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>

#include "model/species.hpp"

namespace gdsmc::theory::detail {

/// One positive, finite temperature per species, or std::invalid_argument naming `caller`.
inline void require_temperatures(const species::Mixture& mix, std::span<const double> temperature,
                                 const char* caller) {
  if (temperature.size() != mix.size())
    throw std::invalid_argument(std::string(caller) + ": " + std::to_string(temperature.size()) +
                                " temperatures for " + std::to_string(mix.size()) + " species");
  for (double t : temperature)
    if (!(t > 0.0) || !std::isfinite(t))
      throw std::invalid_argument(std::string(caller) + ": temperatures must be positive and finite");
}

/// s_kj = T_k/m_k + T_j/m_j (\ref cm_notation "docs/collision-model.md"), no checks (the CVODE right-hand
/// sides call it).
inline double thermal_speed_sum(const species::Mixture& mix, std::span<const double> temperature, std::size_t k,
                                std::size_t j) {
  return temperature[k] / mix.mass[k] + temperature[j] / mix.mass[j];
}

}  // namespace gdsmc::theory::detail
