#include "dsmc/sample.hpp"

#include <cmath>

namespace gdsmc::sample {

Moments measure(const species::Mixture& mix, const particles::System& sys) {
  const std::size_t s = sys.n_species();
  Moments m;
  m.temperature.assign(s, 0.0);
  m.sonine_c.assign(s, 0.0);
  m.number.assign(s, 0.0);
  double momentum[3] = {0.0, 0.0, 0.0}, total_mass = 0.0;
  for (std::size_t k = 0; k < s; ++k) {
    double sum[3] = {0.0, 0.0, 0.0};
    const std::size_t end = sys.first[k] + sys.count[k];
    for (std::size_t i = sys.first[k]; i < end; ++i) {
      sum[0] += sys.v[i].x;
      sum[1] += sys.v[i].y;
      sum[2] += sys.v[i].z;
    }
    for (int d = 0; d < 3; ++d) momentum[d] += mix.mass[k] * sum[d];
    total_mass += mix.mass[k] * static_cast<double>(sys.count[k]);
  }
  for (int d = 0; d < 3; ++d) m.mean_flow[d] = momentum[d] / total_mass;
  const double* u = m.mean_flow;
  double weighted = 0.0, n_total = 0.0;
  for (std::size_t k = 0; k < s; ++k) {
    double v2_sum = 0.0, v4_sum = 0.0;
    const std::size_t end = sys.first[k] + sys.count[k];
    for (std::size_t i = sys.first[k]; i < end; ++i) {
      const double cx = sys.v[i].x - u[0], cy = sys.v[i].y - u[1], cz = sys.v[i].z - u[2];
      const double c2 = cx * cx + cy * cy + cz * cz;
      v2_sum += c2;
      v4_sum += c2 * c2;
    }
    const double n_k = static_cast<double>(sys.count[k]);
    const double v2 = v2_sum / n_k, v4 = v4_sum / n_k;
    m.number[k] = n_k;
    m.temperature[k] = mix.mass[k] * v2 / 3.0;               // \ref output_observables "docs/output.md"
    m.sonine_c[k] = 2.0 * (0.6 * v4 / (v2 * v2) - 1.0);      // Montanero and Garzo 2002, eq. (17), \ref son_scaling "docs/sonine.md"
    weighted += n_k * m.temperature[k];
    n_total += n_k;
  }
  m.total_temperature = weighted / n_total;
  return m;
}

std::vector<double> velocity_histogram(const species::Mixture& mix, const particles::System& sys,
                                       const Moments& moments, std::size_t bins, double range) {
  const std::size_t s = sys.n_species();
  std::vector<double> h(s * bins, 0.0);
  const double width = 2.0 * range / static_cast<double>(bins);
  for (std::size_t k = 0; k < s; ++k) {
    const double inv_scale = std::sqrt(mix.mass[k] / moments.temperature[k]);
    const double* u = moments.mean_flow;
    double* hk = h.data() + k * bins;
    const std::size_t end = sys.first[k] + sys.count[k];
    auto put = [&](double v) {
      const double c = v * inv_scale;
      if (c < -range || c >= range) return;
      const auto b = static_cast<std::size_t>((c + range) / width);
      hk[b < bins ? b : bins - 1] += 1.0;
    };
    for (std::size_t i = sys.first[k]; i < end; ++i) {
      put(sys.v[i].x - u[0]);
      put(sys.v[i].y - u[1]);
      put(sys.v[i].z - u[2]);
    }
    const double norm = 1.0 / (3.0 * static_cast<double>(sys.count[k]) * width);
    for (std::size_t b = 0; b < bins; ++b) hk[b] *= norm;
  }
  return h;
}

std::vector<double> mean_squared_displacement(const particles::System& sys, double t) {
  std::vector<double> msd(sys.n_species(), 0.0);
  for (std::size_t k = 0; k < sys.n_species(); ++k) {
    double sum = 0.0;
    const std::size_t end = sys.first[k] + sys.count[k];
    for (std::size_t i = sys.first[k]; i < end; ++i) {
      const double dt = t - sys.r[i].t_last;
      const double x = sys.r[i].x + sys.v[i].x * dt, y = sys.r[i].y + sys.v[i].y * dt,
                   z = sys.r[i].z + sys.v[i].z * dt;
      sum += x * x + y * y + z * z;
    }
    msd[k] = sum / static_cast<double>(sys.count[k]);
  }
  return msd;
}

double reduced_velocity_scale(const species::Mixture& mix, double total_temperature) {
  if (mix.size() > 2) return 0.0;
  const double m1 = mix.mass[0], m2 = mix.size() == 2 ? mix.mass[1] : mix.mass[0];
  return std::sqrt(2.0 * total_temperature * (m1 + m2) / (m1 * m2));  // \ref son_scaling "docs/sonine.md"
}

void add_reduced_speeds(const species::Mixture& /*mix*/, const particles::System& sys,
                        const Moments& moments, double v0, std::size_t bins, double range,
                        std::vector<double>& counts) {
  const std::size_t s = sys.n_species();
  counts.resize(s * bins, 0.0);
  const double scale = static_cast<double>(bins) / (range * v0);
  const double* u = moments.mean_flow;
  for (std::size_t k = 0; k < s; ++k) {
    double* ck = counts.data() + k * bins;
    const std::size_t end = sys.first[k] + sys.count[k];
    for (std::size_t i = sys.first[k]; i < end; ++i) {
      const double cx = sys.v[i].x - u[0], cy = sys.v[i].y - u[1], cz = sys.v[i].z - u[2];
      const auto b = static_cast<std::size_t>(std::sqrt(cx * cx + cy * cy + cz * cz) * scale);
      if (b < bins) ck[b] += 1.0;
    }
  }
}

std::vector<double> reduced_distribution(const std::vector<double>& counts,
                                         const std::vector<double>& number, double samples,
                                         std::size_t bins, double range) {
  std::vector<double> phi(counts.size(), 0.0);
  const double width = range / static_cast<double>(bins);
  for (std::size_t k = 0; k < number.size(); ++k)
    for (std::size_t b = 0; b < bins; ++b) {
      const double a = width * static_cast<double>(b), e = a + width;
      const double shell = 4.0 * M_PI / 3.0 * (e * e * e - a * a * a);
      phi[k * bins + b] = counts[k * bins + b] / (samples * number[k] * shell);
    }
  return phi;
}

double maxwellian_shell_average(double lambda, double a, double b) {
  // Q(v) = 1 - P(v) = erfc(x) + (2/sqrt(pi)) x exp(-x^2), x = sqrt(lambda) v: the Maxwell speed
  // distribution's upper tail, written without the cancellation of 1 - erf in the far tail.
  auto tail = [lambda](double v) {
    const double x = std::sqrt(lambda) * v;
    return std::erfc(x) + 2.0 / std::sqrt(M_PI) * x * std::exp(-x * x);
  };
  return (tail(a) - tail(b)) / (4.0 * M_PI / 3.0 * (b * b * b - a * a * a));
}

std::array<double, 6> kinetic_pressure_tensor(const species::Mixture& mix, const particles::System& sys,
                                              const Moments& moments) {
  std::array<double, 6> p{};
  const auto& u = moments.mean_flow;
  for (std::size_t k = 0; k < sys.n_species(); ++k) {
    if (sys.count[k] == 0) continue;
    std::array<double, 6> sum{};
    const std::size_t end = sys.first[k] + sys.count[k];
    for (std::size_t i = sys.first[k]; i < end; ++i) {
      const double x = sys.v[i].x - u[0], y = sys.v[i].y - u[1], z = sys.v[i].z - u[2];
      sum[0] += x * x;
      sum[1] += y * y;
      sum[2] += z * z;
      sum[3] += x * y;
      sum[4] += x * z;
      sum[5] += y * z;
    }
    const double weight = mix.mass[k] * mix.number_density[k] / static_cast<double>(sys.count[k]);
    for (std::size_t c = 0; c < 6; ++c) p[c] += weight * sum[c];
  }
  return p;
}

observables::ReducedDistributions reduced_distributions(const species::Mixture& mix, const std::vector<double>& phi,
                                           const std::vector<double>& phi_error, const std::vector<double>& c,
                                           const std::vector<double>& share, double zeta, std::size_t bins,
                                           double range) {
  const std::size_t s = mix.size();
  const double width = range / static_cast<double>(bins);
  observables::ReducedDistributions out;
  out.edges.resize(bins + 1);
  for (std::size_t b = 0; b <= bins; ++b) out.edges[b] = width * static_cast<double>(b);
  const auto& edges = out.edges;
  const double sigma12 = mix.contact_distance(0, s - 1);
  for (std::size_t k = 0; k < s; ++k) {
    observables::ReducedDistributions::Species sp;
    const std::size_t j = s - 1 - k;  // the other species (itself for one species)
    const double mu_jk = mix.mass[j] / (mix.mass[k] + mix.mass[j]);
    const double lambda = 1.0 / (share[k] * mu_jk);  // lambda_i = T/(T_i mu_ji), \ref son_binary "docs/sonine.md"
    double beta = 0.0;  // Montanero and Garzo 2002, eq. (20), \ref son_tails "docs/sonine.md"
    for (std::size_t l = 0; l < s; ++l) {
      const double ratio = mix.contact_distance(k, l) / sigma12;
      beta += M_PI * mix.mole_fraction(l) * mix.pair_correlation(k, l) * ratio * ratio;
    }
    std::vector<double> value(bins), error(bins), delta(bins), delta_error(bins), g(bins), g_error(bins);
    for (std::size_t b = 0; b < bins; ++b) {
      value[b] = phi[k * bins + b];
      error[b] = phi_error.empty() ? 0.0 : phi_error[k * bins + b];
      const double maxwell = maxwellian_shell_average(lambda, edges[b], edges[b + 1]);
      // eq 27; far out the Maxwellian underflows to 0 and Delta is undefined: written as 0 there
      // (never NaN), and Phi itself, always finite, is the quantity to read in the far tail.
      const bool defined = maxwell > 0.0 && c[k] != 0.0;
      delta[b] = defined ? 2.0 / c[k] * (value[b] / maxwell - 1.0) : 0.0;
      delta_error[b] = defined ? 2.0 / std::abs(c[k]) * error[b] / maxwell : 0.0;
      // eq 30; without cooling (zeta* = 0: an elastic or driven gas) there is no exponential tail and
      // the weight overflows: G is written as 0 there, as Delta is (never Inf or NaN).
      const double weight = zeta > 0.0 ? std::exp(2.0 * beta * 0.5 * (edges[b] + edges[b + 1]) / zeta) : 0.0;
      const bool g_defined = std::isfinite(weight * value[b]) && std::isfinite(weight * error[b]);
      g[b] = g_defined ? weight * value[b] : 0.0;
      g_error[b] = g_defined ? weight * error[b] : 0.0;
    }
    sp.value = std::move(value);
    sp.delta = std::move(delta);
    sp.g = std::move(g);
    if (!phi_error.empty()) {
      sp.error = std::move(error);
      sp.delta_error = std::move(delta_error);
      sp.g_error = std::move(g_error);
    }
    sp.sonine_c = c[k];
    sp.lambda = lambda;
    sp.tail_beta = beta;
    out.species.push_back(std::move(sp));
  }
  return out;
}

observables::ClusterTemperature cluster_temperature(const std::vector<std::vector<double>>& number,
                                       const std::vector<std::vector<double>>& energy, std::size_t entries) {
  observables::ClusterTemperature t;
  const std::size_t replicas = number.size();
  for (std::size_t c = 0; c < entries; ++c) {
    double sum_n = 0.0, sum_e = 0.0;
    for (std::size_t r = 0; r < replicas; ++r) {
      sum_n += number[r][c];
      sum_e += energy[r][c];
    }
    const double rho = sum_n > 0.0 ? sum_e / sum_n : 0.0;
    t.value.push_back(2.0 / 3.0 * rho);
    if (replicas > 1) {
      double residual2 = 0.0;
      for (std::size_t r = 0; r < replicas; ++r) {
        const double d = energy[r][c] - rho * number[r][c];
        residual2 += d * d;
      }
      const double mean_n = sum_n / static_cast<double>(replicas);
      const double rr = static_cast<double>(replicas);
      t.error.push_back(mean_n > 0.0 ? 2.0 / 3.0 * std::sqrt(residual2 / (rr * (rr - 1.0))) / mean_n : 0.0);
    }
  }
  return t;
}

}  // namespace gdsmc::sample
