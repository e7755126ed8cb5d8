// Aggregation and fragmentation against the Smoluchowski rate equations (DSMC notes, eqs. (8)-(14), \ref af_outcome "docs/agg-frag.md",
// \ref af_smoluchowski "docs/agg-frag.md"). See README.md for the cases, the references and the tolerances.
//
// usage: validate_agg_frag INPUT.nml [--set ...] [--output F.h5] [--exact-until T]
//   Samples at t <= T (default: nu_0 t <= 0.15) are checked against the theory with statistics
//   only (z = 4): there the closure is exact to first order (Maxwellian monomers at t = 0).
//   Later samples are compared and the theory's drift is printed, not asserted: no independent
//   estimate of it exists beyond the one \ref af_accuracy "docs/agg-frag.md" gives for pure sticking (N_1 about 6 % low when
//   <k> = 8.5), which is checked where it applies (--sticking-drift on).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "analysis/predictions.hpp"
#include "theory/smoluchowski.hpp"
#include "validation.hpp"

using namespace gdsmc;

namespace {

double value_at(const io::h5md::ObservableData& d, std::size_t i, std::size_t column = 0) {
  const std::size_t width = d.shape.size() > 1 ? d.shape[1] : 1;
  return column < width ? d.value[i * width + column] : 0.0;
}
double error_at(const io::h5md::ObservableData& d, std::size_t i, std::size_t column = 0) {
  const std::size_t width = d.shape.size() > 1 ? d.shape[1] : 1;
  return d.error.empty() || column >= width ? 0.0 : d.error[i * width + column];
}

}  // namespace

int main(int argc, char** argv) {
  const auto exact_until_option = validation::take_option(argc, argv, "--exact-until");
  const bool sticking_drift = validation::take_option(argc, argv, "--sticking-drift").value_or("off") == "on";
  const auto run = validation::run_case(argc, argv, "agg_frag.h5");
  const auto& c = run.config;
  validation::Report report("aggregation and fragmentation: " + c.source_file, run.report_file());

  const theory::smoluchowski::Parameters p = analysis::smoluchowski_parameters(c);
  const double n0 = static_cast<double>(c.dsmc.n_particles);
  // nu_0 = 4 sqrt(pi) n sigma^2 sqrt(T0/m): collisions per monomer per unit time at t = 0 (\ref cm_frequency "docs/collision-model.md")
  const double nu0 = 4.0 * std::sqrt(M_PI) * p.monomer_density * p.monomer_diameter * p.monomer_diameter *
                     std::sqrt(p.initial_temperature / p.monomer_mass);
  const double exact_until = exact_until_option ? std::stod(*exact_until_option) : 0.15 / nu0;

  const auto number = validation::observable(run, "number");
  const auto monomers = validation::observable(run, "monomer_fraction");
  const auto mean_size = validation::observable(run, "mean_size");
  const auto temperature = validation::observable(run, "total_temperature");
  const auto energy = validation::observable(run, "kinetic_energy");
  const auto dissipated = validation::observable(run, "dissipated_energy");
  const auto collisions = validation::observable(run, "collisions");
  const auto aggregations = validation::observable(run, "aggregations");
  const auto fragmentations = validation::observable(run, "fragmentations");
  const std::size_t nt = monomers.time.size();
  if (!report.require("replicas > 1, so standard errors exist", !monomers.error.empty())) return report.exit_code();
  const std::size_t width = number.shape.size() > 1 ? number.shape[1] : 1;

  // 1. Exact bookkeeping in every sample (\ref af_observables "docs/agg-frag.md"): mass in monomers, and energy.
  double worst_mass = 0.0, worst_energy = 0.0;
  for (std::size_t i = 0; i < nt; ++i) {
    double mass = 0.0;
    for (std::size_t k = 0; k < width; ++k) mass += static_cast<double>(k + 1) * number.value[i * width + k];
    worst_mass = std::max(worst_mass, std::abs(mass - n0) / n0);
    worst_energy = std::max(worst_energy, std::abs(value_at(energy, i) + value_at(dissipated, i) -
                                                   1.5 * p.initial_temperature) / (1.5 * p.initial_temperature));
  }
  char text[300];
  std::snprintf(text, sizeof text, "sum_k k N_k = N_0 in every sample (replica mean): worst relative gap %.2e <= 1e-12",
                worst_mass);
  report.require(text, worst_mass <= 1e-12);
  std::snprintf(text, sizeof text,
                "E_kin + dissipated = E(0) in every sample (replica mean): worst relative gap %.2e <= 1e-10",
                worst_energy);
  report.require(text, worst_energy <= 1e-10);

  // 2. Theory on the sample times.
  const auto theory = theory::smoluchowski::solve(p, monomers.time);
  std::snprintf(text, sizeof text, "theory: sizes 1..%zu, mass lost beyond them %.2e (< 1e-8)", theory.max_size,
                theory.lost_mass_fraction);
  report.require(text, theory.lost_mass_fraction < 1e-8);
  const std::size_t kt = theory.max_size;
  auto theory_mean_size = [&](std::size_t i) {
    double clusters = 0.0;
    for (std::size_t k = 0; k < kt; ++k) clusters += theory.number_fraction[i * kt + k];
    return 1.0 / clusters;
  };

  struct Quantity {
    const char* name;
    const io::h5md::ObservableData* data;
    double scale;  // DSMC value * scale = the theory's quantity
    std::function<double(std::size_t)> theory;
    bool count = false;  // an event count: Poisson floor on its standard error (below)
  };
  const std::vector<Quantity> quantities = {
      {"N_1/N_0", &monomers, 1.0, [&](std::size_t i) { return theory.number_fraction[i * kt]; }},
      {"<k>", &mean_size, 1.0, theory_mean_size},
      {"T (per cluster)", &temperature, 1.0, [&](std::size_t i) { return theory.total_temperature[i]; }},
      {"E_kin per monomer", &energy, 1.0, [&](std::size_t i) { return theory.kinetic_energy[i]; }},
      {"collisions per monomer", &collisions, 1.0 / n0, [&](std::size_t i) { return theory.collisions[i]; }, true},
      {"aggregations per monomer", &aggregations, 1.0 / n0, [&](std::size_t i) { return theory.aggregations[i]; },
       true},
      {"fragmentations per monomer", &fragmentations, 1.0 / n0,
       [&](std::size_t i) { return theory.fragmentations[i]; }, true},
  };
  std::size_t exact_samples = 0;
  for (std::size_t i = 1; i < nt; ++i) {
    const double t = monomers.time[i];
    const bool exact = t <= exact_until * (1.0 + 1e-12);
    exact_samples += exact;
    for (const auto& q : quantities) {
      const double measured = value_at(*q.data, i) * q.scale;
      const double expected = q.theory(i);
      // A count of rare events (a few per replica, or none) has a sample standard error that can
      // be 0: its Poisson error, sqrt(expected events)/(R N_0) per monomer, is the floor.
      const double replicas = static_cast<double>(c.dsmc.replicas);
      const double error = std::max(error_at(*q.data, i) * q.scale,
                                    q.count ? std::sqrt(expected * n0 * replicas) / (n0 * replicas) : 0.0);
      if (expected == 0.0 && measured == 0.0) continue;  // e.g. no fragmentation in pure sticking
      std::snprintf(text, sizeof text, "%s at t = %.4g (nu_0 t = %.3g)", q.name, t, nu0 * t);
      if (exact) {
        report.check(text, measured, error, expected, 4.0);
      } else {
        char drift[512];
        std::snprintf(drift, sizeof drift, "%s: DSMC %.6g +- %.2g, theory %.6g: theory drift %+.2f %% (%.1f SE)", text,
                      measured, error, expected, 100.0 * (expected - measured) / measured,
                      error > 0 ? (expected - measured) / error : 0.0);
        report.note(drift);
      }
    }
  }
  report.require("at least one sample in the exact window (nu_0 t <= 0.15)", exact_samples > 0);

  // 3. Pure sticking: \ref af_accuracy "docs/agg-frag.md" measured the closure's drift independently: N_1 about 6 % low by the
  // time <k> = 8.5. The sample nearest <k> = 8.5 must show the theory low by 3-9 % (that statement
  // within +-50 % of itself, its precision as stated: "about").
  if (sticking_drift) {
    std::size_t best = 1;
    for (std::size_t i = 1; i < nt; ++i)
      if (std::abs(value_at(mean_size, i) - 8.5) < std::abs(value_at(mean_size, best) - 8.5)) best = i;
    const double measured = value_at(monomers, best), expected = theory.number_fraction[best * kt];
    const double low = (measured - expected) / measured;
    std::snprintf(text, sizeof text,
                  "sticking: at <k> = %.2f the theory's N_1 is %.2f %% low (docs/agg-frag.md: about 6 %% at <k> = 8.5; "
                  "accepted 3-9 %%)",
                  value_at(mean_size, best), 100.0 * low);
    report.require(text, low > 0.03 && low < 0.09);
  }
  return report.exit_code();
}
