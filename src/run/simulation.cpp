// A whole run (simulation.hpp): the work units over threads and ranks, the reduction, the output.
// Orchestration only: the replicas run in run/replica.cpp, the physics is dsmc's, the file's layout
// io/output's, the checkpoints' format run/checkpoint's.
#include "run/simulation.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "analysis/sweep_table.hpp"
#include "dsmc/collide.hpp"
#include "dsmc/particles.hpp"
#include "dsmc/sample.hpp"
#include "io/h5md.hpp"
#include "io/file_guard.hpp"
#include "io/output.hpp"
#include "io/snapshot.hpp"
#include "io/units.hpp"
#include "io/version.hpp"
#include "run/checkpoint.hpp"
#include "run/parallel.hpp"
#include "run/replica.hpp"
#include "run/results.hpp"

namespace gdsmc::simulation {

namespace {

/// `path` without a trailing ".h5".
std::string without_h5(std::string path) {
  if (path.size() > 3 && path.compare(path.size() - 3, 3, ".h5") == 0) path.resize(path.size() - 3);
  return path;
}

/// Work unit u = point * R_p + replica, point-major; unit u runs on rank u mod K (parallel.hpp).
struct Unit {
  std::size_t point, replica;
};

/// The output file, opened on rank 0 before any work, so that an unwritable path fails at once.
void open_output(std::optional<io::h5md::Writer>& writer, const io::config::Config& config, const std::string& output_path,
                 int rank) {
  std::string open_error;
  if (rank == 0) {
    try {
      writer.emplace(output_path, io::config::author_name(config.output), "granular-dsmc", io::build_version());
    } catch (const std::runtime_error& e) {
      open_error = e.what();
      if (open_error.empty()) open_error = "cannot create the output file";
    }
  }
  open_error = parallel::broadcast_from_root(open_error);
  if (!open_error.empty()) throw OutputPathError(rank == 0 ? open_error : "");
}

/// The input's fingerprint in a checkpoint: the namelist text and the overrides.
std::string fingerprint_of(const io::config::Config& config) {
  std::string joined = config.namelist_text + fingerprint_overrides_marker;
  for (const auto& o : config.overrides) joined += o + "\n";
  return joined;
}

/// Reads the checkpoint of --restart on every rank; the first rank's error stops all of them. A damaged file
/// that loops inside HDF5, or an interrupt during the read, ends the process with one line, the temporary
/// output and the lock file (`leave_nothing`, empty on other ranks) removed (io/file_guard.hpp).
void load_restart(CheckpointStore& checkpoints, const Options& options, int rank, std::vector<std::string> leave_nothing) {
  std::string restart_error;
  if (!options.restart_path.empty()) {
    const std::string file = rank_file(options.restart_path, rank);
    try {
      const double limit = io::FileGuard::limit_seconds(file);
      char after[160];
      std::snprintf(after, sizeof after,
                    "the HDF5 library had not finished reading it after %.0f s: the file is damaged, or on a very "
                    "slow disk (GDSMC_READ_LIMIT=SECONDS allows longer)", limit);
      const io::FileGuard guard(limit, options.interrupt,
                                {"granular-dsmc: --restart: checkpoint '" + file + "': " + after,
                                 "granular-dsmc: interrupted while reading the checkpoint '" + file + "': nothing written",
                                 std::move(leave_nothing)});
      checkpoints.load(file);
    } catch (const std::exception& e) {
      restart_error = e.what();
    }
  }
  std::string first;
  for (const auto& e : parallel::gather_to_root(restart_error))
    if (!e.empty() && first.empty()) first = e;
  first = parallel::broadcast_from_root(first);
  if (!first.empty()) throw RestartError(first);
}

/// The finished units a checkpoint holds must have every sample of their point (one row of "time" per
/// sample): a record cut short is refused before any work, not found after the whole run.
void check_finished_units(const CheckpointStore& checkpoints, const std::vector<io::config::Config>& points,
                          const std::vector<Unit>& units, const std::vector<std::size_t>& mine) {
  std::string problem;
  for (std::size_t u : mine) {
    const ReplicaResult* finished = checkpoints.finished_result(u);
    if (!finished || !problem.empty()) continue;
    const io::config::Config& point = points[units[u].point];
    const std::size_t expected = point.dsmc.t_end ? point.sample_times().size() : point.sample_collisions().size();
    const auto times = finished->rows.find("time");
    const std::size_t found = times == finished->rows.end() ? 0 : times->second.second.size();
    if (found != expected)
      problem = "the checkpoint is damaged: finished work unit " + std::to_string(u) + " holds " + std::to_string(found) +
                " samples, its point has " + std::to_string(expected);
    else
      try {
        check_rows(*finished, expected, true);
      } catch (const state::StateError& e) {
        problem = "the checkpoint is damaged: finished work unit " + std::to_string(u) + ": " + e.what();
      }
  }
  std::string first;
  for (const auto& e : parallel::gather_to_root(problem))
    if (!e.empty() && first.empty()) first = e;
  first = parallel::broadcast_from_root(first);
  if (!first.empty()) throw RestartError(first);
}

/// Runs this rank's units (`mine`, indices into `units`) on its threads; returns their results in the
/// order of `mine`. Throws Interrupted, or std::runtime_error with the first failure of a thread.
std::vector<ReplicaResult> run_units(const std::vector<io::config::Config>& points, const std::vector<Unit>& units,
                                     const std::vector<std::size_t>& mine, CheckpointStore& checkpoints,
                                     Progress& progress, const Options& options) {
  std::vector<ReplicaResult> done(mine.size());
  std::string failure;  // first error of a thread (exceptions must not leave an OpenMP region)
  std::atomic<bool> interrupted{false}, failed{false}, restart_failed{false}, unreachable{false};
  // Threads serve the units first; when this rank has fewer units than threads, each unit's cache
  // blocks share the rest (collide.hpp, "Threads inside one replica"), and the output is the same.
  const parallel::ThreadSplit split = parallel::split_threads(mine.size());
  const auto run_unit = [&](std::ptrdiff_t k) {
    if (interrupted.load() || failed.load()) return;
    const std::size_t slot = static_cast<std::size_t>(k), u = mine[slot];
    try {
      if (const ReplicaResult* finished = checkpoints.finished_result(u)) {
        done[slot] = *finished;
        progress.update(slot, 1.0, 0.0, 0, std::nan(""));
        return;
      }
      ReplicaContext context{options, progress, slot, split.per_unit,
                             [&](const std::function<state::Record()>& snapshot) { checkpoints.safe_point(u, snapshot); },
                             &failed};
      done[slot] = run_replica(points[units[u].point], units[u].replica, checkpoints.resume_point(u), context);
      checkpoints.finished(u, done[slot]);
    } catch (const Interrupted&) {
      if (!failed.load()) interrupted.store(true);  // (else abandoned for another unit's failure)
    } catch (const std::exception& e) {
      const bool restart = dynamic_cast<const RestartError*>(&e) != nullptr;
      const bool unreached = dynamic_cast<const UnreachableTarget*>(&e) != nullptr;
#pragma omp critical(gdsmc_failure)
      if (!failed.exchange(true)) {
        failure = e.what();
        restart_failed.store(restart);
        unreachable.store(unreached);
      }
    }
  };
  const auto n_mine = static_cast<std::ptrdiff_t>(mine.size());
  if (split.units > 1) {
#pragma omp parallel for schedule(dynamic, 1) num_threads(split.units)
    for (std::ptrdiff_t k = 0; k < n_mine; ++k) run_unit(k);
  } else {
    // One unit at a time: no enclosing parallel region, so the blocks' parallel regions are not nested
    // (libgomp starts new threads for every nested region instead of reusing its pool).
    for (std::ptrdiff_t k = 0; k < n_mine; ++k) run_unit(k);
  }
  progress.finish();
  if (failed.load() && restart_failed.load()) throw RestartError(failure);
  if (failed.load() && unreachable.load()) throw UnreachableTarget(failure);
  if (failed.load()) throw std::runtime_error(failure);
  if (interrupted.load()) throw Interrupted();
  return done;
}

/// What rank 0 gathered: every rank's packed results, or (one rank) its own results unpacked.
struct Gathered {
  std::vector<std::string> packed;
  std::vector<ReplicaResult> own;
};

/// Every rank's status and results to rank 0, which decides for all: throws Interrupted, RestartError or the
/// failure of any rank (parallel::AgreedFailure) on every rank; else rank 0's Gathered (empty elsewhere), for
/// results_by_point.
Gathered gather_results(const std::vector<std::size_t>& mine, std::vector<ReplicaResult>&& done, char status,
                        const std::string& failure) {
  // One rank keeps its results where they are: packing them into one string and back would copy every
  // snapshot twice (seconds for a gigabyte, where an interrupt is not looked at).
  const bool one_rank = parallel::size() == 1;
  std::string packed(1, status);
  if (status == 'F' || status == 'R' || status == 'U') packed += failure;
  else if (status == 'K' && !one_rank)
    for (std::size_t k = 0; k < mine.size(); ++k) pack(packed, mine[k], done[k]);
  Gathered gathered{parallel::gather_to_root(packed), {}};
  std::string verdict;
  if (parallel::rank() == 0)
    for (const auto& g : gathered.packed)
      if (g[0] != 'K' && verdict.empty()) verdict = g;
  verdict = parallel::broadcast_from_root(verdict);
  if (!verdict.empty() && verdict[0] == 'I') throw Interrupted();
  if (!verdict.empty() && verdict[0] == 'R') throw RestartError(verdict.substr(1));
  if (!verdict.empty() && verdict[0] == 'U') throw UnreachableTarget(verdict.substr(1));
  if (!verdict.empty()) throw parallel::AgreedFailure(verdict.substr(1));
  if (one_rank) gathered.own = std::move(done);
  return gathered;
}

/// The results of every point in replica order (rank 0), from gather_results.
std::vector<std::vector<ReplicaResult>> results_by_point(const std::vector<io::config::Config>& points,
                                                         const std::vector<Unit>& units,
                                                         const std::vector<std::size_t>& mine, Gathered&& gathered) {
  std::vector<std::vector<ReplicaResult>> by_point(points.size());
  for (std::size_t p = 0; p < points.size(); ++p) by_point[p].resize(static_cast<std::size_t>(points[p].dsmc.replicas));
  if (parallel::size() == 1) {
    for (std::size_t k = 0; k < mine.size(); ++k)
      by_point[units[mine[k]].point][units[mine[k]].replica] = std::move(gathered.own[k]);
    return by_point;
  }
  for (const auto& g : gathered.packed) {
    std::size_t pos = 1;
    while (pos < g.size()) {
      std::uint64_t u = 0;
      ReplicaResult r = unpack(g, pos, u);
      by_point[units[u].point][units[u].replica] = std::move(r);
    }
  }
  return by_point;
}

/// What the writer needs of a point: its observables, and what is derived from them (sample.hpp): the
/// HCS distributions in reduced speed, the clusters' temperatures.
io::output::Point output_point(const io::config::Config& config, PointResult& result) {
  io::output::Point point;
  auto& acc = result.observables;
  if (config.has_agg_frag) {
    const auto& number = acc.at("number");
    point.cluster_temperature = sample::cluster_temperature(number.values, acc.at("size_energy").values,
                                                            acc.at("time").mean().size() * number.columns);
  }
  if (acc.count("reduced_distribution")) {
    const auto& phi = acc.at("reduced_distribution");
    point.reduced = sample::reduced_distributions(
        config.mixture(), phi.mean(), phi.standard_error(), acc.at("reduced_sonine_c").mean(),
        acc.at("reduced_temperature_share").mean(), acc.at("reduced_cooling_rate").mean()[0],
        static_cast<std::size_t>(config.output.reduced_bins), config.output.reduced_range);
  }
  point.observables = std::move(acc);
  return point;
}

/// The name of the point's block draw (collide.hpp BlockDraw), nullptr when the number is none.
const char* block_draw_name(const PointResult& result) {
  if (result.block_draw > 255) return nullptr;
  return collide::Collider::block_draw_name(static_cast<collide::Collider::BlockDraw>(result.block_draw));
}

/// How the point's collisions were sampled (\ref output_h5md "docs/output.md"): the attributes cache_blocks,
/// the blocks of a replica (1: the whole gas), and block_draw, their draw (collide.hpp BlockDraw), when known.
void write_blocks(io::h5md::Writer& writer, const std::string& group, const PointResult& result) {
  const char* draw = block_draw_name(result);
  if (result.cache_blocks == 0 || draw == nullptr) return;  // (a checkpoint from before they were kept)
  writer.write_attribute(group, "cache_blocks", static_cast<long long>(result.cache_blocks));
  writer.write_attribute(group, "block_draw", draw);
}

/// The start of the displacements of point `k` (for the warning when it was never reached).
std::string msd_start_text(const io::config::Config& point, bool sweep, std::size_t k) {
  char text[96];
  if (point.output.msd_start_temperature)
    std::snprintf(text, sizeof text, "T <= msd_start_temperature = %g", *point.output.msd_start_temperature);
  else
    std::snprintf(text, sizeof text, "msd_start_time = %g", point.output.msd_start_time.value_or(0.0));
  return std::string(text) + (sweep ? " (point " + std::to_string(k + 1) + ")" : "");
}

/// Throws Interrupted when the caller's flag is set (the writing phase looks between points).
void stop_if_interrupted(const Options& options) {
  if (options.interrupt && options.interrupt->load()) throw Interrupted();
}

/// Writes every point (and a sweep's table) to the output, not yet committed; the summary of the run.
/// Throws Interrupted when the flag is set between two points (or before the table and --compare).
Summary write_output(io::h5md::Writer& writer, const io::config::Config& config,
                     const std::vector<io::config::Config>& points, std::vector<PointResult>& results,
                     const Options& options) {
  writer.write_parameters(config.resolved(), config.namelist_text);
  writer.write_attribute("/parameters", "source_file", config.source_file);
  std::string joined;
  for (const auto& o : config.overrides) joined += o + "\n";
  writer.write_attribute("/parameters", "overrides", joined);
  // H5MD's units module: every time and observable carries its unit, in the units of the namelist
  // (\ref output_units "docs/output.md").
  io::units::declare(writer);
  Summary summary;
  std::uint64_t events = 0;
  double collide_seconds = 0.0;
  const auto sweep_rows = config.sweep.table();
  for (std::size_t k = 0; k < points.size(); ++k) {
    stop_if_interrupted(options);
    auto& acc = results[k].observables;
    summary.final_time = acc.at("time").mean().back();
    summary.final_total_temperature = acc.at("total_temperature").mean().back();
    summary.collisions_per_particle = acc.at("collisions_per_particle").mean().back();

    if (acc.count("acceptance_overshoots"))
      summary.acceptance_overshoots +=
          acc.at("acceptance_overshoots").mean().back() * static_cast<double>(points[k].dsmc.replicas);
    events += results[k].events;
    collide_seconds += results[k].collide_seconds;
    summary.samples_past_target += results[k].samples_past_target;
    if (const auto start = acc.find("msd_start"); start != acc.end())
      for (const auto& row : start->second.values) {
        ++summary.msd_replicas;
        if (row[0] >= 0.0) continue;
        ++summary.msd_never_started;  // (replica.cpp: -1 when tracking never began)
        if (summary.msd_start_missed.empty()) summary.msd_start_missed = msd_start_text(points[k], config.is_sweep(), k);
      }
    summary.most_past_target = std::max(summary.most_past_target, results[k].most_past_target);
    // A sweep point lives in /sweep/point_K (K from 1) with the value it applies.
    const std::string group = config.is_sweep() ? "/sweep/point_" + std::to_string(k + 1) : "";
    // /particles (&output snapshot_times), before output_point takes the rows
    if (const auto snapshots = io::snapshot::from_rows(results[k].observables); !snapshots.empty())
      io::snapshot::write(writer, group, snapshots);
    io::output::write_point(writer, group + "/observables", points[k], output_point(points[k], results[k]));
    if (config.is_sweep()) {
      // One variable: its name and the value as written (as before tables); several: joined by ", ".
      writer.write_attribute(group, "variable", config.sweep.names());
      writer.write_attribute(group, "value", io::config::Sweep::row_text(sweep_rows[k]));
      writer.write_attribute(group, "mean_time_step", results[k].mean_step);
      write_blocks(writer, group, results[k]);
      // Each point is an H5MD root of its own (h5md + observables): a reader opened at the group
      // reads it as a file (docs/output.md "Sweeps").
      writer.write_hard_link("/h5md", group + "/h5md");
    } else {
      writer.write_attribute("/parameters", "mean_time_step", results[k].mean_step);
      write_blocks(writer, "/parameters", results[k]);
    }
    if (const char* draw = block_draw_name(results[k]); draw != nullptr && results[k].cache_blocks > 0)
      summary.blocks = {results[k].cache_blocks, draw,
                        static_cast<double>(points[k].dsmc.n_particles) / static_cast<double>(results[k].cache_blocks)};
    else
      summary.blocks = {};
    if (config.is_sweep())
      summary.points.push_back({config.sweep.row_label(sweep_rows[k]), summary.final_time,
                                summary.final_total_temperature, summary.collisions_per_particle, summary.blocks});
  }
  stop_if_interrupted(options);
  if (config.is_sweep()) {
    writer.write_attribute("/sweep", "variable", config.sweep.names());
    std::vector<std::string> texts;
    for (const auto& row : sweep_rows) texts.push_back(io::config::Sweep::row_text(row));
    writer.write_attribute("/sweep", "values", texts);
    // The table (analysis/sweep_table.hpp): the swept values and the headline results, read back from
    // the points just written.
    analysis::sweep_table::write(writer, analysis::sweep_table::build(config, writer.temporary_path()));
  }
  stop_if_interrupted(options);
  if (options.before_commit) options.before_commit(writer);
  stop_if_interrupted(options);
  summary.events_per_second = collide_seconds > 0 ? static_cast<double>(events) / collide_seconds : 0.0;
  summary.events = static_cast<double>(events);
  return summary;
}

/// Reduces the replicas of every point, writes them and commits the file (rank 0). The writing is watched
/// (io/file_guard.hpp): an interrupt it does not see between points within a quarter of a second (inside one
/// large write of the HDF5 library) ends the process with the caller's line, `leave_nothing` removed.
Summary write_and_commit(io::h5md::Writer& writer, const io::config::Config& config,
                         const std::vector<io::config::Config>& points, std::vector<std::vector<ReplicaResult>> by_point,
                         const Options& options, std::vector<std::string> leave_nothing) {
  Summary summary;
  {
    // (one rank only: under MPI the others wait for rank 0's status, and an exit from the guard would leave
    // them to mpirun's abort; they see the flag between points)
    const bool one_rank = parallel::size() == 1;
    const io::FileGuard watch(std::numeric_limits<double>::infinity(), one_rank ? options.interrupt : nullptr,
                              {"", options.interrupt_line ? options.interrupt_line() : Interrupted().what(),
                               std::move(leave_nothing), 0.25});
    std::vector<PointResult> results;
    for (std::size_t p = 0; p < points.size(); ++p) {
      stop_if_interrupted(options);
      if (points[p].has_agg_frag) pad_size_columns(by_point[p]);
      results.push_back(reduce_point(by_point[p]));
    }
    summary = write_output(writer, config, points, results, options);
  }
  writer.commit();
  return summary;
}

}  // namespace

CheckpointFound find_checkpoint(const io::config::Config& config, const std::string& output_path) {
  const std::string path = checkpoint_path(output_path);
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::symlink_status(path, ec))) return CheckpointFound::none;
  if (!std::filesystem::is_regular_file(path, ec)) return CheckpointFound::not_a_checkpoint;  // never open a FIFO
  try {
    return io::h5md::read_string_attribute(path, "/checkpoint", "fingerprint") == fingerprint_of(config)
               ? CheckpointFound::this_input
               : CheckpointFound::other_input;
  } catch (const std::exception&) {
    return CheckpointFound::not_a_checkpoint;
  }
}

double estimated_memory_bytes(const io::config::Config& config, int threads, int ranks) {
  double per_particle = sizeof(particles::Vec3) + sizeof(std::uint32_t);
  if (config.output.track_displacements) per_particle += sizeof(particles::Displacement);
  if (config.rough()) per_particle += sizeof(particles::Vec3);
  if (config.output.checkpoint_every || !config.output.snapshot_times.empty()) per_particle *= 2.0;
  double units = 0.0;
  for (const auto& point : config.sweep_points()) units += static_cast<double>(point.dsmc.replicas);
  const double at_once = std::min(std::ceil(units / std::max(1, ranks)), static_cast<double>(std::max(1, threads)));
  return at_once * static_cast<double>(config.dsmc.n_particles) * per_particle + estimated_sample_bytes(config);
}

double estimated_sample_bytes(const io::config::Config& config) {
  // Rank 0 gathers every unit's sample rows: about 64 bytes per species and sample (measured with the
  // default observables: 1e5 species, 50 samples more, 318 MB more; docs/performance.md#perf_many_samples).
  double units = 0.0;
  for (const auto& point : config.sweep_points()) units += static_cast<double>(point.dsmc.replicas);
  const double samples = static_cast<double>(std::max(config.sample_times().size(), config.sample_collisions().size()));
  const double species = config.has_agg_frag ? 1.0 : static_cast<double>(config.system.n_species);
  return units * samples * species * 64.0;
}

std::string lock_path(const std::string& output_path) { return without_h5(output_path) + ".lock"; }

std::string checkpoint_path(const std::string& output_path, int rank) {
  const std::string stem = without_h5(output_path) + ".checkpoint";
  return rank == 0 ? stem + ".h5" : stem + ".rank" + std::to_string(rank) + ".h5";
}

double chunk_end_time(double time, std::uint64_t candidates, double t_target, double chunk) {
  if (candidates == 0 || !(time > 0.0)) return t_target;
  const double end = time + chunk * time / static_cast<double>(candidates);
  return end < t_target ? end : t_target;
}

std::uint64_t fnv1a(std::uint64_t hash, const void* data, std::size_t bytes) {
  // FNV-1a, 64 bits (Fowler, Noll and Vo; offset basis 14695981039346656037, prime 1099511628211).
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * 1099511628211ull;
  return hash;
}

Summary run(const io::config::Config& config, const std::string& output_path, const Options& options) {
  const auto started = Clock::now();
  const std::vector<io::config::Config> points = config.sweep_points();
  const int rank = parallel::rank(), ranks = parallel::size();
  std::optional<io::h5md::Writer> writer;  // (not movable: opened in place)
  open_output(writer, config, output_path, rank);
  if (writer && options.replace_any_file) writer->replace_any_file();

  std::vector<Unit> units;
  for (std::size_t p = 0; p < points.size(); ++p)
    for (std::size_t r = 0; r < static_cast<std::size_t>(points[p].dsmc.replicas); ++r) units.push_back({p, r});
  std::vector<std::size_t> mine, point_of;
  for (std::size_t u = 0; u < units.size(); ++u)
    if (u % static_cast<std::size_t>(ranks) == static_cast<std::size_t>(rank)) mine.push_back(u);
  for (std::size_t u : mine) point_of.push_back(units[u].point);

  // Checkpoints: one file per rank (rank 0's is the one \ref output_checkpoint "docs/output.md" names).
  CheckpointStore checkpoints(checkpoint_path(output_path, rank), config.output.checkpoint_every.value_or(0.0),
                              fingerprint_of(config), ranks, units.size());
  if (options.replace_any_file) checkpoints.replace_any_file();
  checkpoints.set_stop_flag(options.interrupt);
  load_restart(checkpoints, options, rank,
               writer ? std::vector<std::string>{writer->temporary_path(), lock_path(output_path)} : std::vector<std::string>{});
  check_finished_units(checkpoints, points, units, mine);
  double restored_events = 0.0;  // every rank's, for the summary's overall rate
  for (const auto& text : parallel::gather_to_root(std::to_string(checkpoints.restored_events())))
    restored_events += std::stod(text);
  Progress progress(options.progress && rank == 0, options.progress_terminal, point_of, points.size());
  std::vector<ReplicaResult> done;
  char status = 'K';
  std::string failure;
  try {
    done = run_units(points, units, mine, checkpoints, progress, options);
  } catch (const Interrupted&) {
    status = 'I';
  } catch (const RestartError& e) {  // a record of the checkpoint refused as its unit resumed
    status = 'R';
    failure = e.what();
  } catch (const UnreachableTarget& e) {
    status = 'U';
    failure = e.what();
  } catch (const std::exception& e) {
    status = 'F';
    failure = e.what();
  }
  Gathered gathered;
  try {
    gathered = gather_results(mine, std::move(done), status, failure);
  } catch (const UnreachableTarget& e) {  // (every rank: its own checkpoint could only fail again)
    if (!checkpoints.remove()) throw;
    throw UnreachableTarget(std::string(e.what()) + " (this run's checkpoint, which would fail the same way, is removed)");
  }
  Summary summary;
  std::exception_ptr write_failure;
  char written = 'K';  // rank 0's output: complete, interrupted (I) or failed (F)
  if (rank == 0) {
    try {
      summary = write_and_commit(*writer, config, points, results_by_point(points, units, mine, std::move(gathered)),
                                 options, {writer->temporary_path(), lock_path(output_path)});
    } catch (const Interrupted&) {
      write_failure = std::current_exception();
      written = 'I';
    } catch (...) {
      write_failure = std::current_exception();
      written = 'F';
    }
  }
  // Every rank keeps its checkpoint unless rank 0's output is complete: an interrupt (or a full disk)
  // while writing leaves the run to resume. The other ranks end as rank 0 does (parallel.hpp: its status).
  written = parallel::broadcast_from_root(std::string(1, written))[0];
  if (write_failure) std::rethrow_exception(write_failure);
  if (written == 'I') throw Interrupted();
  if (written == 'F') throw RootFailed();
  checkpoints.remove();  // the run is complete: its checkpoint is stale
  summary.restored_events = restored_events;
  summary.wall_seconds = std::chrono::duration<double>(Clock::now() - started).count();
  return summary;
}

}  // namespace gdsmc::simulation
