// D_k/D_1 (Bodrova and Osinsky 2024, eq. (19), \ref dif_coefficients "docs/diffusion-msd.md") against DSMC, Figs 4, 5, 7. See README.md.
//
// usage: validate_diffusion_ratio INPUT.nml [--set ...] [--output FILE] --gap g
// `--gap`: the relative systematic allowance of the theory ratio for this case, measured once and
// stated in README.md.
#include <cmath>
#include <cstring>

#include "theory/theory.hpp"
#include "validation.hpp"

using namespace gdsmc;

int main(int argc, char** argv) {
  const auto gap_option = validation::take_option(argc, argv, "--gap");
  const double gap = gap_option ? std::stod(*gap_option) : -1.0;
  const auto run = validation::run_case(argc, argv, "diffusion_ratio.h5");
  validation::Report report("diffusion coefficient ratios D_k/D_1", run.report_file());
  if (!report.require("--gap is given", gap >= 0.0)) return report.exit_code();
  const auto points = run.config.sweep_points();
  for (std::size_t p = 0; p < points.size(); ++p) {
    const auto mix = points[p].mixture();
    const std::size_t s = mix.size();
    const auto long_time_ratio = theory::diffusion_coefficient_ratio(mix);  // eq 19, t -> infinity
    const std::string root = run.config.is_sweep() ? "/sweep/point_" + std::to_string(p + 1) + "/observables/" : "";
    const auto msd = io::h5md::read_observable(run.file, root + "msd");
    if (!report.require("replicas > 1, so standard errors exist", !msd.error.empty())) return report.exit_code();
    // In the HCS every D_k(t) has the same time dependence, so the ratio of the MSD increments over
    // the last decade of time is D_k/D_1 (Bodrova and Osinsky 2024, eqs. (17), (19), \ref dif_msd "docs/diffusion-msd.md").
    const std::size_t nt = msd.time.size(), e = nt - 1;
    std::size_t a = e;
    while (a > 1 && msd.time[a] > msd.time[e] / 10.0) --a;
    // Theory over the same interval: eq 17's increments. They tend to eq 19's D_k/D_1, but a heavy
    // dilute species keeps long velocity correlations, and over a finite decade its increment is
    // still short of the diffusive one (eq 17 accounts for that, eq 19 alone does not).
    const std::vector<double> times(msd.time.begin(), msd.time.end());
    const auto eq17 = theory::mean_squared_displacement(mix, points[p].initial.temperature, times);
    const double d1 = msd.value[e * s] - msd.value[a * s];
    const double d1_se = std::hypot(msd.error[e * s], msd.error[a * s]);
    for (std::size_t k = 1; k < s; ++k) {
      const double dk = msd.value[e * s + k] - msd.value[a * s + k];
      const double dk_se = std::hypot(msd.error[e * s + k], msd.error[a * s + k]);
      const double ratio = dk / d1, se = ratio * std::hypot(dk_se / dk, d1_se / d1);
      const double theory_ratio =
          (eq17.msd[e][k] - eq17.msd[a][k]) / (eq17.msd[e][0] - eq17.msd[a][0]);
      char name[200];
      std::snprintf(name, sizeof name, "point %zu: D_%zu/D_1 over the last decade (DSMC/theory - 1 = %+.1f %%; "
                    "eq 19 long-time %.4g)", p + 1, k + 1, 100.0 * (ratio / theory_ratio - 1.0), long_time_ratio[k]);
      report.check(name, ratio, se, theory_ratio, 4.0, gap * theory_ratio);
    }
  }
  return report.exit_code();
}
