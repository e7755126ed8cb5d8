// The white-noise steady state of a binary mixture of smooth spheres: T_k against the first-Sonine state of the
// driven mixture (theory/sonine_mixture.hpp white_noise_first_sonine; \ref wn_theory "docs/white-noise.md"), c_k
// beside it. See README.md in this folder.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "theory/rough.hpp"
#include "theory/sonine_mixture.hpp"
#include "validation.hpp"

using namespace gdsmc;

namespace {

constexpr double kSteadyFrom = 600.0;  // the samples averaged: t >= 600 (about 20 collisions per particle and more)

}  // namespace

int main(int argc, char** argv) {
  const auto run = validation::run_case(argc, argv, "white_noise_mixture.h5");
  validation::Report report("White noise, binary mixture of smooth spheres, steady state", run.report_file());
  report.note("averages over the samples from t = 600 on, error = the mean of their SEs (an upper bound); T_k against "
              "the first-Sonine steady state at 4 SE + |Sonine - Maxwellian| (the Sonine correction as the estimate of "
              "what it leaves out); c_k noted beside the first-Sonine values (no independent estimate of their error)");
  const auto mix = run.config.mixture();
  const std::size_t s = mix.size();
  const auto& strength = run.config.thermostat.noise_strength;
  const auto maxwell = theory::rough::mixture_driven_state(mix, strength);
  const auto sonine = theory::white_noise_first_sonine(mix, strength, maxwell.translational);
  const auto t = io::h5md::read_observable(run.file, "/observables/temperature");
  const auto c = io::h5md::read_observable(run.file, "/observables/sonine_c");
  if (!report.require("replicas > 1, so standard errors exist", !t.error.empty())) return report.exit_code();
  if (!report.require("one temperature and one c per species and sample",
                      t.value.size() == t.time.size() * s && c.value.size() == c.time.size() * s))
    return report.exit_code();
  for (std::size_t k = 0; k < s; ++k) {
    const auto temperature = validation::steady_average(t, kSteadyFrom, 1.0, k, s),
               ck = validation::steady_average(c, kSteadyFrom, 1.0, k, s);
    char name[200];
    std::snprintf(name, sizeof name, "species %zu: steady T_k vs first Sonine (Maxwellian %.5f)", k + 1, maxwell.translational[k]);
    report.check(name, temperature.value, temperature.error, sonine.temperature[k], 4.0,
                 std::abs(sonine.temperature[k] - maxwell.translational[k]));
    std::snprintf(name, sizeof name, "species %zu: c_k = %.4f +- %.4f; first Sonine %.4f", k + 1, ck.value, ck.error,
                  sonine.sonine_c[k]);
    report.note(name);
  }
  return report.exit_code();
}
