// The white-noise thermostat (dsmc/thermostat.hpp WhiteNoise; \ref wn_forcing "docs/white-noise.md"). See
// README.md in this folder.
#include <cmath>
#include <cstdio>

#include "theory/rough.hpp"
#include "validation.hpp"

using namespace gdsmc;

int main(int argc, char** argv) {
  const auto run = validation::run_case(argc, argv, "white_noise.h5");
  const auto mix = run.config.mixture();
  const double alpha = mix.restitution(0, 0), m = mix.mass[0], chi2 = run.config.thermostat.noise_strength[0];
  const double n_particles = static_cast<double>(run.config.dsmc.n_particles), t0 = run.config.initial.temperature[0];
  char title[160];
  std::snprintf(title, sizeof title, "White noise, alpha = %g, chi^2 = %g%s", alpha, chi2, mix.rough() ? ", rough" : "");
  validation::Report report(title, run.report_file());
  const auto temperature = validation::observable(run, "total_temperature");
  if (!report.require("replicas > 1, so standard errors exist", !temperature.error.empty())) return report.exit_code();
  const std::size_t last = temperature.time.size() - 1;
  if (alpha == 1.0 && !mix.rough()) {
    // Exact: the collisions keep the energy; each stage adds m chi^2 dt (1 - 1/N) per particle to (3/2) T.
    for (std::size_t i = 1; i < temperature.time.size(); ++i) {
      const double t = temperature.time[i], exact = t0 + m * chi2 * t * (1.0 - 1.0 / n_particles);
      char name[64];
      std::snprintf(name, sizeof name, "T(t) at t = %g", t);
      report.check(name, temperature.value[i], temperature.error[i], exact, 4.0);
    }
    return report.exit_code();
  }
  // The steady state: the Maxwellian energy balance m chi^2 = nu (4/3)(A - B theta) T_tr (theory/rough.hpp
  // driven_state), reported beside the last sample, not asserted.
  const bool rough_gas = mix.rough();
  const auto state = theory::rough::driven_state(alpha, rough_gas ? mix.roughness(0, 0) : -1.0,
                                                 rough_gas ? mix.moment_of_inertia[0] : 0.4);
  const double steady = std::pow(m * chi2 / (state.cooling_rate_reduced * theory::rough::frequency_unit(mix)), 2.0 / 3.0);
  const auto c = validation::observable(run, "sonine_c");
  char text[240];
  std::snprintf(text, sizeof text, "T_tr at t = %g: %.5f +- %.5f; Maxwellian energy balance %.5f (not asserted); a2 = c/2 = %.5f +- %.5f",
                temperature.time[last], temperature.value[last], temperature.error[last], steady, 0.5 * c.value[last],
                0.5 * c.error[last]);
  report.note(text);
  report.require("the run reaches a steady state: T at the last two samples within 3 % of each other",
                 std::abs(temperature.value[last] / temperature.value[last - 1] - 1.0) < 0.03);
  return report.exit_code();
}
