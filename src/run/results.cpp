// What one replica measured, between ranks, in checkpoints and reduced (results.hpp).
#include "run/results.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace gdsmc::simulation {

namespace {

// Byte serialisation of ReplicaResult, to send it between MPI ranks (same machine type: raw bytes).
template <class T>
void put(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}
template <class T>
T take(const std::string& in, std::size_t& pos) {
  if (pos + sizeof(T) > in.size()) throw std::runtime_error("corrupt replica result from another rank");
  T value;
  std::memcpy(&value, in.data() + pos, sizeof(T));
  pos += sizeof(T);
  return value;
}

}  // namespace

void pack(std::string& out, std::uint64_t unit, const ReplicaResult& r) {
  put(out, unit);
  put(out, r.mean_step);
  put(out, r.events);
  put(out, r.collide_seconds);
  put(out, r.cache_blocks);
  put(out, r.block_draw);
  put(out, r.samples_past_target);
  put(out, r.most_past_target);
  put(out, static_cast<std::uint64_t>(r.rows.size()));
  for (const auto& [name, entry] : r.rows) {
    put(out, static_cast<std::uint64_t>(name.size()));
    out += name;
    put(out, static_cast<std::uint64_t>(entry.first));
    put(out, static_cast<std::uint64_t>(entry.second.size()));
    out.append(reinterpret_cast<const char*>(entry.second.data()), entry.second.size() * sizeof(double));
  }
}

ReplicaResult unpack(const std::string& in, std::size_t& pos, std::uint64_t& unit) {
  ReplicaResult r;
  unit = take<std::uint64_t>(in, pos);
  r.mean_step = take<double>(in, pos);
  r.events = take<std::uint64_t>(in, pos);
  r.collide_seconds = take<double>(in, pos);
  r.cache_blocks = take<std::uint64_t>(in, pos);
  r.block_draw = take<std::uint64_t>(in, pos);
  r.samples_past_target = take<std::uint64_t>(in, pos);
  r.most_past_target = take<std::uint64_t>(in, pos);
  const auto n = take<std::uint64_t>(in, pos);
  for (std::uint64_t k = 0; k < n; ++k) {
    const auto length = take<std::uint64_t>(in, pos);
    if (pos + length > in.size()) throw std::runtime_error("corrupt replica result from another rank");
    std::string name = in.substr(pos, length);
    pos += length;
    auto& entry = r.rows[name];
    entry.first = take<std::uint64_t>(in, pos);
    const auto count = take<std::uint64_t>(in, pos);
    if (pos + count * sizeof(double) > in.size()) throw std::runtime_error("corrupt replica result from another rank");
    entry.second.resize(count);
    std::memcpy(entry.second.data(), in.data() + pos, count * sizeof(double));
    pos += count * sizeof(double);
  }
  return r;
}

void save(const ReplicaResult& r, state::Record& record) {
  for (const auto& [name, entry] : r.rows) {
    record.put("result/rows/" + name, entry.second);
    record.put_integer("result/columns/" + name, entry.first);
  }
  record.put("result/mean_step", r.mean_step);
  record.put("result/collide_seconds", r.collide_seconds);
  record.put_integer("result/events", r.events);
  record.put_integer("result/cache_blocks", r.cache_blocks);
  record.put_integer("result/block_draw", r.block_draw);
  record.put_integer("result/samples_past_target", r.samples_past_target);
  record.put_integer("result/most_past_target", r.most_past_target);
}

ReplicaResult load_result(const state::Record& record) {
  ReplicaResult r;
  const std::string rows = "result/rows/";
  for (const auto& [name, values] : record.reals)
    if (name.rfind(rows, 0) == 0) {
      const std::string observable = name.substr(rows.size());
      r.rows[observable] = {record.integer("result/columns/" + observable), values};
    }
  r.mean_step = record.real("result/mean_step");
  r.collide_seconds = record.real("result/collide_seconds");
  r.events = record.integer("result/events");
  // (checkpoints written before these were kept: not known)
  if (record.has_integers("result/cache_blocks")) r.cache_blocks = record.integer("result/cache_blocks");
  if (record.has_integers("result/block_draw")) r.block_draw = record.integer("result/block_draw");
  if (record.has_integers("result/samples_past_target")) {
    r.samples_past_target = record.integer("result/samples_past_target");
    r.most_past_target = record.integer("result/most_past_target");
  }
  return r;
}

namespace {
/// Whether `name` is a time series of the table of observables (a per-size row "name@i" is not).
bool is_series(const std::string& name) {
  try {
    return observables::find(name).reduction == observables::Reduction::series;
  } catch (const std::out_of_range&) {
    return false;
  }
}
}  // namespace

void check_rows(const ReplicaResult& result, std::size_t samples, bool finished) {
  for (const auto& row : result.rows) {  // (no structured bindings: the lambda below captures them)
    const std::string& name = row.first;
    const std::size_t columns = row.second.first;
    const std::vector<double>& values = row.second.second;
    const auto refuse = [&](const std::string& what) {
      throw state::StateError("row '" + name + "' holds " + std::to_string(values.size()) + " values of " +
                              std::to_string(columns) + " columns: " + what);
    };
    if (columns == 0 || values.size() % columns != 0) refuse("not a whole number of rows");
    observables::Reduction reduction;
    try {
      reduction = observables::find(name).reduction;
    } catch (const std::out_of_range&) {  // a per-size row of &agg_frag ("number@i"): one row
      if (name.find('@') != std::string::npos && values.size() != columns) refuse("expected one row");
      continue;
    }
    if (reduction == observables::Reduction::series && values.size() != columns * samples)
      refuse(std::to_string(samples) + " samples expected");
    if (reduction == observables::Reduction::per_replica && finished && values.size() != columns)
      refuse("one row expected");
  }
}

PointResult reduce_point(std::vector<ReplicaResult>& replicas) {
  PointResult point;
  double mean_step_sum = 0.0;
  for (std::size_t r = 0; r < replicas.size(); ++r) {
    for (auto& [name, entry] : replicas[r].rows) {
      auto& a = point.observables[name];
      // Every replica's rows of one observable alike (a damaged record must not be read past its end).
      if (!a.values.empty() && (a.columns != entry.first || a.values.front().size() != entry.second.size()) &&
          is_series(name))
        throw std::runtime_error("the replicas' rows of '" + name + "' differ in shape (a damaged checkpoint)");
      a.columns = entry.first;
      // Rows of the reduced_* observables exist only for the replicas that reached the scaling
      // regime: each such replica adds one row, in replica order.
      a.values.push_back(std::move(entry.second));
    }
    mean_step_sum += replicas[r].mean_step;
    if (point.cache_blocks == 0) point.cache_blocks = replicas[r].cache_blocks, point.block_draw = replicas[r].block_draw;
    point.events += replicas[r].events;
    point.collide_seconds += replicas[r].collide_seconds;
    point.samples_past_target += replicas[r].samples_past_target;
    point.most_past_target = std::max(point.most_past_target, replicas[r].most_past_target);
  }
  point.mean_step = mean_step_sum / static_cast<double>(replicas.size());
  return point;
}

std::string sample_row(const char* name, std::size_t i) {
  std::string key(name);
  key += '@';
  key += std::to_string(i);
  return key;
}

void pad_size_rows(ReplicaResult& result, std::size_t n_samples) {
  for (const char* name : kSizeObservables) {
    std::size_t width = 1;
    for (std::size_t i = 0; i < n_samples; ++i) width = std::max(width, result.rows[sample_row(name, i)].first);
    std::vector<double> rows(n_samples * width, 0.0);
    for (std::size_t i = 0; i < n_samples; ++i) {
      const auto key = sample_row(name, i);
      const auto& row = result.rows[key].second;
      std::copy(row.begin(), row.end(), rows.begin() + static_cast<std::ptrdiff_t>(i * width));
      result.rows.erase(key);
    }
    result.rows[name] = {width, std::move(rows)};
  }
}

void pad_size_columns(std::vector<ReplicaResult>& replicas) {
  for (const char* name : kSizeObservables) {
    std::size_t width = 0;
    for (auto& r : replicas) width = std::max(width, r.rows[name].first);
    for (auto& r : replicas) {
      auto& [columns, values] = r.rows[name];
      if (columns == width) continue;
      const std::size_t n = values.size() / columns;
      std::vector<double> wide(n * width, 0.0);
      for (std::size_t i = 0; i < n; ++i)
        std::copy(values.begin() + static_cast<std::ptrdiff_t>(i * columns),
                  values.begin() + static_cast<std::ptrdiff_t>((i + 1) * columns),
                  wide.begin() + static_cast<std::ptrdiff_t>(i * width));
      columns = width;
      values = std::move(wide);
    }
  }
}

}  // namespace gdsmc::simulation
