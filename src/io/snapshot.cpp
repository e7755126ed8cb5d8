#include "io/snapshot.hpp"

#include <cmath>
#include <filesystem>
#include <variant>
#include <stdexcept>

#include "io/units.hpp"

namespace gdsmc::io::snapshot {

namespace {

/// One time-dependent element of H5MD: {step, time, value [S][N][3]}.
void write_element(h5md::Writer& writer, const std::string& group, const Replica& r, const std::vector<double>& value,
                   const char* unit) {
  const std::size_t n = r.species.size();
  writer.write_dataset(group + "/value", value, {r.time.size(), n, 3});
  writer.write_unit(group + "/value", unit);
  writer.write_dataset(group + "/time", r.time, {});
  writer.write_unit(group + "/time", units::kTime);
  writer.write_integers(group + "/step", r.step);
}

}  // namespace

std::vector<Replica> from_rows(const std::map<std::string, observables::Accumulator>& rows) {
  std::vector<Replica> out;
  const auto times = rows.find("snapshot_time");
  if (times == rows.end()) return out;
  const auto of = [&](const char* name, std::size_t r) {
    const auto it = rows.find(name);
    return it == rows.end() || r >= it->second.values.size() ? std::vector<double>{} : it->second.values[r];
  };
  for (std::size_t r = 0; r < times->second.values.size(); ++r) {
    Replica replica;
    const auto& time = times->second.values[r];  // [time, events] per snapshot
    for (std::size_t s = 0; s + 1 < time.size(); s += 2) {
      replica.time.push_back(time[s]);
      replica.step.push_back(static_cast<std::int64_t>(time[s + 1]));
    }
    for (double k : of("snapshot_species", r)) replica.species.push_back(static_cast<std::int64_t>(k));
    replica.velocity = of("snapshot_velocity", r);
    replica.angular_velocity = of("snapshot_angular_velocity", r);
    replica.displacement = of("snapshot_displacement", r);
    out.push_back(std::move(replica));
  }
  return out;
}

void write(h5md::Writer& writer, const std::string& root, const std::vector<Replica>& replicas) {
  for (std::size_t k = 0; k < replicas.size(); ++k) {
    const Replica& r = replicas[k];
    const std::string group = root + "/particles/replica_" + std::to_string(k + 1);
    writer.write_group(group + "/box");
    writer.write_attribute(group + "/box", "dimension", 3LL);
    writer.write_attribute(group + "/box", "boundary", std::vector<std::string>{"none", "none", "none"});
    writer.write_integers(group + "/species", r.species);
    write_element(writer, group + "/velocity", r, r.velocity, "length time-1");
    if (!r.angular_velocity.empty()) write_element(writer, group + "/angular_velocity", r, r.angular_velocity, "time-1");
    if (!r.displacement.empty()) write_element(writer, group + "/displacement", r, r.displacement, "length");
  }
}

Temperatures temperatures(const State& state, const species::Mixture& mix) {
  const std::size_t s = mix.size(), n = state.species.size();
  for (std::uint64_t k : state.species)
    if (k < 1 || k > s) throw std::runtime_error("a snapshot's species " + std::to_string(k) + " is not one of the run's");
  double momentum[3] = {0.0, 0.0, 0.0}, mass = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double m = mix.mass[state.species[i] - 1];
    for (int d = 0; d < 3; ++d) momentum[d] += m * state.velocity[3 * i + d];
    mass += m;
  }
  Temperatures t;
  t.translational.assign(s, 0.0);
  // (a smooth run started from a rough run's snapshot has no moments of inertia: its angular velocities are not read)
  if (!state.angular_velocity.empty() && mix.moment_of_inertia.size() == s) t.rotational.assign(s, 0.0);
  std::vector<double> count(s, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = state.species[i] - 1;
    for (int d = 0; d < 3; ++d) {
      const double c = state.velocity[3 * i + d] - momentum[d] / mass;
      t.translational[k] += c * c;
      if (!t.rotational.empty()) t.rotational[k] += state.angular_velocity[3 * i + d] * state.angular_velocity[3 * i + d];
    }
    count[k] += 1.0;
  }
  for (std::size_t k = 0; k < s; ++k) {
    t.translational[k] *= mix.mass[k] / (3.0 * count[k]);
    if (!t.rotational.empty()) t.rotational[k] *= mix.inertia(k) / (3.0 * count[k]);
  }
  return t;
}

std::size_t replicas(const std::string& file) {
  if (std::error_code ec; !std::filesystem::is_regular_file(file, ec))
    throw std::runtime_error("'" + file + "': " + (std::filesystem::exists(file, ec) ? "not a file" : "no such file"));
  try {
    h5md::read_string_attribute(file, "/parameters", "namelist");
  } catch (const std::runtime_error&) {
    throw std::runtime_error("'" + file + "' is not an output file of granular-dsmc");
  }
  std::size_t r = 0;
  for (;; ++r) {
    try {
      h5md::read_integers(file, "/particles/replica_" + std::to_string(r + 1) + "/species");
    } catch (const std::runtime_error&) {
      return r;
    }
  }
}

namespace {

/// The species of `file`'s `group`: from 1, in order, `counts` of each when given.
std::vector<std::uint64_t> checked_species(const std::string& file, const std::string& group,
                                           const std::vector<std::size_t>& counts) {
  auto species = h5md::read_integers(file, group + "/species");
  std::vector<std::size_t> found(counts.size(), 0);
  for (std::size_t i = 0; i < species.size(); ++i) {
    const std::uint64_t k = species[i];
    if (k < 1 || (i > 0 && k < species[i - 1]) || (!counts.empty() && k > counts.size()))
      throw std::runtime_error("'" + file + "': " + group + "/species: species " + std::to_string(k) + " at particle " +
                               std::to_string(i + 1) + " (expected species from 1" +
                               (counts.empty() ? std::string() : " to " + std::to_string(counts.size())) + ", in order)");
    if (!counts.empty()) ++found[k - 1];
  }
  for (std::size_t k = 0; k < counts.size(); ++k)
    if (found[k] != counts[k])
      throw std::runtime_error("its snapshot has " + std::to_string(found[k]) + " particles of species " +
                               std::to_string(k + 1) + ", this run " + std::to_string(counts[k]) +
                               " (n_particles split over the species)");
  return species;
}

/// The last row [N][3] of `element` of `group`, finite.
std::vector<double> last_row(const std::string& file, const std::string& group, const std::string& element, std::size_t n) {
  const auto value = h5md::read_dataset(file, group + "/" + element + "/value");
  if (value.shape.size() != 3 || value.shape[0] == 0 || value.shape[1] != n || value.shape[2] != 3)
    throw std::runtime_error("'" + file + "': " + group + "/" + element + "/value is not [snapshots][" + std::to_string(n) + "][3]");
  std::vector<double> out(value.data.end() - static_cast<std::ptrdiff_t>(3 * n), value.data.end());
  for (double x : out)
    if (!std::isfinite(x)) throw std::runtime_error("'" + file + "': " + group + "/" + element + " is not finite");
  return out;
}

}  // namespace

State read(const std::string& file, std::size_t r, const std::vector<std::size_t>& counts) {
  const std::size_t count = replicas(file);
  if (count == 0) {
    bool sweep = true;
    try {
      h5md::read_dataset(file, "/sweep/values");
    } catch (const std::runtime_error&) {
      sweep = false;
    }
    throw std::runtime_error("'" + file + "' " +
                             (sweep ? "is a sweep's output, whose snapshots are per point (/sweep/point_K/particles); "
                                      "start from the output of a run that is not a sweep"
                                    : "holds no particle snapshot (/particles/replica_1: &output snapshot_times)"));
  }
  const std::string group = "/particles/replica_" + std::to_string(r % count + 1);
  State s;
  s.species = checked_species(file, group, counts);
  s.velocity = last_row(file, group, "velocity", s.species.size());
  bool rough = true;
  try {
    h5md::read_dataset(file, group + "/angular_velocity/time");
  } catch (const std::runtime_error&) {
    rough = false;  // a smooth gas's snapshot
  }
  if (rough) s.angular_velocity = last_row(file, group, "angular_velocity", s.species.size());
  const auto times = h5md::read_dataset(file, group + "/velocity/time").data;
  s.time = times.empty() ? 0.0 : times.back();
  return s;
}

void check_masses(const std::string& file, const std::vector<double>& masses) {
  const auto stored = h5md::read_attribute(file, "/parameters/system", "mass");
  const auto* m = std::get_if<std::vector<double>>(&stored);
  bool same = m && m->size() == masses.size();
  for (std::size_t k = 0; same && k < masses.size(); ++k) same = std::abs((*m)[k] - masses[k]) <= 1e-12 * masses[k];
  if (!same) throw std::runtime_error("its masses (/parameters/system@mass) are not this run's: the velocities belong to another gas");
}

}  // namespace gdsmc::io::snapshot
