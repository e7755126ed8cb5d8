// <R_k^2>/<R_1^2> at the end of the run against eq 17 for many species (Bodrova and Osinsky 2024, Fig. 8, \ref dif_msd "docs/diffusion-msd.md"). See README.md.
//
// usage: validate_msd_ratio INPUT.nml [--set ...] [--output FILE] --gap g
#include <cmath>
#include <cstring>

#include "theory/theory.hpp"
#include "validation.hpp"

using namespace gdsmc;

int main(int argc, char** argv) {
  const auto gap_option = validation::take_option(argc, argv, "--gap");
  const double gap = gap_option ? std::stod(*gap_option) : -1.0;
  const auto run = validation::run_case(argc, argv, "msd_many_species.h5");
  const auto mix = run.config.mixture();
  const std::size_t s = mix.size();
  validation::Report report("<R_k^2>/<R_1^2> for " + std::to_string(s) + " species, theta = " +
                                std::to_string(run.config.system.density_exponent).substr(0, 3),
                            run.report_file());
  if (!report.require("--gap is given", gap >= 0.0)) return report.exit_code();
  const auto msd = validation::observable(run, "msd");
  if (!report.require("replicas > 1, so standard errors exist", !msd.error.empty())) return report.exit_code();
  const std::size_t e = msd.time.size() - 1;
  const auto eq17 = theory::mean_squared_displacement(mix, run.config.initial.temperature, {0.0, msd.time[e]});
  const double r1 = msd.value[e * s], r1_se = msd.error[e * s];
  double worst = 0.0;
  for (std::size_t k = 1; k < s; ++k) {
    const double ratio = msd.value[e * s + k] / r1;
    const double se = ratio * std::hypot(msd.error[e * s + k] / msd.value[e * s + k], r1_se / r1);
    const double theory_ratio = eq17.msd[1][k] / eq17.msd[1][0];
    worst = std::max(worst, std::abs(ratio / theory_ratio - 1.0));
    char name[128];
    std::snprintf(name, sizeof name, "k = %zu: <R_k^2>/<R_1^2> (DSMC/eq 17 - 1 = %+.1f %%)", k + 1,
                  100.0 * (ratio / theory_ratio - 1.0));
    report.check(name, ratio, se, theory_ratio, 4.0, gap * theory_ratio);
  }
  report.note("largest |DSMC/eq 17 - 1| = " + std::to_string(100.0 * worst) + " %");
  return report.exit_code();
}
