// gamma(t) = T1/T2 against the first-Sonine HCS value (seed 003 Fig 1). See README.md.
#include <cmath>

#include "theory/theory.hpp"
#include "validation.hpp"

using namespace gdsmc;

int main(int argc, char** argv) {
  const auto run = validation::run_case(argc, argv, "temperature_ratio_time.h5");
  validation::Report report("temperature ratio against time (seed 003 Fig 1)", run.report_file());
  const auto points = run.config.sweep_points();
  for (std::size_t p = 0; p < points.size(); ++p) {
    const auto mix = points[p].mixture();
    const double theory_gamma = theory::binary_hcs_first_sonine(mix).temperature_ratio;
    const std::string root = run.config.is_sweep() ? "/sweep/point_" + std::to_string(p + 1) + "/observables/"
                                                   : std::string();
    const auto t = io::h5md::read_observable(run.file, root + "temperature");
    if (!report.require("replicas > 1, so standard errors exist", !t.error.empty())) return report.exit_code();
    const std::size_t nt = t.time.size();
    auto gamma_at = [&](std::size_t i, double& se) {
      const double g = t.value[2 * i] / t.value[2 * i + 1];
      se = g * std::hypot(t.error[2 * i] / t.value[2 * i], t.error[2 * i + 1] / t.value[2 * i + 1]);
      return g;
    };
    double se_end, se_q;
    const double g_end = gamma_at(nt - 1, se_end);
    const double g_quarter = gamma_at(3 * (nt - 1) / 4, se_q);
    const std::string label = "alpha = " + std::to_string(mix.restitution(0, 0)).substr(0, 4) + ": ";
    report.check(label + "gamma at the end", g_end, se_end, theory_gamma, 3.0, 0.02 * theory_gamma);
    report.check(label + "gamma settled (3/4 of the run -> end)", g_end, std::hypot(se_end, se_q), g_quarter,
                 3.0, 0.01 * g_end);
  }
  return report.exit_code();
}
