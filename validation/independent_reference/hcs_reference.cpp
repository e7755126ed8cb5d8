// An independent reference for the homogeneous cooling state of dilute mixtures of inelastic hard
// spheres: temperature ratios T_k/T and cumulants c_k, by a second method that shares no code with
// src/ (its own random numbers, collision rule, pair selection and sampling). See README.md.
//
// Method. In the homogeneous cooling state the scaled velocity distribution is stationary, and time
// only sets the scale of the velocities: the sequence of collisions (the jump chain of the master
// equation) alone determines T_k/T and c_k. So no time is kept. The next colliding pair is (i, j) with
// probability proportional to sigma_ij^2 |v_i - v_j|, drawn by rejection: a uniform pair is accepted
// with probability sigma_ij^2 |g| / (sigma_max^2 2 v_max) (v_max the largest speed, raised exactly when
// a collision produces a faster particle). The collision vector e is drawn with density proportional
// to (g.e) on the hemisphere g.e > 0 (cos theta = sqrt(u) about g, azimuth uniform), and
// v_i' = v_i - m_j/(m_i + m_j) (1 + alpha_ij)(g.e) e, v_j' = v_j + m_i/(m_i + m_j) (1 + alpha_ij)(g.e) e.
// Every N collisions all velocities are multiplied by one factor that brings T back to 1, which
// changes neither the jump chain (every acceptance probability scales alike) nor the scaled
// distribution, and v_max is recomputed.
//
// Sampling: after `warmup` collisions per particle, once per collision per particle, per species k:
// T_k = m_k <|v - u|^2>_k / 3 and c_k = 2 [(3/5) <|v - u|^4>_k / <|v - u|^2>_k^2 - 1] (u = 0: the total
// momentum is set to zero at every rescaling, and conserved between them), T = sum_k x_k T_k. Each replica (its own seed) gives
// the mean over its samples; the output is the mean over replicas and its standard error.
//
// usage: hcs_reference --mass m1,m2,... --diameter d1,... --fraction x1,... --alpha a
//                      [--particles N] [--warmup W] [--samples S] [--replicas R] [--seed s]
//                      [--expect-gamma value,se] [--expect-c1 value,se] [--bins B --range R]
//        hcs_reference --mass ... --diameter ... --density n1,... --alpha a --log-times first,last,count
//                      [--particles N] [--replicas R] [--seed s]
// the time-resolved mode: T_k(t) from T_k(0) = 1 on the DSMC's log grid of `count` samples (t = 0 and
// first..last), one line "temperature t T_1 se T_2 se ..." per time; with --msd 1 also the mean squared
// displacement of each species, "msd t <R_1^2> se ...".
// --enskog-density n1,...: the homogeneous Enskog gas at these number densities (every pair rate times
// its contact value chi_ij, contact_values below; the fractions follow from the densities).
// --bins, --range: also Phi_1(v*) of species 1 on B bins of [0, R) (Montanero and Garzo 2002, eq. (22)),
// one line "phi b low high value se" per bin.
// --expect-*: compare gamma = T_1/T_2 (or c_1) with a published value at 4 combined SE, print PASS or
// FAIL and exit 1 on FAIL: how ctest checks this program itself against the literature (README.md).
//        hcs_reference --shear a --mass ... --diameter ... --density n1,... --alpha a --t-end T --average-from T0
//                      --sample-every dt [--temperature T0] [--particles N] [--replicas R] [--seed s] [--expect-balance 1]
// the steady uniform shear flow without thermostat (run_shear): T, T_k/T, P_ij/(n T), the energy balance
// heating/loss and, for one species, a* = a eta_0(T)/(n T), each "quantity value se" (validation/shear_viscosity);
// --expect-balance 1: PASS or FAIL of heating/loss = 1 at 4 SE, exit 1 on FAIL.
//        hcs_reference --shear a --thermostat gaussian [--enskog 1 [--expect-eos 1]] --mass ... --diameter ...
//                      --density n1,... --alpha a --t-end T --average-from T0 --sample-every dt [...]
// the uniform shear flow under the Gaussian thermostat (run_shear_thermostat), dilute or Enskog: the time averages
// of eta/sqrt(T) and its kinetic part as the DSMC measures them, T, T_k/T and (Enskog) tr P^c/3 over the Enskog
// equation of state; --expect-eos 1: PASS or FAIL of that ratio = 1 at 4 SE, exit 1 on FAIL.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace {

// splitmix64 to seed, xoshiro256** to draw (Blackman and Vigna): written out here so that nothing is
// shared with src/dsmc/rng.hpp.
struct Random {
  std::uint64_t s[4];
  explicit Random(std::uint64_t seed) {
    for (auto& w : s) {
      seed += 0x9e3779b97f4a7c15ULL;
      std::uint64_t z = seed;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      w = z ^ (z >> 31);
    }
  }
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t next() {
    const std::uint64_t result = rotl(s[1] * 5, 7) * 9, t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return result;
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(uniform() * static_cast<double>(n)); }
  double normal() {  // Box-Muller
    const double u = 1.0 - uniform(), v = uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * 3.14159265358979323846 * v);
  }
};

std::vector<double> numbers(const char* text) {
  std::vector<double> out;
  std::string s(text);
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t comma = s.find(',', start);
    out.push_back(std::atof(s.substr(start, comma == std::string::npos ? std::string::npos : comma - start).c_str()));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

/// Contact values of the pair correlation for hard-sphere mixtures (Boublik; Mansoori, Carnahan,
/// Starling and Leland): chi_ij = 1/(1 - x3) + 3 x2 d_ij/(1 - x3)^2 + 2 x2^2 d_ij^2/(1 - x3)^3 with
/// x_l = (pi/6) sum_k n_k sigma_k^l and d_ij = sigma_i sigma_j/(sigma_i + sigma_j); all 1 when `density`
/// is empty (the dilute gas). Written out here, not taken from src/model/species.cpp.
std::vector<double> contact_values(const std::vector<double>& diameter, const std::vector<double>& density) {
  const std::size_t s = diameter.size();
  std::vector<double> chi(s * s, 1.0);
  if (density.empty()) return chi;
  const double pi = 3.14159265358979323846;
  double x2 = 0.0, x3 = 0.0;
  for (std::size_t k = 0; k < s; ++k) {
    x2 += pi / 6.0 * density[k] * diameter[k] * diameter[k];
    x3 += pi / 6.0 * density[k] * diameter[k] * diameter[k] * diameter[k];
  }
  for (std::size_t i = 0; i < s; ++i)
    for (std::size_t j = 0; j < s; ++j) {
      const double d = diameter[i] * diameter[j] / (diameter[i] + diameter[j]);
      chi[i * s + j] = 1.0 / (1.0 - x3) + 3.0 * x2 * d / ((1.0 - x3) * (1.0 - x3)) +
                       2.0 * x2 * x2 * d * d / ((1.0 - x3) * (1.0 - x3) * (1.0 - x3));
    }
  return chi;
}

/// The species of each of n particles, in proportion to the number densities (the last species takes the rest).
std::vector<std::size_t> species_by_density(const std::vector<double>& density, std::size_t n) {
  const std::size_t s = density.size();
  double n_total = 0.0;
  for (double x : density) n_total += x;
  std::vector<std::size_t> kind(n);
  std::size_t i = 0;
  for (std::size_t k = 0; k < s; ++k) {
    const std::size_t count = k + 1 == s ? n - i : static_cast<std::size_t>(std::llround(n * density[k] / n_total));
    for (std::size_t c = 0; c < count && i < n; ++c) kind[i++] = k;
  }
  return kind;
}

/// The collision vector e with density ~ (g.e) on the hemisphere about g (cos theta = sqrt(u) about g, the
/// azimuth uniform, two draws in this order); returns g.e. g = |(gx, gy, gz)| > 0.
double contact(Random& rng, double gx, double gy, double gz, double g, double& ex, double& ey, double& ez) {
  const double ct = std::sqrt(rng.uniform()), st = std::sqrt(1.0 - ct * ct);
  const double phi = 2.0 * 3.14159265358979323846 * rng.uniform();
  const double hx = gx / g, hy = gy / g, hz = gz / g;
  // an orthonormal pair perpendicular to h
  double px, py, pz;
  if (std::abs(hx) < 0.9) {
    px = 0.0;
    py = hz;
    pz = -hy;
  } else {
    px = -hz;
    py = 0.0;
    pz = hx;
  }
  const double pn = std::sqrt(px * px + py * py + pz * pz);
  px /= pn;
  py /= pn;
  pz /= pn;
  const double qx = hy * pz - hz * py, qy = hz * px - hx * pz, qz = hx * py - hy * px;
  ex = ct * hx + st * (std::cos(phi) * px + std::sin(phi) * qx);
  ey = ct * hy + st * (std::cos(phi) * py + std::sin(phi) * qy);
  ez = ct * hz + st * (std::cos(phi) * pz + std::sin(phi) * qz);
  return g * ct;
}

struct Result {
  std::vector<double> ratio, cumulant;  // T_k/T, c_k (replica means)
  std::vector<double> phi;              // Phi_1(v*) per bin (replica mean), when asked for
};

Result run(const std::vector<double>& mass, const std::vector<double>& diameter, const std::vector<double>& fraction,
           double alpha, std::size_t n, double warmup, double samples, std::uint64_t seed, std::size_t bins,
           double range, const std::vector<double>& enskog_density) {
  const std::size_t s = mass.size();
  Random rng(seed);
  std::vector<std::size_t> kind(n);
  {
    std::size_t i = 0;
    double total = 0.0;
    for (double x : fraction) total += x;
    for (std::size_t k = 0; k < s; ++k) {
      const std::size_t count = k + 1 == s ? n - i : static_cast<std::size_t>(std::llround(n * fraction[k] / total));
      for (std::size_t c = 0; c < count && i < n; ++c) kind[i++] = k;
    }
  }
  std::vector<double> vx(n), vy(n), vz(n);
  for (std::size_t i = 0; i < n; ++i) {  // Maxwellian at T = 1 for every species
    const double sd = 1.0 / std::sqrt(mass[kind[i]]);
    vx[i] = sd * rng.normal();
    vy[i] = sd * rng.normal();
    vz[i] = sd * rng.normal();
  }
  // The pair weights sigma_ij^2 chi_ij (chi = 1 for the dilute gas), divided by their largest value.
  const auto chi = contact_values(diameter, enskog_density);
  std::vector<double> sigma2(s * s), fraction_to(s * s);
  double weight_max = 0.0;
  for (std::size_t a = 0; a < s; ++a)
    for (std::size_t b = 0; b < s; ++b) {
      const double sab = 0.5 * (diameter[a] + diameter[b]);
      sigma2[a * s + b] = sab * sab * chi[a * s + b];
      weight_max = std::max(weight_max, sigma2[a * s + b]);
      fraction_to[a * s + b] = mass[b] / (mass[a] + mass[b]) * (1.0 + alpha);  // of a's change
    }
  for (double& w : sigma2) w /= weight_max;
  auto rescale = [&]() -> double {  // T back to 1; returns the new v_max
    // The total momentum is conserved only up to round-off, and every rescaling would amplify that
    // round-off (by about 1e23 over 400 collisions per particle at alpha = 0.5): it is removed first.
    // A common velocity shift changes no relative velocity, so the jump chain is unchanged.
    double px = 0, py = 0, pz = 0, mt = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double m = mass[kind[i]];
      px += m * vx[i];
      py += m * vy[i];
      pz += m * vz[i];
      mt += m;
    }
    for (std::size_t i = 0; i < n; ++i) {
      vx[i] -= px / mt;
      vy[i] -= py / mt;
      vz[i] -= pz / mt;
    }
    double e = 0.0;
    for (std::size_t i = 0; i < n; ++i) e += mass[kind[i]] * (vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]);
    const double f = std::sqrt(3.0 * static_cast<double>(n) / e);
    double vmax2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      vx[i] *= f;
      vy[i] *= f;
      vz[i] *= f;
      vmax2 = std::max(vmax2, vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]);
    }
    return std::sqrt(vmax2);
  };
  double vmax = rescale();
  Result result;
  result.ratio.assign(s, 0.0);
  result.cumulant.assign(s, 0.0);
  result.phi.assign(bins, 0.0);
  const auto total = static_cast<std::uint64_t>((warmup + samples) * n / 2.0);
  const auto first_sample = static_cast<std::uint64_t>(warmup * n / 2.0);
  const std::uint64_t sample_every = n / 2, rescale_every = n;
  std::uint64_t taken = 0;
  for (std::uint64_t event = 1; event <= total; ++event) {
    for (;;) {
      const std::size_t i = rng.below(n);
      std::size_t j = rng.below(n - 1);
      if (j >= i) ++j;
      const double gx = vx[i] - vx[j], gy = vy[i] - vy[j], gz = vz[i] - vz[j];
      const double g = std::sqrt(gx * gx + gy * gy + gz * gz);
      const std::size_t a = kind[i], b = kind[j];
      if (rng.uniform() * 2.0 * vmax >= sigma2[a * s + b] * g) continue;
      double ex, ey, ez;
      const double ge = contact(rng, gx, gy, gz, g, ex, ey, ez);
      const double di = fraction_to[a * s + b] * ge, dj = fraction_to[b * s + a] * ge;
      vx[i] -= di * ex;
      vy[i] -= di * ey;
      vz[i] -= di * ez;
      vx[j] += dj * ex;
      vy[j] += dj * ey;
      vz[j] += dj * ez;
      vmax = std::max({vmax, std::sqrt(vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]),
                       std::sqrt(vx[j] * vx[j] + vy[j] * vy[j] + vz[j] * vz[j])});
      break;
    }
    if (event % rescale_every == 0) vmax = rescale();
    if (event > first_sample && event % sample_every == 0) {
      std::vector<double> v2(s, 0.0), v4(s, 0.0), count(s, 0.0);
      for (std::size_t i = 0; i < n; ++i) {
        const double w2 = vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i];
        v2[kind[i]] += w2;
        v4[kind[i]] += w2 * w2;
        count[kind[i]] += 1.0;
      }
      std::vector<double> t(s);
      double t_mix = 0.0;
      for (std::size_t k = 0; k < s; ++k) {
        t[k] = mass[k] * v2[k] / (3.0 * count[k]);
        t_mix += count[k] * t[k] / static_cast<double>(n);
      }
      for (std::size_t k = 0; k < s; ++k) {
        const double m2 = v2[k] / count[k], m4 = v4[k] / count[k];
        result.ratio[k] += t[k] / t_mix;
        result.cumulant[k] += 2.0 * (0.6 * m4 / (m2 * m2) - 1.0);
      }
      if (bins > 0) {
        // Phi_1(v*), v* = |v|/v0, v0 = sqrt(2 T (m1 + m2)/(m1 m2)) (m2 = m1 for one species), normalised
        // to int Phi_1 d^3v* = 1 (Montanero and Garzo 2002, eq. (22)): counts / (N_1 shell volume).
        const double m1 = mass[0], m2 = s > 1 ? mass[1] : mass[0];
        const double v0 = std::sqrt(2.0 * t_mix * (m1 + m2) / (m1 * m2)), width = range / static_cast<double>(bins);
        std::vector<double> histogram(bins, 0.0);
        for (std::size_t i = 0; i < n; ++i) {
          if (kind[i] != 0) continue;
          const double v = std::sqrt(vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]) / v0;
          const auto b = static_cast<std::size_t>(v / width);
          if (b < bins) histogram[b] += 1.0;
        }
        for (std::size_t b = 0; b < bins; ++b) {
          const double lo = width * static_cast<double>(b), hi = lo + width;
          const double shell = 4.0 * 3.14159265358979323846 / 3.0 * (hi * hi * hi - lo * lo * lo);
          result.phi[b] += histogram[b] / (count[0] * shell);
        }
      }
      ++taken;
    }
  }
  for (std::size_t k = 0; k < s; ++k) {
    result.ratio[k] /= static_cast<double>(taken);
    result.cumulant[k] /= static_cast<double>(taken);
  }
  for (double& p : result.phi) p /= static_cast<double>(taken);
  return result;
}

/// Viscoelastic restitution (--visco-beta), computed from the contact model itself, not from the series
/// of src/model/restitution.hpp. Two viscoelastic spheres (Hertz force plus its dissipative part,
/// F = rho (xi^(3/2) + (3/2) A xi^(1/2) xi')) obey, in units where the impact speed |g.e| is 1 and the
/// Hertz time scale is 1,
///   x'' = -x^(3/2) - delta x^(1/2) x',  x(0) = 0, x'(0) = 1,  delta = beta_ki |g.e|^(1/5)
/// (x the compression, beta_ki = A kappa_ki^(2/5) with kappa of the seed's eq 7, which is (3/2)^(5/2) rho/m_eff:
/// the factor 3/2 of the force is absorbed in delta). The contact ends when the force vanishes,
/// x + delta x' = 0 with x > 0 (the surfaces separate faster than the material recovers, and an
/// attractive force is unphysical), and alpha = -x' then. Checks (--visco-check, README.md): (1 - alpha)/delta
/// -> C1 = 1.1534488580952888 as delta -> 0, the published first coefficient, which fixes this
/// normalisation (with (3/2) delta in front of the damping term the limit is (3/2) C1); alpha agrees with
/// 1 + sum_j h_j u^j (u^2 = delta, \ref visco_series "docs/viscoelastic.md") within 5e-9 for u <= 0.5 and 3.1e-7 at
/// u = 0.65, while ending the contact at x = 0 instead does not (it lacks the u^5 term, h_5 = 4/15).
/// Integrated by RK4 on a graded mesh (steps proportional to t at the start and to x/|x'| near the end,
/// where x^(1/2) is not smooth), started at t = 1e-6 from x = t - (4/15) delta t^(5/2) - (4/35) t^(7/2).
struct ContactState {
  double x, v;
};

ContactState contact_rk4(const ContactState& y, double h, double delta) {
  auto f = [delta](const ContactState& s) {
    const double r = std::sqrt(std::max(s.x, 0.0));
    return ContactState{s.v, -s.x * r - delta * r * s.v};
  };
  const ContactState k1 = f(y);
  const ContactState k2 = f({y.x + 0.5 * h * k1.x, y.v + 0.5 * h * k1.v});
  const ContactState k3 = f({y.x + 0.5 * h * k2.x, y.v + 0.5 * h * k2.v});
  const ContactState k4 = f({y.x + h * k3.x, y.v + h * k3.v});
  return {y.x + h / 6.0 * (k1.x + 2.0 * k2.x + 2.0 * k3.x + k4.x), y.v + h / 6.0 * (k1.v + 2.0 * k2.v + 2.0 * k3.v + k4.v)};
}

/// alpha(delta) of the contact model; `force_end` false ends the contact at x = 0 instead (the check of
/// the convention). `h_max` the largest step, `grade` the step as a fraction of t or x/|x'|.
double contact_restitution(double delta, bool force_end = true, double h_max = 2e-4, double grade = 0.01) {
  if (delta <= 0.0) return 1.0;
  const double t0 = 1e-6;
  ContactState y{t0 - 4.0 / 15.0 * delta * std::pow(t0, 2.5) - 4.0 / 35.0 * std::pow(t0, 3.5),
                 1.0 - 2.0 / 3.0 * delta * std::pow(t0, 1.5) - 0.4 * std::pow(t0, 2.5)};
  double t = t0;
  auto end_value = [&](const ContactState& s) { return force_end ? s.x + delta * s.v : s.x; };
  for (int step = 0; step < 100000000; ++step) {
    double h = std::min(h_max, grade * t);
    if (y.v < 0.0) h = std::min(h, std::max(grade * y.x / -y.v, 1e-15));
    if (!force_end && y.v < 0.0 && y.x < 1e-9) {
      // the last stretch to x = 0: x'' integrated with x = |v| s over the remaining time (error O(x^(5/2)))
      return -(y.v + 2.0 / 3.0 * delta * std::pow(y.x, 1.5) - 0.4 * std::pow(y.x, 2.5) / -y.v);
    }
    const ContactState next = contact_rk4(y, h, delta);
    if (y.v < 0.0 && end_value(next) <= 0.0) {
      // the end lies within this step: bisect the step length
      double lo = 0.0, hi = h;
      for (int b = 0; b < 200 && hi - lo > 1e-16 * std::max(1.0, t); ++b) {
        const double mid = 0.5 * (lo + hi);
        (end_value(contact_rk4(y, mid, delta)) > 0.0 ? lo : hi) = mid;
      }
      return -contact_rk4(y, 0.5 * (lo + hi), delta).v;
    }
    y = next;
    t += h;
  }
  return std::nan("");
}

/// alpha(u), u = sqrt(delta), tabulated once on [0, u_top] with step 1/per_unit and interpolated by
/// cubic Lagrange polynomials through the four nearest nodes (alpha is smooth in u: a power series).
struct RestitutionTable {
  static constexpr double u_top = 1.2;  // delta <= 1.44; the runs stay far below (they report their largest u)
  static constexpr double per_unit = 1000.0;
  std::vector<double> value;
  RestitutionTable() {
    const auto count = static_cast<std::size_t>(u_top * per_unit) + 1;
    value.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const double u = static_cast<double>(i) / per_unit;
      value[i] = contact_restitution(u * u);
    }
  }
  double operator()(double u) const {
    if (!(u >= 0.0) || u > u_top) {
      std::fprintf(stderr, "hcs_reference: viscoelastic u = %g outside the table [0, %g]\n", u, u_top);
      std::exit(3);
    }
    const double x = u * per_unit;
    const auto last = static_cast<std::ptrdiff_t>(value.size()) - 1;
    auto i = static_cast<std::ptrdiff_t>(x) - 1;  // nodes i .. i + 3 around x
    i = std::clamp<std::ptrdiff_t>(i, 0, last - 3);
    double sum = 0.0;
    for (std::ptrdiff_t p = i; p < i + 4; ++p) {
      double w = 1.0;
      for (std::ptrdiff_t q = i; q < i + 4; ++q)
        if (q != p) w *= (x - static_cast<double>(q)) / static_cast<double>(p - q);
      sum += w * value[static_cast<std::size_t>(p)];
    }
    return sum;
  }
};

/// The check of the contact model (--visco-check 1): C1 recovered as delta -> 0, the end-of-contact
/// conventions, step convergence, the interpolation error, and the series of \ref visco_series "docs/viscoelastic.md".
int visco_check() {
  const double c1 = 1.1534488580952888;
  const double h[21] = {0.0,        0.0,        -1.1534489, 0.0,        0.7982666, 0.2666667,  -0.5228826,
                        -0.4613795, 0.3487427,  0.4523511,  -0.1464315, -0.3677283, -0.0432490, 0.2818042,
                        0.1478526,  -0.1794421, -0.1784660, 0.0659336,  0.1713586,  0.0252498,  -0.1379235};
  auto series = [&h](double u) {
    double sum = 1.0, p = 1.0;
    for (int j = 1; j <= 20; ++j) sum += h[j] * (p *= u);
    return sum;
  };
  double c1_error = 0.0;
  std::printf("# contact model: (1 - alpha)/delta as delta -> 0 (published C1 = %.16f)\n", c1);
  for (double d : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
    const double a = contact_restitution(d), a0 = contact_restitution(d, false);
    std::printf("delta %.0e  force-zero end: (1 - alpha)/delta = %.10f  x = 0 end: %.10f\n", d, (1.0 - a) / d,
                (1.0 - a0) / d);
  }
  // C1 by Richardson extrapolation of (1 - alpha)/delta = C1 - C2 delta + O(delta^(3/2)) from delta = 1e-5, 2e-5
  {
    const double d = 1e-5, f1 = (1.0 - contact_restitution(d)) / d, f2 = (1.0 - contact_restitution(2 * d)) / (2 * d);
    const double extrapolated = 2.0 * f1 - f2;
    std::printf("C1 (extrapolated from delta = 1e-5, 2e-5): %.10f, published %.10f, difference %.2e\n", extrapolated,
                c1, extrapolated - c1);
    c1_error = std::abs(extrapolated - c1);
  }
  std::printf("# u  alpha(force-zero end)  alpha(x = 0 end)  series 1 + sum h_j u^j  force-zero - series  "
              "step-halving change\n");
  double worst_series = 0.0, worst_steps = 0.0;
  for (double u : {0.05, 0.1, 0.2, 0.3, 0.35, 0.4, 0.45, 0.5, 0.55, 0.6, 0.65, 0.7, 0.8, 0.9, 1.0}) {
    const double a = contact_restitution(u * u), a0 = contact_restitution(u * u, false);
    const double fine = contact_restitution(u * u, true, 1e-4, 0.005);
    std::printf("%.2f  %.12f  %.12f  %.12f  %+.2e  %.1e\n", u, a, a0, series(u), a - series(u), std::abs(fine - a));
    if (u <= 0.65) worst_series = std::max(worst_series, std::abs(a - series(u)));
    worst_steps = std::max(worst_steps, std::abs(fine - a));
  }
  const RestitutionTable table;
  double worst_interpolation = 0.0;
  for (double u = 0.0003; u < RestitutionTable::u_top; u += 0.0137)
    worst_interpolation = std::max(worst_interpolation, std::abs(table(u) - contact_restitution(u * u)));
  std::printf("largest |alpha - series| for u <= 0.65: %.2e; largest step-halving change: %.2e; largest "
              "interpolation error of the table (87 points off the nodes): %.2e\n",
              worst_series, worst_steps, worst_interpolation);
  // Pass: C1 to 1e-7 (the extrapolation's own error is O(delta^(3/2)) ~ 1e-8), the series to 1e-6 for
  // u <= 0.65 (its stated accuracy; the h_j are given to 7 decimals), step halving and interpolation below 1e-9.
  const bool pass = c1_error < 1e-7 && worst_series < 1e-6 && worst_steps < 1e-9 && worst_interpolation < 1e-9;
  std::printf("%s the contact model's alpha(delta): C1, the h_j series (u <= 0.65), convergence, interpolation\n",
              pass ? "PASS" : "FAIL");
  return pass ? 0 : 1;
}

/// The time-resolved mode (--density, --log-times): T_k(t) of a gas started Maxwellian at T_k = 1, by the
/// same jump chain with the real time kept: each candidate pair (accepted or not) advances time by an
/// exponential with rate (N - 1) n pi sigma_max^2 v_max, the majorant of the total collision rate
/// (n = sum_k n_k the number density, v_max the largest real speed). The rescaling of the velocities to
/// T = 1 is undone by the scale S it accumulates (real v = stored v / S), which also enters the rate.
std::vector<std::vector<double>> run_in_time(const std::vector<double>& mass, const std::vector<double>& diameter,
                                             const std::vector<double>& density, double alpha, std::size_t n,
                                             const std::vector<double>& times, std::uint64_t seed,
                                             std::vector<std::vector<double>>* msd = nullptr,
                                             const RestitutionTable* visco = nullptr, double visco_beta = 0.0,
                                             double msd_start = -1.0, std::vector<std::vector<double>>* msd_late = nullptr,
                                             double* largest_u = nullptr) {
  const std::size_t s = mass.size();
  Random rng(seed);
  double n_total = 0.0;
  for (double x : density) n_total += x;
  const std::vector<std::size_t> kind = species_by_density(density, n);
  std::vector<double> vx(n), vy(n), vz(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double sd = 1.0 / std::sqrt(mass[kind[i]]);
    vx[i] = sd * rng.normal();
    vy[i] = sd * rng.normal();
    vz[i] = sd * rng.normal();
  }
  double sigma_max = 0.0;
  for (double d : diameter) sigma_max = std::max(sigma_max, d);
  std::vector<double> sigma2(s * s), fraction_to(s * s), sqrt_beta(s * s);
  for (std::size_t a = 0; a < s; ++a)
    for (std::size_t b = 0; b < s; ++b) {
      const double sab = 0.5 * (diameter[a] + diameter[b]);
      sigma2[a * s + b] = sab * sab / (sigma_max * sigma_max);
      fraction_to[a * s + b] = mass[b] / (mass[a] + mass[b]);  // times (1 + alpha) at the collision
      // Viscoelastic, one material: beta_ab = beta_11 [sqrt(s_ab/s_11) m_11/m_ab]^(2/5) with the effective
      // radius-like s_ab = sigma_a sigma_b/(sigma_a + sigma_b) (not the contact distance) and the reduced mass
      // m_ab (\ref visco_one_material "docs/viscoelastic.md"); u = sqrt(beta_ab) |g.e|^(1/10).
      const double s_ab = diameter[a] * diameter[b] / (diameter[a] + diameter[b]), s_11 = diameter[0] / 2.0;
      const double m_ab = mass[a] * mass[b] / (mass[a] + mass[b]), m_11 = mass[0] / 2.0;
      sqrt_beta[a * s + b] = std::sqrt(visco_beta * std::pow(std::sqrt(s_ab / s_11) * m_11 / m_ab, 0.4));
    }
  double scale = 1.0;  // real v = stored v / scale
  auto rescale = [&]() -> double {
    double px = 0, py = 0, pz = 0, mt = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double m = mass[kind[i]];
      px += m * vx[i];
      py += m * vy[i];
      pz += m * vz[i];
      mt += m;
    }
    double e = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      vx[i] -= px / mt;
      vy[i] -= py / mt;
      vz[i] -= pz / mt;
      e += mass[kind[i]] * (vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]);
    }
    const double f = std::sqrt(3.0 * static_cast<double>(n) / e);
    scale *= f;
    double vmax2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      vx[i] *= f;
      vy[i] *= f;
      vz[i] *= f;
      vmax2 = std::max(vmax2, vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]);
    }
    return std::sqrt(vmax2);
  };
  auto temperatures = [&]() {
    std::vector<double> v2(s, 0.0), count(s, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      v2[kind[i]] += vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i];
      count[kind[i]] += 1.0;
    }
    std::vector<double> t(s);
    for (std::size_t k = 0; k < s; ++k) t[k] = mass[k] * v2[k] / (3.0 * count[k]) / (scale * scale);
    return t;
  };
  // Displacements (with `msd`): r += v_real (t - t_last) at each collision of the particle and, without
  // changing the state, up to each sample time; the MSD of species k is the mean of |r|^2 over its
  // particles (Bodrova and Osinsky 2024, eq. (15)).
  std::vector<double> rx, ry, rz, t_last;
  if (msd) {
    rx.assign(n, 0.0);
    ry.assign(n, 0.0);
    rz.assign(n, 0.0);
    t_last.assign(n, 0.0);
  }
  auto flush = [&](std::size_t i, double at) {
    const double dt = (at - t_last[i]) / scale;  // stored v / scale is the real velocity
    rx[i] += vx[i] * dt;
    ry[i] += vy[i] * dt;
    rz[i] += vz[i] * dt;
    t_last[i] = at;
  };
  // With a late start (msd_start > 0): the positions at msd_start, R(T) = r + v (T - t_last) without
  // changing the state, and <|R(t) - R(T)|^2> at the samples after T (0 before and at T).
  std::vector<double> x0, y0, z0;
  bool started = false;
  auto mean_squared = [&](double at, bool from_start) {
    std::vector<double> sum(s, 0.0), count(s, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const double dt = (at - t_last[i]) / scale;
      double x = rx[i] + vx[i] * dt, y = ry[i] + vy[i] * dt, z = rz[i] + vz[i] * dt;
      if (from_start) {
        x -= x0[i];
        y -= y0[i];
        z -= z0[i];
      }
      sum[kind[i]] += x * x + y * y + z * z;
      count[kind[i]] += 1.0;
    }
    for (std::size_t k = 0; k < s; ++k) sum[k] /= count[k];
    return sum;
  };
  auto record_start = [&]() {
    x0.resize(n);
    y0.resize(n);
    z0.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double dt = (msd_start - t_last[i]) / scale;
      x0[i] = rx[i] + vx[i] * dt;
      y0[i] = ry[i] + vy[i] * dt;
      z0[i] = rz[i] + vz[i] * dt;
    }
    started = true;
  };
  std::vector<std::vector<double>> out;
  const double pi = 3.14159265358979323846;
  const double rate_factor = static_cast<double>(n - 1) * n_total * pi * sigma_max * sigma_max;
  double vmax = 0.0, t = 0.0;
  {
    // The initial momentum is removed (as the DSMC's initial state has none) without rescaling.
    double px = 0, py = 0, pz = 0, mt = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double m = mass[kind[i]];
      px += m * vx[i];
      py += m * vy[i];
      pz += m * vz[i];
      mt += m;
    }
    double vmax2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      vx[i] -= px / mt;
      vy[i] -= py / mt;
      vz[i] -= pz / mt;
      vmax2 = std::max(vmax2, vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]);
    }
    vmax = std::sqrt(vmax2);
  }
  std::size_t next = 0;
  std::uint64_t events = 0;
  while (next < times.size()) {
    const double dt = -std::log(1.0 - rng.uniform()) * scale / (rate_factor * vmax);
    if (msd_late && !started && msd_start <= t + dt) record_start();  // the state is that of time msd_start
    while (next < times.size() && times[next] <= t + dt) {
      out.push_back(temperatures());
      if (msd) msd->push_back(mean_squared(times[next], false));
      if (msd_late)
        msd_late->push_back(started && times[next] > msd_start ? mean_squared(times[next], true)
                                                                : std::vector<double>(s, 0.0));
      ++next;
    }
    if (next == times.size()) break;
    t += dt;
    const std::size_t i = rng.below(n);
    std::size_t j = rng.below(n - 1);
    if (j >= i) ++j;
    const double gx = vx[i] - vx[j], gy = vy[i] - vy[j], gz = vz[i] - vz[j];
    const double g = std::sqrt(gx * gx + gy * gy + gz * gz);
    const std::size_t a = kind[i], b = kind[j];
    if (rng.uniform() * 2.0 * vmax >= sigma2[a * s + b] * g) continue;
    double ex, ey, ez;
    const double ge = contact(rng, gx, gy, gz, g, ex, ey, ez);
    double restitution = alpha;
    if (visco) {  // |g.e| of the real velocities is ge / scale
      const double u = sqrt_beta[a * s + b] * std::pow(ge / scale, 0.1);
      if (largest_u) *largest_u = std::max(*largest_u, u);
      restitution = (*visco)(u);
    }
    const double di = fraction_to[a * s + b] * (1.0 + restitution) * ge;
    const double dj = fraction_to[b * s + a] * (1.0 + restitution) * ge;
    if (msd) {
      flush(i, t);
      flush(j, t);
    }
    vx[i] -= di * ex;
    vy[i] -= di * ey;
    vz[i] -= di * ez;
    vx[j] += dj * ex;
    vy[j] += dj * ey;
    vz[j] += dj * ez;
    vmax = std::max({vmax, std::sqrt(vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]),
                     std::sqrt(vx[j] * vx[j] + vy[j] * vy[j] + vz[j] * vz[j])});
    if (++events % n == 0) {
      if (msd)  // the rescaling keeps v_real, but its momentum removal changes v: flights end here
        for (std::size_t p = 0; p < n; ++p) flush(p, t);
      vmax = rescale();
    }
  }
  return out;
}


/// One step of the shear modes' real-time candidate process: the exponential wait at total candidate rate `rate`;
/// the samples that fall before the next candidate or the epoch's end are taken (the process is memoryless: the
/// wait is redrawn from the epoch's end, never needed from a sample). Returns false at the epoch's end (t is then
/// the end, streamed to), true at a candidate (t advanced, the pair i != j drawn uniformly).
template <class Measure, class Stream>
bool next_candidate(Random& rng, double rate, double epoch_end, double t_end, double sample_every, double& t,
                    double& next_sample, std::size_t n, std::size_t& i, std::size_t& j, Measure&& measure,
                    Stream&& stream_sums) {
  const double wait = -std::log(1.0 - rng.uniform()) / rate;
  while (next_sample <= t_end && next_sample < std::min(t + wait, epoch_end)) {
    measure(next_sample);
    next_sample += sample_every;
  }
  if (t + wait >= epoch_end) {
    t = epoch_end;
    stream_sums(t);
    return false;
  }
  t += wait;
  i = rng.below(n);
  j = rng.below(n - 1);
  if (j >= i) ++j;
  return true;
}

/// The steady uniform shear flow mode (--shear a, with --density and --t-end): the homogeneous gas in the
/// Lagrangian frame of the flow u_x = a y, whose peculiar velocities stream as dV_x/dt = -a V_y between
/// collisions, exactly: each particle keeps its velocity at the time t_last of its last collision, and
/// V_x(t) = vx - a vy (t - t_last). No thermostat: viscous heating and collisional cooling balance in the
/// steady state. Candidates in real time as in run_in_time: each pair, accepted or not, advances time by an
/// exponential with rate (N - 1) n pi sigma_max^2 v_max, accepted with sigma_ij^2 |g(t)|/(sigma_max^2 2 v_max).
/// The bound holds over an epoch of strain a Delta = 0.01: |V(t)| <= |V(t0)| (1 + a (t - t0)), so v_max is the
/// largest speed at the epoch's start times 1 + a Delta, raised when a collision leaves a particle faster
/// than v_max/(1 + a Delta). Every `sample_every` from `average_from` to `t_end` it measures T, T_k/T and the
/// kinetic pressure tensor over p = n T, sum m V_i V_j/(N T) (V relative to the mean velocity), without
/// changing the state; the run's result is the mean over those samples. Over the same stretch it adds up the
/// viscous heating -a int sum m V_x V_y dt exactly (between collisions sum m V_x V_y falls as -a sum m V_y^2 t) and
/// the energy the collisions lose: in the steady state their ratio is 1 (heating_over_loss).
struct ShearResult {
  double temperature = 0.0;
  std::vector<double> ratio;      // T_k/T
  std::vector<double> pressure;   // P_xx/p, P_yy/p, P_zz/p, P_xy/p
  double heating_over_loss = 0.0;  // the energy balance over the averaged stretch: viscous heating / collisional loss
};

ShearResult run_shear(const std::vector<double>& mass, const std::vector<double>& diameter,
                      const std::vector<double>& density, double alpha, std::size_t n, double shear_rate,
                      double initial_temperature, double t_end, double average_from, double sample_every,
                      std::uint64_t seed) {
  const std::size_t s = mass.size();
  const double pi = 3.14159265358979323846;
  Random rng(seed);
  double n_total = 0.0;
  for (double x : density) n_total += x;
  const std::vector<std::size_t> kind = species_by_density(density, n);
  std::vector<double> vx(n), vy(n), vz(n), t_last(n, 0.0);
  double px = 0.0, py = 0.0, pz = 0.0, total_mass = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double sd = std::sqrt(initial_temperature / mass[kind[i]]);
    vx[i] = sd * rng.normal();
    vy[i] = sd * rng.normal();
    vz[i] = sd * rng.normal();
    px += mass[kind[i]] * vx[i];
    py += mass[kind[i]] * vy[i];
    pz += mass[kind[i]] * vz[i];
    total_mass += mass[kind[i]];
  }
  // Zero total momentum: a mean V_y would shear the mean V_x, u_x(t) = u_x(0) - a u_y t, and the energy of that
  // growing bulk flow would enter the heating but not the loss (collisions conserve momentum: it stays zero).
  for (std::size_t i = 0; i < n; ++i) {
    vx[i] -= px / total_mass;
    vy[i] -= py / total_mass;
    vz[i] -= pz / total_mass;
  }
  double sigma_max = 0.0;
  for (double d : diameter) sigma_max = std::max(sigma_max, d);
  std::vector<double> sigma2(s * s), fraction_to(s * s);
  for (std::size_t a = 0; a < s; ++a)
    for (std::size_t b = 0; b < s; ++b) {
      const double sab = 0.5 * (diameter[a] + diameter[b]);
      sigma2[a * s + b] = sab * sab / (sigma_max * sigma_max);
      fraction_to[a * s + b] = mass[b] / (mass[a] + mass[b]) * (1.0 + alpha);
    }
  const double epoch = 0.01 / shear_rate, margin = 1.0 + shear_rate * epoch;
  const double rate_per_speed = static_cast<double>(n - 1) * n_total * pi * sigma_max * sigma_max;
  auto bring = [&](std::size_t i, double t) {  // particle i's velocity at time t
    vx[i] -= shear_rate * vy[i] * (t - t_last[i]);
    t_last[i] = t;
  };
  // The energy balance: S_xy = sum m V_x V_y and S_yy = sum m V_y^2 at time `now`, the heating and the loss
  double s_xy = 0.0, s_yy = 0.0, now = 0.0, heating = 0.0, loss = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    s_xy += mass[kind[i]] * vx[i] * vy[i];
    s_yy += mass[kind[i]] * vy[i] * vy[i];
  }
  auto stream_sums = [&](double t) {  // S_xy to time t, the heating of [now, t] when it is averaged over
    const double dt = t - now;
    if (now >= average_from) heating += -shear_rate * (s_xy * dt - 0.5 * shear_rate * s_yy * dt * dt);
    s_xy -= shear_rate * s_yy * dt;
    now = t;
  };
  auto pair_sums = [&](std::size_t i, double sign) {  // particle i's share of S_xy, S_yy and its energy
    const double m = mass[kind[i]];
    s_xy += sign * m * vx[i] * vy[i];
    s_yy += sign * m * vy[i] * vy[i];
    return sign * 0.5 * m * (vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]);
  };
  ShearResult result;
  result.ratio.assign(s, 0.0);
  result.pressure.assign(4, 0.0);
  double samples = 0.0;
  auto measure = [&](double t) {
    std::vector<double> wx(n);
    double px = 0, py = 0, pz = 0, mt = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double m = mass[kind[i]];
      wx[i] = vx[i] - shear_rate * vy[i] * (t - t_last[i]);
      px += m * wx[i];
      py += m * vy[i];
      pz += m * vz[i];
      mt += m;
    }
    const double ux = px / mt, uy = py / mt, uz = pz / mt;
    std::vector<double> e(s, 0.0), count(s, 0.0);
    double pxx = 0, pyy = 0, pzz = 0, pxy = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double m = mass[kind[i]], x = wx[i] - ux, y = vy[i] - uy, z = vz[i] - uz;
      pxx += m * x * x;
      pyy += m * y * y;
      pzz += m * z * z;
      pxy += m * x * y;
      e[kind[i]] += m * (x * x + y * y + z * z);
      count[kind[i]] += 1.0;
    }
    const double temperature = (pxx + pyy + pzz) / (3.0 * static_cast<double>(n));
    result.temperature += temperature;
    for (std::size_t k = 0; k < s; ++k) result.ratio[k] += e[k] / (3.0 * count[k]) / temperature;
    const double nt = static_cast<double>(n) * temperature;
    result.pressure[0] += pxx / nt;
    result.pressure[1] += pyy / nt;
    result.pressure[2] += pzz / nt;
    result.pressure[3] += pxy / nt;
    samples += 1.0;
  };
  double t = 0.0, next_sample = average_from;
  while (t < t_end) {
    // an epoch: every particle brought to t, the bound over the epoch
    const double epoch_end = std::min(t + epoch, t_end);
    double vmax2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      bring(i, t);
      vmax2 = std::max(vmax2, vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]);
    }
    double vmax = std::sqrt(vmax2) * margin;
    std::size_t i = 0, j = 0;
    while (next_candidate(rng, rate_per_speed * vmax, epoch_end, t_end, sample_every, t, next_sample, n, i, j, measure,
                          stream_sums)) {
      bring(i, t);
      bring(j, t);
      const double gx = vx[i] - vx[j], gy = vy[i] - vy[j], gz = vz[i] - vz[j];
      const double g = std::sqrt(gx * gx + gy * gy + gz * gz);
      const std::size_t a = kind[i], b = kind[j];
      if (rng.uniform() * 2.0 * vmax >= sigma2[a * s + b] * g) continue;
      double ex, ey, ez;
      const double ge = contact(rng, gx, gy, gz, g, ex, ey, ez);
      const double di = fraction_to[a * s + b] * ge, dj = fraction_to[b * s + a] * ge;
      stream_sums(t);
      const double before = pair_sums(i, -1.0) + pair_sums(j, -1.0);
      vx[i] -= di * ex;
      vy[i] -= di * ey;
      vz[i] -= di * ez;
      vx[j] += dj * ex;
      vy[j] += dj * ey;
      vz[j] += dj * ez;
      const double after = pair_sums(i, 1.0) + pair_sums(j, 1.0);
      if (t >= average_from) loss += -before - after;  // (before is minus the energy before)
      const double fastest = std::max(vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i], vx[j] * vx[j] + vy[j] * vy[j] + vz[j] * vz[j]);
      vmax = std::max(vmax, std::sqrt(fastest) * margin);
    }
  }
  while (next_sample <= t_end * (1.0 + 1e-12)) {  // a sample at t_end itself
    measure(next_sample);
    next_sample += sample_every;
  }
  result.heating_over_loss = heating / loss;
  result.temperature /= samples;
  for (double& r : result.ratio) r /= samples;
  for (double& p : result.pressure) p /= samples;
  return result;
}

/// The uniform shear flow under the Gaussian thermostat (--shear a --thermostat gaussian, optionally --enskog 1): the
/// viscosity as the DSMC measures it (\ref eta_measured "docs/shear-viscosity.md"), by a second method. Streaming is
/// exact as in run_shear. The thermostat acts at every collision rather than once per stage: all velocities are
/// multiplied by s, s^2 = (E + L)/E, E the kinetic energy after the collision and L = (m_ij/2)(1 - alpha^2)(g.e)^2 its
/// inelastic loss, which restores exactly the inelastic loss and not the viscous work (the Gaussian thermostat
/// dV/dt = (zeta/2) V with zeta the instantaneous loss rate, in the limit N -> infinity). The scale is kept in one
/// factor: the stored velocities are u = V/scale (the streaming is linear, so it acts on u alike). The Enskog gas
/// (every pair rate times chi_ij of contact_values): the partner sits at r + sigma_ij e and moves with the flow there,
/// so g = V_i - V_j - a sigma_ij e_y x (e uniform on the sphere, accepted with sigma_ij^2 chi_ij Theta(g.e)(g.e) over
/// its bound, |g.e| <= 2 v_max + a sigma_max/2), and every collision transfers m_ij sigma_ij (1 + alpha)(g.e) e e to the
/// collisional pressure tensor P^c (divided by V = N/n and the sample interval). Every `sample_every` it measures
/// the kinetic tensor P^k = sum m V V/V at that instant and P^c of the interval since the previous sample; from
/// `average_from` on it adds up, per sample, eta/sqrt(T) = -P_xy c/(a sqrt T) and its kinetic part -P^k_xy c/(a sqrt T),
/// with c the finite-shear correction X/X_raw, X = X_raw/(1 - X^2), X_raw = -P_xy/(n T) (a* eta* of the DSMC,
/// which does not depend on eta_0), and T, T_k/T and, Enskog, tr P^c/3 over the Enskog equation of state.
struct ThermostatShearResult {
  double temperature = 0.0, viscosity = 0.0, viscosity_kinetic = 0.0, equation_of_state = 0.0;
  std::vector<double> ratio;  // T_k/T
};

/// The Enskog equation of state's collisional part, sum_ij (pi/3) n_i n_j sigma_ij^3 chi_ij (1 + alpha) (m_j T_i +
/// m_i T_j)/(m_i + m_j) (Garzo and Dufty 1999, with the partial temperatures).
double enskog_collisional_pressure(const std::vector<double>& mass, const std::vector<double>& diameter,
                                   const std::vector<double>& density, const std::vector<double>& chi, double alpha,
                                   const std::vector<double>& partial_temperature) {
  const std::size_t s = mass.size();
  double p = 0.0;
  for (std::size_t i = 0; i < s; ++i)
    for (std::size_t j = 0; j < s; ++j) {
      const double sigma = 0.5 * (diameter[i] + diameter[j]);
      p += 3.14159265358979323846 / 3.0 * density[i] * density[j] * sigma * sigma * sigma * chi[i * s + j] *
           (1.0 + alpha) * (mass[j] * partial_temperature[i] + mass[i] * partial_temperature[j]) / (mass[i] + mass[j]);
    }
  return p;
}

ThermostatShearResult run_shear_thermostat(const std::vector<double>& mass, const std::vector<double>& diameter,
                                           const std::vector<double>& density, double alpha, std::size_t n,
                                           double shear_rate, double initial_temperature, double t_end,
                                           double average_from, double sample_every, bool enskog, std::uint64_t seed) {
  const std::size_t s = mass.size();
  const double pi = 3.14159265358979323846;
  Random rng(seed);
  double n_total = 0.0;
  for (double x : density) n_total += x;
  const double volume = static_cast<double>(n) / n_total;
  const std::vector<std::size_t> kind = species_by_density(density, n);
  const auto chi = contact_values(diameter, enskog ? density : std::vector<double>{});
  std::vector<double> ux(n), uy(n), uz(n), t_last(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double sd = std::sqrt(initial_temperature / mass[kind[i]]);
    ux[i] = sd * rng.normal();
    uy[i] = sd * rng.normal();
    uz[i] = sd * rng.normal();
  }
  double sigma_max = 0.0, weight_max = 0.0;
  for (double d : diameter) sigma_max = std::max(sigma_max, d);
  std::vector<double> sigma(s * s), weight(s * s), reduced(s * s);
  for (std::size_t a = 0; a < s; ++a)
    for (std::size_t b = 0; b < s; ++b) {
      sigma[a * s + b] = 0.5 * (diameter[a] + diameter[b]);
      weight[a * s + b] = sigma[a * s + b] * sigma[a * s + b] * (enskog ? chi[a * s + b] : 1.0);
      weight_max = std::max(weight_max, weight[a * s + b]);
      reduced[a * s + b] = mass[a] * mass[b] / (mass[a] + mass[b]);
    }
  // candidates: N (N - 1)/2 pairs, each at the rate 4 pi weight_max bound / V
  const double rate_per_bound = 2.0 * pi * static_cast<double>(n - 1) * n_total * weight_max;
  const double epoch = 0.01 / shear_rate, margin = 1.0 + shear_rate * epoch;
  double scale = 1.0, s_xy = 0.0, s_yy = 0.0, energy = 0.0, now = 0.0;  // sums of u: sum m u_x u_y, m u_y^2, m u^2/2
  auto bring = [&](std::size_t i, double t) {
    ux[i] -= shear_rate * uy[i] * (t - t_last[i]);
    t_last[i] = t;
  };
  auto stream_sums = [&](double t) {
    const double dt = t - now;
    energy -= shear_rate * (s_xy * dt - 0.5 * shear_rate * s_yy * dt * dt);
    s_xy -= shear_rate * s_yy * dt;
    now = t;
  };
  auto pair_sums = [&](std::size_t i, double sign) {
    const double m = mass[kind[i]];
    s_xy += sign * m * ux[i] * uy[i];
    s_yy += sign * m * uy[i] * uy[i];
    energy += sign * 0.5 * m * (ux[i] * ux[i] + uy[i] * uy[i] + uz[i] * uz[i]);
  };
  ThermostatShearResult result;
  result.ratio.assign(s, 0.0);
  std::array<double, 4> transfer{};  // sum m_ij sigma_ij (1 + alpha)(g.e) e e of the interval: xx, yy, zz, xy
  std::vector<double> previous_partial(s, initial_temperature);
  double samples = 0.0;
  auto measure = [&](double t) {
    double pxx = 0, pyy = 0, pzz = 0, pxy = 0;
    std::vector<double> e(s, 0.0), count(s, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const double m = mass[kind[i]], x = scale * (ux[i] - shear_rate * uy[i] * (t - t_last[i]));
      const double y = scale * uy[i], z = scale * uz[i];
      pxx += m * x * x, pyy += m * y * y, pzz += m * z * z, pxy += m * x * y;
      e[kind[i]] += m * (x * x + y * y + z * z);
      count[kind[i]] += 1.0;
    }
    std::vector<double> partial(s), mean_partial(s);
    for (std::size_t k = 0; k < s; ++k) {
      partial[k] = e[k] / (3.0 * count[k]);
      mean_partial[k] = 0.5 * (partial[k] + previous_partial[k]);  // P^c is the interval's mean
    }
    const double temperature = (pxx + pyy + pzz) / (3.0 * static_cast<double>(n));
    const double collisional_xy = transfer[3] / (volume * sample_every);
    const double collisional_trace = (transfer[0] + transfer[1] + transfer[2]) / (3.0 * volume * sample_every);
    transfer.fill(0.0);
    previous_partial = partial;
    if (t < average_from * (1.0 - 1e-12)) return;
    const double kinetic_xy = pxy / volume, total_xy = kinetic_xy + collisional_xy;
    const double raw = -total_xy / (n_total * temperature);
    double x = raw;
    for (int it = 0; it < 20; ++it) x = raw / (1.0 - x * x);
    if (!(x * x < 0.5)) {  // the correction has no solution near X_raw (it needs a* eta* well below 0.38)
      std::fprintf(stderr, "hcs_reference: -P_xy/(n T) = %g at t = %g: the shear rate is too large for the "
                           "finite-shear correction\n", raw, t);
      std::exit(1);
    }
    const double correction = x / raw, root = std::sqrt(temperature);
    result.viscosity += -total_xy * correction / (shear_rate * root);
    result.viscosity_kinetic += -kinetic_xy * correction / (shear_rate * root);
    result.temperature += temperature;
    for (std::size_t k = 0; k < s; ++k) result.ratio[k] += partial[k] / temperature;
    if (enskog)
      result.equation_of_state +=
          collisional_trace / enskog_collisional_pressure(mass, diameter, density, chi, alpha, mean_partial);
    samples += 1.0;
  };
  double t = 0.0, next_sample = sample_every;
  while (t < t_end) {
    // an epoch: every particle brought to t, the momentum's round-off removed, the sums recomputed, the bound
    const double epoch_end = std::min(t + epoch, t_end);
    double px = 0.0, py = 0.0, pz = 0.0, total_mass = 0.0, umax2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      bring(i, t);
      const double m = mass[kind[i]];
      px += m * ux[i], py += m * uy[i], pz += m * uz[i], total_mass += m;
    }
    s_xy = s_yy = energy = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      ux[i] -= px / total_mass, uy[i] -= py / total_mass, uz[i] -= pz / total_mass;
      pair_sums(i, 1.0);
      umax2 = std::max(umax2, ux[i] * ux[i] + uy[i] * uy[i] + uz[i] * uz[i]);
    }
    now = t;
    double umax = std::sqrt(umax2) * margin, bound = 2.0 * scale * umax + 0.5 * shear_rate * sigma_max;
    std::size_t i = 0, j = 0;
    for (; next_candidate(rng, rate_per_bound * bound, epoch_end, t_end, sample_every, t, next_sample, n, i, j, measure,
                          stream_sums);
         bound = 2.0 * scale * umax + 0.5 * shear_rate * sigma_max) {
      const double ez = 2.0 * rng.uniform() - 1.0, azimuth = 2.0 * pi * rng.uniform();
      const double ex = std::sqrt(1.0 - ez * ez) * std::cos(azimuth), ey = std::sqrt(1.0 - ez * ez) * std::sin(azimuth);
      const std::size_t a = kind[i], b = kind[j], ab = a * s + b;
      bring(i, t);
      bring(j, t);
      const double shift = enskog ? shear_rate * sigma[ab] * ey : 0.0;
      const double ge = scale * ((ux[i] - ux[j]) * ex + (uy[i] - uy[j]) * ey + (uz[i] - uz[j]) * ez) - shift * ex;
      if (rng.uniform() * weight_max * bound >= weight[ab] * ge) continue;  // also every ge <= 0
      stream_sums(t);
      pair_sums(i, -1.0);
      pair_sums(j, -1.0);
      const double impulse = reduced[ab] * (1.0 + alpha) * ge;  // momentum given to j along e
      ux[i] -= impulse / mass[a] * ex / scale, uy[i] -= impulse / mass[a] * ey / scale, uz[i] -= impulse / mass[a] * ez / scale;
      ux[j] += impulse / mass[b] * ex / scale, uy[j] += impulse / mass[b] * ey / scale, uz[j] += impulse / mass[b] * ez / scale;
      pair_sums(i, 1.0);
      pair_sums(j, 1.0);
      if (enskog) {
        const double f = impulse * sigma[ab];
        transfer[0] += f * ex * ex, transfer[1] += f * ey * ey, transfer[2] += f * ez * ez, transfer[3] += f * ex * ey;
      }
      // the thermostat: the inelastic loss restored at once
      const double loss = 0.5 * reduced[ab] * (1.0 - alpha * alpha) * ge * ge, after = scale * scale * energy;
      scale *= std::sqrt((after + loss) / after);
      const double fastest = std::max(ux[i] * ux[i] + uy[i] * uy[i] + uz[i] * uz[i], ux[j] * ux[j] + uy[j] * uy[j] + uz[j] * uz[j]);
      umax = std::max(umax, std::sqrt(fastest) * margin);
    }
  }
  while (next_sample <= t_end * (1.0 + 1e-12)) {  // a sample at t_end itself
    measure(next_sample);
    next_sample += sample_every;
  }
  result.temperature /= samples;
  result.viscosity /= samples;
  result.viscosity_kinetic /= samples;
  result.equation_of_state /= samples;
  for (double& r : result.ratio) r /= samples;
  return result;
}

/// --shear a --thermostat gaussian: `replicas` runs of run_shear_thermostat, their means and standard errors.
int shear_thermostat_mode(const std::vector<double>& mass, const std::vector<double>& diameter,
                          const std::vector<double>& density, double alpha, std::size_t n, double shear,
                          double initial_temperature, double t_end, double average_from, double sample_every,
                          bool enskog, bool expect_eos, std::size_t replicas, std::uint64_t seed, int argc,
                          char** argv) {
  const std::size_t s = mass.size();
  std::vector<ThermostatShearResult> all;
  for (std::size_t r = 0; r < replicas; ++r)
    all.push_back(run_shear_thermostat(mass, diameter, density, alpha, n, shear, initial_temperature, t_end,
                                       average_from, sample_every, enskog, seed * 1000003ULL + r));
  const double rep = static_cast<double>(replicas);
  auto print = [&](const std::string& name, auto&& value) {
    double mean = 0.0, var = 0.0;
    for (const auto& a : all) mean += value(a) / rep;
    for (const auto& a : all) var += (value(a) - mean) * (value(a) - mean);
    std::printf("%s %.9e %.3e\n", name.c_str(), mean, std::sqrt(var / (rep - 1.0) / rep));
  };
  std::printf("# hcs_reference (uniform shear flow, Gaussian thermostat%s): %zu replicas x %zu particles, a = %g, "
              "t_end = %g, averaged from %g every %g\n", enskog ? ", Enskog" : "", replicas, n, shear, t_end,
              average_from, sample_every);
  std::printf("# command:");
  for (int a = 1; a < argc; ++a) std::printf(" %s", argv[a]);
  std::printf("\n# quantity value se (time averages; viscosity = eta/sqrt(T) with the finite-shear correction: "
              "divided by eta_0 at T = 1 it is the DSMC's time average of eta/eta_0)\n");
  print("temperature", [](const ThermostatShearResult& a) { return a.temperature; });
  for (std::size_t k = 0; k < s; ++k)
    print("temperature_ratio_" + std::to_string(k + 1), [k](const ThermostatShearResult& a) { return a.ratio[k]; });
  print("viscosity_over_sqrt_temperature", [](const ThermostatShearResult& a) { return a.viscosity; });
  print("viscosity_kinetic_over_sqrt_temperature", [](const ThermostatShearResult& a) { return a.viscosity_kinetic; });
  if (!enskog) return 0;
  print("collisional_pressure_over_equation_of_state", [](const ThermostatShearResult& a) { return a.equation_of_state; });
  if (!expect_eos) return 0;
  // exact for the Enskog operator whatever the distribution, but for the shear shift's terms of order (a sigma)^2/<g^2>
  // (its square in (g.e)^2, and its cross term with <g_x g_y>, itself proportional to a): use a small a. (In a mixture
  // the N_k (N_k - 1) like pairs against the formula's n_k^2 V^2 add a bias of order 1/N_k, 2e-4 at N = 4000.)
  double mean = 0.0, var = 0.0;
  for (const auto& a : all) mean += a.equation_of_state / rep;
  for (const auto& a : all) var += (a.equation_of_state - mean) * (a.equation_of_state - mean);
  const double se = std::sqrt(var / (rep - 1.0) / rep), z = std::abs(mean - 1.0) / se;
  std::printf("%s the collisional transfer: tr P^c/3 over the Enskog equation of state = %.5f +- %.5f against 1: %.2f SE "
              "(tolerance 4)\n", z <= 4.0 ? "PASS" : "FAIL", mean, se, z);
  return z <= 4.0 ? 0 : 1;
}

/// --shear: `replicas` runs of run_shear, their means and standard errors; for one species also the
/// reduced shear rate a* = a eta_0(T)/(n T), eta_0 = (5/(16 sigma^2)) sqrt(m T/pi) (the elastic first
/// Chapman-Enskog viscosity), of each replica's mean T.
int shear_mode(const std::vector<double>& mass, const std::vector<double>& diameter, const std::vector<double>& density,
               double alpha, std::size_t n, double shear, double initial_temperature, double t_end, double average_from,
               double sample_every, std::size_t replicas, std::uint64_t seed, bool expect_balance, int argc, char** argv) {
  const std::size_t s = mass.size();
  if (s == 0 || diameter.size() != s || density.size() != s || !(alpha >= 0.0 && alpha < 1.0) || !(shear > 0.0) ||
      !(t_end > 0.0) || !(average_from >= 0.0 && average_from <= t_end) || !(sample_every > 0.0) ||
      !(initial_temperature > 0.0) || replicas < 2 || n < 100) {
    std::fprintf(stderr, "usage: hcs_reference --shear a --mass ... --diameter ... --density n1,... --alpha a (< 1) "
                         "--t-end T --average-from T0 --sample-every dt [--temperature T0] [--particles N] "
                         "[--replicas R >= 2] [--seed s]\n");
    return 2;
  }
  std::vector<ShearResult> all;
  for (std::size_t r = 0; r < replicas; ++r)
    all.push_back(run_shear(mass, diameter, density, alpha, n, shear, initial_temperature, t_end, average_from,
                            sample_every, seed * 1000003ULL + r));
  const double rep = static_cast<double>(replicas);
  auto print = [&](const char* name, auto&& value) {
    double mean = 0.0, var = 0.0;
    for (const auto& a : all) mean += value(a) / rep;
    for (const auto& a : all) var += (value(a) - mean) * (value(a) - mean);
    std::printf("%s %.9e %.3e\n", name, mean, std::sqrt(var / (rep - 1.0) / rep));
  };
  std::printf("# hcs_reference (steady uniform shear flow): %zu replicas x %zu particles, a = %g, t_end = %g, "
              "averaged from %g every %g\n", replicas, n, shear, t_end, average_from, sample_every);
  std::printf("# command:");
  for (int a = 1; a < argc; ++a) std::printf(" %s", argv[a]);
  std::printf("\n# quantity value se\n");
  print("temperature", [](const ShearResult& a) { return a.temperature; });
  for (std::size_t k = 0; k < s; ++k) {
    const std::string name = "temperature_ratio_" + std::to_string(k + 1);
    print(name.c_str(), [k](const ShearResult& a) { return a.ratio[k]; });
  }
  const char* components[4] = {"pressure_xx", "pressure_yy", "pressure_zz", "pressure_xy"};
  for (std::size_t c = 0; c < 4; ++c) print(components[c], [c](const ShearResult& a) { return a.pressure[c]; });
  print("heating_over_loss", [](const ShearResult& a) { return a.heating_over_loss; });
  int status = 0;
  if (expect_balance) {  // the steady state's energy balance, exact: heating / loss = 1 at 4 SE
    double mean = 0.0, var = 0.0;
    for (const auto& a : all) mean += a.heating_over_loss / rep;
    for (const auto& a : all) var += (a.heating_over_loss - mean) * (a.heating_over_loss - mean);
    const double se = std::sqrt(var / (rep - 1.0) / rep), z = std::abs(mean - 1.0) / se;
    std::printf("%s the energy balance: viscous heating / collisional loss = %.5f +- %.5f against 1: %.2f SE (tolerance 4)\n",
                z <= 4.0 ? "PASS" : "FAIL", mean, se, z);
    if (z > 4.0) status = 1;
  }
  if (s == 1) {
    const double pi = 3.14159265358979323846;
    print("reduced_shear_rate", [&](const ShearResult& a) {
      const double eta0 = 5.0 / (16.0 * diameter[0] * diameter[0]) * std::sqrt(mass[0] * a.temperature / pi);
      return shear * eta0 / (density[0] * a.temperature);
    });
  }
  return status;
}
}  // namespace

int main(int argc, char** argv) {
  std::vector<double> mass, diameter, fraction;
  double alpha = -1.0, warmup = 40.0, samples = 400.0;
  std::size_t n = 100000, replicas = 8;
  std::uint64_t seed = 1;
  std::vector<double> expect_gamma, expect_c1;
  std::size_t bins = 0;
  double range = 4.0;
  std::vector<double> density, log_times, enskog_density;
  bool want_msd = false;
  double visco_beta = -1.0, msd_start = -1.0;
  bool want_visco_check = false;
  double shear = -1.0, t_end = -1.0, average_from = -1.0, sample_every = -1.0, initial_temperature = 1.0;
  bool expect_balance = false, gaussian = false, enskog_shear = false, expect_eos = false;
  for (int i = 1; i + 1 < argc; i += 2) {
    const char* key = argv[i];
    const char* value = argv[i + 1];
    if (!std::strcmp(key, "--mass")) mass = numbers(value);
    else if (!std::strcmp(key, "--diameter")) diameter = numbers(value);
    else if (!std::strcmp(key, "--fraction")) fraction = numbers(value);
    else if (!std::strcmp(key, "--alpha")) alpha = std::atof(value);
    else if (!std::strcmp(key, "--particles")) n = std::strtoull(value, nullptr, 10);
    else if (!std::strcmp(key, "--warmup")) warmup = std::atof(value);
    else if (!std::strcmp(key, "--samples")) samples = std::atof(value);
    else if (!std::strcmp(key, "--replicas")) replicas = std::strtoull(value, nullptr, 10);
    else if (!std::strcmp(key, "--seed")) seed = std::strtoull(value, nullptr, 10);
    else if (!std::strcmp(key, "--expect-gamma")) expect_gamma = numbers(value);
    else if (!std::strcmp(key, "--expect-c1")) expect_c1 = numbers(value);
    else if (!std::strcmp(key, "--bins")) bins = std::strtoull(value, nullptr, 10);
    else if (!std::strcmp(key, "--density")) density = numbers(value);
    else if (!std::strcmp(key, "--log-times")) log_times = numbers(value);
    else if (!std::strcmp(key, "--enskog-density")) enskog_density = numbers(value);
    else if (!std::strcmp(key, "--msd")) want_msd = std::atoi(value) != 0;
    else if (!std::strcmp(key, "--range")) range = std::atof(value);
    else if (!std::strcmp(key, "--visco-beta")) visco_beta = std::atof(value);
    else if (!std::strcmp(key, "--msd-start")) msd_start = std::atof(value);
    else if (!std::strcmp(key, "--visco-check")) want_visco_check = std::atoi(value) != 0;
    else if (!std::strcmp(key, "--shear")) shear = std::atof(value);
    else if (!std::strcmp(key, "--t-end")) t_end = std::atof(value);
    else if (!std::strcmp(key, "--average-from")) average_from = std::atof(value);
    else if (!std::strcmp(key, "--sample-every")) sample_every = std::atof(value);
    else if (!std::strcmp(key, "--temperature")) initial_temperature = std::atof(value);
    else if (!std::strcmp(key, "--expect-balance")) expect_balance = std::atoi(value) != 0;
    else if (!std::strcmp(key, "--thermostat")) {
      if (std::strcmp(value, "gaussian") != 0) {
        std::fprintf(stderr, "hcs_reference: --thermostat %s: the only thermostat is 'gaussian'\n", value);
        return 2;
      }
      gaussian = true;
    }
    else if (!std::strcmp(key, "--enskog")) enskog_shear = std::atoi(value) != 0;
    else if (!std::strcmp(key, "--expect-eos")) expect_eos = std::atoi(value) != 0;
    else {
      std::fprintf(stderr, "hcs_reference: unknown option %s\n", key);
      return 2;
    }
  }
  if (want_visco_check) return visco_check();
  const std::size_t s = mass.size();
  const bool visco = visco_beta >= 0.0;
  if (shear >= 0.0 && (gaussian || enskog_shear || expect_eos)) {
    if (!gaussian || expect_balance || (expect_eos && !enskog_shear) || mass.empty() || diameter.size() != s || density.size() != s ||
        !(alpha >= 0.0 && alpha <= 1.0) || !(shear > 0.0) || !(t_end > 0.0) ||
        !(average_from >= 0.0 && average_from <= t_end) || !(sample_every > 0.0) || !(initial_temperature > 0.0) ||
        replicas < 2 || n < 100) {
      std::fprintf(stderr, "usage: hcs_reference --shear a --thermostat gaussian [--enskog 1] --mass ... --diameter ... "
                           "--density n1,... --alpha a --t-end T --average-from T0 --sample-every dt [--temperature T0] "
                           "[--particles N] [--replicas R >= 2] [--seed s] [--expect-eos 1 (with --enskog 1)]\n");
      return 2;
    }
    return shear_thermostat_mode(mass, diameter, density, alpha, n, shear, initial_temperature, t_end, average_from,
                                 sample_every, enskog_shear, expect_eos, replicas, seed, argc, argv);
  }
  if (shear >= 0.0) return shear_mode(mass, diameter, density, alpha, n, shear, initial_temperature, t_end,
                                       average_from, sample_every, replicas, seed, expect_balance, argc, argv);
  if (!density.empty()) {  // the time-resolved mode
    if (density.size() != s || diameter.size() != s || log_times.size() != 3 || !(log_times[0] > 0.0) ||
        !(log_times[1] > log_times[0]) || log_times[2] < 3 || !(visco || (alpha >= 0.0 && alpha <= 1.0)) ||
        (visco && alpha >= 0.0) || replicas < 2 || (msd_start >= 0.0 && !(want_msd && msd_start > 0.0))) {
      std::fprintf(stderr, "usage: hcs_reference --mass ... --diameter ... --density n1,... (--alpha a | --visco-beta b11) "
                           "--log-times first,last,count [--particles N] [--replicas R >= 2] [--seed s] "
                           "[--msd 1 [--msd-start T > 0]]\n");
      return 2;
    }
    // The DSMC's log grid (&output spacing = 'log'): t = 0, then first (last/first)^(i/(count - 2)).
    const auto count = static_cast<std::size_t>(log_times[2]);
    std::vector<double> times{0.0};
    for (std::size_t i = 0; i + 1 < count; ++i)
      times.push_back(log_times[0] * std::pow(log_times[1] / log_times[0], static_cast<double>(i) / (count - 2.0)));
    std::vector<std::vector<std::vector<double>>> all, all_msd(replicas), all_late(replicas);
    const bool late = msd_start > 0.0;
    std::unique_ptr<RestitutionTable> table;
    if (visco) table = std::make_unique<RestitutionTable>();
    double largest_u = 0.0;
    for (std::size_t r = 0; r < replicas; ++r)
      all.push_back(run_in_time(mass, diameter, density, alpha, n, times, seed * 1000003ULL + r,
                                want_msd ? &all_msd[r] : nullptr, table.get(), visco_beta, msd_start,
                                late ? &all_late[r] : nullptr, &largest_u));
    std::printf("# hcs_reference (time-resolved): %zu replicas x %zu particles, T_k(0) = 1\n", replicas, n);
    std::printf("# command:");
    for (int a = 1; a < argc; ++a) std::printf(" %s", argv[a]);
    std::printf("\n");
    if (visco)
      std::printf("# viscoelastic restitution from the contact model (force-zero end), beta_11 = %g, other pairs "
                  "beta_ki = beta_11 [sqrt(s_ki/s_11) m_11/m_ki]^(2/5); largest u = sqrt(beta) |g.e|^(1/10) met: %.4f\n",
                  visco_beta, largest_u);
    std::printf("# temperature  t  T_1 se  T_2 se ...\n");
    const double rep = static_cast<double>(replicas);
    for (std::size_t i = 0; i < times.size(); ++i) {
      std::printf("temperature %.9g", times[i]);
      for (std::size_t k = 0; k < s; ++k) {
        double mean = 0.0, var = 0.0;
        for (const auto& a : all) mean += a[i][k] / rep;
        for (const auto& a : all) var += (a[i][k] - mean) * (a[i][k] - mean);
        std::printf(" %.9e %.3e", mean, std::sqrt(var / (rep - 1.0) / rep));
      }
      std::printf("\n");
    }
    auto write_msd = [&](const char* keyword, const std::vector<std::vector<std::vector<double>>>& series) {
      for (std::size_t i = 0; i < times.size(); ++i) {
        std::printf("%s %.9g", keyword, times[i]);
        for (std::size_t k = 0; k < s; ++k) {
          double mean = 0.0, var = 0.0;
          for (const auto& a : series) mean += a[i][k] / rep;
          for (const auto& a : series) var += (a[i][k] - mean) * (a[i][k] - mean);
          std::printf(" %.9e %.3e", mean, std::sqrt(var / (rep - 1.0) / rep));
        }
        std::printf("\n");
      }
    };
    if (want_msd) {
      std::printf("# msd  t  <R_1^2> se  <R_2^2> se ...\n");
      write_msd("msd", all_msd);
    }
    if (late) {
      std::printf("# msd_late  t  <|R_1(t) - R_1(%g)|^2> se ... (0 up to t = %g)\n", msd_start, msd_start);
      write_msd("msd_late", all_late);
    }
    return 0;
  }
  if (!enskog_density.empty() && fraction.empty()) fraction = enskog_density;
  if (!enskog_density.empty() && enskog_density.size() != s) {
    std::fprintf(stderr, "hcs_reference: --enskog-density needs one density per species\n");
    return 2;
  }
  if (s == 0 || diameter.size() != s || fraction.size() != s || !(alpha >= 0.0 && alpha <= 1.0) || n < 100 ||
      replicas < 2 || !(samples >= 1.0) || !(warmup >= 0.0)) {
    std::fprintf(stderr,
                 "usage: hcs_reference --mass m1,... --diameter d1,... --fraction x1,... --alpha a [--particles N] "
                 "[--warmup W] [--samples S] [--replicas R >= 2] [--seed s]\n");
    return 2;
  }
  std::vector<Result> all;
  for (std::size_t r = 0; r < replicas; ++r)
    all.push_back(
        run(mass, diameter, fraction, alpha, n, warmup, samples, seed * 1000003ULL + r, bins, range, enskog_density));
  std::printf("# hcs_reference: %zu replicas x %zu particles, warmup %g, %g samples (one per collision per particle)\n",
              replicas, n, warmup, samples);
  std::printf("# species  T_k/T  se  c_k  se\n");
  std::vector<double> ratio(s), ratio_se(s), cumulant(s), cumulant_se(s);
  std::vector<double> gamma_replica(replicas);
  for (std::size_t k = 0; k < s; ++k) {
    double mr = 0, mc = 0;
    for (const auto& a : all) {
      mr += a.ratio[k];
      mc += a.cumulant[k];
    }
    mr /= replicas;
    mc /= replicas;
    double vr = 0, vc = 0;
    for (const auto& a : all) {
      vr += (a.ratio[k] - mr) * (a.ratio[k] - mr);
      vc += (a.cumulant[k] - mc) * (a.cumulant[k] - mc);
    }
    const double rep = static_cast<double>(replicas);
    ratio[k] = mr;
    ratio_se[k] = std::sqrt(vr / (rep - 1.0) / rep);
    cumulant[k] = mc;
    cumulant_se[k] = std::sqrt(vc / (rep - 1.0) / rep);
    std::printf("%zu %.6f %.6f %.6f %.6f\n", k + 1, ratio[k], ratio_se[k], cumulant[k], cumulant_se[k]);
  }
  int status = 0;
  auto expect = [&status](const char* name, double value, double se, const std::vector<double>& published) {
    if (published.size() != 2) return;
    const double combined = std::hypot(se, published[1]), z = std::abs(value - published[0]) / combined;
    const bool pass = z <= 4.0;
    std::printf("%s %s: %.5f +- %.5f against the published %.5f +- %.5f: %.2f combined SE (tolerance 4)\n",
                pass ? "PASS" : "FAIL", name, value, se, published[0], published[1], z);
    if (!pass) status = 1;
  };
  if (s >= 2 && expect_gamma.size() == 2) {
    double mean = 0.0, var = 0.0;
    for (std::size_t r = 0; r < replicas; ++r) {
      gamma_replica[r] = all[r].ratio[0] / all[r].ratio[1];
      mean += gamma_replica[r] / static_cast<double>(replicas);
    }
    for (double g : gamma_replica) var += (g - mean) * (g - mean);
    expect("gamma = T_1/T_2", mean, std::sqrt(var / (replicas - 1.0) / replicas), expect_gamma);
  }
  expect("c_1", cumulant[0], cumulant_se[0], expect_c1);
  if (bins > 0) {
    std::printf("# Phi_1(v*): bin  v*_low  v*_high  value  se\n");
    const double width = range / static_cast<double>(bins), rep = static_cast<double>(replicas);
    for (std::size_t b = 0; b < bins; ++b) {
      double mean = 0.0, var = 0.0;
      for (const auto& a : all) mean += a.phi[b] / rep;
      for (const auto& a : all) var += (a.phi[b] - mean) * (a.phi[b] - mean);
      std::printf("phi %zu %.6f %.6f %.9e %.3e\n", b, width * b, width * (b + 1), mean, std::sqrt(var / (rep - 1.0) / rep));
    }
  }
  return status;
}
