// D_k/D_1 (Bodrova and Osinsky 2024, eq. (19), \ref dif_coefficients "docs/diffusion-msd.md") against DSMC, Figs 4, 5, 7. See README.md.
//
// usage: validate_diffusion_ratio INPUT.nml [--set ...] [--output FILE]
//        validate_diffusion_ratio INPUT.nml [--set ...] [--output FILE] --check elastic
// The systematic allowance of every ratio is an independent estimate of the error of the first
// (Maxwellian, first Sonine) approximation behind eqs 17 and 19: the change of D_k/D_1 from one to
// three Sonine functions of the inelastic tracer problem in the homogeneous cooling state, plus the
// tail beyond three functions estimated from the slowest-converging exactly known case (the Lorentz
// gas), at the point's masses, sizes, densities, restitution and asymptotic temperature ratios
// (\ref dif_second_sonine_inelastic "docs/diffusion-msd.md"; theory::tracer_diffusion_sonine_ratio).
#include <cmath>
#include <cstring>
#include <string>

#include "theory/theory.hpp"
#include "validation.hpp"

using namespace gdsmc;

namespace {

// Elastic gas (--check elastic, README.md "Elastic mixture"): T_k stay at T_k(0) = T, every species is
// Maxwellian, and the MSD grows as 6 D_k t at t >> tau_v,k. D_k from the slope of the MSD over the last
// decade against the third Sonine (Chapman-Enskog) approximation [D_k]_3 = [D_k]_1 [D_k]_3/[D_k]_1
// (\ref dif_second_sonine_inelastic "docs/diffusion-msd.md"), [D_k]_1 = Bodrova and Osinsky 2024, eq. (19)
// at alpha = 1 (\ref dif_coefficients "docs/diffusion-msd.md"). Allowance for the Sonine terms beyond the
// third: theory::sonine_tail_factor ([D_k]_3 - [D_k]_2), the tail of the slowest-converging case whose
// converged value is known (the Lorentz gas: 1.07 times the last increment).
int check_elastic(int argc, char** argv) {
  const auto run = validation::run_case(argc, argv, "diffusion_elastic.h5");
  const auto mix = run.config.mixture();
  const std::size_t s = mix.size();
  validation::Report report("elastic mixture: D_k against the third Sonine (Chapman-Enskog) approximation", run.report_file());
  bool elastic = true;
  for (std::size_t k = 0; k < s; ++k)
    for (std::size_t j = 0; j < s; ++j) elastic = elastic && mix.restitution(k, j) == 1.0;
  const auto& t0 = run.config.initial.temperature;
  bool equal = true;
  for (std::size_t k = 0; k < s; ++k) equal = equal && t0[k] == t0[0];
  if (!report.require("every restitution coefficient is 1 and every T_k(0) the same", elastic && equal))
    return report.exit_code();
  const auto msd = validation::observable(run, "msd");
  if (!report.require("replicas > 1, so standard errors exist", !msd.error.empty())) return report.exit_code();
  const auto first = theory::diffusion_coefficients(mix, t0);
  const auto sonine = theory::tracer_diffusion_sonine_ratios(mix, t0);
  const auto& second = sonine[1];
  const auto& third = sonine[2];
  const auto tau_inverse = theory::inverse_velocity_correlation_time(mix, t0);
  const std::size_t e = msd.time.size() - 1;
  std::size_t a = e;
  while (a > 1 && msd.time[a] > msd.time[e] / 10.0) --a;
  char text[400];
  std::snprintf(text, sizeof text, "ensemble: %lld replicas x %lld particles, %s scheme; slope over t = %g..%g",
                run.config.dsmc.replicas, run.config.dsmc.n_particles, name(run.config.dsmc.scheme).c_str(), msd.time[a],
                msd.time[e]);
  report.note(text);
  for (std::size_t k = 0; k < s; ++k) {
    double rate = 0.0;
    for (std::size_t i = 0; i < s; ++i) rate += tau_inverse(k, i);
    // The Ornstein-Uhlenbeck form (\ref dif_limits "docs/diffusion-msd.md"): the increment from t_a to t_e is
    // 6 D [dt - tau_v (exp(-t_a/tau_v) - exp(-t_e/tau_v))]; require the second term below 1e-3 of the first.
    const double dt = msd.time[e] - msd.time[a];
    const double offset = std::exp(-msd.time[a] * rate) / (rate * dt);
    std::snprintf(text, sizeof text, "species %zu: t = %g..%g, tau_v = %g: velocity-correlation remainder %.2g < 1e-3",
                  k + 1, msd.time[a], msd.time[e], 1.0 / rate, offset);
    if (!report.require(text, offset < 1e-3)) continue;
    const double d = (msd.value[e * s + k] - msd.value[a * s + k]) / (6.0 * dt);
    const double d_se = std::hypot(msd.error[e * s + k], msd.error[a * s + k]) / (6.0 * dt);
    const double reference = first[k] * third[k];
    const double allowance = theory::sonine_tail_factor * std::abs(third[k] - second[k]) / third[k];
    std::snprintf(text, sizeof text,
                  "D_%zu (DSMC/[D]_3 - 1 = %+.2f %%, DSMC/[D]_2 - 1 = %+.2f %%, DSMC/[D]_1 - 1 = %+.2f %%) [allowance "
                  "%.2f %%: 1.07 x the third Sonine increment %.2f %%]",
                  k + 1, 100.0 * (d / reference - 1.0), 100.0 * (d / (first[k] * second[k]) - 1.0),
                  100.0 * (d / first[k] - 1.0), 100.0 * allowance, 100.0 * (third[k] / second[k] - 1.0));
    report.check(text, d, d_se, reference, 4.0, allowance * reference);
  }
  return report.exit_code();
}

}  // namespace

int main(int argc, char** argv) {
  const std::string check = validation::take_option(argc, argv, "--check").value_or("ratio");
  if (check == "elastic") return check_elastic(argc, argv);
  const auto run = validation::run_case(argc, argv, "diffusion_ratio.h5");
  validation::Report report("diffusion coefficient ratios D_k/D_1", run.report_file());
  const auto points = run.config.sweep_points();
  char text[400];
  std::snprintf(text, sizeof text, "ensemble: %lld replicas x %lld particles per point, %s scheme",
                run.config.dsmc.replicas, run.config.dsmc.n_particles, name(run.config.dsmc.scheme).c_str());
  report.note(text);
  for (std::size_t p = 0; p < points.size(); ++p) {
    const auto mix = points[p].mixture();
    const std::size_t s = mix.size();
    const auto long_time_ratio = theory::diffusion_coefficient_ratio(mix);  // eq 19, t -> infinity
    // Independent estimate of the first approximation's error: Sonine approximations with two and
    // three functions at the asymptotic temperature ratios (\ref dif_second_sonine_inelastic "docs/diffusion-msd.md").
    const auto hcs_temperature = theory::asymptotic_temperature_ratios(mix);
    const auto sonine = theory::tracer_diffusion_sonine_ratios(mix, hcs_temperature);
    const auto& second = sonine[1];
    const auto& third = sonine[2];
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
      // D_k/D_1 with two and three Sonine functions, relative to the first Sonine ratio.
      const double ratio2 = second[k] / second[0], ratio3 = third[k] / third[0];
      const double allowance = std::abs(ratio3 - 1.0) + theory::sonine_tail_factor * std::abs(ratio3 - ratio2);
      if (!report.require("point " + std::to_string(p + 1) + ": a Sonine estimate exists for D_" + std::to_string(k + 1) +
                              "/D_1 (the truncated systems have positive solutions)",
                          std::isfinite(allowance)))
        continue;
      std::snprintf(text, sizeof text,
                    "point %zu: D_%zu/D_1 over t = %g..%g: DSMC/theory - 1 = %+.1f %% (eq 19 long-time %.4g); "
                    "Sonine approximations change it by %+.2f %% (two functions), %+.2f %% (three)",
                    p + 1, k + 1, msd.time[a], msd.time[e], 100.0 * (ratio / theory_ratio - 1.0), long_time_ratio[k],
                    100.0 * (ratio2 - 1.0), 100.0 * (ratio3 - 1.0));
      report.note(text);
      std::snprintf(text, sizeof text,
                    "point %zu D_%zu/D_1 [allowance %.2f %%: third Sonine change + 1.07 x its last increment]", p + 1,
                    k + 1, 100.0 * allowance);
      report.check(text, ratio, se, theory_ratio, 4.0, allowance * theory_ratio);
    }
  }
  return report.exit_code();
}
