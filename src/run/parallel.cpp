#include "run/parallel.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <sys/types.h>
#include <unistd.h>

#ifdef GDSMC_HAVE_MPI
#include <mpi.h>
#endif
#ifdef _OPENMP
#include <omp.h>
#endif

namespace gdsmc::parallel {

namespace {
bool launched_by_mpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

#ifdef GDSMC_HAVE_MPI
bool active() {
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  return initialized && !finalized;
}
void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}
#endif
}  // namespace

Session::Session(int& argc, char**& argv) {
#ifdef GDSMC_HAVE_MPI
  if (launched_by_mpirun()) check(MPI_Init(&argc, &argv), "MPI_Init");
#else
  (void)argc;
  (void)argv;
  (void)launched_by_mpirun;
#endif
}

Session::~Session() {
#ifdef GDSMC_HAVE_MPI
  if (active()) MPI_Finalize();
#endif
}

#ifdef GDSMC_HAVE_MPI
namespace {
std::string host_name() {
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) != 0) return "";
  return name;
}

/// What rank 0 learns of the others at the end: the process ids of those on its node and the largest status.
struct Peers {
  std::vector<pid_t> on_this_node;
  int largest_status = 0;
};
Peers gather_peers(int status) {
  const std::vector<std::string> all =
      gather_to_root(std::to_string(status) + " " + std::to_string(getpid()) + " " + host_name());
  Peers peers;
  const std::string here = host_name();
  for (std::size_t k = 0; k < all.size(); ++k) {
    std::istringstream in(all[k]);
    int code = 0;
    long pid = 0;
    std::string host;
    if (!(in >> code >> pid)) continue;
    if (!(in >> host)) host.clear();
    peers.largest_status = std::max(peers.largest_status, code);
    if (k > 0 && host == here && pid > 0) peers.on_this_node.push_back(static_cast<pid_t>(pid));
  }
  return peers;
}

void wait_until_ended(const std::vector<pid_t>& peers) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  for (const pid_t pid : peers)
    while (kill(pid, 0) == 0 && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
}
}  // namespace
#endif

int Session::finish(int status) {
#ifdef GDSMC_HAVE_MPI
  if (!active()) return status;
  const bool several = size() > 1;
  const bool root = rank() == 0;
  Peers peers;
  if (several) peers = gather_peers(status);  // collective: every rank, whatever its status
  MPI_Finalize();
  if (!several) return status;
  if (!root) return 0;
  const int job_status = std::max(status, peers.largest_status);
  if (job_status != 0) wait_until_ended(peers.on_this_node);
  return job_status;
#else
  return status;
#endif
}

bool built_with_mpi() {
#ifdef GDSMC_HAVE_MPI
  return true;
#else
  return false;
#endif
}

int rank() {
#ifdef GDSMC_HAVE_MPI
  if (active()) {
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
  }
#endif
  return 0;
}

int size() {
#ifdef GDSMC_HAVE_MPI
  if (active()) {
    int s = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &s);
    return s;
  }
#endif
  return 1;
}

int threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

ThreadSplit split_threads(std::size_t units) {
  const int total = threads();
  ThreadSplit split;
  if (units == 0 || units >= static_cast<std::size_t>(total)) {
    split.units = total;
    return split;
  }
  split.units = static_cast<int>(units);
  split.per_unit = total / split.units;
#ifdef _OPENMP
  if (split.per_unit > 1 && omp_get_max_active_levels() < 2) omp_set_max_active_levels(2);
#endif
  return split;
}

std::vector<std::string> gather_to_root(const std::string& mine) {
  if (size() == 1) return {mine};
#ifdef GDSMC_HAVE_MPI
  const int n = size(), me = rank();
  // The lengths as 64-bit numbers and the verdict on their sum broadcast: every rank refuses a gather
  // beyond MPI's int counts together (one rank throwing alone would leave the others waiting in it).
  long long length = static_cast<long long>(mine.size());
  std::vector<long long> lengths(me == 0 ? n : 0);
  check(MPI_Gather(&length, 1, MPI_LONG_LONG, lengths.data(), 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD), "MPI_Gather");
  long long total = 0;
  for (long long l : lengths) total += l;
  check(MPI_Bcast(&total, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD), "MPI_Bcast");
  if (total > INT32_MAX)
    throw AgreedFailure("MPI: the ranks' results (" + std::to_string(total) +
                        " bytes) exceed the 2147483647 bytes one gather to rank 0 carries: nothing written; "
                        "fewer samples, snapshots or sweep points per run");
  std::vector<int> counts(lengths.size()), offsets(lengths.size(), 0);
  for (std::size_t k = 0; k < lengths.size(); ++k) {
    counts[k] = static_cast<int>(lengths[k]);
    if (k > 0) offsets[k] = offsets[k - 1] + counts[k - 1];
  }
  std::string all(static_cast<std::size_t>(me == 0 ? total : 0), '\0');
  check(MPI_Gatherv(mine.data(), static_cast<int>(length), MPI_CHAR, all.data(), counts.data(), offsets.data(),
                    MPI_CHAR, 0, MPI_COMM_WORLD),
        "MPI_Gatherv");
  std::vector<std::string> out;
  for (std::size_t k = 0; k < counts.size(); ++k) out.push_back(all.substr(offsets[k], counts[k]));
  return out;
#else
  return {mine};
#endif
}

std::string broadcast_from_root(const std::string& value) {
  if (size() == 1) return value;
#ifdef GDSMC_HAVE_MPI
  // (the length as a 64-bit number: beyond MPI's int counts every rank refuses, as in gather_to_root)
  long long length = static_cast<long long>(value.size());
  check(MPI_Bcast(&length, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD), "MPI_Bcast");
  if (length > INT32_MAX)
    throw AgreedFailure("MPI: rank 0's " + std::to_string(length) + " bytes exceed the 2147483647 one broadcast carries");
  std::string out = rank() == 0 ? value : std::string(static_cast<std::size_t>(length), '\0');
  check(MPI_Bcast(out.data(), static_cast<int>(length), MPI_CHAR, 0, MPI_COMM_WORLD), "MPI_Bcast");
  return out;
#else
  return value;
#endif
}

int largest_over_ranks(int value) {
  if (size() == 1) return value;
#ifdef GDSMC_HAVE_MPI
  int largest = value;
  check(MPI_Allreduce(&value, &largest, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce");
  return largest;
#else
  return value;
#endif
}

}  // namespace gdsmc::parallel
