// The steady uniform shear flow without thermostat (Montanero 2003, sec. 5; \ref eta_usf_steady
// "docs/shear-viscosity.md"): viscous heating balances the collisional cooling. The steady temperature,
// the reduced shear rate a*, the partial temperatures T_k/T (mixtures) and the pressure tensor P_ij/p
// against the independent program of validation/independent_reference (a second DSMC that shares no code
// with src/: --shear mode, exact streaming between collisions), 4 combined SE, no allowance; and against
// Grad's solution (theory::viscosity::steady_shear_grad, one species or a binary) with the gaps between Grad
// and the independent program, fixed when they were measured, as its known error. See README.md in this folder.
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <utility>

#include "analysis/compare.hpp"
#include "theory/viscosity.hpp"
#include "validation.hpp"

using namespace gdsmc;

namespace {

/// Grad's known errors, measured against the independent program when the theory was written (docs/
/// shear-viscosity.md, \ref eta_usf_steady): one species, the table of analysis::compare::steady_shear_known_error;
/// the binary of usf_steady_binary.nml, |Grad - independent| of usf_binary_alpha0.8.txt. Fixed numbers, so that a
/// change of the theory fails the checks.
double grad_known_error(const species::Mixture& mix, const std::string& key) {
  if (mix.size() == 1) {
    const std::map<std::string, std::size_t> which{{"reduced_shear_rate", 0}, {"pressure_xx", 1}, {"pressure_yy", 2},
                                                   {"pressure_zz", 3}, {"pressure_xy", 4}};
    return analysis::compare::steady_shear_known_error(mix.restitution(0, 0), which.at(key));
  }
  const std::map<std::string, double> binary{
      {"temperature_ratio_1", 0.00109}, {"temperature_ratio_2", 0.00109}, {"reduced_shear_rate", 0.01987},
      {"pressure_xx", 0.00602},         {"pressure_yy", 0.01436},         {"pressure_zz", 0.02038},
      {"pressure_xy", 0.00048}};
  return binary.at(key);
}

struct Measured {
  validation::SteadyAverage temperature;  ///< T = tr P/(3 n), at the middle of the streaming jump
  validation::SteadyAverage reduced_rate;  ///< a* = a eta_0(T)/(n T) of that T
  std::map<std::string, validation::SteadyAverage> values;  ///< by the independent file's keys
};

/// a* and P_ij/p: each replica's time average from &shear average_from on (/observables/shear_state, T and P at the
/// middle of the streaming jump), with the SE over the replicas; T from a* (a* = a eta_0(T)/(n T) ~ T^-1/2 for one
/// species or a mixture). A mixture's T_k/T from the series (both temperatures after the jump: the ratio's shift is
/// second order), its error an upper bound (the mean of the samples' SEs, the two relative errors added).
Measured measure(const validation::Case& run, const species::Mixture& mix, double from) {
  const auto value = io::h5md::read_dataset(run.file, "/observables/shear_state/value").data;
  const auto error = io::h5md::read_dataset(run.file, "/observables/shear_state/error").data;
  const double n = mix.total_density(), shear = *run.config.shear.rate;
  const double eta0_at_1 = mix.size() == 1 ? theory::viscosity::elastic_viscosity(mix.mass[0], mix.diameter[0], 1.0)
                                           : theory::viscosity::elastic_mixture_viscosity(mix, 1.0);
  Measured m;
  m.reduced_rate = {value.at(0), error.at(0)};
  const double t = std::pow(shear * eta0_at_1 / (n * m.reduced_rate.value), 2.0);  // a* = a eta_0(1) / (n sqrt(T))
  m.temperature = {t, 2.0 * t * m.reduced_rate.error / m.reduced_rate.value};
  m.values["temperature"] = m.temperature;
  m.values["reduced_shear_rate"] = m.reduced_rate;
  const char* components[4] = {"xx", "yy", "zz", "xy"};
  for (std::size_t c = 0; c < 4; ++c) m.values[std::string("pressure_") + components[c]] = {value.at(c + 1), error.at(c + 1)};
  if (mix.size() > 1) {
    const auto partial = io::h5md::read_observable(run.file, "/observables/temperature");
    const auto total = io::h5md::read_observable(run.file, "/observables/total_temperature");
    const auto mean = validation::steady_average(total, from);
    for (std::size_t k = 0; k < mix.size(); ++k) {
      auto a = validation::steady_average(partial, from, 1.0, k, mix.size());
      a.error = std::abs(a.value / mean.value) * (a.error / a.value + mean.error / mean.value);
      a.value /= mean.value;
      m.values["temperature_ratio_" + std::to_string(k + 1)] = a;
    }
  }
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  const auto independent_file = validation::take_option(argc, argv, "--independent");
  const auto steady_from = validation::take_option(argc, argv, "--steady-from");  // (T_k/T; a*, P: &shear average_from)
  const auto run = validation::run_case(argc, argv, "usf_steady.h5");
  validation::Report report("Steady uniform shear flow without thermostat", run.report_file());
  const double from = steady_from ? std::stod(*steady_from) : 1500.0;
  char from_text[32];
  std::snprintf(from_text, sizeof from_text, "%g", from);
  report.note("a*, P_ij/(n T): each replica's time average from t = " + std::string(from_text) +
              " on (T = tr P^k/(3n), both at the middle of the streaming jump), SE over the replicas; T from a*; T_k/T: "
              "the mean of the samples from then on, error an upper bound; against the independent program at 4 "
              "combined SE, no allowance; against Grad's solution with its known error, |Grad - independent| as measured, at "
              "4 SE of the two combined");
  if (!report.require("an independent reference file (--independent)", independent_file.has_value()))
    return report.exit_code();
  const auto reference = validation::read_independent_rows(*independent_file);
  report.note("independent reference: " + *independent_file);
  const auto mix = run.config.mixture();
  if (!report.require("one species or a binary mixture, dilute", mix.size() <= 2 && !mix.enskog))
    return report.exit_code();
  const Measured m = measure(run, mix, from);
  const auto grad = mix.size() == 1 ? [&] {
    const auto one = theory::viscosity::steady_shear_grad(mix.restitution(0, 0));
    return theory::viscosity::MixtureSteadyShear{{1.0}, one.reduced_shear_rate, one.pressure_xx, one.pressure_yy,
                                                 one.pressure_zz, one.pressure_xy};
  }() : theory::viscosity::steady_shear_grad(mix);
  std::map<std::string, double> theory{{"reduced_shear_rate", grad.reduced_shear_rate}, {"pressure_xx", grad.pressure_xx},
                                       {"pressure_yy", grad.pressure_yy}, {"pressure_zz", grad.pressure_zz},
                                       {"pressure_xy", grad.pressure_xy}};
  if (mix.size() > 1)
    for (std::size_t k = 0; k < mix.size(); ++k) theory["temperature_ratio_" + std::to_string(k + 1)] = grad.temperature_ratio[k];
  const auto label = [](const std::string& key) -> std::string {
    if (key == "temperature") return "steady T";
    if (key == "reduced_shear_rate") return "a* = a eta_0(T)/(n T)";
    if (key.rfind("pressure_", 0) == 0) return "P_" + key.substr(9) + "/p";
    return "T_" + key.substr(18) + "/T";  // temperature_ratio_k
  };
  for (const auto& [key, a] : m.values) {
    const auto it = reference.find(key);
    double reference_value = it == reference.end() ? NAN : it->second.first, reference_error = NAN;
    if (key == "reduced_shear_rate" && mix.size() > 1 && reference.count("temperature")) {
      // the independent program's a* from its T (eta_0 of the elastic mixture, as above; SE from T's)
      const auto& [t, t_error] = reference.at("temperature");
      const double shear = *run.config.shear.rate, eta0 = theory::viscosity::elastic_mixture_viscosity(mix, t);
      reference_value = shear * eta0 / (mix.total_density() * t);
      reference_error = 0.5 * reference_value * t_error / t;
    } else if (it != reference.end()) {
      reference_error = it->second.second;
    }
    if (!report.require("the independent file holds " + key, std::isfinite(reference_value))) continue;
    report.check(label(key) + " vs the independent program", a.value, std::hypot(a.error, reference_error),
                 reference_value, 4.0);
    // the known error was measured with the independent program's SE: the two SEs combined
    if (theory.count(key))
      report.check(label(key) + " vs Grad (known error |Grad - independent|)", a.value, std::hypot(a.error, reference_error),
                   theory.at(key), 4.0, grad_known_error(mix, key));
  }
  char line[200];
  std::snprintf(line, sizeof line, "a* %.4f against Grad %.4f (%+.1f %%); eta/eta_0 = -P_xy/(p a*) = %.4f",
                m.reduced_rate.value, grad.reduced_shear_rate,
                100.0 * (grad.reduced_shear_rate / m.reduced_rate.value - 1.0),
                -m.values.at("pressure_xy").value / m.reduced_rate.value);
  report.note(line);
  return report.exit_code();
}
