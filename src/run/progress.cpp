// The progress line of a run (progress.hpp).
#include "run/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace gdsmc::simulation {

std::string replicas_position(const std::vector<double>& fraction, const std::vector<double>& time,
                              const std::vector<double>& temperature, const std::vector<char>& started) {
  // The replicas running now (started, not finished): with more replicas than threads the others have not
  // begun (t = 0) or are done (a later t, a lower T), and a mean over all would mix the waves.
  const auto position = [&](bool running) {
    double t = running ? std::numeric_limits<double>::infinity() : 0.0, sum = 0.0;
    std::size_t units = 0, counted = 0;
    for (std::size_t u = 0; u < time.size(); ++u) {
      if (!started[u] || (fraction[u] < 1.0) != running) continue;
      ++units;
      t = running ? std::min(t, time[u]) : std::max(t, time[u]);
      if (!std::isnan(temperature[u])) sum += temperature[u], ++counted;
    }
    char text[80] = "";
    if (units == 0) return std::string();
    if (counted == 0) std::snprintf(text, sizeof text, ", t = %.4g", t);
    else std::snprintf(text, sizeof text, ", t = %.4g, T = %.4g at the last sample", t, sum / static_cast<double>(counted));
    return std::string(text);
  };
  const std::string running = position(true);
  if (!running.empty()) return running;
  const std::string finished = position(false);
  return finished.empty() ? ", t = 0" : finished;
}

bool ProgressLine::due(double fraction_done) const {
  if (!enabled_) return false;
  if (!terminal_ && fraction_done >= 1.0) return false;  // the summary line follows
  if (fraction_done >= 1.0) return true;
  const auto now = Clock::now();
  const auto interval = terminal_ ? std::chrono::milliseconds(200) : std::chrono::milliseconds(10000);
  return now - last_ >= interval && (terminal_ || last_ != Clock::time_point{} || now - start_ >= interval);
}

void ProgressLine::update(double fraction_done, const std::string& what, double events_per_second) {
  if (!due(fraction_done)) return;
  const auto now = Clock::now();
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  // Before the first collisions there is no rate to tell the ETA from: "-", not 0.
  char rate[32] = "-", eta[32] = "-";
  if (events_per_second > 0.0 && fraction_done > 0.0) {
    std::snprintf(rate, sizeof rate, "%.3g", events_per_second);
    std::snprintf(eta, sizeof eta, "%.0f s", elapsed * (1.0 - fraction_done) / fraction_done);
  }
  if (terminal_) {
    const int width = 30;
    const int filled = static_cast<int>(fraction_done * width);
    std::fprintf(stderr, "\r[%.*s%*s] %5.1f%%  %s  %s coll/s  ETA %s  ", filled, "##############################",
                 width - filled, "", 100.0 * fraction_done, what.c_str(), rate, eta);
  } else {
    std::fprintf(stderr, "granular-dsmc: %5.1f%% done, %s, %s coll/s, %.0f s elapsed, ETA %s\n", 100.0 * fraction_done,
                 what.c_str(), rate, elapsed, eta);
  }
  std::fflush(stderr);
  printed_ = true;
}

void ProgressLine::finish() {
  if (enabled_ && terminal_ && printed_) std::fputs("\n", stderr);
}

Progress::Progress(bool enabled, bool terminal, std::vector<std::size_t> point_of, std::size_t points)
    : line_(enabled, terminal), partial_(point_of.size(), 0.0), time_(point_of.size(), 0.0),
      temperature_(point_of.size(), std::nan("")), started_(point_of.size(), 0), point_of_(std::move(point_of)), open_(points, 0) {
  for (std::size_t p : point_of_) ++open_[p];
  for (std::size_t n : open_) points_ += n > 0 ? 1 : 0;
}

void Progress::update(std::size_t slot, double fraction, double time, std::uint64_t new_events, double temperature) {
  std::lock_guard<std::mutex> lock(mutex_);
  const double before = partial_[slot];
  partial_[slot] = fraction;
  sum_ += fraction - before;
  if (before < 1.0 && fraction >= 1.0) {
    ++units_done_;
    if (--open_[point_of_[slot]] == 0) ++points_done_;
  }
  events_ += new_events;
  time_[slot] = time;
  started_[slot] = 1;
  if (!std::isnan(temperature)) temperature_[slot] = temperature;
  const double done = std::min(sum_ / static_cast<double>(partial_.size()), units_done_ == partial_.size() ? 1.0 : 0.999);
  if (!line_.due(done)) return;
  std::string what = std::to_string(units_done_) + "/" + std::to_string(partial_.size()) + " replicas";
  if (points_ > 1) what += ", " + std::to_string(points_done_) + "/" + std::to_string(points_) + " sweep points";
  if (points_ <= 1) what += replicas_position(partial_, time_, temperature_, started_);
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  line_.update(done, what, elapsed > 0 ? static_cast<double>(events_) / elapsed : 0.0);
}

}  // namespace gdsmc::simulation
