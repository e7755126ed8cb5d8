// The steady uniform shear flow without thermostat (Montanero 2003, sec. 5; \ref eta_usf_steady
// "docs/shear-viscosity.md"): viscous heating balances the collisional cooling. The steady temperature,
// the reduced shear rate a* (one species), the partial temperatures T_k/T (mixtures) and the pressure
// tensor P_ij/(n T) against the independent program of validation/independent_reference (a second DSMC
// that shares no code with src/: --shear mode, exact streaming between collisions), 4 combined SE, no
// allowance; and against Grad's solution (theory::viscosity::steady_shear_grad, one species or a binary), with the
// gap between Grad and the independent program as its known error. See README.md in this folder.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>

#include "theory/viscosity.hpp"
#include "validation.hpp"

using namespace gdsmc;

namespace {

/// The rows "quantity value se" of the independent program's --shear output.
std::map<std::string, std::pair<double, double>> read_independent(const std::string& file) {
  std::map<std::string, std::pair<double, double>> rows;
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string name;
    double value = NAN, se = NAN;
    if (fields >> name >> value >> se) rows[name] = {value, se};
  }
  return rows;
}

/// The mean over the samples at t >= from of P_ij/p, p = tr P/3 of the same sample (column `column` of the pressure
/// tensor), and an upper bound of its SE: the mean of the samples' relative SEs of P_ij and p added in
/// quadrature. (p from the tensor itself: the tensor is sampled at the middle of a stage's streaming jump and
/// the temperature after it, which differ by a dt |P_xy|/3, 0.17 % of p at a dt = 0.01: thermostat.hpp.)
validation::SteadyAverage pressure_ratio(const io::h5md::ObservableData& p, double from, std::size_t column) {
  validation::SteadyAverage a;
  int n = 0;
  for (std::size_t i = 0; i < p.time.size(); ++i)
    if (p.time[i] >= from) {
      const double* row = p.value.data() + i * 6;
      const double* row_error = p.error.data() + i * 6;
      const double trace = (row[0] + row[1] + row[2]) / 3.0;
      const double trace_error = std::sqrt(row_error[0] * row_error[0] + row_error[1] * row_error[1] +
                                           row_error[2] * row_error[2]) / 3.0;
      const double ratio = row[column] / trace;
      a.value += ratio;
      a.error += std::abs(ratio) * std::hypot(row_error[column] / row[column], trace_error / trace);
      ++n;
    }
  a.value /= n;
  a.error /= n;
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  const auto independent_file = validation::take_option(argc, argv, "--independent");
  const auto steady_from = validation::take_option(argc, argv, "--steady-from");
  const auto run = validation::run_case(argc, argv, "usf_steady.h5");
  validation::Report report("Steady uniform shear flow without thermostat", run.report_file());
  const double from = steady_from ? std::stod(*steady_from) : 1500.0;
  char from_text[32];
  std::snprintf(from_text, sizeof from_text, "%g", from);
  report.note("averages over the samples from t = " + std::string(from_text) +
              " on (P_ij/p with p = tr P/3 of each sample), error = the mean of their SEs (an upper bound); against the independent program at 4 combined SE, "
              "no allowance; against Grad's solution with |Grad - independent| as its known error");
  if (!report.require("an independent reference file (--independent)", independent_file.has_value()))
    return report.exit_code();
  const auto reference = read_independent(*independent_file);
  report.note("independent reference: " + *independent_file);
  const auto mix = run.config.mixture();
  const std::size_t s = mix.size();
  const auto t = io::h5md::read_observable(run.file, "/observables/total_temperature");
  const auto p = io::h5md::read_observable(run.file, "/observables/pressure_tensor");
  if (!report.require("replicas > 1, so standard errors exist", !t.error.empty() && !p.error.empty()))
    return report.exit_code();
  const auto compare = [&](const std::string& quantity, const std::string& key, const validation::SteadyAverage& a) {
    const auto it = reference.find(key);
    if (!report.require("the independent file holds " + key, it != reference.end())) return;
    report.check(quantity + " vs the independent program", a.value, std::hypot(a.error, it->second.second),
                 it->second.first, 4.0);
  };
  compare("steady T", "temperature", validation::steady_average(t, from));
  const char* components[4] = {"xx", "yy", "zz", "xy"};
  const std::size_t columns[4] = {0, 1, 2, 3};  // pressure_tensor columns xx yy zz xy
  std::map<std::string, validation::SteadyAverage> pressure;
  for (std::size_t c = 0; c < 4; ++c) {
    pressure[components[c]] = pressure_ratio(p, from, columns[c]);
    compare(std::string("P_") + components[c] + "/p", std::string("pressure_") + components[c], pressure[components[c]]);
  }
  // Grad's solution, its known error the gap to the independent program (\ref eta_usf_steady "docs/shear-viscosity.md")
  const auto against_grad = [&](const std::string& quantity, const std::string& key, const validation::SteadyAverage& a,
                                double theory) {
    const auto it = reference.find(key);
    if (it == reference.end()) return;
    report.check(quantity + " vs Grad (allowance |Grad - independent|)", a.value, a.error, theory, 4.0,
                 std::abs(theory - it->second.first));
  };
  const auto rate = io::h5md::read_observable(run.file, "/observables/reduced_shear_rate");
  const auto reduced_rate = validation::steady_average(rate, from);
  theory::viscosity::MixtureSteadyShear grad;
  if (s == 1) {
    compare("a* = a eta_0(T)/(n T)", "reduced_shear_rate", reduced_rate);
    const auto one = theory::viscosity::steady_shear_grad(mix.restitution(0, 0));
    grad = {{1.0}, one.reduced_shear_rate, one.pressure_xx, one.pressure_yy, one.pressure_zz, one.pressure_xy};
    char line[240];
    std::snprintf(line, sizeof line, "eta/eta_0 = -P_xy/(p a*) = %.4f (Grad %.4f)",
                  -pressure["xy"].value / reduced_rate.value, one.viscosity);
    report.note(line);
  } else {
    const auto ratio = io::h5md::read_observable(run.file, "/observables/temperature");
    grad = theory::viscosity::steady_shear_grad(mix);
    for (std::size_t k = 0; k < s; ++k) {
      auto a = validation::steady_average(ratio, from, 1.0, k, s);
      const auto mean = validation::steady_average(t, from);
      a.error = std::abs(a.value / mean.value) * std::hypot(a.error / a.value, mean.error / mean.value);
      a.value /= mean.value;
      const std::string key = "temperature_ratio_" + std::to_string(k + 1), label = "T_" + std::to_string(k + 1) + "/T";
      compare(label, key, a);
      against_grad(label, key, a, grad.temperature_ratio[k]);
    }
    // a* of the independent program's T (eta_0 of the elastic mixture, as the run's reduced_shear_rate): its SE
    // from T's, a* ~ T^-1/2
    const auto it = reference.find("temperature");
    if (report.require("the independent file holds temperature", it != reference.end())) {
      const double t_ind = it->second.first, shear = *run.config.shear.rate;
      const double rate_ind =
          shear * theory::viscosity::elastic_mixture_viscosity(mix, t_ind) / (mix.total_density() * t_ind);
      report.check("a* = a eta_0(T)/(n T) vs the independent program", reduced_rate.value,
                   std::hypot(reduced_rate.error, 0.5 * rate_ind * it->second.second / t_ind), rate_ind, 4.0);
      report.check("a* vs Grad (allowance |Grad - independent|)", reduced_rate.value, reduced_rate.error,
                   grad.reduced_shear_rate, 4.0, std::abs(grad.reduced_shear_rate - rate_ind));
    }
  }
  if (s == 1) against_grad("a*", "reduced_shear_rate", reduced_rate, grad.reduced_shear_rate);
  against_grad("P_xx/p", "pressure_xx", pressure["xx"], grad.pressure_xx);
  against_grad("P_yy/p", "pressure_yy", pressure["yy"], grad.pressure_yy);
  against_grad("P_zz/p", "pressure_zz", pressure["zz"], grad.pressure_zz);
  against_grad("P_xy/p", "pressure_xy", pressure["xy"], grad.pressure_xy);
  char line[240];
  std::snprintf(line, sizeof line, "a* %.4f against Grad %.4f (%+.1f %%)", reduced_rate.value, grad.reduced_shear_rate,
                100.0 * (grad.reduced_shear_rate / reduced_rate.value - 1.0));
  report.note(line);
  return report.exit_code();
}
