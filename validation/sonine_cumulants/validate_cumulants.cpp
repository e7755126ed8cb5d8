// c1, c2 of the binary HCS against first Sonine (Montanero and Garzo 2002, Fig. 2, \ref son_binary_cumulants "docs/sonine.md"). See README.md.
#include <algorithm>
#include <cmath>

#include "theory/theory.hpp"
#include "validation.hpp"

using namespace gdsmc;

namespace {

/// First Sonine's relative error for the cumulant of ONE species at this alpha, from the Sonine
/// hierarchy beyond it (theory::sonine_cumulant_bracket, orders K = 4 and 5; docs/sonine.md "Beyond first
/// Sonine"): (|c_first - c_bracket| + half-width)/|c_first|, an estimate independent of any DSMC output.
/// Applied to a mixture species as the same relative error of its first-Sonine c_k (README.md: tested at the
/// one mixture point with an exact value, mu = 2, alpha = 0.5: estimate 11.0 %, actual 10.4 %). Undefined
/// where the one-species c goes through zero (|c_first| < 0.01, 0.62 < alpha < 0.77): there is then no
/// independent estimate, and the check falls back to the measured allowance (a consistency check).
struct OneSpeciesEstimate {
  bool defined;
  double relative;     ///< the relative error above
  double c_first;      ///< one-species first Sonine 2 a2(alpha)
  double c_bracket, half_width;
};
OneSpeciesEstimate one_species_estimate(double alpha) {
  const double c_first = 2.0 * theory::sonine_a2(alpha);
  const auto bracket = theory::sonine_cumulant_bracket(alpha);
  const double relative = (std::abs(c_first - bracket.value) + bracket.half_width) / std::abs(c_first);
  return {std::abs(c_first) >= 0.01, relative, c_first, bracket.value, bracket.half_width};
}

}  // namespace

int main(int argc, char** argv) {
  const auto run = validation::run_case(argc, argv, "sonine_cumulants.h5");
  // First Sonine overestimates the cumulants (\ref son_one_species "docs/sonine.md": 9-14 % for one species, c1 = 0.1280 +- 0.0004
  // against 0.1428 at mu = 2, alpha = 0.5). Allowance (issue 13): the one-species estimate of first
  // Sonine's relative error at the same alpha (above), where it is defined; else the gap measured with the
  // paper tier of this check, 20 % of the first-Sonine value (README.md), a consistency check only.
  const double sonine_gap = 0.20;
  validation::Report report("Sonine cumulants c1, c2 against alpha", run.report_file());
  const auto points = run.config.sweep_points();
  for (std::size_t p = 0; p < points.size(); ++p) {
    const auto mix = points[p].mixture();
    const auto hcs = theory::binary_hcs_first_sonine(mix);
    const double alpha = mix.restitution(0, 0);
    const auto estimate = one_species_estimate(alpha);
    {
      char text[400];
      if (estimate.defined)
        std::snprintf(text, sizeof text,
                      "alpha = %.2f: allowance %.1f %% of first Sonine: one species at this alpha, first Sonine "
                      "%.5f against the K = 4/5 Sonine bracket %.5f +- %.5f (independent estimate, README.md)",
                      alpha, 100.0 * estimate.relative, estimate.c_first, estimate.c_bracket, estimate.half_width);
      else
        std::snprintf(text, sizeof text,
                      "alpha = %.2f: the one-species first-Sonine c = %.5f is near its sign change (bracket %.5f +- "
                      "%.5f): no independent estimate of first Sonine's error; c1, c2 are asserted against the "
                      "independent program (validation/independent_reference) and first Sonine is stated beside them; "
                      "without a table entry, a consistency check with the measured %.0f %% (README.md)",
                      alpha, estimate.c_first, estimate.c_bracket, estimate.half_width, 100.0 * sonine_gap);
      report.note(text);
    }
    const double allowance_share = estimate.defined ? estimate.relative : sonine_gap;
    const std::string root = run.config.is_sweep() ? "/sweep/point_" + std::to_string(p + 1) + "/observables/"
                                                   : std::string();
    const auto c = io::h5md::read_observable(run.file, root + "sonine_c");
    const auto coll = io::h5md::read_observable(run.file, root + "collisions_per_particle");
    if (!report.require("replicas > 1, so standard errors exist", !c.error.empty())) return report.exit_code();
    // Average over the scaling regime (>= 10 collisions per particle). Without the file's scaling_state
    // the mean of the per-sample SEs bounds the SE of the average (the samples are positively correlated
    // at most).
    for (std::size_t k = 0; k < 2; ++k) {
      double sum = 0.0, se = 0.0;
      std::size_t count = 0;
      for (std::size_t i = 0; i < coll.value.size(); ++i)
        if (coll.value[i] >= 10.0) {
          sum += c.value[2 * i + k];
          se += c.error[2 * i + k];
          ++count;
        }
      if (!report.require("samples in the scaling regime", count > 0)) return report.exit_code();
      double mean = sum / count;
      const double theory_c = hcs.sonine_c[k];
      // The file's scaling_state (each replica's own average over the same samples, SE over the replicas:
      // that of the time average itself) replaces the mean of the samples' SE, an upper bound.
      const auto state = validation::read_scaling_state(
          run.file, run.config.is_sweep() ? "/sweep/point_" + std::to_string(p + 1) + "/observables" : "/observables", 2);
      if (state.known && points[p].output.scaling_start == 10.0) {
        mean = state.c[k];
        se = state.c_error[k] * static_cast<double>(count);  // se / count below is the SE
        if (k == 0) report.note("alpha = " + std::to_string(alpha) + ": c_k of each replica averaged over its " +
                                std::to_string(count) + " samples, SE over the replicas (scaling_state)");
      }
      char name[300];
      const auto exact = k == 0 ? validation::exact_cumulant_species1(mix) : validation::ExactValue{};
      if (exact.known) {
        // Independent exact value (docs/sonine.md "How good it is"): 3 SE (combined) + 0.001 (the last
        // digit stated, as for one species).
        std::snprintf(name, sizeof name, "alpha = %.2f: c1 vs exact %.4f +- %.4f (DSMC/exact - 1 = %+.1f %%)",
                      mix.restitution(0, 0), exact.value, exact.error, 100.0 * (mean / exact.value - 1.0));
        report.check(name, mean, std::hypot(se / count, exact.error), exact.value, 3.0, 0.001);
        // The test of the one-species estimate (theory only): at this point the mixture's actual first-Sonine
        // error is known, |c1(first Sonine) - exact|; the estimate must cover it.
        char text[300];
        std::snprintf(text, sizeof text,
                      "alpha = %.2f: the one-species estimate of first Sonine's error, %.1f %% of c1 = %.5f, covers the "
                      "actual one against the exact value, %.1f %%",
                      alpha, 100.0 * estimate.relative, theory_c, 100.0 * std::abs(theory_c - exact.value) / theory_c);
        report.require(text, estimate.defined && estimate.relative * std::abs(theory_c) >= std::abs(theory_c - exact.value));
        continue;
      }
      // The second method (validation/independent_reference): the same c_k from a program that shares no
      // code with src/, at 4 combined SE with no allowance (issue 13).
      const auto independent = validation::independent_hcs_reference(mix);
      if (independent.known) {
        std::snprintf(name, sizeof name,
                      "alpha = %.2f: c%zu vs the independent program %.5f +- %.5f (DSMC - independent = %+.5f; 4 "
                      "combined SE, no allowance)",
                      alpha, k + 1, independent.cumulant[k], independent.cumulant_error[k], mean - independent.cumulant[k]);
        report.check(name, mean, std::hypot(se / count, independent.cumulant_error[k]), independent.cumulant[k], 4.0, 0.0);
      }
      std::snprintf(name, sizeof name, "alpha = %.2f: c%zu, %zu samples x %lld replicas (DSMC/Sonine - 1 = %+.1f %%; %s)",
                    alpha, k + 1, count, points[p].dsmc.replicas, 100.0 * (mean / theory_c - 1.0),
                    estimate.defined ? "allowance: one-species estimate" : "no independent estimate of first Sonine's error");
      if (estimate.defined || !independent.known) {
        report.check(name, mean, se / count, theory_c, 3.0, allowance_share * std::abs(theory_c));
      } else {
        // No estimate of first Sonine's error here: the theory is stated beside the DSMC, and the DSMC is
        // asserted against the independent program above instead of against a measured allowance.
        char text[400];
        std::snprintf(text, sizeof text, "%s: DSMC %.5f +- %.5f, first Sonine %.5f (stated, not asserted)", name, mean,
                      se / count, theory_c);
        report.note(text);
      }
    }
    report.note("one-component first Sonine c = 2 a2 = " + std::to_string(2.0 * theory::sonine_a2(mix.restitution(0, 0))));
    // gamma at the exact point (docs/sonine.md: 1.3616 for mu = 2, delta = 1, alpha = 0.5), the last
    // sample, 3 SE + 0.3 % (issue 13).
    const auto exact_gamma = validation::exact_temperature_ratio(mix);
    if (exact_gamma.known) {
      const auto t = io::h5md::read_observable(run.file, root + "temperature");
      const std::size_t i = t.time.size() - 1;
      const double gamma = t.value[2 * i] / t.value[2 * i + 1];
      const double se = gamma * std::hypot(t.error[2 * i] / t.value[2 * i], t.error[2 * i + 1] / t.value[2 * i + 1]);
      char name[200];
      std::snprintf(name, sizeof name, "alpha = %.2f: gamma vs exact %.4f (DSMC/exact - 1 = %+.2f %%; 3 SE + 0.3 %%)",
                    mix.restitution(0, 0), exact_gamma.value, 100.0 * (gamma / exact_gamma.value - 1.0));
      report.check(name, gamma, std::hypot(se, exact_gamma.error), exact_gamma.value, 3.0, 0.003 * exact_gamma.value);
    }
  }
  return report.exit_code();
}
