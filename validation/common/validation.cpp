#include "validation.hpp"


#include <array>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <iostream>

#include "io/namelist.hpp"
#include "io/version.hpp"
#include "analysis/json.hpp"

namespace gdsmc::validation {

namespace json = analysis::json;

std::optional<std::string> take_option(int& argc, char** argv, const std::string& name) {
  for (int i = 1; i + 1 < argc; ++i)
    if (name == argv[i]) {
      std::string value = argv[i + 1];
      for (int j = i; j + 2 < argc; ++j) argv[j] = argv[j + 2];
      argc -= 2;
      return value;
    }
  return std::nullopt;
}

std::vector<double> number_list(const std::string& text) {
  std::vector<double> out;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) out.push_back(std::stod(item));
  return out;
}

Variants read_variants(int argc, char** argv, const std::string& default_stem) {
  Variants v;
  v.stem = default_stem;
  std::string input;
  std::vector<std::string> overrides;
  v.args.push_back(argv[0]);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--output" && i + 1 < argc) {
      v.stem = std::filesystem::path(argv[++i]).replace_extension().string();
      continue;
    }
    v.args.push_back(arg);
    if (arg == "--set" && i + 1 < argc) {
      overrides.push_back(argv[++i]);
      v.args.push_back(argv[i]);
    } else if (arg.rfind("--", 0) != 0) {
      input = arg;
    }
  }
  try {
    v.config = io::config::read_file(input, overrides);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    std::exit(2);
  }
  return v;
}

Case Variants::run(const std::vector<std::string>& extra) const {
  std::vector<std::string> storage = args;
  storage.insert(storage.end(), extra.begin(), extra.end());
  std::vector<char*> argv;
  for (auto& s : storage) argv.push_back(s.data());
  return run_case(static_cast<int>(argv.size()), argv.data(), stem + ".h5");
}

Case run_case(int argc, char** argv, const std::string& default_output) {
  std::string input, output = default_output;
  std::vector<std::string> overrides;
  bool reuse = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--set" && i + 1 < argc) overrides.push_back(argv[++i]);
    else if (arg == "--output" && i + 1 < argc) output = argv[++i];
    else if (arg == "--reuse") reuse = true;
    else input = arg;
  }
  if (input.empty()) {
    std::cerr << "usage: " << argv[0] << " INPUT.nml [--set group:variable=value]... [--output FILE] [--reuse]\n";
    std::exit(2);
  }
  Case c;
  try {
    c.config = io::config::read_file(input, overrides);
  } catch (const io::namelist::Error& e) {
    std::cerr << e.what() << "\n";
    std::exit(2);
  }
  c.file = output;
  std::printf("input %s", input.c_str());
  for (const auto& o : overrides) std::printf(" --set %s", o.c_str());
  std::printf("\noutput %s\n", output.c_str());
  if (!(reuse && std::filesystem::exists(output))) {
    const auto summary = simulation::run(c.config, output, simulation::Options{});
    std::printf("ran %lld replica(s) x %lld particles: %.4g collisions per particle, %.3g collisions/s, %.1f s\n",
                c.config.dsmc.replicas, c.config.dsmc.n_particles, summary.collisions_per_particle,
                summary.events_per_second, summary.wall_seconds);
    // The kernel's invariant (collide.hpp Counters::overshoots): a candidate accepted with a probability
    // above 1 means the bound was not a majorant and the rates are wrong, whatever the checks say.
    if (summary.acceptance_overshoots > 0.0) {
      std::printf("FAIL acceptance probability above 1 in %.0f candidates (collide.hpp, Counters::overshoots)\n",
                  summary.acceptance_overshoots);
      std::exit(1);
    }
  }
  return c;
}

namespace {
/// `X.report.json` for the text report `X.report.txt`, else "".
std::string json_file(const std::string& text_report) {
  const std::string suffix = ".report.txt";
  if (text_report.size() <= suffix.size() ||
      text_report.compare(text_report.size() - suffix.size(), suffix.size(), suffix) != 0)
    return "";
  return text_report.substr(0, text_report.size() - 4) + ".json";
}

/// The present time in UTC, ISO 8601 to the second.
std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}
}  // namespace

Report::Report(std::string title, std::string copy_to) : title_(std::move(title)), copy_to_(std::move(copy_to)) {
  if (!copy_to_.empty()) {
    copy_ = std::fopen(copy_to_.c_str(), "w");
    // An earlier run's JSON report would otherwise stand beside this run's text if this one stopped
    // before exit_code().
    std::error_code ignored;
    if (const std::string json = json_file(copy_to_); !json.empty()) std::filesystem::remove(json, ignored);
  }
  print("== %s\n", title_.c_str());
}

Report::~Report() {
  if (copy_) std::fclose(copy_);
}

void Report::print(const char* format, ...) {
  std::va_list args;
  va_start(args, format);
  std::va_list again;
  va_copy(again, args);
  std::vprintf(format, args);
  if (copy_) std::vfprintf(copy_, format, again);
  va_end(again);
  va_end(args);
}

bool Report::check(const std::string& quantity, double measured, double standard_error,
                   double theory, double z, double systematic) {
  const double diff = std::abs(measured - theory);
  const double tolerance = z * standard_error + systematic;
  const bool pass = std::isfinite(measured) && diff <= tolerance;
  ++checks_;
  if (!pass) ++failures_;
  print("%s %-34s measured %.6g +- %.2g (SE)  theory %.6g  |diff| %.3g = %.2f SE  "
              "tolerance %g SE + %.3g systematic\n",
              pass ? "PASS" : "FAIL", quantity.c_str(), measured, standard_error, theory, diff,
              standard_error > 0 ? diff / standard_error : INFINITY, z, systematic);
  json_checks_.push_back("{\"quantity\": " + json::quote(quantity) + ", \"pass\": " + (pass ? "true" : "false") +
                         ", \"measured\": " + json::number(measured) + ", \"standard_error\": " +
                         json::number(standard_error) + ", \"theory\": " + json::number(theory) +
                         ", \"z\": " + json::number(z) + ", \"systematic\": " + json::number(systematic) +
                         ", \"tolerance\": " + json::number(tolerance) + ", \"diff_se\": " +
                         json::number(standard_error > 0 ? diff / standard_error : INFINITY) + "}");
  return pass;
}

bool Report::require(const std::string& what, bool condition) {
  ++checks_;
  if (!condition) ++failures_;
  print("%s %s\n", condition ? "PASS" : "FAIL", what.c_str());
  json_checks_.push_back("{\"quantity\": " + json::quote(what) + ", \"pass\": " + (condition ? "true" : "false") + "}");
  return condition;
}

void Report::state(const std::string& quantity, double measured, double standard_error, double reference) {
  const double diff = measured - reference;
  print("STATED %-32s measured %.6g +- %.2g (SE)  reference %.6g  reference - measured %+.2f %% = %+.2f SE (not asserted)\n",
        quantity.c_str(), measured, standard_error, reference, 100.0 * -diff / measured,
        standard_error > 0 ? -diff / standard_error : INFINITY);
  json_checks_.push_back("{\"quantity\": " + json::quote(quantity) + ", \"stated\": true, \"measured\": " +
                         json::number(measured) + ", \"standard_error\": " + json::number(standard_error) +
                         ", \"theory\": " + json::number(reference) + ", \"diff_se\": " +
                         json::number(standard_error > 0 ? std::abs(diff) / standard_error : INFINITY) + "}");
}

void Report::note(const std::string& text) {
  print("     %s\n", text.c_str());
  notes_.push_back(text);
}

int Report::exit_code() {
  print("== %s: %d checks, %d failed\n", title_.c_str(), checks_, failures_);
  write_json();
  return failures_ ? 1 : 0;
}

void Report::write_json() const {
  const std::string file = json_file(copy_to_);
  if (file.empty()) return;
  const std::string temporary = file + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << "{\n  \"title\": " << json::quote(title_) << ",\n  \"version\": " << json::quote(io::build_version())
        << ",\n  \"date\": " << json::quote(utc_now()) << ",\n  \"failed\": " << failures_ << ",\n  \"checks\": [";
    for (std::size_t i = 0; i < json_checks_.size(); ++i) out << (i ? ",\n    " : "\n    ") << json_checks_[i];
    out << "\n  ],\n  \"notes\": [";
    for (std::size_t i = 0; i < notes_.size(); ++i) out << (i ? ",\n    " : "\n    ") << json::quote(notes_[i]);
    out << "\n  ]\n}\n";
    out.close();  // (a failure of the last write shows only here)
    if (!out) {
      std::fprintf(stderr, "validation: cannot write the report '%s'\n", temporary.c_str());
      return;
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, file, error);
  if (error) std::fprintf(stderr, "validation: cannot write the report '%s': %s\n", file.c_str(), error.message().c_str());
}

io::h5md::ObservableData observable(const Case& c, const std::string& name) {
  return io::h5md::read_observable(c.file, name);
}

namespace {
bool close(double a, double b) { return std::abs(a - b) <= 1e-9 * std::abs(b); }
/// Dilute binary, one common alpha, in the parameters mu = m1/m2, delta = n1/n2, w = sigma1/sigma2.
bool binary_case(const species::Mixture& mix, double mu, double delta, double w, double alpha) {
  if (mix.size() != 2 || mix.enskog) return false;
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t j = 0; j < 2; ++j)
      if (!close(mix.restitution(i, j), alpha)) return false;
  return close(mix.mass[0] / mix.mass[1], mu) && close(mix.number_density[0] / mix.number_density[1], delta) &&
         close(mix.diameter[0] / mix.diameter[1], w);
}
}  // namespace

ExactValue exact_temperature_ratio(const species::Mixture& mix) {
  if (binary_case(mix, 10.0, 2.0, 1.0, 0.5)) return {true, 3.7968, 0.0011};
  if (binary_case(mix, 2.0, 1.0, 1.0, 0.5)) return {true, 1.3616, 0.0001};
  return {};
}

ExactValue exact_cumulant_species1(const species::Mixture& mix) {
  if (binary_case(mix, 2.0, 1.0, 1.0, 0.5)) return {true, 0.1280, 0.0004};
  return {};
}

ExactValue exact_cumulant_one_species(double alpha) {
  if (close(alpha, 0.5)) return {true, 0.0959, 0.0001};
  if (close(alpha, 0.3)) return {true, 0.2078, 0.0001};
  return {};
}

IndependentHcs independent_hcs_reference(const species::Mixture& mix) {
  // validation/independent_reference/README.md: hcs_reference --particles 50000 --warmup 300 --samples 1000
  // --replicas 8; per species T_k/T, its SE, c_k, its SE.
  struct Entry {
    std::vector<double> mass, diameter, fraction;
    double alpha;
    std::uint64_t seed;
    std::vector<std::array<double, 4>> values;
    std::vector<double> enskog_density = {};  ///< the Enskog gas at these densities (empty: dilute)
  };
  static const std::vector<Entry> table = {
      {{2.0, 1.0}, {1.0, 1.0}, {1.0, 1.0}, 0.3, 11,
       {{{1.221774, 0.000098, 0.236530, 0.000369}}, {{0.778226, 0.000098, 0.156619, 0.000432}}}},
      {{2.0, 1.0}, {1.0, 1.0}, {1.0, 1.0}, 0.5, 11,
       {{{1.153311, 0.000062, 0.129490, 0.000187}}, {{0.846689, 0.000062, 0.063553, 0.000181}}}},
      {{2.0, 1.0}, {1.0, 1.0}, {1.0, 1.0}, 0.7, 11,
       {{{1.087650, 0.000080, 0.022617, 0.000272}}, {{0.912350, 0.000080, -0.015063, 0.000182}}}},
      {{2.0, 1.0}, {1.0, 1.0}, {1.0, 1.0}, 0.9, 11,
       {{{1.027075, 0.000088, -0.024674, 0.000184}}, {{0.972925, 0.000088, -0.033346, 0.000192}}}},
      {{1.0, 3.0, 10.0}, {1.0, 1.0, 1.0}, {1.0, 1.0, 1.0}, 0.7, 12,
       {{{0.619266, 0.000103, -0.025200, 0.000187}},
        {{0.896023, 0.000135, 0.030983, 0.000261}},
        {{1.484740, 0.000203, 0.076300, 0.000326}}}},
      {{1.0, 2.0, 4.0, 8.0, 16.0}, {1.0, 1.1, 1.2, 1.3, 1.4}, {1.0, 1.0, 1.0, 1.0, 1.0}, 0.8, 13,
       {{{0.724424, 0.000119, -0.059611, 0.000146}},
        {{0.845345, 0.000168, -0.034895, 0.000266}},
        {{0.971698, 0.000249, -0.012513, 0.000199}},
        {{1.122021, 0.000318, 0.003521, 0.000336}},
        {{1.336512, 0.000260, 0.021660, 0.000291}}}},
      {{10.0, 1.0}, {1.0, 1.0}, {2.0, 1.0}, 0.5, 14,
       {{{1.325498, 0.000031, 0.099764, 0.000292}}, {{0.349023, 0.000062, 0.011453, 0.000261}}}},
      // Enskog (validation/temperature_ratio_density): --enskog-density, 30000 x 8 replicas, warmup 200, 600 samples
      {{2.0, 1.0}, {2.0, 1.0}, {0.0098765, 0.019753}, 0.6, 41,
       {{{0.953658, 0.000150, 0.029970, 0.000242}}, {{1.023171, 0.000075, 0.069530, 0.000260}}},
       {0.0098765, 0.019753}},
      {{2.0, 1.0}, {2.0, 1.0}, {0.019753, 0.039506}, 0.6, 42,
       {{{0.947383, 0.000153, 0.028404, 0.000260}}, {{1.026308, 0.000077, 0.070739, 0.000387}}},
       {0.019753, 0.039506}},
      {{2.0, 1.0}, {2.0, 1.0}, {0.029630, 0.059259}, 0.6, 43,
       {{{0.941082, 0.000185, 0.029132, 0.000313}}, {{1.029459, 0.000092, 0.074658, 0.000344}}},
       {0.029630, 0.059259}},
      {{2.0, 1.0}, {2.0, 1.0}, {0.039506, 0.079012}, 0.6, 44,
       {{{0.934207, 0.000224, 0.028884, 0.000637}}, {{1.032896, 0.000112, 0.077107, 0.000464}}},
       {0.039506, 0.079012}},
      {{2.0, 1.0}, {2.0, 1.0}, {0.049383, 0.098765}, 0.6, 45,
       {{{0.927161, 0.000183, 0.029124, 0.000382}}, {{1.036420, 0.000091, 0.080245, 0.000395}}},
       {0.049383, 0.098765}},
      {{2.0, 1.0}, {2.0, 1.0}, {0.0098765, 0.019753}, 0.8, 41,
       {{{0.971527, 0.000086, -0.022214, 0.000392}}, {{1.014236, 0.000043, -0.035627, 0.000357}}},
       {0.0098765, 0.019753}},
      {{2.0, 1.0}, {2.0, 1.0}, {0.019753, 0.039506}, 0.8, 42,
       {{{0.967776, 0.000142, -0.022576, 0.000382}}, {{1.016112, 0.000071, -0.035120, 0.000283}}},
       {0.019753, 0.039506}},
      {{2.0, 1.0}, {2.0, 1.0}, {0.029630, 0.059259}, 0.8, 43,
       {{{0.964474, 0.000193, -0.023028, 0.000362}}, {{1.017763, 0.000096, -0.034902, 0.000369}}},
       {0.029630, 0.059259}},
      {{2.0, 1.0}, {2.0, 1.0}, {0.039506, 0.079012}, 0.8, 44,
       {{{0.961099, 0.000148, -0.022229, 0.000425}}, {{1.019450, 0.000074, -0.034505, 0.000209}}},
       {0.039506, 0.079012}},
      {{2.0, 1.0}, {2.0, 1.0}, {0.049383, 0.098765}, 0.8, 45,
       {{{0.957474, 0.000217, -0.022407, 0.000193}}, {{1.021263, 0.000109, -0.033154, 0.000317}}},
       {0.049383, 0.098765}},
  };
  const std::size_t s = mix.size();
  if (s == 0) return {};
  const double alpha = mix.restitution(0, 0);
  for (std::size_t i = 0; i < s; ++i)
    for (std::size_t j = 0; j < s; ++j)
      if (!close(mix.restitution(i, j), alpha)) return {};
  for (const Entry& e : table) {
    if (e.mass.size() != s || !close(alpha, e.alpha) || mix.enskog != !e.enskog_density.empty()) continue;
    bool same_density = true;
    for (std::size_t k = 0; k < e.enskog_density.size(); ++k)
      same_density = same_density && std::abs(mix.number_density[k] - e.enskog_density[k]) <= 1e-6 * e.enskog_density[k];
    if (!same_density) continue;
    double fraction_sum = 0.0;
    for (double x : e.fraction) fraction_sum += x;
    bool same = true;
    for (std::size_t k = 0; k < s && same; ++k)
      same = close(mix.mass[k] / mix.mass[0], e.mass[k] / e.mass[0]) &&
             close(mix.diameter[k] / mix.diameter[0], e.diameter[k] / e.diameter[0]) &&
             close(mix.mole_fraction(k), e.fraction[k] / fraction_sum);
    if (!same) continue;
    IndependentHcs r;
    r.known = true;
    for (const auto& v : e.values) {
      r.ratio.push_back(v[0]);
      r.ratio_error.push_back(v[1]);
      r.cumulant.push_back(v[2]);
      r.cumulant_error.push_back(v[3]);
    }
    char text[200];
    std::snprintf(text, sizeof text, "validation/independent_reference: hcs_reference (alpha = %g%s, seed %llu)",
                  e.alpha, e.enskog_density.empty() ? ", 50000 particles x 8 replicas x 1000 samples"
                                                    : ", Enskog, 30000 particles x 8 replicas x 600 samples",
                  static_cast<unsigned long long>(e.seed));
    r.source = text;
    return r;
  }
  return {};
}

IndependentSeries read_independent_series(const std::string& file, const std::string& keyword, std::size_t species) {
  IndependentSeries series;
  std::ifstream in(file);
  std::string word;
  while (in >> word) {
    if (word != keyword) {
      std::string rest;
      std::getline(in, rest);
      continue;
    }
    double t = 0.0;
    in >> t;
    std::vector<double> value(species), error(species);
    for (std::size_t k = 0; k < species; ++k) in >> value[k] >> error[k];
    if (!in) break;
    series.time.push_back(t);
    series.value.push_back(std::move(value));
    series.error.push_back(std::move(error));
  }
  return series;
}

std::map<std::string, std::pair<double, double>> read_independent_rows(const std::string& file) {
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

ScalingState read_scaling_state(const std::string& file, const std::string& observables_root, std::size_t species) {
  ScalingState state;
  try {
    const std::string group = observables_root + "/scaling_state/";
    state.c = io::h5md::read_dataset(file, group + "sonine_c").data;
    state.c_error = io::h5md::read_dataset(file, group + "sonine_c_error").data;
    state.share = io::h5md::read_dataset(file, group + "temperature_over_mean").data;
    state.share_error = io::h5md::read_dataset(file, group + "temperature_over_mean_error").data;
  } catch (const std::runtime_error&) {
    return ScalingState{};
  }
  state.known = state.c.size() == species && state.c_error.size() == species && state.share.size() == species &&
                state.share_error.size() == species;
  return state;
}

SteadyAverage steady_average(const io::h5md::ObservableData& o, double from, double scale, std::size_t column,
                             std::size_t columns) {
  SteadyAverage a;
  int n = 0;
  for (std::size_t i = 0; i < o.time.size(); ++i)
    if (o.time[i] >= from) {
      a.value += scale * o.value[i * columns + column];
      a.error += scale * (o.error.empty() ? NAN : o.error[i * columns + column]);
      ++n;
    }
  a.value /= n;
  a.error /= n;
  return a;
}

}  // namespace gdsmc::validation
