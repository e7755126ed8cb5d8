// The white-noise steady state of smooth spheres over a sweep of alpha: T_tr against the Sonine energy balance
// and a2 beside van Noije and Ernst's value (theory/rough.hpp sonine_driven_state; \ref wn_theory
// "docs/white-noise.md"). See README.md in this folder.
#include <cmath>
#include <cstdio>
#include <string>

#include "theory/rough.hpp"
#include "validation.hpp"

using namespace gdsmc;

namespace {

constexpr double kSteadyFrom = 600.0;  // the samples averaged: t >= 600 (16-26 collisions per particle and more)

}  // namespace

int main(int argc, char** argv) {
  const auto run = validation::run_case(argc, argv, "white_noise_alpha.h5");
  validation::Report report("White noise, smooth spheres, steady state over alpha", run.report_file());
  report.note("averages over the samples from t = 600 on, error = the mean of their SEs (an upper bound); T_tr against "
              "the Sonine energy balance at 4 SE + |Sonine - Maxwellian|; a2 = c/2 noted beside van Noije and Ernst's "
              "first Sonine value (no independent estimate of its error)");
  const auto points = run.config.sweep_points();
  for (std::size_t p = 0; p < points.size(); ++p) {
    const auto& config = points[p];
    const auto mix = config.mixture();
    const double alpha = mix.restitution(0, 0);
    const std::string root = run.config.is_sweep() ? "/sweep/point_" + std::to_string(p + 1) + "/observables/" : "/observables/";
    const auto t = io::h5md::read_observable(run.file, root + "total_temperature");
    const auto c = io::h5md::read_observable(run.file, root + "sonine_c");
    if (!report.require("replicas > 1, so standard errors exist", !t.error.empty())) return report.exit_code();
    const auto temperature = validation::steady_average(t, kSteadyFrom), a2 = validation::steady_average(c, kSteadyFrom, 0.5);
    // T^(3/2) = m chi^2/(zeta* nu_1) (docs/white-noise.md)
    const double unit = mix.mass[0] * config.thermostat.noise_strength[0] / theory::rough::frequency_unit(mix);
    const auto sonine = theory::rough::sonine_driven_state(alpha, -1.0, 0.4);
    const auto maxwell = theory::rough::driven_state(alpha, -1.0, 0.4);
    const double t_sonine = std::pow(unit / sonine.state->cooling_rate_reduced, 2.0 / 3.0);
    const double t_maxwell = std::pow(unit / maxwell.cooling_rate_reduced, 2.0 / 3.0);
    char name[200];
    std::snprintf(name, sizeof name, "alpha = %.2f: steady T_tr vs Sonine balance (Maxwellian %.5f)", alpha, t_maxwell);
    report.check(name, temperature.value, temperature.error, t_sonine, 4.0, std::abs(t_sonine - t_maxwell));
    std::snprintf(name, sizeof name, "alpha = %.2f: a2 = %.4f +- %.4f; van Noije and Ernst %.4f", alpha, a2.value, a2.error,
                  sonine.state->cumulants.a20);
    report.note(name);
  }
  return report.exit_code();
}
