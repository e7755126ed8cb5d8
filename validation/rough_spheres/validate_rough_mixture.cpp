// A binary mixture of rough spheres against the Maxwellian equations of rough mixtures (theory/rough.hpp
// integrate_mixture, mixture_cooling_state; \ref rough_mixtures "docs/rough-spheres.md"). See README.md here.
#include <cmath>
#include <cstdio>
#include <string>

#include "theory/rough.hpp"
#include "validation.hpp"

using namespace gdsmc;

int main(int argc, char** argv) {
  const auto run = validation::run_case(argc, argv, "rough_binary.h5");
  const auto mix = run.config.mixture();
  const std::size_t s = mix.size();
  validation::Report report("Rough binary mixture: Maxwellian exchange rates and HCS", run.report_file());
  const auto tr = validation::observable(run, "temperature");
  const auto rot = validation::observable(run, "rotational_temperature");
  const auto total = validation::observable(run, "total_temperature");
  const auto c = validation::observable(run, "collisions_per_particle");
  if (!report.require("replicas > 1, so standard errors exist", !tr.error.empty())) return report.exit_code();
  const auto& t0 = run.config.initial.temperature;
  const auto& r0 = run.config.initial.rotational_temperature;
  const auto theory = theory::rough::integrate_mixture(mix, t0, r0, c.value, true);

  // 1. Early times (c <= 0.2): each species' change of T and T_rot against the Maxwellian equations, exact at
  // t = 0 (README: the cumulants' correction is far below the SE there).
  for (std::size_t i = 1; i < c.value.size() && c.value[i] <= 0.2 + 1e-12; ++i)
    for (std::size_t k = 0; k < s; ++k) {
      char name[96];
      std::snprintf(name, sizeof name, "species %zu: T(c) - T(0) at c = %g", k + 1, c.value[i]);
      report.check(name, tr.value[i * s + k] - t0[k], tr.error[i * s + k], theory.translational[i][k] - t0[k], 4.0);
      std::snprintf(name, sizeof name, "species %zu: T_rot(c) - T_rot(0) at c = %g", k + 1, c.value[i]);
      report.check(name, rot.value[i * s + k] - r0[k], rot.error[i * s + k], theory.rotational[i][k] - r0[k], 4.0);
    }

  // 2. The relaxed state beside the Maxwellian HCS (noted: no independent estimate of its error).
  const auto hcs = theory::rough::mixture_cooling_state(mix);
  const std::size_t last = c.value.size() - 1;
  for (std::size_t k = 0; k < s && !hcs.theta.empty(); ++k) {
    const double tk = tr.value[last * s + k], rk = rot.value[last * s + k], mean = total.value[last];
    const double share_error = tk / mean * std::hypot(tr.error[last * s + k] / tk, total.error[last] / mean);
    const double theta_error = rk / tk * std::hypot(rot.error[last * s + k] / rk, tr.error[last * s + k] / tk);
    char text[200];
    std::snprintf(text, sizeof text, "species %zu at c = %g: T_k/T %.4f +- %.4f (Maxwellian %.4f), theta_k %.4f +- %.4f "
                  "(Maxwellian %.4f)", k + 1, c.value[last], tk / mean, share_error, hcs.translational_over_mean[k], rk / tk,
                  theta_error, hcs.theta[k]);
    report.note(text);
  }
  return report.exit_code();
}
