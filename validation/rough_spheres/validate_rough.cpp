// Rough spheres of one species against the Maxwellian two-temperature equations (theory/rough.hpp;
// \ref rough_maxwellian "docs/rough-spheres.md"). See README.md in this folder.
#include <cmath>
#include <cstdio>

#include "theory/rough.hpp"
#include "validation.hpp"

using namespace gdsmc;

int main(int argc, char** argv) {
  const auto run = validation::run_case(argc, argv, "rough_spheres.h5");
  const auto mix = run.config.mixture();
  const double alpha = mix.restitution(0, 0), beta = mix.roughness(0, 0), kappa = mix.moment_of_inertia[0];
  const double tr0 = run.config.initial.temperature[0], rot0 = run.config.initial.rotational_temperature[0];
  char title[160];
  std::snprintf(title, sizeof title, "Rough spheres, alpha = %g, beta = %g, kappa = %g", alpha, beta, kappa);
  validation::Report report(title, run.report_file());

  const auto tr = validation::observable(run, "total_temperature");
  const auto rot = validation::observable(run, "rotational_temperature");
  const auto c = validation::observable(run, "collisions_per_particle");
  const auto energy = validation::observable(run, "total_energy");
  if (!report.require("replicas > 1, so standard errors exist", !tr.error.empty())) return report.exit_code();
  const auto theory = theory::rough::integrate(mix, tr0, rot0, c.value, true);

  // 1. Early times (c <= 0.2): T(0) is set exactly, so the change since t = 0 carries only the noise of
  // the collisions; the Maxwellian equations are exact at t = 0 and off by O(c^2) after (README).
  for (std::size_t i = 1; i < c.value.size() && c.value[i] <= 0.2 + 1e-12; ++i) {
    char name[96];
    std::snprintf(name, sizeof name, "T_tr(c) - T_tr(0) at c = %g", c.value[i]);
    report.check(name, tr.value[i] - tr0, tr.error[i], theory.translational[i] - tr0, 4.0);
    std::snprintf(name, sizeof name, "T_rot(c) - T_rot(0) at c = %g", c.value[i]);
    report.check(name, rot.value[i] - rot0, rot.error[i], theory.rotational[i] - rot0, 4.0);
  }

  const std::size_t last = c.value.size() - 1;
  const double theta = rot.value[last] / tr.value[last];
  const double theta_error = theta * std::hypot(rot.error[last] / rot.value[last], tr.error[last] / tr.value[last]);
  const auto hcs = theory::rough::cooling_state(alpha, beta, kappa);
  if (alpha == 1.0 && beta == 1.0) {
    // 2. Elastic, perfectly rough: every collision keeps the energy, and the two temperatures equalise
    // (theta = 1 exactly).
    double drift = 0.0;
    for (double e : energy.value) drift = std::max(drift, std::abs(e / energy.value.front() - 1.0));
    report.require("the energy is conserved: largest relative drift " + std::to_string(drift) + " <= 1e-9", drift <= 1e-9);
    report.check("theta at the last sample (equipartition)", theta, theta_error, 1.0, 4.0);
  } else {
    char text[200];
    std::snprintf(text, sizeof text, "theta = T_rot/T_tr at c = %g: %.5f +- %.5f; Maxwellian HCS %.5f (not asserted: "
                  "no independent estimate of the Maxwellian theory's error)", c.value[last], theta, theta_error, hcs.theta);
    report.note(text);
  }
  for (const char* name : {"cumulant_a20", "cumulant_a02", "cumulant_a11"}) {
    const auto a = validation::observable(run, name);
    char text[120];
    std::snprintf(text, sizeof text, "%s at c = %g: %.5f +- %.5f", name, c.value[last], a.value[last], a.error[last]);
    report.note(text);
  }
  return report.exit_code();
}
