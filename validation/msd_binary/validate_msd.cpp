// Partial MSDs against seed 001 eq 17 (ERRATA §8), Figs 1, 2, 6, 9, 10. See README.md.
//
// usage: validate_msd INPUT.nml [--set ...] [--output FILE] --gap g1,g2[,g3]
// `--gap` gives, per species, the relative systematic allowance of eq 17 for this case: the gap
// between eq 17 and DSMC measured once and stated in README.md (ERRATA §8: eq 17 is itself an
// approximation), never adjusted to make a run pass.
#include <cmath>
#include <cstring>

#include "theory/theory.hpp"
#include "validation.hpp"

using namespace gdsmc;

int main(int argc, char** argv) {
  const auto gap_option = validation::take_option(argc, argv, "--gap");
  const std::vector<double> gap = gap_option ? validation::number_list(*gap_option) : std::vector<double>{};
  const auto run = validation::run_case(argc, argv, "msd.h5");
  const auto mix = run.config.mixture();
  const std::size_t s = mix.size();
  validation::Report report("partial MSDs against eq 17, " + std::to_string(s) + " species, " +
                                run.config.system.restitution_model + " restitution",
                            run.report_file());
  if (!report.require("--gap gives one allowance per species", gap.size() == s)) return report.exit_code();
  const auto beta = run.config.viscoelastic_beta();
  const auto msd = validation::observable(run, "msd");
  if (!report.require("replicas > 1, so standard errors exist", !msd.error.empty())) return report.exit_code();
  // Measurement from msd_start_time (seed 001 Fig 3, dashed lines): eq 17 then starts from the
  // theory's temperatures at that time, T_1 != T_2, and counts time from there.
  const double start = run.config.output.msd_start_time.value_or(0.0);
  std::vector<double> start_temperature = run.config.initial.temperature;
  if (start > 0.0) {
    const auto at = beta ? theory::integrate_partial_temperatures_viscoelastic(mix, *beta, start_temperature, {0.0, start})
                         : theory::integrate_partial_temperatures(mix, start_temperature, {0.0, start});
    start_temperature = at.temperature.back();
  }
  // Samples before the start carry msd = 0 and are skipped.
  std::size_t first = 1;
  while (first < msd.time.size() && msd.time[first] <= start) ++first;
  std::vector<double> times;
  for (std::size_t i = 0; i < msd.time.size(); ++i) times.push_back(i < first ? 0.0 : msd.time[i] - start);
  std::vector<double> since(times.begin() + (first - 1), times.end());
  since[0] = 0.0;
  const auto tail = theory::mean_squared_displacement(mix, start_temperature, since, beta ? &*beta : nullptr);
  theory::MsdResult theory_msd;
  theory_msd.msd.assign(msd.time.size(), std::vector<double>(s, 0.0));
  for (std::size_t i = first; i < msd.time.size(); ++i) theory_msd.msd[i] = tail.msd[i - first + 1];
  const std::size_t nt = times.size();
  for (std::size_t i = first; i < nt; ++i)
    for (std::size_t k = 0; k < s; ++k) {
      const double th = theory_msd.msd[i][k], measured = msd.value[i * s + k];
      // Short times: eq 17 is ballistic to within its first collision correction (gap measured
      // <= 0.3 % at the first sample from t = 0), so that sample gets 1 %, the others the stated gap.
      const double allowance = (i == 1 && start == 0.0 ? 0.01 : gap[k]) * th;
      char name[128];
      std::snprintf(name, sizeof name, "<R_%zu^2>(t = %.3g) (DSMC/eq 17 - 1 = %+.1f %%)", k + 1, msd.time[i],
                    100.0 * (measured / th - 1.0));
      report.check(name, measured, msd.error[i * s + k], th, 4.0, allowance);
    }
  // Regimes: the start as ballistic as eq 17 says (within 0.05 in log-slope), slow at the end
  // (log-slope over the last decade of time).
  for (std::size_t k = 0; k < s; ++k) {
    std::size_t a = nt - 1;
    while (a > first && times[a] > times[nt - 1] / 10.0) --a;
    const double slope = std::log(msd.value[(nt - 1) * s + k] / msd.value[a * s + k]) /
                         std::log(times[nt - 1] / times[a]);
    const std::size_t p = first, q = first + 1;
    const double start_slope = std::log(msd.value[q * s + k] / msd.value[p * s + k]) / std::log(times[q] / times[p]);
    const double theory_start =
        std::log(theory_msd.msd[q][k] / theory_msd.msd[p][k]) / std::log(times[q] / times[p]);
    char text[240];
    std::snprintf(text, sizeof text,
                  "species %zu: d ln<R^2>/d ln t = %.3f at the start (eq 17: %.3f; ballistic 2) and %.3f over the "
                  "last decade (< 1: slower than normal diffusion)", k + 1, start_slope, theory_start, slope);
    report.require(text, std::abs(start_slope - theory_start) < 0.05 && slope < 1.0);
  }
  return report.exit_code();
}
