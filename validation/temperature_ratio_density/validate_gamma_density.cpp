// gamma = T1/T2 of the Enskog HCS against n* (Montanero and Garzo 2002, Fig. 6, \ref son_binary_gamma "docs/sonine.md"). See README.md.
#include <cmath>

#include "theory/theory.hpp"
#include "validation.hpp"

using namespace gdsmc;

int main(int argc, char** argv) {
  const auto run = validation::run_case(argc, argv, "temperature_ratio_density.h5");
  const double alpha = run.config.system.restitution(0, 0);
  validation::Report report("gamma against n*, alpha = " + std::to_string(alpha).substr(0, 4), run.report_file());
  const auto points = run.config.sweep_points();
  double gamma_first = 0.0, se_first = 0.0, theory_first = 0.0, independent_first_se = 0.0;
  bool independent_first = false;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const auto mix = points[p].mixture();
    const double sigma12 = mix.contact_distance(0, 1);
    // A dilute run (enskog = .false.: gamma(alpha, 0) of the figure's normalisation) is n* = 0.
    const double n_star = mix.enskog ? mix.total_density() * sigma12 * sigma12 * sigma12 : 0.0;
    const double theory_gamma = theory::binary_hcs_first_sonine(mix).temperature_ratio;
    const auto dilute = species::make_mixture(mix.mass, mix.diameter, mix.number_density, mix.restitution, false);
    const double theory_dilute = theory::binary_hcs_first_sonine(dilute).temperature_ratio;
    const std::string root = "/sweep/point_" + std::to_string(p + 1) + "/observables/";
    const auto t = io::h5md::read_observable(run.file, run.config.is_sweep() ? root + "temperature" : "temperature");
    if (!report.require("replicas > 1, so standard errors exist", !t.error.empty())) return report.exit_code();
    const std::size_t i = t.time.size() - 1;
    const double gamma = t.value[2 * i] / t.value[2 * i + 1];
    const double se = gamma * std::hypot(t.error[2 * i] / t.value[2 * i], t.error[2 * i + 1] / t.value[2 * i + 1]);
    // Allowance (issue 13; was 2 %): first Sonine's own correction |gamma(first Sonine) - gamma(Maxwellian)|
    // at the same n* (the Maxwellian ODE with chi_ij, \ref haff_mixture_odes "docs/haff-and-mixtures.md", \ref cm_chi "docs/collision-model.md"), an estimate of the next correction's
    // size independent of this code's output (docs/sonine.md: at the two exact dilute cases the next
    // correction is 1/7 and 1/60 of it).
    const auto maxwell = theory::asymptotic_temperature_ratios(mix);
    const double correction = std::abs(theory_gamma - maxwell[0] / maxwell[1]);
    char name[200];
    std::snprintf(name, sizeof name, "n* = %.2f: gamma (DSMC - Sonine = %+.2f %%, allowance %.2f %%)", n_star,
                  100.0 * (gamma / theory_gamma - 1.0), 100.0 * correction / theory_gamma);
    report.check(name, gamma, se, theory_gamma, 3.0, correction);
    // The second method (validation/independent_reference, issue 13): gamma of the homogeneous Enskog
    // gas from a program that shares no code with src/ (its own chi_ij), 4 combined SE, no allowance.
    const auto independent = validation::independent_hcs_reference(mix);
    double gamma_independent = 0.0, gamma_independent_se = 0.0;
    if (independent.known) {
      // T_1/T_2 from T_k/T; the two ratios are tied by x_1 T_1/T + x_2 T_2/T = 1, so the SE of gamma is
      // that of T_2/T times d gamma/d(T_2/T) = -(x_2/x_1 + gamma) / (T_2/T).
      const double x1 = mix.mole_fraction(0), x2 = mix.mole_fraction(1);
      gamma_independent = independent.ratio[0] / independent.ratio[1];
      gamma_independent_se = (x2 / x1 + gamma_independent) * independent.ratio_error[1] / independent.ratio[1];
      std::snprintf(name, sizeof name, "n* = %.2f: gamma vs the independent program %.4f +- %.4f (4 combined SE, no allowance)",
                    n_star, gamma_independent, gamma_independent_se);
      report.check(name, gamma, std::hypot(se, gamma_independent_se), gamma_independent, 4.0, 0.0);
    }
    std::snprintf(name, sizeof name, "n* = %.2f: gamma(n*)/gamma(0) = %.4f (DSMC over dilute theory), theory %.4f",
                  n_star, gamma / theory_dilute, theory_gamma / theory_dilute);
    report.note(name);
    // The density dependence gamma(n*)/gamma(first n*): against the independent program's ratio at 4
    // combined SE with no allowance where its table has both points (issue 13); else against first
    // Sonine's ratio with 3 SE + 1 % (the size of the gaps Figs 4-5 show; a consistency check).
    if (p == 0) {
      gamma_first = gamma;
      se_first = se;
      theory_first = independent.known ? gamma_independent : theory_gamma;
      independent_first = independent.known;
      independent_first_se = gamma_independent_se;
    } else {
      const double ratio = gamma / gamma_first, ratio_se = ratio * std::hypot(se / gamma, se_first / gamma_first);
      if (independent.known && independent_first) {
        const double reference = gamma_independent / theory_first;
        const double reference_se = reference * std::hypot(gamma_independent_se / gamma_independent,
                                                           independent_first_se / theory_first);
        std::snprintf(name, sizeof name,
                      "n* = %.2f: gamma / gamma(n* = first) vs the independent program (4 combined SE, no allowance)",
                      n_star);
        report.check(name, ratio, std::hypot(ratio_se, reference_se), reference, 4.0, 0.0);
      } else {
        std::snprintf(name, sizeof name, "n* = %.2f: gamma / gamma(n* = first) (consistency check: 1 %%)", n_star);
        report.check(name, ratio, ratio_se, theory_gamma / theory_first, 3.0, 0.01 * theory_gamma / theory_first);
      }
    }
  }
  return report.exit_code();
}
