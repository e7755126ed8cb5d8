/**
 * \file progress.hpp
 * \brief The progress line of a run (\ref output_progress "docs/output.md"): one line for the whole
 *        run on stderr, over all replicas and sweep points of this rank.
 *
 * On a terminal the line is rewritten in place (at most 5 times a second); otherwise (a log file, a
 * pipe) a full line is printed every 10 s, so that logs stay readable. It shows the fraction of the
 * work done (the mean of the units' fractions), the replicas and sweep points finished, the collision
 * rate since the start over all threads (collisions per wall-clock second: the summary's "overall"
 * rate) and the ETA ("-" until there is a rate to tell it from); for a run that is not a sweep the
 * simulated time of its slowest running replica and the mean T of the running replicas at their last samples
 * (replicas_position). Every update is O(1), and the text is composed only when a line is due.
 * Under MPI rank 0 prints its own units.
 */
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace gdsmc::simulation {

using Clock = std::chrono::steady_clock;  ///< the wall clock of progress, checkpoints and timings

/// One line on stderr, rewritten in place on a terminal, else printed every 10 s.
class ProgressLine {
 public:
  /// `enabled`: print at all; `terminal`: stderr is a terminal.
  ProgressLine(bool enabled, bool terminal) : enabled_(enabled), terminal_(terminal), start_(Clock::now()) {}
  /// Whether a line is due now (so that the caller composes it only then).
  bool due(double fraction_done) const;
  /// Prints the line for `fraction_done` with `what` and the rate, if one is due.
  void update(double fraction_done, const std::string& what, double events_per_second);
  /// Ends the line on a terminal.
  void finish();

 private:
  bool enabled_, terminal_;
  bool printed_ = false;
  Clock::time_point start_, last_{};
};

/// ", t = .., T = .. at the last sample" of the progress line: the slowest running unit's time (started,
/// `fraction` < 1) and the running units' mean `temperature` at their last samples (NaN: none yet; no T
/// while none has one); when none is running, the latest time and mean T of the finished units.
std::string replicas_position(const std::vector<double>& fraction, const std::vector<double>& time,
                              const std::vector<double>& temperature, const std::vector<char>& started);

/// Progress over all units of this rank (replicas of every sweep point), shared by its threads.
class Progress {
 public:
  /// `point_of` gives the sweep point of each unit (slot) of this rank; `points` their number.
  Progress(bool enabled, bool terminal, std::vector<std::size_t> point_of, std::size_t points);
  /// Unit `slot` is `fraction` done, at simulated `time`, with `new_events` since its last update and
  /// total temperature `temperature` at its last sample (NaN: none yet).
  void update(std::size_t slot, double fraction, double time, std::uint64_t new_events, double temperature);
  /// Ends the line.
  void finish() { line_.finish(); }

 private:
  std::mutex mutex_;
  ProgressLine line_;
  std::vector<double> partial_;
  std::vector<double> time_;         ///< each unit's simulated time
  std::vector<double> temperature_;  ///< each unit's T at its last sample (NaN: none yet)
  std::vector<char> started_;        ///< each unit's first update came
  std::vector<std::size_t> point_of_;
  std::vector<std::size_t> open_;  ///< units of each point not finished
  std::size_t points_ = 0, points_done_ = 0, units_done_ = 0;
  double sum_ = 0.0;  ///< sum of partial_
  std::uint64_t events_ = 0;
  Clock::time_point start_ = Clock::now();
};

}  // namespace gdsmc::simulation
