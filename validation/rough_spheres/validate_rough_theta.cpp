// Rough spheres, one species, the homogeneous cooling state over a sweep of alpha and beta: theta, zeta* and
// the cumulants against the Sonine theory (theory/rough.hpp; \ref rough_sonine "docs/rough-spheres.md").
// See README.md in this folder.
#include <cmath>
#include <cstdio>
#include <string>

#include "analysis/compare.hpp"
#include "theory/rough.hpp"
#include "validation.hpp"

using namespace gdsmc;

namespace {

/// The value and standard error of an observable's single column at sample i.
struct Value {
  double value, error;
};
Value at(const io::h5md::ObservableData& o, std::size_t i) { return {o.value[i], o.error.empty() ? NAN : o.error[i]}; }

}  // namespace

int main(int argc, char** argv) {
  const auto run = validation::run_case(argc, argv, "rough_theta_alpha.h5");
  char title[160];
  std::snprintf(title, sizeof title, "Rough spheres, HCS over alpha and beta, kappa = %g", run.config.system.moment_of_inertia[0]);
  validation::Report report(title, run.report_file());
  report.note("theta and zeta* against the Sonine HCS at 4 SE + |Sonine - Maxwellian| (the size of the Sonine correction "
              "bounds the neglected terms); cumulants noted, not asserted; points without a Sonine state noted");
  const auto points = run.config.sweep_points();
  for (std::size_t p = 0; p < points.size(); ++p) {
    const auto mix = points[p].mixture();
    const double alpha = mix.restitution(0, 0), beta = mix.roughness(0, 0), kappa = mix.moment_of_inertia[0];
    const std::string root = run.config.is_sweep() ? "/sweep/point_" + std::to_string(p + 1) + "/observables/" : "/observables/";
    const auto tr = io::h5md::read_observable(run.file, root + "total_temperature");
    const auto rot = io::h5md::read_observable(run.file, root + "rotational_temperature");
    const auto time = io::h5md::read_observable(run.file, root + "time");
    if (!report.require("replicas > 1, so standard errors exist", !tr.error.empty())) return report.exit_code();
    const std::size_t i = tr.value.size() - 1;
    const Value ta = at(tr, i - 1), tb = at(tr, i), r = at(rot, i);
    const double theta = r.value / tb.value, theta_error = theta * std::hypot(r.error / r.value, tb.error / tb.value);
    const double nu_unit = theory::rough::frequency_unit(mix) / mix.pair_correlation(0, 0);
    // zeta* from T_tr(t) of the HCS (README): T^(-1/2) grows as zeta* nu_unit t/2
    const auto [zeta, zeta_error] =
        analysis::compare::hcs_zeta_star(ta.value, ta.error, tb.value, tb.error, time.value[i] - time.value[i - 1], nu_unit);
    const auto maxwell = theory::rough::cooling_state(alpha, beta, kappa);
    const auto sonine = theory::rough::sonine_cooling_state(alpha, beta, kappa);
    char name[220];
    if (!sonine.state) {
      std::snprintf(name, sizeof name, "alpha = %.2f, beta = %+.2f: theta %.4f +- %.4f, Maxwellian %.4f; zeta* %.4f +- %.4f, "
                    "Maxwellian %.4f; no Sonine state", alpha, beta, theta, theta_error, maxwell.theta, zeta, zeta_error,
                    maxwell.cooling_rate_reduced);
      report.note(name + std::string(": ") + sonine.why_not);
      continue;
    }
    const auto& st = *sonine.state;
    std::snprintf(name, sizeof name, "alpha = %.2f, beta = %+.2f: theta vs Sonine (Maxwellian %.4f)", alpha, beta, maxwell.theta);
    report.check(name, theta, theta_error, st.theta, 4.0, std::abs(st.theta - maxwell.theta));
    std::snprintf(name, sizeof name, "alpha = %.2f, beta = %+.2f: zeta* vs Sonine (Maxwellian %.4f)", alpha, beta,
                  maxwell.cooling_rate_reduced);
    report.check(name, zeta, zeta_error, st.cooling_rate_reduced, 4.0, std::abs(st.cooling_rate_reduced - maxwell.cooling_rate_reduced));
    std::string cumulants = "  cumulants (DSMC, Sonine):";
    for (const auto& [obs, theory_value] : {std::pair{"cumulant_a20", st.cumulants.a20}, std::pair{"cumulant_a02", st.cumulants.a02},
                                            std::pair{"cumulant_a11", st.cumulants.a11}}) {
      const Value a = at(io::h5md::read_observable(run.file, root + obs), i);
      char text[96];
      std::snprintf(text, sizeof text, " %s %.4f +- %.4f, %.4f;", obs + 9, a.value, a.error, theory_value);
      cumulants += text;
    }
    report.note(cumulants);
  }
  return report.exit_code();
}
