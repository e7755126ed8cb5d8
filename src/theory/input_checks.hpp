/**
 * \file input_checks.hpp
 * \brief Internal: argument checks the theory functions share (namespace gdsmc::theory::detail).
 */
#pragma once

#include <cmath>
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

}  // namespace gdsmc::theory::detail
