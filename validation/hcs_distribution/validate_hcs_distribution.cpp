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

/// A bin measured to 20 %: a positive value with a positive error at most a fifth of it (a bin with a zero
/// error holds one count or none: not measured).
bool measured(double value, double error) { return value > 0.0 && error > 0.0 && error <= 0.2 * value; }

/// A point of a weighted straight-line fit: x, y and the standard error of y.
struct LogPoint {
  double x, y, error;
};
struct Line {
  double slope = 0.0, slope_error = 0.0;
  std::size_t points = 0;
};
/// The weighted least-squares line through `points` (weights 1/error^2): its slope and the slope's
/// standard error.
Line fit_line(const std::vector<LogPoint>& points) {
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& p : points) {
    const double w = 1.0 / (p.error * p.error);
    sw += w, sx += w * p.x, sy += w * p.y, sxx += w * p.x * p.x, sxy += w * p.x * p.y;
  }
  const double det = sw * sxx - sx * sx;
  if (points.size() < 2 || !(det > 0.0)) return {0.0, 0.0, points.size()};
  return {(sw * sxy - sx * sy) / det, std::sqrt(sw / det), points.size()};
}

/// Fig 7 against the independent program (validation/independent_reference), beyond the thermal bins
/// (hcs_distribution/README.md, item 4):
/// (a) Phi_1 bin by bin over the tail (lambda v*^2 > 3, both measured to 20 %), 4 combined SE, no allowance;
/// (b) Phi_1/Phi_MB at v* = 2.2, the paper's number (about 37 at alpha = 0.5), 4 combined SE against the
///     second method, the paper's value stated beside it (alpha = 0.5);
/// (c) eq 21's exponent 2 beta_1/zeta*_1 (eq 20) where the tail is reached, fixed in advance: beyond four thermal
///     speeds of species 1 (lambda v*^2 >= 16), over the bins both programs measure to 20 %. The two programs'
///     slopes of ln Phi_1 there are asserted against each other at 4 combined SE, no allowance, and this run's
///     exponent against eq 21 at 3 SE plus the second method's distance from eq 21 in the same bins (|its
///     exponent - eq 21| + 2 of its SEs: how far from the asymptote the window still is, estimated without this
///     code); with `require_exponent` false a run that measures fewer than 3 bins there (the quick tier) notes it.
void check_tail_against_reference(validation::Report& report, bool require_exponent, double alpha,
                                  const std::vector<double>& edges, double lambda, double tail_rate,
                                  const std::vector<double>& phi, const std::vector<double>& phi_error,
                                  const std::vector<double>& reference, const std::vector<double>& reference_error) {
  const auto centre = [&](std::size_t b) { return 0.5 * (edges[b] + edges[b + 1]); };
  char name[300];
  for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
    const double v = centre(b);
    if (lambda * v * v <= 3.0 || !measured(phi[b], phi_error[b]) || !measured(reference[b], reference_error[b]))
      continue;
    std::snprintf(name, sizeof name, "tail Phi_1(v* = %.3f) vs the independent program (4 combined SE, no allowance)", v);
    report.check(name, phi[b], std::hypot(phi_error[b], reference_error[b]), reference[b], 4.0, 0.0);
  }
  // (b) Phi_1/Phi_MB at 2.2: ln-interpolated between the two bin centres around it, both with this run's lambda.
  const auto maxwellian = [&](double v) { return std::pow(lambda / M_PI, 1.5) * std::exp(-lambda * v * v); };
  for (std::size_t b = 0; b + 2 < edges.size(); ++b) {
    const double va = centre(b), vb = centre(b + 1);
    if (!(va <= 2.2 && 2.2 < vb)) continue;
    const double w = (2.2 - va) / (vb - va);
    const auto ratio = [&](const std::vector<double>& p, const std::vector<double>& e, double& error) {
      if (!(p[b] > 0.0 && p[b + 1] > 0.0)) return error = 0.0, 0.0;
      const double r = std::exp((1.0 - w) * std::log(p[b] / maxwellian(va)) + w * std::log(p[b + 1] / maxwellian(vb)));
      error = r * std::hypot((1.0 - w) * e[b] / p[b], w * e[b + 1] / p[b + 1]);
      return r;
    };
    double run_error = 0.0, reference_ratio_error = 0.0;
    const double run_ratio = ratio(phi, phi_error, run_error);
    const double reference_ratio = ratio(reference, reference_error, reference_ratio_error);
    if (!(run_ratio > 0.0 && reference_ratio > 0.0)) break;
    report.check("Phi_1/Phi_MB at v* = 2.2 vs the independent program (4 combined SE, no allowance)", run_ratio,
                 std::hypot(run_error, reference_ratio_error), reference_ratio, 4.0, 0.0);
    if (std::abs(alpha - 0.5) < 1e-12)
      report.state("Phi_1/Phi_MB at v* = 2.2 vs Montanero and Garzo 2002's 'about 37' (alpha = 0.5; no error given)",
                   run_ratio, run_error, 37.0);
    break;
  }
  // (c) beyond four thermal speeds, the bins both programs measure; weighted fits of ln Phi_1 over the same bins.
  constexpr double tail_start = 16.0;  // lambda v*^2: v = 4 sqrt(2 T_1/m_1)
  std::vector<LogPoint> run_points, reference_points;
  for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
    const double v = centre(b);
    if (lambda * v * v < tail_start || !measured(phi[b], phi_error[b]) || !measured(reference[b], reference_error[b]))
      continue;
    run_points.push_back({v, std::log(phi[b]), phi_error[b] / phi[b]});
    reference_points.push_back({v, std::log(reference[b]), reference_error[b] / reference[b]});
  }
  const double window = std::sqrt(tail_start / lambda);
  std::snprintf(name, sizeof name, "tail bins beyond v* = %.2f (lambda v*^2 >= 16) measured to 20 %% by both programs: %zu",
                window, run_points.size());
  report.note(name);
  if (run_points.size() < 3 && !require_exponent) {  // (the quick tier: the paper tier passes --require-tail-exponent 1)
    report.note("tail exponent not checked: fewer than 3 bins beyond four thermal speeds are measured to 20 % by both");
    return;
  }
  if (!report.require("at least 3 bins beyond four thermal speeds measured to 20 % by both programs", run_points.size() >= 3))
    return;
  const Line run = fit_line(run_points), second = fit_line(reference_points);
  std::snprintf(name, sizeof name,
                "tail exponent -d ln Phi_1/dv* from v* = %.2f vs the independent program's over the same %zu bins "
                "(4 combined SE, no allowance)",
                window, run.points);
  report.check(name, -run.slope, std::hypot(run.slope_error, second.slope_error), -second.slope, 4.0, 0.0);
  const double distance = std::abs(-second.slope - tail_rate) + 2.0 * second.slope_error;
  std::snprintf(name, sizeof name,
                "tail exponent -d ln Phi_1/dv* from v* = %.2f vs eq 21's 2 beta_1/zeta*_1 (eq 20; 3 SE + the independent "
                "program's distance from it there, %.3f)",
                window, distance);
  report.check(name, -run.slope, run.slope_error, tail_rate, 3.0, distance);
}
}  // namespace

int main(int argc, char** argv) {
  const auto independent_file = validation::take_option(argc, argv, "--independent");
  // "--require-tail-exponent 1": (c) below must run (paper tier); without it a run too short to resolve the tail
  // says so in a note.
  const auto require_option = validation::take_option(argc, argv, "--require-tail-exponent");
  if (require_option && *require_option != "0" && *require_option != "1") {
    std::fprintf(stderr, "validate_hcs_distribution: --require-tail-exponent takes 0 or 1, not '%s'\n", require_option->c_str());
    return 2;
  }
  const bool require_exponent = require_option && *require_option == "1";
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
  const double tail_rate = 2.0 * beta / zeta;  // eq 21's exponent with this run's zeta*: G = exp(tail_rate v*) Phi
  std::vector<std::size_t> tail;  // the bins beyond lambda v*^2 = 9 that this run measures to 20 %
  for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
    const double v = 0.5 * (edges[b] + edges[b + 1]);
    if (lambda * v * v >= 9.0 && measured(phi[b], phi_error[b])) tail.push_back(b);
  }
  const auto centre = [&](std::size_t b) { return 0.5 * (edges[b] + edges[b + 1]); };
  const auto run_fit = [&](double from) {
    std::vector<LogPoint> points;
    for (std::size_t b : tail)
      if (centre(b) >= from - 1e-9) points.push_back({centre(b), std::log(g[b]), g_error[b] / g[b]});
    return fit_line(points);
  };
  if (report.require("at least 4 tail bins measured to 20 % beyond lambda v*^2 = 9", tail.size() >= 4)) {
    const double v_first = centre(tail.front()), v_last = centre(tail.back());
    const Line fit = run_fit(v_first);
    const double v_mid = 0.5 * (v_first + v_last);
    const double maxwell_slope = tail_rate - 2.0 * lambda * v_mid;  // d ln G/dv* for a Maxwellian
    char text[240];
    std::snprintf(text, sizeof text,
                  "G_1 flattens over v* = %.2f..%.2f: d ln G/dv* = %.3f +- %.3f, |.| < 1/4 of the Maxwellian's %.3f",
                  v_first, v_last, fit.slope, fit.slope_error, maxwell_slope);
    report.require(text, std::abs(fit.slope) < 0.25 * std::abs(maxwell_slope));
    // Overpopulation at the end of the window.
    const std::size_t b_last = tail.back();
    const double maxwell = (std::pow(lambda / M_PI, 1.5)) * std::exp(-lambda * v_last * v_last);
    std::snprintf(text, sizeof text, "overpopulation Phi_1/Maxwellian at v* = %.2f: %.3g (+- %.2g)", v_last,
                  phi[b_last] / maxwell, phi_error[b_last] / maxwell);
    report.require(text, phi[b_last] > maxwell);
    report.note("theory tail exponent 2 beta_1/zeta*_1 = " + std::to_string(theory::tail_decay_rate(hcs, 0)) +
                " (measured zeta*: " + std::to_string(tail_rate) + ")");
  }
  if (!reference.empty()) check_tail_against_reference(report, require_exponent, alpha, edges, lambda, tail_rate, phi, phi_error, reference,
                                                       reference_error);
  return report.exit_code();
}
