// The reduced distributions of the binary HCS (Montanero and Garzo 2002, Figs. 3 and 7; and of the HSS, Montanero 2003 Fig. 2, \ref son_reduced_distributions "docs/sonine.md"). See README.md.
#include <cmath>
#include <fstream>

#include "theory/sonine.hpp"
#include "theory/theory.hpp"
#include "validation.hpp"

using namespace gdsmc;

namespace {
std::vector<double> dataset(const std::string& file, const std::string& path) {
  return io::h5md::read_dataset(file, path).data;
}
}  // namespace

int main(int argc, char** argv) {
  const auto independent_file = validation::take_option(argc, argv, "--independent");
  const auto run = validation::run_case(argc, argv, "hcs_distribution.h5");
  const auto mix = run.config.mixture();
  const double alpha = mix.restitution(0, 0);
  // The HSS of the Gaussian thermostat (homogeneous_steady_state/hss_fig2.nml) has the HCS's scaled state.
  const bool hss = run.config.thermostat.kind == io::config::ThermostatKind::gaussian;
  validation::Report report(std::string(hss ? "HSS (Gaussian thermostat)" : "HCS") + " distributions, alpha = " +
                                std::to_string(alpha).substr(0, 4),
                            run.report_file());
  const auto hcs = theory::binary_hcs_first_sonine(mix);
  const std::string group = "/observables/reduced_distribution";
  const std::string sp = group + "/species_1";
  const auto edges = dataset(run.file, group + "/bin_edges");
  const auto phi = dataset(run.file, sp + "/value"), phi_error = dataset(run.file, sp + "/error");
  const auto delta = dataset(run.file, sp + "/delta"), delta_error = dataset(run.file, sp + "/delta_error");
  const auto g = dataset(run.file, sp + "/g"), g_error = dataset(run.file, sp + "/g_error");
  const double lambda = io::h5md::read_double_attribute(run.file, sp, "lambda");
  const double zeta = io::h5md::read_double_attribute(run.file, group, "cooling_rate_reduced");
  const double zeta_error = io::h5md::read_double_attribute(run.file, group, "cooling_rate_reduced_error");
  const double beta = io::h5md::read_double_attribute(run.file, sp, "tail_beta");

  // The reduced cooling rate of the HCS (eq 45 common value) against first Sonine.
  // Allowance (issue 13), an estimate independent of this code's output: the first-Sonine correction
  // to zeta*, |zeta*(first Sonine) - zeta*(Maxwellian)|, times first Sonine's relative error on that
  // correction for one species at the same alpha, from the order 4-5 Sonine bracket (docs/sonine.md
  // "Beyond first Sonine"): (|f_1S - f_45| + half-width)/|f_1S - 1|, f = zeta/zeta_Maxwell
  // (0.13 at alpha = 0.5, 0.27 at alpha = 0.3). Was 2 % of zeta*.
  const auto maxwell = theory::asymptotic_temperature_ratios(mix);
  const double zeta_maxwell = theory::binary_sonine_coefficients(mix, maxwell[0] / maxwell[1]).zeta0[0];
  const auto bracket = theory::sonine_cumulant_bracket(alpha);
  const double f_first = 1.0 + 3.0 * theory::sonine_a2(alpha) / 16.0;  // docs/sonine.md, one species
  const double relative_error =
      (std::abs(f_first - bracket.cooling_factor) + bracket.cooling_half_width) / std::abs(f_first - 1.0);
  const double zeta_allowance = std::abs(hcs.cooling_rate - zeta_maxwell) * relative_error;
  report.note("zeta*: first Sonine " + std::to_string(hcs.cooling_rate) + ", Maxwellian " +
              std::to_string(zeta_maxwell) + ", first Sonine's relative error on the correction (one species) " +
              std::to_string(relative_error));
  report.check("zeta* (reduced cooling rate) vs first Sonine", zeta, zeta_error,
               hcs.cooling_rate, 3.0, zeta_allowance);

  // Fig 3: Delta_1(v*) against the Sonine polynomial (eq 28) over thermal speeds, 0.3 <= lambda v*^2 <= 3.
  // With --independent FILE (validation/independent_reference: Phi_1(v*) on the same bins from a program
  // that shares no code with src/), Phi_1 is asserted against it bin by bin at 4 combined SE with no
  // allowance, and eq 28, which omits the higher Sonine terms, is stated beside it (issue 13). Without it,
  // Delta_1 vs eq 28 with 0.35: the largest gap measured with the paper tier + 25 % (a consistency check).
  const double higher_sonine = 0.35;
  std::vector<double> reference, reference_error;
  if (independent_file) {
    std::ifstream in(*independent_file);
    std::string word;
    while (in >> word) {
      if (word != "phi") {
        std::string rest;
        std::getline(in, rest);
        continue;
      }
      std::size_t b = 0;
      double lo = 0, hi = 0, value = 0, error = 0;
      in >> b >> lo >> hi >> value >> error;
      if (b != reference.size() || b + 1 >= edges.size() || std::abs(lo - edges[b]) > 1e-6 ||
          std::abs(hi - edges[b + 1]) > 1e-6)
        break;
      reference.push_back(value);
      reference_error.push_back(error);
    }
    if (!report.require("the independent Phi_1 has the run's bins (" + *independent_file + ")",
                        reference.size() + 1 == edges.size()))
      return report.exit_code();
  }
  double worst = 0.0;
  for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
    const double v = 0.5 * (edges[b] + edges[b + 1]), x = lambda * v * v;
    if (x < 0.3 || x > 3.0) continue;
    const double sonine = 0.5 * x * x - 2.5 * x + 15.0 / 8.0;  // eq 28
    worst = std::max(worst, std::abs(delta[b] - sonine));
    char name[200];
    if (!reference.empty()) {
      std::snprintf(name, sizeof name,
                    "Phi_1(v* = %.3f) vs the independent program (4 combined SE, no allowance; Delta_1 %.3f, eq 28 %.3f)",
                    v, delta[b], sonine);
      report.check(name, phi[b], std::hypot(phi_error[b], reference_error[b]), reference[b], 4.0, 0.0);
    } else {
      std::snprintf(name, sizeof name, "Delta_1(v* = %.3f) vs eq 28 (consistency check, measured allowance)", v);
      report.check(name, delta[b], delta_error[b], sonine, 3.0, higher_sonine);
    }
  }
  report.note("largest |Delta_1 - eq 28| over the thermal range: " + std::to_string(worst) +
              (reference.empty() ? "" : " (eq 28 omits the higher Sonine terms; stated, not asserted)"));

  // Fig 7: G_1 = exp(2 beta v*/zeta*) Phi_1 flattens at large v* (eqs 21, 29-30). Window: beyond the
  // thermal range (lambda v*^2 >= 9) while Phi is still measured to 20 %. Weighted fit of ln G.
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, v_first = 0, v_last = 0;
  int used = 0;
  for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
    const double v = 0.5 * (edges[b] + edges[b + 1]);
    if (lambda * v * v < 9.0 || phi[b] <= 0.0 || phi_error[b] > 0.2 * phi[b]) continue;
    const double y = std::log(g[b]), sy_b = g_error[b] / g[b], w = 1.0 / (sy_b * sy_b);
    sw += w;
    sx += w * v;
    sy += w * y;
    sxx += w * v * v;
    sxy += w * v * y;
    if (!used) v_first = v;
    v_last = v;
    ++used;
  }
  if (report.require("at least 4 tail bins measured to 20 % beyond lambda v*^2 = 9", used >= 4)) {
    const double det = sw * sxx - sx * sx;
    const double slope = (sw * sxy - sx * sy) / det, slope_error = std::sqrt(sw / det);
    const double v_mid = 0.5 * (v_first + v_last);
    const double maxwell_slope = 2.0 * beta / zeta - 2.0 * lambda * v_mid;  // d ln G/dv* for a Maxwellian
    char text[240];
    std::snprintf(text, sizeof text,
                  "G_1 flattens over v* = %.2f..%.2f: d ln G/dv* = %.3f +- %.3f, |.| < 1/4 of the Maxwellian's %.3f",
                  v_first, v_last, slope, slope_error, maxwell_slope);
    report.require(text, std::abs(slope) < 0.25 * std::abs(maxwell_slope));
    // Overpopulation at the end of the window.
    std::size_t b_last = 0;
    for (std::size_t b = 0; b + 1 < edges.size(); ++b)
      if (0.5 * (edges[b] + edges[b + 1]) == v_last) b_last = b;
    const double maxwell = (std::pow(lambda / M_PI, 1.5)) * std::exp(-lambda * v_last * v_last);
    std::snprintf(text, sizeof text, "overpopulation Phi_1/Maxwellian at v* = %.2f: %.3g (+- %.2g)", v_last,
                  phi[b_last] / maxwell, phi_error[b_last] / maxwell);
    report.require(text, phi[b_last] > maxwell);
    report.note("theory tail exponent 2 beta_1/zeta*_1 = " + std::to_string(theory::tail_decay_rate(hcs, 0)) +
                " (measured zeta*: " + std::to_string(2.0 * beta / zeta) + ")");
  }
  // Montanero and Garzo 2002 (text of Fig 7): Phi_1/Phi_MB ~ 37 at v* = 2.2 for alpha = 0.5. The ratio
  // at 2.2, interpolated in ln between the two bin centres around it, with its standard error; stated,
  // not asserted: the paper gives neither an error nor how its ratio was taken (binning, reference).
  for (std::size_t b = 0; b + 2 < edges.size(); ++b) {
    const double va = 0.5 * (edges[b] + edges[b + 1]), vb = 0.5 * (edges[b + 1] + edges[b + 2]);
    if (!(va <= 2.2 && 2.2 < vb) || phi[b] <= 0.0 || phi[b + 1] <= 0.0) continue;
    const auto maxwellian = [&](double v) { return std::pow(lambda / M_PI, 1.5) * std::exp(-lambda * v * v); };
    const double w = (2.2 - va) / (vb - va);
    const double ratio = std::exp((1.0 - w) * std::log(phi[b] / maxwellian(va)) + w * std::log(phi[b + 1] / maxwellian(vb)));
    const double relative = std::hypot((1.0 - w) * phi_error[b] / phi[b], w * phi_error[b + 1] / phi[b + 1]);
    char text[240];
    std::snprintf(text, sizeof text,
                  "Phi_1/Phi_MB at v* = 2.2: %.3g +- %.2g (Montanero and Garzo 2002 at alpha = 0.5: about 37; this run alpha = %.2f)",
                  ratio, ratio * relative, alpha);
    report.note(text);
  }
  return report.exit_code();
}
