// granular-dsmc --compare: DSMC beside theory (compare.hpp). The theory values come from
// analysis::predict, the known errors from the estimates listed in compare.hpp \ref compare_known
// (docs/physics.md "Comparison with theory").
#include "analysis/compare.hpp"
#include "analysis/json.hpp"

#include <gsl/gsl_cdf.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "io/units.hpp"
#include "theory/theory.hpp"

namespace gdsmc::analysis::compare {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// First Sonine's own error: 15 % of a first-Sonine correction or cumulant (\ref son_one_species "docs/sonine.md": 9-14 %).
constexpr double kFirstSonineShare = 0.15;
/// T_k/T in first Sonine: binary 0.2 % (\ref son_one_species "docs/sonine.md": 0.1 % against exact DSMC at mu = 10);
/// three or more species 0.4 % (\ref physics_compare "docs/physics.md": independent work, ternary, 0.1-0.4 %).
constexpr double kRatioErrorBinary = 0.002;
constexpr double kRatioErrorMany = 0.004;
/// At most this many distinct alpha_ij are solved in second Sonine for the known error of c_k (0.1 s each).
constexpr std::size_t kCumulantAlphas = 16;
/// Stage splitting of &shear runs at the default stage_step 0.125: +0.33 % of eta (validation/shear_viscosity).
constexpr double kStageBias = 0.0033;

const char* kMaxwellianOdeSource =
    "docs/physics.md Known limits: Maxwellian rates omit first-Sonine corrections (3/16)|a2| (docs/haff-and-mixtures.md), "
    "integrated over ln T, plus 15 % (docs/sonine.md)";
const char* kNone = "none stated";

std::string species_label(const std::string& label, std::size_t k) {  // k: 0-based index; every {k}
  const std::string key = "{k}", index = std::to_string(k + 1);
  std::string out = label;
  for (auto at = out.find(key); at != std::string::npos; at = out.find(key, at + index.size()))
    out.replace(at, key.size(), index);
  return out;
}

std::vector<double> errors_or_nan(const io::h5md::ObservableData& o) {
  return o.error.empty() ? std::vector<double>(o.value.size(), kNaN) : o.error;
}

std::size_t columns_of(const io::h5md::ObservableData& o) { return o.shape.size() > 1 ? o.shape[1] : 1; }

/// T_1/T_2 of a binary from its T_k/T (`ratio`): tau_1/tau_2; with x_1 tau_1 + x_2 tau_2 = 1 (x_k = n_k/n)
/// an error e_1 of tau_1 moves tau_2 by -(x_1/x_2) e_1, so the ratio's error is exactly
/// (tau_1/tau_2) e_1 (1/tau_1 + x_1/(x_2 tau_2)); the known error likewise (\ref compare_known).
Quantity temperature_ratio(const Quantity& ratio, const species::Mixture& mix) {
  double n = 0.0;
  for (double density : mix.number_density) n += density;
  const double x1 = mix.number_density[0] / n, x2 = mix.number_density[1] / n;
  const auto carried = [&](const std::vector<double>& tau, double e1) {
    return tau[0] / tau[1] * e1 * (1.0 / tau[0] + x1 / (x2 * tau[1]));
  };
  Quantity q{"temperature_ratio", "T_1/T_2", ratio.approximation,
             "the allowance of T_1/T (docs/sonine.md, 0.2 %) carried through x_1 T_1/T + x_2 T_2/T = 1", {}, 1,
             {ratio.value[0] / ratio.value[1]}, {carried(ratio.value, ratio.error[0])},
             {ratio.theory[0] / ratio.theory[1]}, {carried(ratio.theory, ratio.known_error[0])}};
  q.at = ratio.at;
  return q;
}

/// The scaling-state quantities (T_k/T, c_k, zeta*) of a free-cooling or thermostatted run.
void add_scaling_state(Point& pt, const io::config::Config& config, const analysis::Predictions& p, const Measured& m) {
  const auto mix = config.mixture();
  const std::size_t s = mix.size();
  for (const char* name : {"temperature", "total_temperature", "sonine_c", "collisions_per_particle"})
    if (!m.has(name)) {
      pt.notes.push_back(std::string("scaling state not compared: the file has no observable ") + name);
      return;
    }
  const auto& per_particle = m.observables.at("collisions_per_particle").value;
  const double start = config.output.scaling_start;
  const auto& fs = *p.hcs_first_sonine;
  Quantity ratio{"temperature_over_mean", "T_{k}/T", "first_sonine",
                 s == 2 ? "docs/sonine.md: 0.1 % against exact DSMC at mu = 10; allowance 0.2 %"
                        : "docs/physics.md#physics_compare: independent work, ternary HCS, 0.1-0.4 %; allowance 0.4 %",
                 {}, s, {}, {}, {}, {}};
  Quantity cumulant{"sonine_c", "c_{k}", "first_sonine",
                    "the larger of 15 % of c_k (docs/sonine.md: first Sonine 9-14 % high) and the second-Sonine "
                    "correction |c(K=2) - c(K=3)| of one species at each alpha_ij (theory/sonine.hpp sonine_higher)",
                    {}, s, {}, {}, {}, {}};
  const double correction = config.viscoelastic_beta() ? 0.0 : cumulant_known_error(mix);
  // /scaling_state (docs/output.md): each replica's own average over its scaling samples, so that the SE
  // over the replicas is that of the time average; files without it: the samples' average, with the mean
  // of their SE (as if fully correlated: an upper bound).
  const ScalingState state = *scaling_state(m, start, true);
  const bool per_replica = state.per_replica;
  const std::size_t count = state.samples;
  for (std::size_t k = 0; k < s; ++k) {
    ratio.value.push_back(state.ratio[k]);
    ratio.error.push_back(state.ratio_error[k]);
    ratio.theory.push_back(fs.temperature_over_mean[k]);
    ratio.known_error.push_back((s == 2 ? kRatioErrorBinary : kRatioErrorMany) * fs.temperature_over_mean[k]);
    cumulant.value.push_back(state.cumulant[k]);
    cumulant.error.push_back(state.cumulant_error[k]);
    cumulant.theory.push_back(fs.sonine_c[k]);
    cumulant.known_error.push_back(std::max(kFirstSonineShare * std::abs(fs.sonine_c[k]), correction));
  }
  if (count == 0) {
    char text[240];
    std::snprintf(text, sizeof text,
                  "scaling state not compared: no sample past scaling_start = %g collisions per particle (the run "
                  "reaches %.3g)",
                  start, per_particle.empty() ? 0.0 : per_particle.back());
    pt.notes.push_back(text);
    return;
  }
  char text[300];
  const bool no_error = std::none_of(state.cumulant_error.begin(), state.cumulant_error.end(),
                                     [](double e) { return std::isfinite(e); });
  if (no_error)  // one replica: neither the replicas' nor the samples' SE exists
    std::snprintf(text, sizeof text, "T_k/T, c_k: averages of the %zu samples past scaling_start = %g collisions per "
                  "particle; no SE (one replica)", count, start);
  else if (per_replica)
    std::snprintf(text, sizeof text, "T_k/T, c_k: each replica's average over its samples past scaling_start = %g "
                  "collisions per particle (%zu samples), averaged over the replicas; SE over the replicas", start, count);
  else
    std::snprintf(text, sizeof text, "T_k/T, c_k: averages of the %zu samples past scaling_start = %g collisions per "
                  "particle; SE = mean of the samples' SE (an upper bound)", count, start);
  pt.notes.push_back(text);
  ratio.at = cumulant.at = "scaling state";
  if (s == 2) pt.quantities.push_back(temperature_ratio(ratio, mix));
  if (s > 1) pt.quantities.push_back(std::move(ratio));
  pt.quantities.push_back(std::move(cumulant));
  const auto zeta = m.attributes.find("reduced_distribution@cooling_rate_reduced");
  if (s <= 2 && zeta != m.attributes.end() && p.hcs_maxwellian_cooling_rate_reduced) {
    const auto zeta_error = m.attributes.find("reduced_distribution@cooling_rate_reduced_error");
    Quantity q{"cooling_rate_reduced", "zeta*", "first_sonine",
               "15 % of the first-Sonine correction zeta*_FS - zeta*_M (docs/sonine.md)", {}, 1, {zeta->second},
               {zeta_error == m.attributes.end() ? kNaN : zeta_error->second}, {fs.cooling_rate_reduced},
               {kFirstSonineShare * std::abs(fs.cooling_rate_reduced - *p.hcs_maxwellian_cooling_rate_reduced)}};
    q.at = "scaling state";
    pt.quantities.push_back(std::move(q));
  }
}

/// T(t), T_k(t), and the collision count (or the sample times) of a free-cooling run.
void add_free_cooling(Point& pt, const io::config::Config& config, const analysis::Predictions& p, const Measured& m) {
  const auto mix = config.mixture();
  const std::size_t s = mix.size();
  const std::size_t nt = p.time.size();
  const bool viscoelastic = config.viscoelastic_beta().has_value();
  // The \ref haff_sonine "docs/haff-and-mixtures.md" a2 needs a constant alpha: no estimate for viscoelastic restitution.
  const std::vector<double> sonine_c = p.hcs_first_sonine ? p.hcs_first_sonine->sonine_c : std::vector<double>{};
  const double eps = viscoelastic ? kNaN : sonine_rate_error(mix, sonine_c);
  const double a2_max = eps * 16.0 / 3.0;
  std::vector<double> ratio_gap(s, 0.0);  // |tau_k^M / tau_k^FS - 1|
  if (s > 1 && p.hcs_first_sonine && p.hcs_maxwellian_temperature_over_mean)
    for (std::size_t k = 0; k < s; ++k)
      ratio_gap[k] =
          std::abs((*p.hcs_maxwellian_temperature_over_mean)[k] / p.hcs_first_sonine->temperature_over_mean[k] - 1.0);
  else if (s > 1)
    ratio_gap.assign(s, kNaN);
  auto aligned = [&](const std::string& name) -> const io::h5md::ObservableData* {
    if (!m.has(name)) return nullptr;
    const auto& o = m.observables.at(name);
    if (o.time.size() != nt) {
      pt.notes.push_back(name + " not compared: the file has " + std::to_string(o.time.size()) +
                         " samples, the theory " + std::to_string(nt));
      return nullptr;
    }
    return &o;
  };
  const double t0 = p.total_temperature.front();
  // (viscoelastic restitution: eps is NaN, no known error, and so no source of one)
  const std::string ode_source = viscoelastic ? kNone : kMaxwellianOdeSource;
  if (const auto* o = aligned("total_temperature")) {
    Quantity q{"total_temperature", "T", "maxwellian", ode_source, o->time, 1, o->value, errors_or_nan(*o),
               p.total_temperature, {}};
    for (std::size_t i = 0; i < nt; ++i)
      q.known_error.push_back((1.0 + kFirstSonineShare) * eps * std::abs(std::log(t0 / p.total_temperature[i])) *
                              p.total_temperature[i]);
    pt.quantities.push_back(std::move(q));
  }
  if (s > 1)
    if (const auto* o = aligned("temperature")) {
      Quantity q{"temperature", "T_{k}", "maxwellian",
                 viscoelastic ? ode_source : ode_source + "; plus 1.15 |tau_k^M/tau_k^FS - 1| (mixtures)", o->time, s,
                 o->value, errors_or_nan(*o), {}, {}};
      for (std::size_t i = 0; i < nt; ++i)
        for (std::size_t k = 0; k < s; ++k) {
          const double th = p.temperature[i][k], th0 = p.temperature[0][k];
          q.theory.push_back(th);
          q.known_error.push_back((1.0 + kFirstSonineShare) * (eps * std::abs(std::log(th0 / th)) + ratio_gap[k]) * th);
        }
      pt.quantities.push_back(std::move(q));
    }
  // Collisions: the frequency carries (1 - a2/16) and follows a temperature off by eps |ln(T0/T)|.
  auto collision_error = [&](std::size_t i) {
    return (1.0 + kFirstSonineShare) * (a2_max / 16.0 + 0.5 * eps * std::abs(std::log(t0 / p.total_temperature[i])));
  };
  const std::string collision_source =
      viscoelastic ? kNone
                   : "collision frequency (1 - a2/16) along T off by eps |ln(T0/T)| (validation/collision_rate), plus 15 %";
  if (!config.sample_times().empty()) {
    if (const auto* o = aligned("collisions_per_particle")) {
      Quantity q{"collisions_per_particle", "collisions/particle", "maxwellian", collision_source, o->time, 1,
                 o->value, errors_or_nan(*o), p.collisions_per_particle, {}};
      for (std::size_t i = 0; i < nt; ++i) q.known_error.push_back(collision_error(i) * p.collisions_per_particle[i]);
      pt.quantities.push_back(std::move(q));
    }
  } else if (const auto* o = aligned("time")) {  // collision-driven: when the counts were reached
    Quantity q{"time", "t", "maxwellian", collision_source, o->time, 1, o->value, errors_or_nan(*o), p.time, {}};
    for (std::size_t i = 0; i < nt; ++i) q.known_error.push_back(collision_error(i) * p.time[i]);
    pt.quantities.push_back(std::move(q));
  }
}

/// hcs_zeta_star of the last two samples of T(t), if there are two with positive T and time between them.
std::optional<std::pair<double, double>> measured_zeta_star(const io::h5md::ObservableData& tr, double nu_unit) {
  const std::size_t n = tr.value.size();
  if (n < 2 || tr.time.size() != n || !(nu_unit > 0.0)) return std::nullopt;
  const double ta = tr.value[n - 2], tb = tr.value[n - 1], dt = tr.time[n - 1] - tr.time[n - 2];
  if (!(ta > 0.0) || !(tb > 0.0) || !(dt > 0.0)) return std::nullopt;
  const bool errors = tr.error.size() == n;
  return hcs_zeta_star(ta, errors ? tr.error[n - 2] : kNaN, tb, errors ? tr.error[n - 1] : kNaN, dt, nu_unit);
}

/// Rough spheres of one species (\ref rough_maxwellian "docs/rough-spheres.md"): T_tr(t) and T_rot(t) of the
/// Maxwellian two-temperature equations, the collision count (or times), and theta = T_rot/T_tr at the last
/// sample beside the Maxwellian HCS value, and (where the Sonine state exists) theta, zeta*, a20, a02, a11
/// beside the Sonine HCS (theory/rough.hpp). theta_sonine and zeta_star_sonine carry |Sonine - Maxwellian| as
/// their known error (the size of the Sonine correction); the Maxwellian rows and the cumulants none (no
/// independent estimate; validation/rough_spheres measures the gaps).
void add_rough(Point& pt, const analysis::Predictions& p, const Measured& m, bool time_driven) {
  const std::size_t nt = p.time.size();
  const std::string source = std::string(kNone) + " (the Maxwellian two-temperature theory omits a20, a02, a11; "
                                                  "docs/rough-spheres.md)";
  const auto series = [&](const char* name, const char* label, const std::vector<double>& theory) {
    if (!m.has(name)) return pt.notes.push_back(std::string(name) + " not compared: not in the file");
    const auto& o = m.observables.at(name);
    if (o.time.size() != nt || o.value.size() != nt)
      return pt.notes.push_back(std::string(name) + " not compared: the file's samples differ from the theory's");
    pt.quantities.push_back(Quantity{name, label, "maxwellian", source, o.time, 1, o.value, errors_or_nan(o), theory,
                                     std::vector<double>(nt, kNaN)});
  };
  series("total_temperature", "T_tr", p.total_temperature);
  series("rotational_temperature", "T_rot", p.rotational_temperature);
  if (time_driven) series("collisions_per_particle", "collisions/particle", p.collisions_per_particle);
  else series("time", "t", p.time);
  if (!p.rough_hcs_maxwellian || !m.has("rotational_temperature") || !m.has("total_temperature")) return;
  const auto& rot = m.observables.at("rotational_temperature");
  const auto& tr = m.observables.at("total_temperature");
  if (rot.value.empty() || tr.value.size() != rot.value.size()) return;
  const double r = rot.value.back(), t = tr.value.back(), theta = r / t;
  // delta method, the two errors taken as independent (an approximation: they are correlated)
  const double er = rot.error.empty() ? kNaN : rot.error.back(), et = tr.error.empty() ? kNaN : tr.error.back();
  const double error = theta * std::sqrt((er / r) * (er / r) + (et / t) * (et / t));
  const auto last = [&](const char* name, const char* label, const char* approximation, const std::string& known,
                        double value, double value_error, double theory, double known_error = kNaN) {
    Quantity q{name, label, approximation, known + "; the HCS value, reached only after the relaxation", {}, 1,
               {value}, {value_error}, {theory}, {known_error}};
    q.at = "last sample";
    pt.quantities.push_back(std::move(q));
  };
  last("theta", "T_rot/T_tr", "maxwellian", source, theta, error, p.rough_hcs_maxwellian->theta);
  const auto zeta = measured_zeta_star(tr, p.rough_unit_frequency);
  if (zeta) last("zeta_star", "zeta/nu_M", "maxwellian", source, zeta->first, zeta->second, p.rough_zeta_star);
  const auto& sonine = p.rough_hcs_sonine;
  if (!sonine || !sonine->state)
    return pt.notes.push_back("theta_sonine, cumulants, zeta_star_sonine not compared: " +
                              (sonine ? sonine->why_not : std::string("no Sonine theory")));
  const std::string sonine_source = std::string(kNone) + " (the first Sonine theory: its gap grows with a02, "
                                                         "docs/rough-spheres.md)";
  const std::string bound_source = "|Sonine - Maxwellian|: the size of the Sonine correction bounds the neglected terms "
                                   "(docs/rough-spheres.md, validation/rough_spheres)";
  const auto& st = *sonine->state;
  last("theta_sonine", "T_rot/T_tr", "first_sonine", bound_source, theta, error, st.theta,
       std::abs(st.theta - p.rough_hcs_maxwellian->theta));
  if (zeta)
    last("zeta_star_sonine", "zeta/nu_M", "first_sonine", bound_source, zeta->first, zeta->second, st.cooling_rate_reduced,
         std::abs(st.cooling_rate_reduced - p.rough_zeta_star));
  for (const auto& [name, value] : {std::pair{"cumulant_a20", st.cumulants.a20}, std::pair{"cumulant_a02", st.cumulants.a02},
                                    std::pair{"cumulant_a11", st.cumulants.a11}}) {
    if (!m.has(name)) continue;
    const auto& o = m.observables.at(name);
    if (o.value.empty()) continue;
    last(name, name + 9, "first_sonine", sonine_source, o.value.back(), o.error.empty() ? kNaN : o.error.back(), value);
  }
}

/// Rough mixtures (\ref rough_mixtures "docs/rough-spheres.md"): T_k/T (translational) and theta_k = T_rot,k/T_k at
/// the last sample beside the Maxwellian HCS; errors by the delta method with the errors taken as independent.
void add_rough_mixture(Point& pt, const theory::rough::MixtureCoolingState& hcs, const Measured& m) {
  if (!m.has("temperature") || !m.has("rotational_temperature") || !m.has("total_temperature"))
    return pt.notes.push_back("rough mixture HCS not compared: temperatures missing from the file");
  const auto& t = m.observables.at("temperature");
  const auto& r = m.observables.at("rotational_temperature");
  const auto& total = m.observables.at("total_temperature");
  const std::size_t s = hcs.theta.size();
  if (t.value.size() < s || r.value.size() != t.value.size() || total.value.empty()) return;
  const std::size_t row = t.value.size() - s;  // the last sample
  const double mean = total.value.back(), mean_error = total.error.empty() ? kNaN : total.error.back();
  Quantity share{"rough_temperature_over_mean", "T_{k}/T", "maxwellian", std::string(kNone) + " (the Maxwellian HCS of rough mixtures)",
                 {}, s, {}, {}, hcs.translational_over_mean, std::vector<double>(s, kNaN)};
  Quantity theta{"rough_theta", "T_rot,{k}/T_{k}", "maxwellian", std::string(kNone) + " (the Maxwellian HCS of rough mixtures)",
                 {}, s, {}, {}, hcs.theta, std::vector<double>(s, kNaN)};
  for (std::size_t k = 0; k < s; ++k) {
    const double tk = t.value[row + k], rk = r.value[row + k];
    const double et = t.error.empty() ? kNaN : t.error[row + k], er = r.error.empty() ? kNaN : r.error[row + k];
    share.value.push_back(tk / mean);
    share.error.push_back(tk / mean * std::hypot(et / tk, mean_error / mean));
    theta.value.push_back(rk / tk);
    theta.error.push_back(rk / tk * std::hypot(er / rk, et / tk));
  }
  share.at = theta.at = "last sample";
  pt.quantities.push_back(std::move(share));
  pt.quantities.push_back(std::move(theta));
}

/// The white-noise steady state of one species (\ref wn_theory "docs/white-noise.md"): T_tr beside the Sonine
/// value (the Maxwellian one where there is none) and the Sonine theta and cumulants (smooth spheres: a20 =
/// sonine_c/2), at the last sample.
void add_white_noise(Point& pt, const analysis::Predictions::WhiteNoise& w, const Measured& m) {
  const auto last = [&](const std::string& name, const std::string& label, const char* approximation, double value,
                        double error, double theory) {
    Quantity q{name, label, approximation,
               std::string(kNone) + " (the " + approximation + " theory of the driven gas; docs/white-noise.md)", {}, 1,
               {value}, {error}, {theory}, {kNaN}};
    q.at = "last sample";
    pt.quantities.push_back(std::move(q));
  };
  const auto final_value = [&](const char* name, double scale) -> std::optional<std::pair<double, double>> {
    if (!m.has(name) || m.observables.at(name).value.empty()) return std::nullopt;
    const auto& o = m.observables.at(name);
    return std::pair{scale * o.value.back(), o.error.empty() ? kNaN : scale * o.error.back()};
  };
  const auto* st = w.sonine.state ? &*w.sonine.state : nullptr;
  if (const auto t = final_value("total_temperature", 1.0))
    last("white_noise_temperature", "T_tr", st ? "first_sonine" : "maxwellian", t->first, t->second,
         st ? *w.sonine_temperature : w.translational_temperature);
  if (!st) return pt.notes.push_back("white noise cumulants not compared: " + w.sonine.why_not);
  const auto rough = m.has("cumulant_a20");
  if (const auto a = rough ? final_value("cumulant_a20", 1.0) : final_value("sonine_c", 0.5))
    last("white_noise_a20", "a20", "first_sonine", a->first, a->second, st->cumulants.a20);
  if (!rough || !w.theta) return;
  const auto tr = final_value("total_temperature", 1.0), rot = final_value("rotational_temperature", 1.0);
  if (tr && rot) {
    const double theta = rot->first / tr->first;
    const double error = theta * std::hypot(rot->second / rot->first, tr->second / tr->first);  // independent errors
    last("white_noise_theta", "T_rot/T_tr", "first_sonine", theta, error, st->theta);
  }
  if (const auto a = final_value("cumulant_a02", 1.0)) last("white_noise_a02", "a02", "first_sonine", a->first, a->second, st->cumulants.a02);
  if (const auto a = final_value("cumulant_a11", 1.0)) last("white_noise_a11", "a11", "first_sonine", a->first, a->second, st->cumulants.a11);
}

/// The white-noise steady state of a mixture (\ref wn_theory "docs/white-noise.md"): T_k beside the first-Sonine state
/// (smooth spheres; else the Maxwellian one) and, for rough spheres, theta_k beside the Maxwellian state, at the
/// last sample (no stated allowance).
void add_white_noise_mixture(Point& pt, const theory::rough::MixtureDrivenState& w,
                             const std::optional<theory::DrivenFirstSonine>& sonine, const Measured& m) {
  const std::size_t s = w.translational.size();
  if (!m.has("temperature")) return;
  const auto& t = m.observables.at("temperature");
  if (t.value.size() < s) return;
  const std::size_t row = t.value.size() - s;
  const std::string source = std::string(kNone) + " (the Maxwellian theory of the driven mixture; docs/white-noise.md)";
  const std::string sonine_source = std::string(kNone) + " (the first-Sonine theory of the driven mixture; docs/white-noise.md)";
  Quantity q{"white_noise_temperature", "T_{k}", sonine ? "first_sonine" : "maxwellian", sonine ? sonine_source : source, {}, s,
             {}, {}, sonine ? sonine->temperature : w.translational, std::vector<double>(s, kNaN)};
  for (std::size_t k = 0; k < s; ++k) {
    q.value.push_back(t.value[row + k]);
    q.error.push_back(t.error.empty() ? kNaN : t.error[row + k]);
  }
  q.at = "last sample";
  pt.quantities.push_back(std::move(q));
  if (w.theta.empty() || !m.has("rotational_temperature")) return;
  const auto& r = m.observables.at("rotational_temperature");
  if (r.value.size() != t.value.size()) return;
  Quantity theta{"white_noise_theta", "T_rot,{k}/T_{k}", "maxwellian", source, {}, s, {}, {}, w.theta, std::vector<double>(s, kNaN)};
  for (std::size_t k = 0; k < s; ++k) {
    const double tk = t.value[row + k], rk = r.value[row + k];
    const double et = t.error.empty() ? kNaN : t.error[row + k], er = r.error.empty() ? kNaN : r.error[row + k];
    theta.value.push_back(rk / tk);
    theta.error.push_back(rk / tk * std::hypot(er / rk, et / tk));
  }
  theta.at = "last sample";
  pt.quantities.push_back(std::move(theta));
}

/// The MSD (Bodrova and Osinsky 2024, eq. (17), \ref dif_msd "docs/diffusion-msd.md") and D_k/D_1 over the last decade of time (validation/diffusion_ratio).
void add_diffusion(Point& pt, const io::config::Config& config, const analysis::Predictions& p, const Measured& m) {
  if (!p.msd) {
    pt.notes.push_back(config.output.msd_start_temperature
                           ? "msd not compared: it starts at msd_start_temperature, a time the theory does not fix"
                           : "msd not compared: no theory MSD for this input");
    return;
  }
  if (!m.has("msd")) {
    pt.notes.push_back("msd not compared: the file has no msd observable");
    return;
  }
  const auto& o = m.observables.at("msd");
  const std::size_t s = columns_of(o), nt = p.msd->time.size();
  if (o.time.size() < nt || nt < 2) {
    pt.notes.push_back("msd not compared: fewer samples in the file than in the theory");
    return;
  }
  const std::size_t first = o.time.size() - nt;  // the samples from msd_start_time on
  const auto err = errors_or_nan(o);
  Quantity q{"msd", "<R_{k}^2>", "maxwellian", std::string(kNone) + " (eq 17 is an approximation, docs/diffusion-msd.md)",
             {}, s, {}, {}, {}, {}};
  for (std::size_t i = 0; i < nt; ++i) {
    q.time.push_back(o.time[first + i]);
    for (std::size_t k = 0; k < s; ++k) {
      q.value.push_back(o.value[(first + i) * s + k]);
      q.error.push_back(err[(first + i) * s + k]);
      q.theory.push_back(p.msd->value[i][k]);
      q.known_error.push_back(kNaN);
    }
  }
  if (s > 1) {
    // D_k/D_1: MSD increments over the last decade of time (Bodrova and Osinsky 2024, eqs. (17), (19), \ref dif_msd "docs/diffusion-msd.md"; validation/diffusion_ratio).
    const std::size_t e = nt - 1;
    std::size_t a = e;
    while (a > 1 && q.time[a] > q.time[e] / 10.0) --a;
    Quantity d{"diffusion_coefficient_ratio", "D_{k}/D_1", "maxwellian",
               std::string(kNone) + " (eq 17 increments over the last decade of time)", {}, s, {}, {}, {}, {}};
    const double d1 = q.value[e * s] - q.value[a * s];
    const double d1_se = std::hypot(q.error[e * s], q.error[a * s]);
    const double t1 = q.theory[e * s] - q.theory[a * s];
    d.columns = s - 1;  // k = 2..s
    d.label_offset = 1;
    d.at = "last decade";
    for (std::size_t k = 1; k < s; ++k) {
      const double dk = q.value[e * s + k] - q.value[a * s + k];
      const double dk_se = std::hypot(q.error[e * s + k], q.error[a * s + k]);
      const double ratio = dk / d1;
      d.value.push_back(ratio);
      d.error.push_back(std::abs(ratio) * std::hypot(dk_se / dk, d1_se / d1));
      d.theory.push_back((q.theory[e * s + k] - q.theory[a * s + k]) / t1);
      d.known_error.push_back(kNaN);
    }
    pt.quantities.push_back(std::move(q));
    pt.quantities.push_back(std::move(d));
  } else {
    pt.quantities.push_back(std::move(q));
  }
}

/// Cluster populations, mean size and temperature of an &agg_frag run (Smoluchowski, \ref af_smoluchowski "docs/agg-frag.md").
void add_agg_frag(Point& pt, const analysis::Predictions& p, const Measured& m) {
  const auto& af = *p.agg_frag;
  const auto& sol = af.solution;
  const std::size_t nt = sol.time.size(), kt = sol.max_size;
  const std::string source = std::string(kNone) + " (the closure is exact only at t = 0, docs/agg-frag.md)";
  auto aligned = [&](const std::string& name) -> const io::h5md::ObservableData* {
    if (!m.has(name)) return nullptr;
    const auto& o = m.observables.at(name);
    if (o.time.size() != nt) {
      pt.notes.push_back(name + " not compared: sample counts of file and theory differ");
      return nullptr;
    }
    return &o;
  };
  if (const auto* o = aligned("number")) {
    const std::size_t kd = columns_of(*o), width = std::min(kd, af.width);
    const auto err = errors_or_nan(*o);
    Quantity q{"number", "N_{k}", "maxwellian", source, o->time, width, {}, {}, {}, {}};
    for (std::size_t i = 0; i < nt; ++i)
      for (std::size_t k = 0; k < width; ++k) {
        q.value.push_back(o->value[i * kd + k]);
        q.error.push_back(err[i * kd + k]);
        q.theory.push_back(sol.number_fraction[i * kt + k] * af.initial_monomers);
        q.known_error.push_back(kNaN);
      }
    pt.quantities.push_back(std::move(q));
  }
  auto series = [&](const std::string& name, const std::string& label, const std::vector<double>& theory) {
    if (const auto* o = aligned(name))
      pt.quantities.push_back(Quantity{name, label, "maxwellian", source, o->time, 1, o->value, errors_or_nan(*o),
                                       theory, std::vector<double>(nt, kNaN)});
  };
  series("mean_size", "<k>", af.mean_size);
  series("total_temperature", "T", sol.total_temperature);
}

}  // namespace

std::pair<double, double> hcs_zeta_star(double t_a, double error_a, double t_b, double error_b, double dt, double nu_unit) {
  const double zeta = 2.0 * (1.0 / std::sqrt(t_b) - 1.0 / std::sqrt(t_a)) / (nu_unit * dt);
  const double da = 0.5 * std::pow(t_a, -1.5) * error_a, db = 0.5 * std::pow(t_b, -1.5) * error_b;
  return {zeta, 2.0 * std::sqrt(da * da + db * db) / (nu_unit * dt)};
}

Mark classify(double difference, double standard_error, double known_error, double scale, double threshold) {
  const double d = std::abs(difference);
  const bool usable = standard_error > 0.0 && std::isfinite(threshold);  // fewer than kMinReplicas: not
  const double statistics = usable ? threshold * standard_error : 0.0;
  if (d <= statistics || d <= kRoundOff * std::abs(scale)) return Mark::statistics;
  if (!(known_error >= 0.0)) return Mark::beyond_no_estimate;  // NaN: none stated
  if (d <= statistics + known_error) return Mark::approximation;
  // Without a usable standard error (one replica, or too few) "beyond statistics" cannot be told.
  return usable && std::isfinite(standard_error) ? Mark::beyond : Mark::beyond_no_estimate;
}

double statistical_threshold(std::size_t replicas) {
  if (replicas == 0) return kStatisticalZ;
  if (replicas < kMinReplicas) return kNaN;
  // Two-sided 3 sigma of the normal distribution, 1 - 2.6998e-3, as a t quantile of R - 1 degrees of freedom.
  return gsl_cdf_tdist_Pinv(1.0 - 0.5 * std::erfc(kStatisticalZ / std::sqrt(2.0)), static_cast<double>(replicas - 1));
}

const char* mark_name(Mark mark) {
  switch (mark) {
    case Mark::statistics: return "stat";
    case Mark::approximation: return "approx";
    case Mark::beyond: return "off";
    case Mark::beyond_no_estimate: return "?";
  }
  return "?";
}

std::optional<ScalingState> scaling_state(const Measured& m, double from, bool replica_averages) {
  for (const char* name : {"temperature", "total_temperature", "sonine_c", "collisions_per_particle"})
    if (!m.has(name)) return std::nullopt;
  const auto& temperature = m.observables.at("temperature");
  const auto& total = m.observables.at("total_temperature");
  const auto& sonine = m.observables.at("sonine_c");
  const auto& per_particle = m.observables.at("collisions_per_particle").value;
  const std::size_t s = columns_of(temperature), nt = total.value.size();
  const auto te = errors_or_nan(temperature), tte = errors_or_nan(total), ce = errors_or_nan(sonine);
  const auto array = [&](const char* name) -> const std::vector<double>* {
    const auto it = m.arrays.find(std::string("scaling_state/") + name);
    return replica_averages && it != m.arrays.end() && it->second.size() == s ? &it->second : nullptr;
  };
  const auto *replica_c = array("sonine_c"), *replica_c_error = array("sonine_c_error");
  const auto *replica_ratio = array("temperature_over_mean"), *replica_ratio_error = array("temperature_over_mean_error");
  ScalingState state;
  state.per_replica = replica_c && replica_c_error && replica_ratio && replica_ratio_error;
  for (std::size_t k = 0; k < s; ++k) {
    std::vector<double> r(nt), re(nt), c(nt), cerr(nt);
    for (std::size_t i = 0; i < nt; ++i) {
      const double tk = temperature.value[i * s + k], t = total.value[i];
      r[i] = tk / t;  // ratio of the replica means (sample.hpp)
      re[i] = r[i] * std::hypot(te[i * s + k] / tk, tte[i] / t);
      c[i] = sonine.value[i * s + k];
      cerr[i] = ce[i * s + k];
    }
    Average ar = scaling_average(r, re, per_particle, from);
    Average ac = scaling_average(c, cerr, per_particle, from);
    state.samples = ar.count;
    if (state.per_replica) {  // the averages per replica, and the SE over the replicas (/scaling_state)
      ar.value = replica_ratio->at(k), ar.error = replica_ratio_error->at(k);
      ac.value = replica_c->at(k), ac.error = replica_c_error->at(k);
    }
    state.ratio.push_back(ar.value);
    state.ratio_error.push_back(ar.error);
    state.cumulant.push_back(ac.value);
    state.cumulant_error.push_back(ac.error);
  }
  return state;
}

Average scaling_average(const std::vector<double>& value, const std::vector<double>& error,
                        const std::vector<double>& collisions_per_particle, double start) {
  Average a;
  for (std::size_t i = 0; i < value.size() && i < collisions_per_particle.size(); ++i) {
    if (collisions_per_particle[i] < start) continue;
    a.value += value[i];
    a.error += i < error.size() ? error[i] : kNaN;
    ++a.count;
  }
  if (a.count > 0) {
    a.value /= static_cast<double>(a.count);
    a.error /= static_cast<double>(a.count);
  }
  return a;
}

double sonine_rate_error(const species::Mixture& mix, const std::vector<double>& sonine_c) {
  // docs/physics.md "Known limits": the Maxwellian rates omit (3/16)|a2| (\ref haff_sonine "docs/haff-and-mixtures.md"); largest over the
  // pairs and over the species' first-Sonine a2 = c_k/2 (validation/polydisperse).
  double a2 = 0.0;
  for (double alpha : mix.restitution.values) a2 = std::max(a2, std::abs(theory::sonine_a2(alpha)));
  for (double c : sonine_c) a2 = std::max(a2, 0.5 * std::abs(c));
  return 3.0 / 16.0 * a2;
}

double cumulant_known_error(const species::Mixture& mix) {
  std::vector<double> alphas;
  const std::size_t s = mix.size(), stride = std::max<std::size_t>(1, s / 64);  // many species: a grid of pairs
  for (std::size_t k = 0; k < s; k += stride)
    for (std::size_t j = k; j < s; j += stride) {
      const double alpha = mix.restitution(k, j);
      if (alpha < 1.0 && std::none_of(alphas.begin(), alphas.end(), [&](double a) { return std::abs(a - alpha) < 1e-12; }))
        alphas.push_back(alpha);
    }
  std::sort(alphas.begin(), alphas.end());
  if (alphas.size() > kCumulantAlphas) {  // many pair values: an even spread of them, the extremes included
    std::vector<double> spread;
    for (std::size_t i = 0; i < kCumulantAlphas; ++i) spread.push_back(alphas[i * (alphas.size() - 1) / (kCumulantAlphas - 1)]);
    alphas = spread;
  }
  double size = 0.0;
  for (double alpha : alphas)  // \ref sonine_higher "theory/sonine.hpp": nonlinear K = 2 and K = 3
    size = std::max(size, std::abs(theory::one_species_hcs_sonine(alpha, 2).cumulant_c -
                                   theory::one_species_hcs_sonine(alpha, 3).cumulant_c));
  return size;
}

double shear_viscosity_known_error(const species::Mixture& mix) {
  if (mix.enskog) return kNaN;  // no independent estimate at finite density (validation/shear_viscosity)
  double alpha_min = 1.0;
  for (double a : mix.restitution.values) alpha_min = std::min(alpha_min, a);
  if (mix.size() == 1) {
    // \ref eta_measured "docs/shear-viscosity.md" and Chapman-Cowling: 1.6 % for alpha >= 0.75, linear to 2.8 % at alpha = 0.6.
    const double first = alpha_min >= 0.75 ? 0.016
                         : alpha_min <= 0.6 ? 0.028
                                            : 0.016 + (0.75 - alpha_min) / 0.15 * (0.028 - 0.016);
    return first + kStageBias;
  }
  if (mix.size() == 2 && alpha_min >= 0.85) return 0.01 + kStageBias;  // \ref eta_mixture "docs/shear-viscosity.md", mass ratio 3
  return kNaN;
}

Measured read_measured(const std::string& file, const std::string& root) {
  Measured m;
  for (const char* name : {"total_temperature", "temperature", "sonine_c", "collisions_per_particle", "time", "msd",
                           "number", "mean_size", "rotational_temperature", "cumulant_a20", "cumulant_a02", "cumulant_a11",
                           "reduced_shear_rate", "pressure_tensor"}) {
    try {
      m.observables.emplace(name, io::h5md::read_observable(file, root + "/" + name));
    } catch (const std::runtime_error&) {
      // not written for this kind of run
    }
  }
  if (m.observables.empty()) throw std::runtime_error("cannot read the observables of '" + file + "' under " + root);
  for (const auto& [group, name] : std::vector<std::pair<std::string, std::string>>{
           {"reduced_distribution", "cooling_rate_reduced"},
           {"reduced_distribution", "cooling_rate_reduced_error"},
           {"shear_viscosity", "time_average"},
           {"shear_viscosity", "time_average_error"}}) {
    try {
      m.attributes[group + "@" + name] = io::h5md::read_double_attribute(file, root + "/" + group, name);
    } catch (const std::runtime_error&) {
    }
  }
  for (const char* name : {"value", "error"}) {
    try {
      m.arrays[std::string("shear_state/") + name] = io::h5md::read_dataset(file, root + "/shear_state/" + name).data;
    } catch (const std::runtime_error&) {
      // runs without &shear, or one replica (no error)
    }
  }
  for (const char* name : {"sonine_c", "sonine_c_error", "temperature_over_mean", "temperature_over_mean_error"}) {
    try {
      m.arrays[std::string("scaling_state/") + name] = io::h5md::read_dataset(file, root + "/scaling_state/" + name).data;
    } catch (const std::runtime_error&) {
      // files of runs without a scaling state, or written before it existed
    }
  }
  return m;
}

/// The known error of Grad's steady shear flow (\ref eta_usf_steady "docs/shear-viscosity.md"): |Grad - the independent
/// program| at alpha = 0.9, 0.7, 0.5 (the table there), at a table point its own, between two the larger (0 at
/// alpha = 1); NaN below 0.5, where no estimate was made. `which`: 0 a*, 1-4 P_xx, P_yy, P_zz, P_xy over p.
double steady_shear_known_error(double alpha, std::size_t which) {
  constexpr double kAlpha[4] = {1.0, 0.9, 0.7, 0.5};
  constexpr double kGap[5][4] = {{0.0, 0.00548, 0.03704, 0.08436},
                                 {0.0, 0.00342, 0.00595, 0.00342},
                                 {0.0, 0.00773, 0.01970, 0.03183},
                                 {0.0, 0.01115, 0.02565, 0.02842},
                                 {0.0, 0.00076, 0.00125, 0.00352}};
  if (!(alpha >= kAlpha[3])) return kNaN;
  for (std::size_t i = 0; i < 4; ++i)
    if (alpha == kAlpha[i]) return kGap[which][i];  // a table point: its own gap
  for (std::size_t i = 1; i < 4; ++i)
    if (alpha > kAlpha[i]) return std::max(kGap[which][i - 1], kGap[which][i]);
  return kNaN;
}

namespace {

/// a* and P_ij/p of the steady shear flow from /observables/shear_state (docs/output.md): each replica's time
/// average from &shear average_from on, and the SE over the replicas; false when the file has none (or the
/// gas is dense: its P/(nT) there is the kinetic part's, not the P_ij/p of Grad's solution).
bool add_steady_shear_average(const std::function<void(const std::string&, const std::string&, double, double, double,
                                                       std::size_t)>& add,
                              const io::config::Config& config, const theory::viscosity::MixtureSteadyShear& grad,
                              const Measured& m) {
  const auto value = m.arrays.find("shear_state/value"), error = m.arrays.find("shear_state/error");
  if (config.system.enskog || value == m.arrays.end() || value->second.size() != 5) return false;
  const auto se = [&](std::size_t c) { return error == m.arrays.end() || error->second.size() != 5 ? kNaN : error->second[c]; };
  add("steady_shear_rate", "a*", value->second[0], se(0), grad.reduced_shear_rate, 0);
  const double theory[4] = {grad.pressure_xx, grad.pressure_yy, grad.pressure_zz, grad.pressure_xy};
  const char* component[4] = {"xx", "yy", "zz", "xy"};
  for (std::size_t c = 0; c < 4; ++c)  // (dilute: p = n T, with T = tr P/(3 n) as shear_state's)
    add(std::string("steady_shear_pressure_") + component[c], std::string("P_") + component[c] + "/p",
        value->second[c + 1], se(c + 1), theory[c], c + 1);
  return true;
}

/// The steady shear flow without thermostat of one dilute species: a* and P_ij/p, time averages of the steady
/// state (/observables/shear_state; in files without it, at the last sample), beside Grad's solution (\ref
/// eta_usf_steady "docs/shear-viscosity.md"); a mixture's T_k/T at the last sample.
void add_steady_shear(Point& pt, const io::config::Config& config, const theory::viscosity::MixtureSteadyShear& grad,
                      const Measured& m) {
  if (!m.has("reduced_shear_rate") || !m.has("pressure_tensor")) return;
  const auto& rate = m.observables.at("reduced_shear_rate");
  const auto& pressure = m.observables.at("pressure_tensor");
  if (rate.value.empty() || pressure.value.size() < 6) return;
  // known errors from the second method for one species (the table of docs/shear-viscosity.md); none for mixtures
  const bool one = grad.temperature_ratio.size() == 1;
  const double alpha = config.mixture().restitution(0, 0);
  const std::string source = one ? "docs/shear-viscosity.md#eta_usf_steady: |Grad - the independent program| at alpha = 0.9, 0.7, 0.5"
                                 : kNone;
  std::string at = "last sample";
  const auto add = [&](const std::string& name, const std::string& label, double value, double error, double theory,
                       std::size_t which) {
    Quantity q{name, label, "grad", source, {}, 1, {value}, {error}, {theory},
               {one ? steady_shear_known_error(alpha, which) : kNaN}};
    q.at = at;
    pt.quantities.push_back(std::move(q));
  };
  if (!one && m.has("temperature") && m.has("total_temperature")) {  // T_k/T of the mixture
    const auto& t = m.observables.at("temperature");
    const auto& total = m.observables.at("total_temperature");
    const std::size_t s = grad.temperature_ratio.size();
    if (t.value.size() >= s && !total.value.empty()) {
      const double mean = total.value.back(), mean_error = total.error.empty() ? kNaN : total.error.back();
      for (std::size_t k = 0; k < s; ++k) {
        const double tk = t.value[t.value.size() - s + k], tk_error = t.error.empty() ? kNaN : t.error[t.error.size() - s + k];
        const double ratio = tk / mean;
        add("steady_shear_temperature_ratio_" + std::to_string(k + 1), "T_" + std::to_string(k + 1) + "/T", ratio,
            ratio * std::hypot(tk_error / tk, mean_error / mean), grad.temperature_ratio[k], 0);
      }
    }
  }
  at = "time average";
  if (add_steady_shear_average(add, config, grad, m)) return;
  at = "last sample";
  add("steady_shear_rate", "a*", rate.value.back(), rate.error.empty() ? kNaN : rate.error.back(),
      grad.reduced_shear_rate, 0);
  // p = tr P/3 of the same sample (the tensor is sampled at the middle of the streaming jump, the temperature
  // after it: thermostat.hpp, "Sampling point")
  const std::size_t last = pressure.value.size() - 6;  // columns xx yy zz xy xz yz
  const double* row = pressure.value.data() + last;
  const double p = (row[0] + row[1] + row[2]) / 3.0;
  double p_error = kNaN;
  if (!pressure.error.empty()) {
    const double* e = pressure.error.data() + last;
    p_error = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]) / 3.0;
  }
  const double theory[4] = {grad.pressure_xx, grad.pressure_yy, grad.pressure_zz, grad.pressure_xy};
  const char* component[4] = {"xx", "yy", "zz", "xy"};
  for (std::size_t c = 0; c < 4; ++c) {
    const double pij = row[c], ratio = pij / p;
    const double pij_error = pressure.error.empty() ? kNaN : pressure.error[last + c];
    // (P_ij and p of one sample are correlated: the two relative errors added in quadrature, an upper bound)
    const double error = std::abs(ratio) * std::hypot(pij_error / pij, p_error / p);
    add(std::string("steady_shear_pressure_") + component[c], std::string("P_") + component[c] + "/p", ratio, error,
        theory[c], c + 1);
  }
}

}  // namespace

Point compare_point(const io::config::Config& config, const analysis::Predictions& p, const Measured& m) {
  Point pt;
  pt.replicas = static_cast<std::size_t>(config.dsmc.replicas);
  for (const auto& note : p.notes) pt.notes.push_back("theory: " + note);
  if (p.agg_frag) {
    add_agg_frag(pt, p, m);
  } else {
    if (p.has_history && config.rough()) add_rough(pt, p, m, config.dsmc.t_end.has_value());
    else if (p.has_history) add_free_cooling(pt, config, p, m);
    if (p.rough_mixture_hcs && config.thermostat.kind == io::config::ThermostatKind::none)  // the free-cooling state
      add_rough_mixture(pt, *p.rough_mixture_hcs, m);
    const bool hss = config.thermostat.kind == io::config::ThermostatKind::gaussian && !config.shear.rate;
    if ((!config.staged() || hss) && p.hcs_first_sonine) add_scaling_state(pt, config, p, m);
    if (config.output.track_displacements) add_diffusion(pt, config, p, m);
    if (p.white_noise) add_white_noise(pt, *p.white_noise, m);
    if (p.white_noise_mixture) add_white_noise_mixture(pt, *p.white_noise_mixture, p.white_noise_mixture_sonine, m);
    if (config.shear.rate) {
      const auto eta = m.attributes.find("shear_viscosity@time_average");
      if (config.thermostat.kind != io::config::ThermostatKind::gaussian) {
        pt.notes.push_back("shear_viscosity not compared: the theory is that of the thermostatted state (HSS); "
                           "this &shear run has no Gaussian thermostat");
        if (config.thermostat.kind == io::config::ThermostatKind::none && p.steady_shear_grad)
          add_steady_shear(pt, config, *p.steady_shear_grad, m);
      } else if (!p.shear_viscosity_hss) {
        pt.notes.push_back("shear_viscosity not compared: no viscosity theory for this mixture");
      } else if (eta != m.attributes.end()) {
        const auto eta_error = m.attributes.find("shear_viscosity@time_average_error");
        const double known = shear_viscosity_known_error(config.mixture());
        pt.quantities.push_back(Quantity{
            "shear_viscosity", "eta/eta_0", "first_sonine",
            "docs/shear-viscosity.md, Chapman-Cowling (validation/shear_viscosity), plus 0.33 % stage splitting", {}, 1,
            {eta->second}, {eta_error == m.attributes.end() ? kNaN : eta_error->second}, {*p.shear_viscosity_hss},
            {known * *p.shear_viscosity_hss}, "time average"});
      }
    }
    if (p.binary_hcs)
      pt.notes.push_back("tail exponents not compared: the file holds no measured exponent "
                         "(reduced_distribution/species_k@tail_beta is the theory's beta_k, Montanero and Garzo 2002, eq. (20), docs/sonine.md)");
  }
  if (pt.quantities.empty()) pt.notes.push_back("no theory applies to this input: nothing compared");
  return pt;
}

std::vector<PointTheory> predict_points(const io::config::Config& config, const theory::smoluchowski::Stop& stop) {
  std::vector<PointTheory> out;
  for (const auto& point : config.sweep_points()) {
    PointTheory t;
    try {
      if (stop && stop()) throw theory::smoluchowski::Stopped();
      t.predictions = analysis::predict(point, stop);
    } catch (const std::exception& e) {  // the theory failed: the table says so instead of failing
      t.error = e.what();
    }
    out.push_back(std::move(t));
  }
  return out;
}

Comparison compare_file(const io::config::Config& config, const std::string& file, std::vector<PointTheory> theory) {
  Comparison c;
  c.sweep = config.is_sweep();
  c.sweep_variable = config.sweep.names();
  const auto table = config.sweep.table();
  if (c.sweep)
    for (const auto& row : table) c.sweep_values.push_back(io::config::Sweep::row_text(row));
  const auto points = config.sweep_points();
  if (theory.size() != points.size()) theory = predict_points(config);
  for (std::size_t k = 0; k < points.size(); ++k) {
    std::string root = "/observables";
    if (c.sweep) {
      root = "/sweep/point_";
      root += std::to_string(k + 1);
      root += "/observables";
    }
    Point pt;
    if (!theory[k].predictions) {
      pt.notes.push_back("nothing compared: the theory failed: " + theory[k].error);
    } else {
      try {
        pt = compare_point(points[k], *theory[k].predictions, read_measured(file, root));
      } catch (const std::exception& e) {
        pt.notes.push_back(std::string("nothing compared: ") + e.what());
      }
    }
    if (c.sweep) pt.label = config.sweep.variable.size() == 1 ? config.sweep.variable[0] + " = " + table[k][0]
                                                              : config.sweep.row_label(table[k]);
    c.points.push_back(std::move(pt));
  }
  return c;
}

std::vector<Row> rows(const Comparison& comparison) {
  std::vector<Row> out;
  for (const auto& pt : comparison.points)
    for (const auto& q : pt.quantities) {
      const std::size_t n = q.samples(), last = n - 1;
      for (std::size_t k = 0; k < q.columns; ++k) {
        Row r;
        r.point = pt.label;
        r.name = q.name;
        r.quantity = species_label(q.label, k + q.label_offset);
        r.at = q.at;
        r.trajectory = !q.time.empty();
        r.time = r.trajectory ? q.time[last] : 0.0;
        const std::size_t at = last * q.columns + k;
        r.value = q.value[at];
        r.error = q.error[at];
        r.theory = q.theory[at];
        r.known_error = q.known_error[at];
        r.approximation = q.approximation;
        const double d = r.value - r.theory;
        r.z = r.error > 0.0 ? d / r.error : kNaN;
        // (a theory value below round-off of the measured one is a zero computed with round-off, e.g. the
        // cooling rate of an elastic, perfectly rough gas: no percentage of it)
        const double measured_scale = std::max(std::abs(r.value), std::isfinite(r.error) ? r.error : 0.0);
        r.percent = std::abs(r.theory) > kRoundOff * measured_scale ? 100.0 * d / std::abs(r.theory) : kNaN;
        r.threshold = statistical_threshold(pt.replicas);
        r.mark = classify(d, r.error, r.known_error, r.theory, r.threshold);
        if (r.trajectory)
          for (std::size_t i = 0; i < n; ++i) {
            const std::size_t j = i * q.columns + k;
            ++r.counts[static_cast<int>(
                classify(q.value[j] - q.theory[j], q.error[j], q.known_error[j], q.theory[j], r.threshold))];
          }
        out.push_back(std::move(r));
      }
    }
  return out;
}

namespace {

std::string format(const char* spec, double x) {
  if (std::isnan(x)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, spec, x);
  return buf;
}

/// Pads the columns of `cells` (rows of strings) to a common width, two spaces apart.
std::string aligned_table(const std::vector<std::vector<std::string>>& cells) {
  std::vector<std::size_t> width;
  for (const auto& row : cells)
    for (std::size_t c = 0; c < row.size(); ++c) {
      if (width.size() <= c) width.push_back(0);
      width[c] = std::max(width[c], row[c].size());
    }
  std::string out;
  for (const auto& row : cells) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c) {
      line += row[c];
      if (c + 1 < row.size()) line += std::string(width[c] - row[c].size() + 2, ' ');
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  }
  return out;
}

}  // namespace

namespace {

/// The last lines of the table: what the marks mean for the replicas of these points.
std::string legend(const Comparison& comparison) {
  std::vector<std::size_t> replicas;
  for (const auto& pt : comparison.points)
    if (std::find(replicas.begin(), replicas.end(), pt.replicas) == replicas.end()) replicas.push_back(pt.replicas);
  std::string statistics;
  for (std::size_t r : replicas) {
    char text[200];
    const double z = statistical_threshold(r);
    if (r == 0)
      std::snprintf(text, sizeof text, "|D-T| <= %g SE", kStatisticalZ);
    else if (std::isnan(z))
      std::snprintf(text, sizeof text, "%zu replica(s): fewer than %zu, no statistical mark but to round-off agreement (give &dsmc replicas >= %zu)", r,
                    kMinReplicas, kMinReplicas);
    else
      std::snprintf(text, sizeof text, "%zu replicas: |D-T| <= %.3g SE (Student's t, %zu degrees of freedom, at the "
                    "level of %g normal SE)", r, z, r - 1, kStatisticalZ);
    statistics += (statistics.empty() ? "" : "; ") + std::string(text);
  }
  return "mark: stat within statistics (" + statistics +
         "); approx within that plus the approximation's known error; off beyond both; ? beyond statistics with no "
         "known error stated, or beyond the known error with no usable SE (docs/physics.md \"Comparison with "
         "theory\"). (D-T)/T % divides by |T| (\"-\": T is 0, or at most 1e-12 max(|D|, SE)). \"at t\": the last sample of a trajectory (every sample is in "
         "/comparison), or what a single value averages.\n";
}

}  // namespace

std::string table(const Comparison& comparison) {
  std::string out = "granular-dsmc --compare: DSMC (mean +- SE over replicas) against theory\n";
  std::vector<std::vector<std::string>> cells;
  std::vector<std::string> header;
  if (comparison.sweep) header.push_back("point");
  for (const char* h : {"quantity", "at t", "DSMC", "+- SE", "theory", "approximation", "(D-T)/SE", "(D-T)/T %",
                        "mark", "samples (stat/approx/off/?)"})
    header.push_back(h);
  cells.push_back(header);
  std::vector<std::string> cut;  // quantities with more columns than the table shows
  for (const auto& pt : comparison.points)
    for (const auto& q : pt.quantities)
      if (q.columns > kTableColumns)
        cut.push_back((pt.label.empty() ? "" : pt.label + ": ") + species_label(q.label, kTableColumns + q.label_offset) +
                      " to " + species_label(q.label, q.columns - 1 + q.label_offset) + " are in /comparison/" + q.name +
                      " and the JSON, not in this table");
  std::size_t column = 0;
  std::string previous;
  for (const auto& r : rows(comparison)) {
    const std::string key = r.point + "\n" + r.name;
    column = key == previous ? column + 1 : 0;
    previous = key;
    if (column >= kTableColumns) continue;
    std::vector<std::string> row;
    if (comparison.sweep) row.push_back(r.point);
    row.push_back(r.quantity);
    row.push_back(r.trajectory ? format("%.6g", r.time) : r.at);
    row.push_back(format("%.6g", r.value));
    row.push_back(format("%.2g", r.error));
    row.push_back(format("%.6g", r.theory));
    row.push_back(r.approximation);
    row.push_back(format("%+.1f", r.z));
    row.push_back(format("%+.3f", r.percent));
    row.push_back(mark_name(r.mark));
    if (r.trajectory) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%zu/%zu/%zu/%zu", r.counts[0], r.counts[1], r.counts[2], r.counts[3]);
      row.push_back(buf);
    } else {
      row.push_back("");
    }
    cells.push_back(std::move(row));
  }
  if (cells.size() > 1) out += aligned_table(cells);
  for (const auto& text : cut) out += "note: " + text + "\n";
  for (const auto& pt : comparison.points)
    for (const auto& note : pt.notes) out += "note: " + (pt.label.empty() ? "" : pt.label + ": ") + note + "\n";
  out += legend(comparison);
  return out;
}

namespace {

using json::number;
using json::quote;

/// [e(0), ...] or, for a trajectory with several columns, [[...], ...]: an entry per value of `q`, in its shape.
template <class Entry>
std::string shaped(const Quantity& q, Entry entry) {
  std::string out = "[";
  const bool nested = !q.time.empty() && q.columns > 1;
  for (std::size_t i = 0; i < q.samples(); ++i) {
    if (nested) out += (i ? ", [" : "[");
    for (std::size_t k = 0; k < q.columns; ++k) {
      const std::size_t at = i * q.columns + k;
      out += ((nested ? k : at) ? ", " : "") + entry(at);
    }
    if (nested) out += "]";
  }
  return out + "]";
}

/// The numbers `v` of `q` in its shape.
std::string values(const Quantity& q, const std::vector<double>& v) {
  return shaped(q, [&](std::size_t at) { return number(v[at]); });
}

/// The Mark of every entry of `q`, row-major as its values.
std::vector<std::string> marks(const Quantity& q, double threshold) {
  std::vector<std::string> out;
  for (std::size_t j = 0; j < q.value.size(); ++j)
    out.emplace_back(mark_name(classify(q.value[j] - q.theory[j], q.error[j], q.known_error[j], q.theory[j], threshold)));
  return out;
}

/// The marks of `q` in its shape.
std::string mark_values(const Quantity& q, double threshold) {
  const auto all = marks(q, threshold);
  return shaped(q, [&](std::size_t at) { return quote(all[at]); });
}

std::string point_json(const Point& pt, const std::string& indent) {
  std::ostringstream j;
  const std::string in = indent + "  ";
  j << indent << "{\n";
  if (!pt.label.empty()) j << in << "\"point\": " << quote(pt.label) << ",\n";
  const double threshold = statistical_threshold(pt.replicas);
  j << in << "\"replicas\": " << pt.replicas << ",\n" << in << "\"statistical_threshold\": " << number(threshold)
    << ",\n";
  j << in << "\"quantities\": {";
  for (std::size_t n = 0; n < pt.quantities.size(); ++n) {
    const auto& q = pt.quantities[n];
    j << (n ? "," : "") << "\n" << in << "  " << quote(q.name) << ": {\"label\": " << quote(q.label)
      << ", \"approximation\": " << quote(q.approximation) << ", \"known_error_source\": "
      << quote(q.known_error_source) << ", \"columns\": " << q.columns;
    if (q.label_offset) j << ", \"first_column\": " << q.label_offset + 1;
    if (!q.at.empty()) j << ", \"at\": " << quote(q.at);
    if (!q.time.empty()) {
      std::string t = "[";
      for (std::size_t i = 0; i < q.time.size(); ++i) t += (i ? ", " : "") + number(q.time[i]);
      j << ", \"time\": " << t << "]";
    }
    j << ", \"value\": " << values(q, q.value) << ", \"error\": " << values(q, q.error)
      << ", \"theory\": " << values(q, q.theory) << ", \"known_error\": " << values(q, q.known_error)
      << ", \"mark\": " << mark_values(q, threshold) << "}";
  }
  j << (pt.quantities.empty() ? "" : "\n" + in) << "},\n" << in << "\"notes\": [";
  for (std::size_t n = 0; n < pt.notes.size(); ++n) j << (n ? ", " : "") << quote(pt.notes[n]);
  j << "]\n" << indent << "}";
  return j.str();
}

}  // namespace

std::string json(const Comparison& comparison) {
  if (!comparison.sweep) return point_json(comparison.points.at(0), "") + "\n";
  std::string out = "{\n  \"sweep\": {\"variable\": " + quote(comparison.sweep_variable) + ", \"values\": [";
  for (std::size_t k = 0; k < comparison.sweep_values.size(); ++k)
    out += (k ? ", " : "") + quote(comparison.sweep_values[k]);
  out += "]},\n  \"points\": [\n";
  for (std::size_t k = 0; k < comparison.points.size(); ++k)
    out += (k ? ",\n" : "") + point_json(comparison.points[k], "    ");
  return out + "\n  ]\n}\n";
}

namespace {

/// The unit of a compared quantity (io/units.hpp): an observable's own (the table of observables,
/// model/observables.hpp), else that of the quantities only --compare makes, all ratios or reduced
/// values but the white-noise steady temperature; empty for a name neither knows (then no attribute;
/// FiniteOutputs.EveryDatasetOfEveryKindOfOutputIsFinite checks that every compared quantity has one).
std::string unit_of(const std::string& name) {
  try {
    return io::units::of_observable(name);
  } catch (const std::out_of_range&) {  // (not an observable: one of --compare's own quantities)
  }
  if (name == "white_noise_temperature") return io::units::kEnergy;
  for (const char* ratio : {"diffusion_coefficient_ratio", "rough_temperature_over_mean", "rough_theta", "steady_shear_rate",
                            "temperature_ratio", "theta", "theta_sonine", "white_noise_a20", "white_noise_a02",
                            "white_noise_a11", "white_noise_theta", "zeta_star", "zeta_star_sonine"})
    if (name == ratio) return io::units::kDimensionless;
  for (const char* family : {"steady_shear_pressure_", "steady_shear_temperature_ratio_"})  // P_ij/p, T_k/T
    if (name.rfind(family, 0) == 0) return io::units::kDimensionless;
  return {};
}

}  // namespace

void write(io::h5md::Writer& writer, const Comparison& comparison) {
  writer.write_group("/comparison");
  writer.write_attribute("/comparison", "description",
                         "DSMC against theory (granular-dsmc --compare; src/analysis/compare.hpp, docs/physics.md "
                         "\"Comparison with theory\")");
  for (std::size_t p = 0; p < comparison.points.size(); ++p) {
    const Point& pt = comparison.points[p];
    std::string base = "/comparison";
    if (comparison.sweep) {
      base += "/point_";
      base += std::to_string(p + 1);
      writer.write_group(base);
      writer.write_attribute(base, "point", pt.label);
    }
    if (!pt.notes.empty()) writer.write_attribute(base, "notes", pt.notes);
    const double threshold = statistical_threshold(pt.replicas);
    writer.write_attribute(base, "replicas", static_cast<long long>(pt.replicas));
    // What is not given at all (z_R below 4 replicas, the standard errors of one replica, a known error
    // none states) is left out, not written as NaN (docs/physics.md "Comparison with theory"); a dataset
    // with some entries given keeps NaN for the others, as the JSON keeps null.
    const auto given = [](const std::vector<double>& x) {
      return std::any_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); });
    };
    if (std::isfinite(threshold)) writer.write_attribute(base, "statistical_threshold", threshold);
    for (const auto& q : pt.quantities) {
      const std::string g = base + "/" + q.name;
      std::vector<std::size_t> shape;
      if (!q.time.empty()) shape.push_back(q.time.size());
      if (q.time.empty() || q.columns > 1) shape.push_back(q.columns);
      // (a unit on every dataset, as on the observables and the sweep table: a reader needs none of the others)
      const std::string unit = unit_of(q.name);
      const auto put = [&](const char* dataset, const std::vector<double>& x) {
        writer.write_dataset(g + "/" + dataset, x, shape);
        if (!unit.empty()) writer.write_unit(g + "/" + dataset, unit);
      };
      put("value", q.value);
      if (given(q.error)) put("error", q.error);
      put("theory", q.theory);
      if (given(q.known_error)) put("known_error", q.known_error);
      writer.write_attribute(g, "approximation", q.approximation);
      writer.write_attribute(g, "known_error_source", q.known_error_source);
      writer.write_attribute(g, "label", q.label);
      if (q.label_offset) writer.write_attribute(g, "first_column", static_cast<long long>(q.label_offset + 1));
      if (!q.at.empty()) writer.write_attribute(g, "at", q.at);
      if (!q.time.empty()) writer.write_attribute(g, "time", q.time);
      writer.write_attribute(g, "mark", marks(q, threshold));  // row-major as value
    }
  }
}

}  // namespace gdsmc::analysis::compare
