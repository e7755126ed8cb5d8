// granular-dsmc: runs the simulation a namelist describes and writes one H5MD file (\ref output_h5md "docs/output.md").
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <iostream>
#include <new>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "run/checkpoint.hpp"
#include "run/parallel.hpp"
#include "run/simulation.hpp"
#include "analysis/compare.hpp"
#include "analysis/run_checks.hpp"
#include "io/config.hpp"
#include "io/file_lock.hpp"
#include "io/h5md.hpp"
#include "io/namelist.hpp"
#include "io/file_guard.hpp"
#include "analysis/run_table.hpp"
#include "io/version.hpp"
#include "model/observables.hpp"

namespace {

/// "a FIFO (named pipe)", "a device", "a socket" when `path` (followed through links) exists and is one
/// of them, else "": outputs are written beside and renamed into place, which must never replace such a
/// file (a device node, for root) nor open it (a FIFO blocks until someone reads it).
std::string special_file_kind(const std::string& path) {
  std::error_code ec;
  switch (std::filesystem::status(path, ec).type()) {
    case std::filesystem::file_type::fifo: return "a FIFO (named pipe)";
    case std::filesystem::file_type::block:
    case std::filesystem::file_type::character: return "a device";
    case std::filesystem::file_type::socket: return "a socket";
    default: return "";
  }
}

/// Whether `path` holds an earlier output of this program (an HDF5 file whose /h5md creator is
/// granular-dsmc), which a new run may replace; anything else is the user's and is kept.
bool is_earlier_output(const std::string& path) { return gdsmc::io::h5md::written_by(path, "granular-dsmc"); }

/// Whether `path` is a regular file that --compare=F.json wrote (its JSON has "statistical_threshold"
/// within its first 64 kB), which a new run may replace; anything else is the user's and is kept.
bool is_earlier_compare_json(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(std::filesystem::symlink_status(path, ec))) return false;
  std::ifstream in(path, std::ios::binary);
  std::string head(65536, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return !head.empty() && head[0] == '{' && head.find("\"statistical_threshold\"") != std::string::npos;
}

/// Whether two paths name the same file, also when neither exists yet (lexically, after resolving
/// what exists of them).
bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (std::filesystem::equivalent(a, b, ec)) return true;
  const auto ca = std::filesystem::weakly_canonical(std::filesystem::absolute(a, ec), ec);
  if (ec) return false;
  const auto cb = std::filesystem::weakly_canonical(std::filesystem::absolute(b, ec), ec);
  return !ec && ca == cb;
}

/// Checks before the run that the --compare=FILE.json path can be written (a probe file beside it,
/// removed at once); returns the reason it cannot, or "".
std::string unwritable_reason(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return "it is a directory";
  if (const std::string kind = special_file_kind(path); !kind.empty()) return "it is " + kind + ", not a regular file";
  const std::string probe = path + ".tmp." + std::to_string(::getpid());
  std::ofstream out(probe, std::ios::binary);
  if (!out) return std::strerror(errno);
  out.close();
  std::filesystem::remove(probe, ec);
  return "";
}

/// Writes `text` to `path` through a temporary file renamed into place; "" or the reason of failure
/// (the temporary file is removed then).
std::string write_atomically(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".tmp." + std::to_string(::getpid());
  std::error_code ec;
  {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    out.flush();
    if (!out) {
      const std::string reason = std::strerror(errno);
      std::filesystem::remove(temporary, ec);
      return reason;
    }
  }
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    return ec.message();
  }
  return "";
}

std::atomic<bool> g_interrupted{false};  // written only by the signal handler
std::atomic<bool> g_run_started{false};  // set by run(): from then on a signal only sets g_interrupted
/// SIGINT, SIGTERM: once the run has started, the flag that its set-up and loops look at (the run ends
/// within a second, status 130, no output); before, while the input and the files it names are read (HDF5
/// calls that look at no flag), the signal's default action, at once. Installed as the input is read, so
/// that a run started in the background by a script, whose shell ignores SIGINT for it, still ends on one.
extern "C" void on_signal(int signal) {
  if (g_run_started.load()) {
    g_interrupted.store(true);
    return;
  }
  std::signal(signal, SIG_DFL);  // (async-signal-safe; the raised signal is delivered as this handler returns)
  std::raise(signal);
}

const char* kUsage =
    "usage: granular-dsmc FILE.nml [--output PATH] [--quiet] [--compare[=FILE.json]] [--restart CHECKPOINT]\n"
    "                     [--set group:variable=value]...\n"
    "       granular-dsmc --print-defaults\n"
    "       granular-dsmc --table OUTPUT.h5 [QUANTITY...] [--point K] [--theory]\n"
    "  --output PATH     write the result to PATH (overrides &output file)\n"
    "  --quiet           no progress line (on a terminal one line rewritten in place; otherwise a\n"
    "                    line every 10 s) and no summary line\n"
    "  --compare         end with a table of DSMC (mean +- SE over replicas) against the theory for the\n"
    "                    input (the values granular-theory prints), the approximation's name and a mark:\n"
    "                    within statistics, within the approximation's known error, or beyond; the same\n"
    "                    numbers go to /comparison of the output file (docs/physics.md \"Comparison\n"
    "                    with theory\")\n"
    "  --compare=F.json  the same, and the numbers as JSON in F.json\n"
    "  --restart FILE    continue the run saved in checkpoint FILE (see &output checkpoint_every);\n"
    "                    the output is the same as that of an uninterrupted run\n"
    "  --set G:V=X       override variable V of group &G with X (Fortran syntax), e.g.\n"
    "                    --set dsmc:n_particles=2000 --set \"output:file='x.h5'\"; given again for\n"
    "                    the same variable, the later --set counts\n"
    "  --force           write the output (and --compare=F.json) over an existing file that is not an earlier\n"
    "                    output of granular-dsmc,\n"
    "                    and start afresh over the checkpoint of another or an interrupted run (replaced)\n"
    "  --print-defaults  print a commented namelist with every variable and its default\n"
    "  --print-reference  print every namelist variable (default, allowed values, units, meaning) as Markdown\n"
    "  --print-observables  print the table of observables (name, unit, columns, definition) as Markdown\n"
    "  --table FILE.h5   print an output file as CSV (docs/output.md \"granular-dsmc --table\"): every time\n"
    "                    series of a run (time, then each column and its _error; species from 1), or the\n"
    "                    QUANTITY... named (see --print-observables); 'summary': the final and scaling-\n"
    "                    state values in one row; 'reduced_distribution': Phi, Delta, G per bin of v*;\n"
    "                    a sweep: its table (one row per point), --point K: the trajectories of point K;\n"
    "                    --theory: the theory of --compare beside each trajectory it has\n"
    "Exit status: 0 success, 2 bad input, 1 run-time failure, 130 interrupted.\n";

}  // namespace

namespace {

/// The command line of a run.
struct Arguments {
  std::string input;
  std::vector<std::string> overrides;
  bool quiet = false, force = false, compare = false;
  std::string restart;
  std::string compare_json;     ///< --compare=FILE.json
  std::string output_option;    ///< the --output argument, for messages
  std::string output_override;  ///< the override --output became
};

/// What a FileGuard says of a read of `limit` seconds that did not finish (io/file_guard.hpp).
std::string unfinished_read(double limit) {
  char text[200];
  std::snprintf(text, sizeof text,
                "the HDF5 library had not finished reading it after %.0f s: the file is damaged, or on a very slow "
                "disk (GDSMC_READ_LIMIT=SECONDS allows longer)", limit);
  return text;
}

/// `--table FILE.h5 [QUANTITY...] [--point K] [--theory]` from argv[first] on: the CSV on stdout, notes
/// on stderr; exit status 2 with one line for a request that cannot be answered.
int print_table(int argc, char** argv, int first) {
  gdsmc::analysis::run_table::Request request;
  const auto refuse = [](const std::string& message) {
    std::cerr << "granular-dsmc: --table: " << message << "\n";
    return 2;
  };
  for (int i = first; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--theory") {
      request.theory = true;
    } else if (arg == "--point") {
      if (i + 1 >= argc) return refuse("--point needs a sweep point (1, 2, ...)");
      const std::string k = argv[++i];
      if (k.empty() || k.size() > 9 || k.find_first_not_of("0123456789") != std::string::npos || std::stoul(k) == 0)
        return refuse("--point " + gdsmc::io::namelist::printable(k) + ": a sweep point is a number from 1");
      request.point = std::stoul(k);
    } else if (!arg.empty() && arg[0] == '-') {
      return refuse("unknown option " + gdsmc::io::namelist::printable(arg) + " (--table takes QUANTITY..., --point K and --theory)");
    } else if (request.file.empty()) {
      if (arg.find_first_of("\n\r") != std::string::npos) return refuse("a file name with a line break is not accepted");
      request.file = arg;
    } else {
      request.quantities.push_back(arg);
    }
  }
  if (request.file.empty()) return refuse("no output file named");
  try {
    std::optional<gdsmc::analysis::run_table::Printed> read;
    {  // (a damaged file can loop inside HDF5: the guard ends the process then, io/file_guard.hpp; the theory of
       // --theory, which may take long, is computed after the guard, from a file read once under it)
      const double limit = gdsmc::io::FileGuard::limit_seconds(request.file);
      const gdsmc::io::FileGuard guard(limit, nullptr,
                                       {"granular-dsmc: --table " + request.file + ": " + unfinished_read(limit), "", {}});
      auto file_only = request;
      file_only.theory = false;
      read = gdsmc::analysis::run_table::print(file_only);
    }
    if (request.theory) read = gdsmc::analysis::run_table::print(request);
    const auto& printed = *read;
    std::cout << printed.csv << std::flush;
    for (const auto& note : printed.notes) std::cerr << "granular-dsmc: --table " << request.file << ": " << note << "\n";
  } catch (const std::exception& e) {
    std::cerr << "granular-dsmc: --table " << request.file << ": " << gdsmc::io::namelist::printable(e.what(), 1000)
              << "\n";  // (a quantity's name is the user's: it may hold a line break)
    return 2;
  }
  return 0;
}

/// Reads the command line into `a`; an exit status when the program is done (an option that prints and
/// exits, or a bad command line), nothing when a run follows.
/// The options that print something and end the program (--help, --version, the references): whether `arg` is one
/// (then it has printed).
bool prints_and_ends(const std::string& arg) {
  if (arg == "--help" || arg == "-h") std::cout << kUsage;
  else if (arg == "--version") std::cout << "granular-dsmc " << gdsmc::io::build_version() << "\n";
  else if (arg == "--print-defaults") std::cout << gdsmc::io::config::defaults_template();
  else if (arg == "--print-reference") std::cout << gdsmc::io::config::reference_markdown();  // Markdown, for docs/
  else if (arg == "--print-observables") std::cout << gdsmc::observables::markdown();  // model/observables.hpp, for docs/
  else return false;
  return true;
}

/// Whether `value` of `option` holds a line break, which is refused (said on stderr): one name or override a line.
bool has_line_break(const std::string& option, const std::string& value, const char* what) {
  if (value.find_first_of("\n\r") == std::string::npos) return false;
  std::cerr << "granular-dsmc: " << option << ": " << what << " with a line break is not accepted\n";
  return true;
}

std::optional<int> parse_arguments(int argc, char** argv, Arguments& a) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "granular-dsmc: " << gdsmc::io::namelist::printable(arg) << " needs a value (granular-dsmc --help lists the options)\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (prints_and_ends(arg)) {
      return 0;
    } else if (arg == "--table") {  // any output file as CSV (analysis/run_table.hpp)
      return print_table(argc, argv, i + 1);
    } else if (arg == "--quiet" || arg == "-q") {
      a.quiet = true;
    } else if (arg == "--force") {
      a.force = true;
    } else if (arg == "--output" || arg == "-o") {
      std::string path = next();
      if (has_line_break(arg, path, "a file name")) return 2;
      std::string quoted;
      for (char c : path) quoted += (c == '\'') ? std::string("''") : std::string(1, c);
      a.overrides.push_back("output:file='" + quoted + "'");
      a.output_option = "--output " + (path.empty() ? std::string("''") : path);
      a.output_override = "--set " + a.overrides.back();
    } else if (arg == "--compare") {
      a.compare = true;
    } else if (arg.rfind("--compare=", 0) == 0) {
      a.compare = true;
      a.compare_json = arg.substr(std::strlen("--compare="));
      if (a.compare_json.empty()) {
        std::cerr << "granular-dsmc: --compare=: no JSON file named (give --compare alone for the table only)\n";
        return 2;
      }
      if (has_line_break("--compare=", a.compare_json, "a file name")) return 2;
    } else if (arg == "--restart") {
      a.restart = next();
      if (has_line_break(arg, a.restart, "a file name")) return 2;
    } else if (arg == "--set") {
      a.overrides.push_back(next());
      if (has_line_break(arg, a.overrides.back(), "a value")) return 2;  // (one override a line: the fingerprint)
    } else if (!arg.empty() && arg[0] == '-') {
      std::cerr << "granular-dsmc: unknown option " << gdsmc::io::namelist::printable(arg) << " (granular-dsmc --help lists the options)\n";
      return 2;
    } else if (arg.empty()) {
      std::cerr << "granular-dsmc: an empty argument where the namelist file was expected\n";
      return 2;
    } else if (a.input.empty()) {
      a.input = arg;
    } else {
      std::cerr << "granular-dsmc: one input file only (got '" << gdsmc::io::namelist::printable(a.input) << "' and '" << gdsmc::io::namelist::printable(arg) << "')\n";
      return 2;
    }
  }
  if (a.input.empty()) {  // one line, as every refusal (--help prints the usage)
    std::cerr << "granular-dsmc: no input file: granular-dsmc FILE.nml [options] (granular-dsmc --help lists the options)\n";
    return 2;
  }
  return std::nullopt;
}

/// The line of output_error (without its newline).
std::string output_error_line(const Arguments& a, const gdsmc::io::config::Config& config, const std::string& message) {
  const auto it = config.origin.find("output:file");
  const bool set = it != config.origin.end();
  const std::string where = !set ? a.input : it->second.first == a.output_override ? a.output_option : it->second.first;
  return std::string("granular-dsmc: ") +
         gdsmc::io::namelist::Error(where, set ? it->second.second : 0, "output", "file", message).what();
}

/// `read()` of the HDF5 file `file` before the run, under a FileGuard (a damaged file can loop inside HDF5;
/// io/file_guard.hpp): a read that does not finish ends the process with the output error "'FILE' `what`:
/// (not finished after N s); `remedy`", exit status 2, the lock file removed.
template <class Read>
auto read_before_run(const Arguments& a, const gdsmc::io::config::Config& config, const std::string& file,
                     const std::string& what, const std::string& remedy, Read&& read) {
  const double limit = gdsmc::io::FileGuard::limit_seconds(file);
  const bool root = gdsmc::parallel::rank() == 0;  // (the lock is rank 0's: another rank leaves it)
  const gdsmc::io::FileGuard guard(
      limit, nullptr,
      {output_error_line(a, config, "'" + file + "' " + what + ": " + unfinished_read(limit) + "; " + remedy), "",
       root ? std::vector<std::string>{gdsmc::simulation::lock_path(config.output.file)} : std::vector<std::string>{}});
  return read();
}

/// An output path that cannot be written is an input error: named where it was set (the namelist
/// line, --set or --output; the namelist file itself for the default). Exit status 2.
int output_error(const Arguments& a, const gdsmc::io::config::Config& config, bool root, const std::string& message) {
  if (root) std::cerr << output_error_line(a, config, message) << "\n";
  return 2;
}

/// `bytes` as "1.23 GB" (decimal units, 3 significant digits).
std::string format_bytes(double bytes) {
  const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB"};
  int u = 0;
  while (bytes >= 1000.0 && u < 5) {
    bytes /= 1000.0;
    ++u;
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.3g %s", bytes, units[u]);
  return text;
}

/// A run whose particles alone need more memory than the machine has (its physical memory, or the
/// address-space limit of ulimit -v when lower) is refused before any work, naming n_particles, instead
/// of failing with std::bad_alloc after start.
/// With --compare (`theory`), the theory computed beside the run on rank 0 counts too.
std::optional<int> check_memory(const gdsmc::io::config::Config& config, bool root, bool theory) {
  const double total = gdsmc::simulation::estimated_memory_bytes(config, gdsmc::parallel::threads(), gdsmc::parallel::size());
  const double samples = gdsmc::simulation::estimated_sample_bytes(config), particles = total - samples;
  const double theory_bytes = theory ? gdsmc::analysis::theory_memory_bytes(config) : 0.0;
  const auto [have, what] = gdsmc::analysis::memory_limit();
  if (!(have > 0.0) || total + theory_bytes <= have) return std::nullopt;
  // The variable named: n_particles, or n_samples when the samples' rows are the most of it.
  const bool rows = samples > particles;
  const auto it = config.origin.find(rows ? "output:n_samples" : "dsmc:n_particles");
  const std::string file = it == config.origin.end() ? config.source_file : it->second.first;
  const int line = it == config.origin.end() ? 0 : it->second.second;
  std::string need = "the particles of the replicas run at once need about " + format_bytes(particles) +
                     ", the samples' rows of every replica " + format_bytes(samples);
  if (theory_bytes > 0.0) need += ", --compare's theory beside them " + format_bytes(theory_bytes);
  if (root)
    std::cerr << "granular-dsmc: "
              << gdsmc::io::namelist::Error(file, line, rows ? "output" : "dsmc", rows ? "n_samples" : "n_particles",
                                            need + ", more than " + what + " (" + format_bytes(have) +
                                                "): fewer particles, replicas, threads (OMP_NUM_THREADS) or samples, or "
                                                "more MPI ranks" + (theory_bytes > 0.0 ? ", or no --compare" : ""))
                     .what()
              << "\n";
  return 2;
}

/// A checkpoint at the output's checkpoint path that this run would replace (its first checkpoint) and
/// another run may need: refused without --force, unless it is the checkpoint this run resumes (or one of
/// the same input, when --restart resumes from a copy).
std::optional<int> check_checkpoint(const Arguments& a, const gdsmc::io::config::Config& config, bool root) {
  using gdsmc::simulation::CheckpointFound;
  const std::string& path = config.output.file;
  const std::string checkpoint = gdsmc::simulation::checkpoint_path(path);
  if (a.force || (!a.restart.empty() && same_file(a.restart, checkpoint))) return std::nullopt;
  const auto found = read_before_run(a, config, checkpoint, "(the checkpoint this run would replace)",
                                     "give --force to replace it unread",
                                     [&] { return gdsmc::simulation::find_checkpoint(config, path); });
  switch (found) {
    case CheckpointFound::none: return std::nullopt;
    case CheckpointFound::this_input:  // resuming this input from a copy elsewhere replaces it: as asked
      if (!a.restart.empty()) return std::nullopt;
      return output_error(a, config, root,
                          "'" + checkpoint + "' holds the checkpoint of an interrupted run of this input: resume it "
                          "with --restart " + checkpoint + ", or give --force to start afresh and replace it");
    case CheckpointFound::other_input:
      return output_error(a, config, root,
                          "'" + checkpoint + "' holds the checkpoint of a run of another input (namelist or --set) "
                          "with the same output: choose another output file, or give --force to replace it");
    case CheckpointFound::not_a_checkpoint:
      break;
  }
  return output_error(a, config, root,
                      "'" + checkpoint + "' exists and is not a checkpoint of granular-dsmc; this run's checkpoints "
                      "go there: choose another output file, or give --force to replace it");
}

/// The files a run writes, checked before it: never the input, the checkpoint being resumed, or a file
/// this program did not write; the JSON of --compare writable. An exit status when one is refused.
std::optional<int> check_paths(const Arguments& a, const gdsmc::io::config::Config& config, bool root) {
  const std::string& path = config.output.file;
  if (std::error_code ec; !a.restart.empty() && std::filesystem::is_directory(a.restart, ec)) {
    if (root) std::cerr << "granular-dsmc: --restart: '" << a.restart << "' is a directory, not a checkpoint file\n";
    return 2;
  }
  if (std::error_code ec; !a.restart.empty() && !std::filesystem::exists(a.restart, ec)) {
    if (root) std::cerr << "granular-dsmc: --restart: checkpoint '" << a.restart << "': no such file\n";
    return 2;
  }
  if (const std::string kind = a.restart.empty() ? "" : special_file_kind(a.restart); !kind.empty()) {
    if (root) std::cerr << "granular-dsmc: --restart: '" << a.restart << "' is " << kind << ", not a checkpoint file\n";
    return 2;
  }
  // A directory would only be found when the finished run is renamed into place.
  if (std::error_code ec; std::filesystem::is_directory(path, ec))
    return output_error(a, config, root, "cannot write output file '" + path + "': it is a directory");
  if (const std::string kind = special_file_kind(path); !kind.empty())
    return output_error(a, config, root, "cannot write output file '" + path + "': it is " + kind + ", not a regular file");
  // The temporary `<name>.tmp.<pid>` and the checkpoint `<stem>.checkpoint.rank<k>.h5` need room beside the name.
  if (const auto name = std::filesystem::path(path).filename().string(); name.size() > 200)
    return output_error(a, config, root,
                        "the file name is " + std::to_string(name.size()) + " characters long: at most 200, so that its "
                        "temporary and checkpoint names stay within the file system's limit of 255");
  std::error_code ec;
  if (std::filesystem::equivalent(path, a.input, ec))
    return output_error(a, config, root, "the output file '" + path + "' is the input namelist: it would be overwritten");
  if (!a.restart.empty() && std::filesystem::equivalent(path, a.restart, ec))
    return output_error(a, config, root, "the output file '" + path + "' is the checkpoint given to --restart");
  if (!config.initial.from_file.empty() && std::filesystem::equivalent(path, config.initial.from_file, ec))
    return output_error(a, config, root, "the output file '" + path + "' is the snapshot of &initial from_file: "
                        "it would be overwritten (choose another output file)");
  // (a link counts as what is at the path, also when it leads nowhere: never replaced without --force)
  if (!a.force && std::filesystem::exists(std::filesystem::symlink_status(path, ec)) &&
      !read_before_run(a, config, path, "exists, and whether it is an output of granular-dsmc is not known",
                       "choose another file, or give --force to replace it", [&] { return is_earlier_output(path); }))
    return output_error(a, config, root,
                        "'" + path + "' exists and is not an output of granular-dsmc: choose another file, or "
                        "give --force to replace it");
  if (const auto refused = check_checkpoint(a, config, root)) return refused;
  if (a.compare_json.empty()) return std::nullopt;
  // The JSON of --compare: never the input, the output or the checkpoint; writable before the run.
  const auto json_error = [&](const std::string& message) {
    if (root) std::cerr << "granular-dsmc: --compare=" << a.compare_json << ": " << message << "\n";
    return 2;
  };
  if (same_file(a.compare_json, a.input)) return json_error("it is the input namelist: it would be overwritten");
  // (the run's own files, before the look at what exists there: this run holds the lock, and its end removes it)
  if (same_file(a.compare_json, gdsmc::simulation::lock_path(path)))
    return json_error("it is this run's lock file (" + gdsmc::simulation::lock_path(path) + "): choose another file");
  for (int rank = 0; rank < gdsmc::parallel::size(); ++rank)  // (the checkpoints of this output, written or not)
    if (same_file(a.compare_json, gdsmc::simulation::checkpoint_path(path, rank)))
      return json_error("it is where this run's checkpoints go (" + gdsmc::simulation::checkpoint_path(path, rank) +
                        "): choose another file");
  if (std::error_code ec; !a.force && std::filesystem::exists(std::filesystem::symlink_status(a.compare_json, ec)) &&
                          special_file_kind(a.compare_json).empty() && !is_earlier_compare_json(a.compare_json))
    return json_error("'" + a.compare_json + "' exists and is not a --compare JSON of granular-dsmc: choose another "
                      "file, or give --force to replace it");
  if (same_file(a.compare_json, path)) return json_error("it is the output file of the run (&output file)");
  if (!a.restart.empty() && same_file(a.compare_json, a.restart)) return json_error("it is the checkpoint given to --restart");
  if (root)
    if (const std::string reason = unwritable_reason(a.compare_json); !reason.empty())
      return json_error("cannot write the JSON file: " + reason);
  return std::nullopt;
}

/// How a replica sampled its collisions, for the summary: "; K cache blocks of about N_b particles (draw)",
/// "; K cache blocks of about N_b clusters" (&agg_frag, at its first step), "; no cache blocks", or "" (not known).
std::string blocks_words(const gdsmc::simulation::Summary::Blocks& blocks) {
  char words[160] = "";
  if (blocks.count > 1 && blocks.draw == "clusters")
    std::snprintf(words, sizeof words, "; %llu cache blocks of about %.0f clusters",
                  static_cast<unsigned long long>(blocks.count), blocks.per_block);
  else if (blocks.count > 1)
    std::snprintf(words, sizeof words, "; %llu cache blocks of about %.0f particles (%s)",
                  static_cast<unsigned long long>(blocks.count), blocks.per_block, blocks.draw.c_str());
  else if (blocks.count == 1)
    std::snprintf(words, sizeof words, "; no cache blocks");
  return words;
}

/// The line after a run, and its warnings: a bound that was not a majorant, samples past their targets,
/// displacements never tracked.
void print_summary(const gdsmc::io::config::Config& config, const gdsmc::simulation::Summary& summary, bool quiet,
                   bool root) {
  const std::string& path = config.output.file;
  if (!quiet && root) {
    // A sweep: a line per point, then the file; a run: its final state on the line of the file.
    for (std::size_t k = 0; k < summary.points.size(); ++k) {
      const auto& p = summary.points[k];
      std::fprintf(stderr, "granular-dsmc: point %zu (%s): t = %.6g, T = %.6g, %.4g collisions per particle%s\n", k + 1,
                   p.label.c_str(), p.final_time, p.final_total_temperature, p.collisions_per_particle,
                   blocks_words(p.blocks).c_str());
    }
    char state[160] = "";
    if (summary.points.empty())
      std::snprintf(state, sizeof state, "t = %.6g, T = %.6g, %.4g collisions per particle, ", summary.final_time,
                    summary.final_total_temperature, summary.collisions_per_particle);
    // The rate of the collision loop per thread (what bench/ measures; a replica's blocks on several
    // threads count each thread's seconds), and the overall one, the progress line's: this process's
    // events over its wall time.
    const double made_here = summary.events - summary.restored_events;
    std::fprintf(stderr,
                 "granular-dsmc: wrote %s: %s%.3g collisions/s per thread in the collision loop (%.3g/s overall%s), "
                 "%.1f s%s\n",
                 path.c_str(), state, summary.events_per_second,
                 summary.wall_seconds > 0 ? made_here / summary.wall_seconds : 0.0,
                 summary.restored_events > 0 ? " since the restart" : "", summary.wall_seconds,
                 summary.points.empty()
                     ? blocks_words(summary.blocks).c_str()
                     : "");  // (a sweep's points have theirs on their lines)
  }
  if (root && summary.acceptance_overshoots > 0.0)
    std::fprintf(stderr,
                 "granular-dsmc: warning: %.0f candidates had an acceptance probability above 1 (the bound was "
                 "not a majorant; see /observables/acceptance_overshoots): please report this input\n",
                 summary.acceptance_overshoots);
  if (root && summary.msd_never_started > 0) {
    const bool by_temperature = summary.msd_start_missed.rfind("T <=", 0) == 0;
    std::fprintf(stderr,
                 "granular-dsmc: warning: %llu of %llu replicas never reached %s (%s, or a longer run, starts them): "
                 "their msd is 0 at every sample and their /observables/msd/start_time is -1\n",
                 static_cast<unsigned long long>(summary.msd_never_started),
                 static_cast<unsigned long long>(summary.msd_replicas), summary.msd_start_missed.c_str(),
                 by_temperature ? "a higher one" : "an earlier one");
  }
  if (root && summary.samples_past_target > 0)
    std::fprintf(stderr,
                 "granular-dsmc: warning: %llu %s taken past %s event target%s, by up to %llu collisions (see "
                 "/observables/collisions): a cache-blocked step's collisions outran the bound of its length, as in "
                 "a gas far from equilibrium; &dsmc block_size = 0 meets every target exactly (docs/schemes.md, "
                 "\"Event targets\")\n",
                 static_cast<unsigned long long>(summary.samples_past_target),
                 summary.samples_past_target == 1 ? "sample was" : "samples were",
                 summary.samples_past_target == 1 ? "its" : "their", summary.samples_past_target == 1 ? "" : "s",
                 static_cast<unsigned long long>(summary.most_past_target));
}

/// The one line of a run stopped by a signal (without its newline): what is left to resume from (the
/// checkpoint of the last safe point, when there is one), or how to have one.
std::string interrupt_report(const gdsmc::io::config::Config& config, const std::string& what) {
  // (the progress line was ended by the run: Progress::finish)
  std::string line = "granular-dsmc: " + what;
  const std::string checkpoint = gdsmc::simulation::checkpoint_path(config.output.file);
  if (std::error_code ec; config.output.checkpoint_every && std::filesystem::exists(checkpoint, ec)) {
    line += "; resume with --restart " + gdsmc::io::namelist::shell_word(checkpoint);
    // (the checkpoint holds the overrides in its fingerprint: a resumed run must be given them again)
    if (!config.overrides.empty())
      line += " and the same options (" + gdsmc::simulation::override_options(config.overrides) + ")";
  }
  else if (!config.output.checkpoint_every)
    line += " (with &output checkpoint_every = SECONDS an interrupted run leaves a checkpoint to resume)";
  return line;
}

/// Seconds the --compare theory may go on after the run, when the run took less (granular_dsmc.cpp run()).
constexpr double theory_allowance_seconds = 30.0;

/// Runs the input, with --compare's theory in a thread of its own (the theory depends on the input
/// only: computed while the DSMC runs, so that --compare adds almost nothing to the wall time); the
/// program's exit status.
/// The simulation's options from the command line: progress, the interrupt flag and its line, --restart, --force.
gdsmc::simulation::Options run_options(const Arguments& a, const gdsmc::io::config::Config& config, bool root) {
  gdsmc::simulation::Options options;
  options.progress = !a.quiet && root;
  options.progress_terminal = isatty(STDERR_FILENO) != 0;
  options.interrupt = &g_interrupted;
  options.interrupt_line = [&config] { return interrupt_report(config, gdsmc::simulation::Interrupted().what()); };
  options.restart_path = a.restart;
  options.replace_any_file = a.force;
  return options;
}

/// After a complete run with --compare (rank 0): the table on stdout and, with --compare=FILE.json, the JSON
/// file; 1 when that file cannot be written, else 0.
int print_comparison(const Arguments& a, const gdsmc::analysis::compare::Comparison& comparison,
                     const std::string& path) {
  std::cout << gdsmc::analysis::compare::table(comparison) << std::flush;
  if (a.compare_json.empty()) return 0;
  const std::string reason = write_atomically(a.compare_json, gdsmc::analysis::compare::json(comparison));
  if (reason.empty()) return 0;
  std::cerr << "granular-dsmc: --compare=" << a.compare_json << ": cannot write the JSON file: " << reason
            << " (the run's output " << path << " is complete)\n";
  return 1;
}

int run(const Arguments& a, const gdsmc::io::config::Config& config, bool root) {
  g_run_started.store(true);  // a signal now sets g_interrupted (on_signal)
  gdsmc::simulation::Options options = run_options(a, config, root);
  const std::string& path = config.output.file;
  gdsmc::analysis::compare::Comparison comparison;
  // The theory stops at an interrupt, and once the run is done it may take as long again as the run
  // did, at least theory_allowance_seconds (the Smoluchowski equations of a sticking gas can take
  // hours: granular-theory computes them without a limit). Declared before the future, whose
  // destructor waits for the theory's thread.
  using Clock = std::chrono::steady_clock;
  const auto started = Clock::now();
  std::atomic<Clock::rep> theory_deadline{Clock::time_point::max().time_since_epoch().count()};
  const gdsmc::theory::smoluchowski::Stop stop_theory = [&theory_deadline] {
    return g_interrupted.load() || Clock::now().time_since_epoch().count() > theory_deadline.load();
  };
  std::future<std::vector<gdsmc::analysis::compare::PointTheory>> theory;
  if (a.compare && root) {
    // With one thread the theory waits for the run (deferred): it must not take a second core.
    const auto policy = gdsmc::parallel::threads() > 1 ? std::launch::async : std::launch::deferred;
    theory = std::async(policy, [&config, &stop_theory] { return gdsmc::analysis::compare::predict_points(config, stop_theory); });
    options.before_commit = [&](gdsmc::io::h5md::Writer& writer) {
      const double allowance =
          std::max(theory_allowance_seconds, std::chrono::duration<double>(Clock::now() - started).count());
      theory_deadline.store((Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                std::chrono::duration<double>(allowance))).time_since_epoch().count());
      auto points = theory.get();
      if (g_interrupted.load()) throw gdsmc::simulation::Interrupted();
      for (auto& point : points)
        if (point.error == gdsmc::theory::smoluchowski::Stopped().what())
          point.error = "the Smoluchowski equations did not reach the end of the run within " +
                        std::to_string(static_cast<long>(std::ceil(allowance))) +
                        " s (as long as the run took, at least " +
                        std::to_string(static_cast<long>(theory_allowance_seconds)) + " s): granular-theory " +
                        config.source_file + " computes them without a limit";
      comparison = gdsmc::analysis::compare::compare_file(config, writer.temporary_path(), std::move(points));
      gdsmc::analysis::compare::write(writer, comparison);
    };
  }
  try {
    const auto summary = gdsmc::simulation::run(config, path, options);
    if (a.compare && root)
      if (const int status = print_comparison(a, comparison, path)) return status;
    print_summary(config, summary, a.quiet, root);
  } catch (const gdsmc::simulation::Interrupted& e) {
    if (root) std::cerr << interrupt_report(config, e.what()) << "\n";
    return 130;
  } catch (const gdsmc::simulation::RestartError& e) {
    if (root) std::cerr << "granular-dsmc: --restart: " << e.what() << "\n";
    return 2;
  } catch (const gdsmc::simulation::RootFailed&) {  // (another rank: rank 0 says why)
    return 1;
  } catch (const gdsmc::parallel::AgreedFailure& e) {  // (every rank has it: rank 0 says it)
    if (root) std::cerr << "granular-dsmc: " << e.what() << "\n";
    return 1;
  } catch (const gdsmc::simulation::UnreachableTarget& e) {  // (as AgreedFailure)
    if (root) std::cerr << "granular-dsmc: " << e.what() << "\n";
    return 1;
  } catch (const gdsmc::simulation::OutputPathError& e) {
    if (!root) return 2;
    return output_error(a, config, root, e.what());
  } catch (const std::bad_alloc&) {
    std::cerr << "granular-dsmc: out of memory (the particles and samples alone need about "
              << format_bytes(gdsmc::simulation::estimated_memory_bytes(config, gdsmc::parallel::threads(),
                                                                         gdsmc::parallel::size()))
              << " on this rank): nothing written; fewer particles, replicas, threads or samples\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "granular-dsmc: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

/// Everything but MPI's start and end: reads the input, runs, writes; the exit status.
int run_program(int argc, char** argv) {
  const bool root = gdsmc::parallel::rank() == 0;
  Arguments arguments;
  if (const auto done = parse_arguments(argc, argv, arguments)) return *done;
  std::signal(SIGINT, on_signal);  // (on_signal: the default action until run() starts)
  std::signal(SIGTERM, on_signal);
  gdsmc::io::config::Config config;
  try {
    config = gdsmc::io::config::read_file(arguments.input, arguments.overrides, gdsmc::analysis::check_run_cost);
  } catch (const gdsmc::io::namelist::Error& e) {
    // (an error of the override --output became is named by the option the user typed)
    const std::string message =
        !arguments.output_override.empty() && e.file == arguments.output_override
            ? gdsmc::io::namelist::Error(arguments.output_option, e.line, e.group, e.variable, e.message).what()
            : e.what();
    if (root) std::cerr << "granular-dsmc: " << message << "\n";
    return 2;
  }
  // The lock first (rank 0 takes it, every rank learns the answer): the checks below then see no other
  // run of this output at work. Released, and its file removed, when run_program returns.
  std::optional<gdsmc::io::FileLock> lock;
  std::string busy;
  if (root) try {
      lock.emplace(gdsmc::simulation::lock_path(config.output.file));
      // Under the lock no other run writes this output or its checkpoints: a temporary of theirs is what a
      // killed run left, whatever its process id has become since (the other ranks wait below, none of
      // theirs exists yet). A checkpoint's name may be another run's output (x.checkpoint.h5 beside x.h5),
      // whose own lock then says whether that run is at work.
      if (lock->held()) {
        gdsmc::io::h5md::remove_others_temporaries(config.output.file);
        for (int rank = 0; rank < gdsmc::parallel::size(); ++rank) {
          const std::string checkpoint = gdsmc::simulation::checkpoint_path(config.output.file, rank);
          try {
            const gdsmc::io::FileLock idle(gdsmc::simulation::lock_path(checkpoint));
            gdsmc::io::h5md::remove_others_temporaries(checkpoint);
          } catch (const gdsmc::io::LockRefused&) {  // (a run of that output at work, or a file there: left)
          }
        }
      }
    } catch (const gdsmc::io::LockRefused& e) {
      busy = e.what();
    }
  busy = gdsmc::parallel::broadcast_from_root(busy);
  if (!busy.empty())
    return output_error(arguments, config, root, "cannot write output file '" + config.output.file + "': " + busy);
  // The checks look at this rank's node (its files, its memory; --compare's JSON on rank 0 only): the ranks
  // agree on the largest refusal, so that all of them stop, or none.
  std::optional<int> refused = check_paths(arguments, config, root);
  if (!refused && arguments.compare && root) try {  // (the theory alone first: its remedy is not the particles')
      gdsmc::analysis::check_theory_memory(config, "run without --compare (granular-dsmc needs no theory)");
    } catch (const gdsmc::io::namelist::Error& e) {
      std::cerr << "granular-dsmc: --compare: " << e.what() << "\n";
      refused = 2;
    }
  if (!refused) refused = check_memory(config, root, arguments.compare && root);
  if (const int agreed = gdsmc::parallel::largest_over_ranks(refused.value_or(0)); agreed != 0) {
    if (root && !refused)
      std::cerr << "granular-dsmc: another MPI rank refused the run before it started (the output's folder or the memory "
                   "of its node)\n";
    return agreed;
  }
  if (root)
    for (const auto& warning : gdsmc::analysis::input_warnings(config)) std::cerr << "granular-dsmc: warning: " << warning << "\n";
  return run(arguments, config, root);
}

}  // namespace

int main(int argc, char** argv) {
  // Under mpirun every rank runs this main: all read the input (each reports a bad input the same
  // way) and run their share of the work; rank 0 alone writes the file and the summary (parallel.hpp).
  gdsmc::io::h5md::skip_library_shutdown();  // before any HDF5 call (h5md.hpp)
  // A file size limit (ulimit -f) makes a write fail with EFBIG, reported like a full disk, instead
  // of killing the process and leaving its temporary file.
  std::signal(SIGXFSZ, SIG_IGN);
  gdsmc::parallel::Session mpi(argc, argv);
  return mpi.finish(run_program(argc, argv));
}
