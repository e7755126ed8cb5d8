// Haff cooling against \ref haff_law "docs/haff-and-mixtures.md" (DSMC notes, Figs. 1 and 3). See README.md in this folder.
#include <cmath>
#include <numbers>

#include "theory/sonine.hpp"
#include "theory/theory.hpp"
#include "validation.hpp"

using namespace gdsmc;

int main(int argc, char** argv) {
  const auto run = validation::run_case(argc, argv, "haff_cooling.h5");
  const auto& sys = run.config.system;
  const double m = sys.mass[0], sigma = sys.diameter[0], n = sys.number_density[0];
  const double alpha = sys.restitution(0, 0);
  const double chi = run.config.mixture().pair_correlation(0, 0);
  const double t0_temperature = run.config.initial.temperature[0];

  const double a2 = theory::sonine_a2(alpha);
  // The cooling-rate factor zeta/zeta_Maxwell of the HCS: the bracket of the Sonine approximations of
  // orders 4 and 5 (docs/sonine.md "Beyond first Sonine"), allowance half their spread. Was first
  // Sonine 1 + 3 a2/16 (\ref haff_sonine "docs/haff-and-mixtures.md") with 15 % of its correction.
  const auto bracket = theory::sonine_cumulant_bracket(alpha);
  const double sonine = bracket.cooling_factor;
  const double zeta0 = theory::haff_cooling_rate(n, sigma, chi, m, alpha, t0_temperature);
  const double sonine_error = bracket.cooling_half_width;

  validation::Report report("Haff cooling, alpha = " + std::to_string(alpha), run.report_file());
  report.note("zeta0 = " + std::to_string(zeta0) + ", t0 = " + std::to_string(2.0 / zeta0) +
              ", first-Sonine a2 = " + std::to_string(a2) + " (factor " + std::to_string(1.0 + 3.0 * a2 / 16.0) +
              "), Sonine orders 4-5 factor " + std::to_string(sonine) + " +- " + std::to_string(sonine_error));

  const auto temperature = validation::observable(run, "total_temperature");
  const auto collisions = validation::observable(run, "collisions_per_particle");
  const std::size_t nt = temperature.time.size();
  const bool have_error = !temperature.error.empty();
  if (!report.require("replicas > 1, so standard errors exist", have_error)) return report.exit_code();

  // 1. T(t)/T0 against the band [Haff Maxwellian rate, Haff Sonine rate].
  for (std::size_t i = 1; i < nt; ++i) {
    const double t = temperature.time[i];
    const double maxwell = theory::haff_temperature(t, t0_temperature, zeta0) / t0_temperature;
    const double scaled = theory::haff_temperature(t, t0_temperature, zeta0 * sonine) / t0_temperature;
    const double scaled_error =
        std::abs(theory::haff_temperature(t, t0_temperature, zeta0 * (1.0 + sonine_error)) /
                     t0_temperature - maxwell);
    const double middle = 0.5 * (maxwell + scaled);
    const double half_band = 0.5 * std::abs(maxwell - scaled) + scaled_error;
    char name[128];
    std::snprintf(name, sizeof name, "T/T0 at t = %.4g", t);
    report.check(name, temperature.value[i] / t0_temperature, temperature.error[i] / t0_temperature,
                 middle, 4.0, half_band);
  }

  // 2. Slope of T^(-1/2) in the scaling regime (>= 10 collisions per particle).
  std::size_t first = nt - 1;
  for (std::size_t i = 0; i < nt; ++i)
    if (collisions.value[i] >= 10.0) {
      first = i;
      break;
    }
  if (report.require("the run reaches the scaling regime (10 collisions per particle) before its end",
                     first + 2 < nt)) {
    const std::size_t last = nt - 1;
    const double ta = temperature.time[first], tb = temperature.time[last];
    const double xa = std::pow(temperature.value[first], -0.5), xb = std::pow(temperature.value[last], -0.5);
    // d(T^-1/2) = -(1/2) T^-3/2 dT
    const double ea = 0.5 * xa * temperature.error[first] / temperature.value[first];
    const double eb = 0.5 * xb * temperature.error[last] / temperature.value[last];
    const double slope = (xb - xa) / (tb - ta);
    const double slope_error = std::hypot(ea, eb) / (tb - ta);
    const double unit_rate = zeta0 / (2.0 * std::sqrt(t0_temperature));  // zeta/(2 sqrt T), Maxwellian
    report.check("slope of T^-1/2 (Sonine rate)", slope, slope_error, unit_rate * sonine, 3.0,
                 unit_rate * sonine_error);
    report.note("Maxwellian-rate slope would be " + std::to_string(unit_rate) +
                " (the Sonine correction is " + std::to_string(100.0 * (sonine - 1.0)) + " %)");
  }

  // 3. Two decades of temperature.
  const double decades = std::log10(temperature.value.front() / temperature.value.back());
  report.require("covers " + std::to_string(decades) + " >= 2 decades of temperature", decades >= 2.0);
  return report.exit_code();
}
