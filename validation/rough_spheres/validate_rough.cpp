// Rough spheres of one species against the Maxwellian two-temperature equations and the Sonine HCS
// (theory/rough.hpp; \ref rough_maxwellian and \ref rough_sonine "docs/rough-spheres.md"). See README.md here.
#include <algorithm>
#include <cmath>
#include <string>
#include <cstdio>

#include "analysis/compare.hpp"
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
  } else if (const auto sonine = theory::rough::sonine_cooling_state(alpha, beta, kappa); sonine.state) {
    // 3. The relaxed state against the Sonine HCS: theta and zeta* within 4 SE plus the size of the Sonine
    // correction itself (|Sonine - Maxwellian|), the estimate of what the truncation leaves out (README).
    const auto& st = *sonine.state;
    report.check("theta = T_rot/T_tr at the last sample vs Sonine HCS (allowance |Sonine - Maxwellian|)", theta, theta_error,
                 st.theta, 4.0, std::abs(st.theta - hcs.theta));
    const auto t = validation::observable(run, "time");
    const double nu_unit = theory::rough::frequency_unit(mix) / mix.pair_correlation(0, 0);
    const auto [zeta, zeta_error] = analysis::compare::hcs_zeta_star(tr.value[last - 1], tr.error[last - 1], tr.value[last],
                                                                     tr.error[last], t.value[last] - t.value[last - 1], nu_unit);
    report.check("zeta* = zeta/nu_M over the last two samples vs Sonine HCS (allowance |Sonine - Maxwellian|)", zeta,
                 zeta_error, mix.pair_correlation(0, 0) * st.cooling_rate_reduced, 4.0,
                 mix.pair_correlation(0, 0) * std::abs(st.cooling_rate_reduced - hcs.cooling_rate_reduced));
    char text[200];
    std::snprintf(text, sizeof text, "Sonine HCS cumulants (not asserted): a20 %.5f, a02 %.5f, a11 %.5f; Maxwellian theta %.5f",
                  st.cumulants.a20, st.cumulants.a02, st.cumulants.a11, hcs.theta);
    report.note(text);
  } else {
    report.note("theta = " + std::to_string(theta) + " +- " + std::to_string(theta_error) + "; Maxwellian HCS " +
                std::to_string(hcs.theta) + "; no Sonine HCS: " + sonine.why_not);
  }
  return report.exit_code();
}
