// Unit tests for gdsmc::io::h5md: the H5MD 1.1 layout of \ref output_h5md "docs/output.md", round trips of every
// attribute type, and the atomic-write guarantee (no temporary or half-written file left behind).
#include "io/h5md.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using namespace gdsmc::io::h5md;

namespace {

/// A fresh directory per test, removed afterwards whatever the test left in it.
class TempDir {
 public:
  TempDir() {
    std::random_device random;
    path_ = fs::temp_directory_path() /
            ("gdsmc-h5md-test-" + std::to_string(::getpid()) + "-" + std::to_string(random()));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    for (const auto& entry : fs::recursive_directory_iterator(path_, ignored))
      if (entry.is_directory(ignored))
        fs::permissions(entry.path(), fs::perms::owner_all, fs::perm_options::add, ignored);
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const fs::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

  /// Files whose name marks them as a Writer's temporary file.
  std::vector<std::string> temporaries() const {
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator(path_))
      if (entry.path().filename().string().find(".tmp.") != std::string::npos)
        found.push_back(entry.path().string());
    return found;
  }

 private:
  fs::path path_;
};

template <class Body>
std::string runtime_error_message(Body&& body) {
  try {
    body();
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  ADD_FAILURE() << "expected std::runtime_error";
  return {};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::vector<Parameter> every_kind_of_parameter() {
  return {
      {"system", "enskog", true},
      {"system", "thermostat", false},
      {"system", "species", 2LL},
      {"system", "alpha", 0.9},
      {"system", "seeds", std::vector<long long>{1, -2, 1LL << 40}},
      {"system", "masses", std::vector<double>{1.0, 4.5}},
      {"system", "one_mass", std::vector<double>{2.5}},
      {"system", "no_seeds", std::vector<long long>{}},
      {"output", "file", std::string("run_α.h5")},
      {"output", "names", std::vector<std::string>{"small", "βig", ""}},
      {"output", "empty_text", std::string()},
      {"system", "restitution", std::vector<double>{0.9, 0.8, 0.8, 0.7}, {2, 2}},  // read back flat
      {"sweep", "values", std::vector<std::string>{"0.6", "2.0", "0.9", "5.0", "0.5", "1"}, {3, 2}},
  };
}

const std::string namelist_text =
    "&system\n  alpha = 0.9  ! restitution, \xc3\xbc\n  masses = 1.0, 4.5\n/\n&output\n/\n";

Series temperature_series() {  // Nt = 3, S = 2
  Series s;
  s.time = {0.0, 0.5, 1.0};
  s.step = {0, 10, 20};
  s.value = {1.0, 2.0, 0.9, 1.8, 0.8, 1.6};
  s.columns = 2;
  s.error = {0.01, 0.02, 0.03, 0.04, 0.05, 0.06};
  return s;
}

Series total_temperature_series() {  // Nt = 4, 1-D
  Series s;
  s.time = {0.0, 0.25, 0.5, 0.75};
  s.step = {0, 5, 10, 15};
  s.value = {1.5, 1.4, 1.3, 1.2};
  s.error = {0.1, 0.2, 0.3, 0.4};
  return s;
}

/// A complete, committed file as the simulation would write it.
void write_example(const std::string& path, const std::string& author = "A. Uthor") {
  Writer writer(path, author, "granular-dsmc", "0.1.0");
  writer.write_parameters(every_kind_of_parameter(), namelist_text);
  writer.write_observable("temperature", temperature_series());
  writer.write_observable("total_temperature", total_temperature_series());
  Series histogram;
  histogram.time = {1.0};
  histogram.step = {100};
  histogram.value = {0.1, 0.2, 0.3};
  histogram.columns = 3;
  writer.write_observable("histogram/species_1", histogram);
  writer.write_dataset("/observables/histogram/edges", {0.0, 1.0, 2.0, 3.0}, {});
  writer.write_dataset("/extra/matrix", {1, 2, 3, 4, 5, 6}, {2, 3});
  writer.write_attribute("/observables/temperature", "unit", "energy");
  writer.write_attribute("/observables/temperature/value", "scale", 2.5);
  writer.commit();
}

}  // namespace

TEST(H5md, RoundTripOfParametersObservablesAndMetadata) {
  const TempDir dir;
  const std::string path = dir.file("out.h5");
  write_example(path);
  ASSERT_TRUE(fs::exists(path));
  EXPECT_TRUE(dir.temporaries().empty());

  EXPECT_EQ(read_attribute(path, "/h5md", "version"), ParameterValue(std::vector<long long>{1, 1}));
  EXPECT_EQ(read_string_attribute(path, "/h5md/author", "name"), "A. Uthor");
  EXPECT_EQ(read_string_attribute(path, "/h5md/creator", "name"), "granular-dsmc");
  EXPECT_EQ(read_string_attribute(path, "/h5md/creator", "version"), "0.1.0");

  for (const Parameter& p : every_kind_of_parameter())
    EXPECT_EQ(read_attribute(path, "/parameters/" + p.group, p.name), p.value)
        << p.group << "/" << p.name;
  EXPECT_EQ(read_string_attribute(path, "/parameters", "namelist"), namelist_text);
  EXPECT_DOUBLE_EQ(read_double_attribute(path, "/parameters/system", "alpha"), 0.9);
  EXPECT_DOUBLE_EQ(read_double_attribute(path, "/parameters/system", "species"), 2.0);

  const Series t = temperature_series();
  const ObservableData temperature = read_observable(path, "temperature");
  EXPECT_EQ(temperature.shape, (std::vector<std::size_t>{3, 2}));
  EXPECT_EQ(temperature.time, t.time);
  EXPECT_EQ(temperature.step, t.step);
  EXPECT_EQ(temperature.value, t.value);
  EXPECT_EQ(temperature.error, t.error);

  const Series total = total_temperature_series();
  const ObservableData total_read = read_observable(path, "total_temperature");
  EXPECT_EQ(total_read.shape, (std::vector<std::size_t>{4}));
  EXPECT_EQ(total_read.time, total.time);
  EXPECT_EQ(total_read.step, total.step);
  EXPECT_EQ(total_read.value, total.value);
  EXPECT_EQ(total_read.error, total.error);

  const ObservableData histogram = read_observable(path, "histogram/species_1");
  EXPECT_EQ(histogram.shape, (std::vector<std::size_t>{1, 3}));
  EXPECT_EQ(histogram.value, (std::vector<double>{0.1, 0.2, 0.3}));
  EXPECT_TRUE(histogram.error.empty());

  const ArrayData edges = read_dataset(path, "/observables/histogram/edges");
  EXPECT_EQ(edges.shape, (std::vector<std::size_t>{4}));
  EXPECT_EQ(edges.data, (std::vector<double>{0.0, 1.0, 2.0, 3.0}));
  const ArrayData matrix = read_dataset(path, "/extra/matrix");
  EXPECT_EQ(matrix.shape, (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(matrix.data, (std::vector<double>{1, 2, 3, 4, 5, 6}));

  EXPECT_EQ(read_string_attribute(path, "/observables/temperature", "unit"), "energy");
  EXPECT_DOUBLE_EQ(read_double_attribute(path, "/observables/temperature/value", "scale"), 2.5);
}

TEST(H5md, TemporaryFileUntilCommit) {
  const TempDir dir;
  const std::string path = dir.file("out.h5");
  Writer writer(path, "me", "granular-dsmc", "0.1.0");
  EXPECT_EQ(writer.temporary_path(), path + ".tmp." + std::to_string(::getpid()));
  EXPECT_TRUE(fs::exists(writer.temporary_path()));
  EXPECT_FALSE(fs::exists(path));
  writer.commit();
  EXPECT_TRUE(fs::exists(path));
  EXPECT_FALSE(fs::exists(writer.temporary_path()));
}

// A Writer removes the temporaries of its path left by processes that are gone, a zombie (killed, not
// yet collected by its parent: it still answers kill(pid, 0)) among them, and keeps a live process's;
// remove_others_temporaries (for the lock's holder) removes the live one too, and nothing of other paths.
TEST(H5md, TemporariesOfGoneProcessesAreRemoved) {
  const TempDir dir;
  const std::string path = dir.file("out.h5");
  const pid_t zombie = ::fork();
  if (zombie == 0) ::_exit(0);
  ASSERT_GT(zombie, 0);
  siginfo_t exited{};
  ASSERT_EQ(::waitid(P_PID, static_cast<id_t>(zombie), &exited, WEXITED | WNOWAIT), 0);  // (a zombie until waited for)
  const std::string of_zombie = path + ".tmp." + std::to_string(zombie), of_live = path + ".tmp.1";
  const std::string not_a_pid = path + ".tmp.1x", other_path = dir.file("other.h5") + ".tmp.4194300";
  for (const std::string& f : {of_zombie, of_live, not_a_pid, other_path}) std::ofstream(f) << "left";
  {
    Writer writer(path, "me", "granular-dsmc", "0.1.0");
    EXPECT_FALSE(fs::exists(of_zombie));
    EXPECT_TRUE(fs::exists(of_live));
  }
  ::waitpid(zombie, nullptr, 0);
  remove_others_temporaries(path);
  EXPECT_FALSE(fs::exists(of_live));
  EXPECT_TRUE(fs::exists(not_a_pid));
  EXPECT_TRUE(fs::exists(other_path));
}

// A link planted at the temporary's name (a symlink attack, or a leftover) is removed, never written
// through: its target keeps its content and the output is a regular file of its own.
TEST(H5md, ALinkAtTheTemporaryNameIsNotFollowed) {
  const TempDir dir;
  const std::string path = dir.file("out.h5"), victim = dir.file("victim.txt");
  std::ofstream(victim) << "precious";
  fs::create_symlink(victim, path + ".tmp." + std::to_string(::getpid()));
  Writer writer(path, "me", "granular-dsmc", "0.1.0");
  EXPECT_FALSE(fs::is_symlink(writer.temporary_path()));
  writer.commit();
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(path)));
  std::ifstream in(victim);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "precious");
}

// A file that appears at the final path during the run and is not this creator's stays; the complete
// new file is kept beside it under a name that says so. An earlier file of the creator, and anything
// with replace_any_file(), is replaced.
TEST(H5md, AFileThatAppearedDuringTheRunIsNotReplaced) {
  const TempDir dir;
  const std::string path = dir.file("out.h5");
  {
    Writer writer(path, "me", "granular-dsmc", "0.1.0");
    std::ofstream(path) << "the user's";
    try {
      writer.commit();
      ADD_FAILURE() << "commit replaced a file that is not granular-dsmc's";
    } catch (const std::runtime_error& e) {
      const std::string kept = dir.file("out.kept-" + std::to_string(::getpid()) + ".h5");
      EXPECT_NE(std::string(e.what()).find("the complete output is in '" + kept + "'"), std::string::npos) << e.what();
      EXPECT_TRUE(written_by(kept, "granular-dsmc"));
    }
  }
  std::ifstream in(path);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "the user's");
  EXPECT_FALSE(written_by(path, "granular-dsmc"));
  {
    Writer writer(path, "me", "granular-dsmc", "0.1.0");
    writer.replace_any_file();
    writer.commit();
  }
  EXPECT_TRUE(written_by(path, "granular-dsmc"));
  EXPECT_FALSE(written_by(path, "granular-dsmc checkpoint"));
  Writer again(path, "me", "granular-dsmc", "0.1.0");  // its own earlier file: replaced
  again.commit();
  EXPECT_TRUE(written_by(path, "granular-dsmc"));
}

TEST(H5md, DestructionWithoutCommitLeavesNothing) {
  const TempDir dir;
  const std::string path = dir.file("out.h5");
  std::string temporary;
  {
    Writer writer(path, "me", "granular-dsmc", "0.1.0");
    writer.write_parameters(every_kind_of_parameter(), namelist_text);
    writer.write_observable("temperature", temperature_series());
    temporary = writer.temporary_path();
    ASSERT_TRUE(fs::exists(temporary));
  }
  EXPECT_FALSE(fs::exists(temporary));
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(H5md, ExceptionDuringWritingLeavesNothing) {
  const TempDir dir;
  const std::string path = dir.file("out.h5");
  try {
    Writer writer(path, "me", "granular-dsmc", "0.1.0");
    writer.write_observable("temperature", temperature_series());
    writer.write_observable("temperature", temperature_series());  // already there
    FAIL() << "a second observable of the same name must be refused";
  } catch (const std::runtime_error& error) {
    const std::string message = error.what();
    EXPECT_TRUE(contains(message, "cannot write output file '" + path + "'")) << message;
    EXPECT_TRUE(contains(message, "H5Dcreate2")) << message;
    EXPECT_TRUE(contains(message, "/observables/temperature/step")) << message;
  }
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(H5md, DuplicateParameterIsAnError) {
  const TempDir dir;
  const std::string path = dir.file("out.h5");
  Writer writer(path, "me", "granular-dsmc", "0.1.0");
  const std::string message = runtime_error_message([&] {
    writer.write_parameters({{"system", "alpha", 0.9}, {"system", "alpha", 0.8}}, "");
  });
  EXPECT_TRUE(contains(message, "/parameters/system@alpha")) << message;
  EXPECT_THROW(writer.write_parameters({{"", "alpha", 0.9}}, ""), std::invalid_argument);
  EXPECT_THROW(writer.write_parameters({{"a/b", "alpha", 0.9}}, ""), std::invalid_argument);
}

TEST(H5md, WriteAttributeReplacesAndNeedsAnExistingObject) {
  const TempDir dir;
  const std::string path = dir.file("out.h5");
  {
    Writer writer(path, "me", "granular-dsmc", "0.1.0");
    writer.write_observable("temperature", total_temperature_series());
    writer.write_attribute("/observables/temperature", "unit", "energy");
    writer.write_attribute("/observables/temperature", "unit", std::string("kT"));
    const std::string message =
        runtime_error_message([&] { writer.write_attribute("/observables/nothing", "unit", 1LL); });
    EXPECT_TRUE(contains(message, "/observables/nothing")) << message;
    writer.commit();
  }
  EXPECT_EQ(read_string_attribute(path, "/observables/temperature", "unit"), "kT");
}

TEST(H5md, InconsistentArgumentsAreRejected) {
  const TempDir dir;
  Writer writer(dir.file("out.h5"), "me", "granular-dsmc", "0.1.0");
  Series s = temperature_series();
  s.step.pop_back();
  EXPECT_THROW(writer.write_observable("a", s), std::invalid_argument);
  s = temperature_series();
  s.columns = 3;
  EXPECT_THROW(writer.write_observable("a", s), std::invalid_argument);
  s = temperature_series();
  s.error.pop_back();
  EXPECT_THROW(writer.write_observable("a", s), std::invalid_argument);
  s = temperature_series();
  s.columns = 0;
  EXPECT_THROW(writer.write_observable("a", s), std::invalid_argument);
  EXPECT_THROW(writer.write_observable("/", temperature_series()), std::invalid_argument);
  EXPECT_THROW(writer.write_dataset("/edges", {1.0, 2.0}, {3}), std::invalid_argument);
  writer.commit();
  EXPECT_THROW(writer.write_observable("b", temperature_series()), std::logic_error);
  EXPECT_THROW(writer.commit(), std::logic_error);
}

// A series whose datasets do not make one time series (an error dataset of another length, as a hand-edited or
// damaged file may hold) is NotAsWritten, not "not measured" and not read past its end (--table printed
// memory beyond a 1-element error, and crashed on an empty value).
TEST(H5md, ASeriesNotAsWrittenIsSaidSo) {
  const TempDir dir;
  const std::string path = dir.file("out.h5");
  {
    Writer writer(path, "me", "granular-dsmc", "0.1.0");
    writer.write_observable("temperature", temperature_series());
    writer.commit();
  }
  EXPECT_EQ(read_observable(path, "temperature").error.size(), 6u);
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  ASSERT_GE(H5Ldelete(file, "/observables/temperature/error", H5P_DEFAULT), 0);
  const hsize_t one = 1;
  const hid_t space = H5Screate_simple(1, &one, nullptr);
  const hid_t set = H5Dcreate2(file, "/observables/temperature/error", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT,
                               H5P_DEFAULT, H5P_DEFAULT);
  const double x = 0.5;
  EXPECT_GE(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &x), 0);
  H5Dclose(set), H5Sclose(space), H5Fclose(file);
  try {
    read_observable(path, "temperature");
    ADD_FAILURE() << "read";
  } catch (const NotAsWritten& e) {
    EXPECT_NE(std::string(e.what()).find("/observables/temperature is not a time series as granular-dsmc writes it: 3 "
                                         "times, 3 steps, a value of 2 dimensions and 3 rows, 1 errors for 6 values"),
              std::string::npos) << e.what();
  }
}

TEST(H5md, EmptySeriesRoundTrip) {
  const TempDir dir;
  const std::string path = dir.file("out.h5");
  {
    Writer writer(path, "me", "granular-dsmc", "0.1.0");
    Series empty;
    empty.columns = 2;
    writer.write_observable("msd", empty);
    writer.commit();
  }
  const ObservableData msd = read_observable(path, "msd");
  EXPECT_EQ(msd.shape, (std::vector<std::size_t>{0, 2}));
  EXPECT_TRUE(msd.time.empty());
  EXPECT_TRUE(msd.value.empty());
}

TEST(H5md, NonexistentDirectoryThrowsWithPath) {
  const TempDir dir;
  const std::string path = dir.file("missing/out.h5");
  const std::string message =
      runtime_error_message([&] { Writer writer(path, "me", "granular-dsmc", "0.1.0"); });
  EXPECT_TRUE(contains(message, "cannot write output file '" + path + "'")) << message;
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(H5md, ReadOnlyDirectoryThrowsWithPath) {
  const TempDir dir;
  const fs::path read_only = dir.path() / "read-only";
  fs::create_directory(read_only);
  fs::permissions(read_only, fs::perms::owner_read | fs::perms::owner_exec,
                  fs::perm_options::replace);
  {
    std::ofstream probe(read_only / "probe");
    if (probe) {
      probe.close();
      fs::remove(read_only / "probe");
      GTEST_SKIP() << "this user (root?) can write into a read-only directory";
    }
  }
  const std::string path = (read_only / "out.h5").string();
  const std::string message =
      runtime_error_message([&] { Writer writer(path, "me", "granular-dsmc", "0.1.0"); });
  EXPECT_TRUE(contains(message, "cannot write output file '" + path + "'")) << message;
  EXPECT_TRUE(fs::is_empty(read_only));
}

// A hard link to the old file keeps the old inode: if commit rewrote the file in place, the link
// would show the new content; with rename it still shows the old one.
TEST(H5md, CommitReplacesExistingFileAtomically) {
  const TempDir dir;
  const std::string path = dir.file("out.h5");
  write_example(path, "old author");
  fs::create_hard_link(path, dir.file("old-link.h5"));

  Writer writer(path, "new author", "granular-dsmc", "0.1.0");
  writer.write_observable("total_temperature", total_temperature_series());
  EXPECT_EQ(read_string_attribute(path, "/h5md/author", "name"), "old author");
  writer.commit();

  EXPECT_EQ(read_string_attribute(path, "/h5md/author", "name"), "new author");
  EXPECT_THROW(read_observable(path, "temperature"), std::runtime_error);
  EXPECT_EQ(read_string_attribute(dir.file("old-link.h5"), "/h5md/author", "name"), "old author");
  EXPECT_TRUE(dir.temporaries().empty());
}

TEST(H5md, ReadErrorsNameTheFile) {
  const TempDir dir;
  const std::string path = dir.file("out.h5");
  write_example(path);
  const std::string missing = dir.file("missing.h5");
  EXPECT_TRUE(contains(runtime_error_message([&] { read_observable(missing, "temperature"); }),
                       missing));
  std::string message = runtime_error_message([&] { read_observable(path, "pressure"); });
  EXPECT_TRUE(contains(message, "cannot read output file '" + path + "'")) << message;
  EXPECT_TRUE(contains(message, "/observables/pressure")) << message;
  message = runtime_error_message([&] { read_double_attribute(path, "/h5md/author", "name"); });
  EXPECT_TRUE(contains(message, "/h5md/author@name")) << message;
  message =
      runtime_error_message([&] { read_string_attribute(path, "/parameters/system", "alpha"); });
  EXPECT_TRUE(contains(message, "/parameters/system@alpha")) << message;
}

// HDF5 would print its error stack to stderr on every failure; the module must keep it quiet and
// leave the program's own setting untouched.
TEST(H5md, HdfErrorStackIsNotPrintedAndSettingIsRestored) {
  const TempDir dir;
  const std::string not_hdf5 = dir.file("not.h5");
  std::ofstream(not_hdf5) << "not an HDF5 file\n";

  H5E_auto2_t function_before = nullptr;
  void* data_before = nullptr;
  ASSERT_GE(H5Eget_auto2(H5E_DEFAULT, &function_before, &data_before), 0);

  testing::internal::CaptureStderr();
  EXPECT_THROW(read_observable(not_hdf5, "temperature"), std::runtime_error);
  EXPECT_THROW(Writer(dir.file("missing/out.h5"), "me", "granular-dsmc", "0.1.0"),
               std::runtime_error);
  const std::string printed = testing::internal::GetCapturedStderr();
  EXPECT_EQ(printed, "");

  H5E_auto2_t function_after = nullptr;
  void* data_after = nullptr;
  ASSERT_GE(H5Eget_auto2(H5E_DEFAULT, &function_after, &data_after), 0);
  EXPECT_EQ(function_after, function_before);
  EXPECT_EQ(data_after, data_before);
}

TEST(H5md, H5dumpReadsTheHeader) {
  if (std::system("command -v h5dump > /dev/null 2>&1") != 0) GTEST_SKIP() << "h5dump not on PATH";
  const TempDir dir;
  const std::string path = dir.file("out.h5");
  write_example(path);
  const std::string listing = dir.file("header.txt");
  const std::string command = "h5dump -H '" + path + "' > '" + listing + "' 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::stringstream header;
  header << std::ifstream(listing).rdbuf();
  // Types external scripts rely on: UTF-8 strings for h5py's str, int32 version, int64 step.
  EXPECT_TRUE(contains(header.str(), "H5T_CSET_UTF8")) << header.str();
  EXPECT_TRUE(contains(header.str(), "H5T_STD_I32LE")) << header.str();
  EXPECT_TRUE(contains(header.str(), "H5T_STD_I64LE")) << header.str();
  EXPECT_TRUE(contains(header.str(), "GROUP \"observables\"")) << header.str();
}

// Every file and object the module opens must be closed again, on success and on the error
// paths. (HDF5 offers no count of dataspace, datatype or property list identifiers to applications;
// those are covered by the same RAII wrapper.)
TEST(H5md, NoHdf5FilesOrObjectsLeftOpen) {
  const TempDir dir;
  const std::string path = dir.file("out.h5");
  // Relative to what is open already, so a leak elsewhere in unit_tests is not blamed on us.
  const ssize_t baseline = H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL);
  ASSERT_GE(baseline, 0);
  auto open_count = [&] { return H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL) - baseline; };

  write_example(path);
  read_observable(path, "temperature");
  read_dataset(path, "/extra/matrix");
  for (const Parameter& p : every_kind_of_parameter())
    read_attribute(path, "/parameters/" + p.group, p.name);
  EXPECT_THROW(read_observable(path, "pressure"), std::runtime_error);
  EXPECT_THROW(read_double_attribute(path, "/h5md/author", "name"), std::runtime_error);
  EXPECT_EQ(open_count(), 0);
  {
    Writer writer(path, "me", "granular-dsmc", "0.1.0");
    writer.write_observable("temperature", temperature_series());
    EXPECT_THROW(writer.write_observable("temperature", temperature_series()), std::runtime_error);
    EXPECT_THROW(writer.write_attribute("/nothing", "unit", "energy"), std::runtime_error);
    EXPECT_EQ(open_count(), 1);  // the temporary file itself, nothing in it
  }
  EXPECT_EQ(open_count(), 0);
}

// ---- Units (H5MD's units module, \ref output_units "docs/output.md") ----

namespace {

/// The dimensions of attribute `name` of `object` (empty: a scalar).
std::vector<hsize_t> attribute_dims(const std::string& file, const std::string& object, const char* name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t a = H5Aopen_by_name(f, object.c_str(), name, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t space = H5Aget_space(a);
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(0, H5Sget_simple_extent_ndims(space))));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  H5Aclose(a);
  H5Fclose(f);
  return dims;
}

/// The character set and whether the string attribute `name` of `object` is of variable length.
std::pair<H5T_cset_t, bool> string_kind(const std::string& file, const std::string& object, const char* name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t a = H5Aopen_by_name(f, object.c_str(), name, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t t = H5Aget_type(a);
  const std::pair<H5T_cset_t, bool> kind{H5Tget_cset(t), H5Tis_variable_str(t) > 0};
  H5Tclose(t);
  H5Aclose(a);
  H5Fclose(f);
  return kind;
}

}  // namespace

// /parameters arrays in their shape: a pair matrix (S, S), a sweep table (points, variables); the
// others as before (a scalar, 1-D lists). A shape that does not hold the value is refused.
TEST(H5md, ParametersAreWrittenInTheirShape) {
  const TempDir dir;
  const std::string path = dir.file("out.h5");
  write_example(path);
  EXPECT_EQ(attribute_dims(path, "/parameters/system", "restitution"), (std::vector<hsize_t>{2, 2}));
  EXPECT_EQ(attribute_dims(path, "/parameters/sweep", "values"), (std::vector<hsize_t>{3, 2}));
  EXPECT_EQ(attribute_dims(path, "/parameters/system", "masses"), (std::vector<hsize_t>{2}));
  EXPECT_EQ(attribute_dims(path, "/parameters/system", "alpha"), (std::vector<hsize_t>{}));
  for (const Parameter& bad : {Parameter{"system", "restitution", std::vector<double>{0.9, 0.8, 0.8}, {2, 2}},
                               Parameter{"system", "alpha", 0.9, {1}}}) {
    Writer w(dir.file("bad.h5"), "A. Uthor", "granular-dsmc", "0.1.0");
    EXPECT_THROW(w.write_parameters({bad}, namelist_text), std::invalid_argument) << bad.name;
  }
}

TEST(H5md, UnitStringGrammar) {
  for (const char* good : {"1", "nm+3", "um+2 s-1", "60 s", "10+3 m", "0.5 m", "energy length-3 time", "length+2"})
    EXPECT_TRUE(is_unit_string(good)) << good;
  for (const char* bad : {"", " m", "m ", "m  s", "m+", "m+0", "m-01", "m2", "s 60", "60 2 s", "m^2", "m/s", "1.",
                          ".5", "m m", "m s m-1", "\xc3\x85"})
    EXPECT_FALSE(is_unit_string(bad)) << bad;
}

TEST(H5md, UnitsModuleAndUnitAttributes) {
  const TempDir dir;
  const std::string path = dir.file("units.h5");
  {
    Writer w(path, "A. Uthor", "granular-dsmc", "0.1.0");
    w.declare_units_module("namelist");
    Series s;
    s.time = {0.0, 1.0};
    s.step = {0, 10};
    s.value = {1.0, 0.5};
    s.error = {0.1, 0.1};
    s.time_unit = "time";
    s.value_unit = "energy";
    w.write_observable("temperature", s);
    Series plain = s;  // no units: no attributes
    plain.time_unit.clear();
    plain.value_unit.clear();
    w.write_observable("plain", plain);
    w.write_dataset("/observables/edges", {0.0, 1.0, 2.0}, {});
    w.write_unit("/observables/edges", "1");
    w.write_unit("/observables/edges", "length-1");  // replaces
    EXPECT_THROW(w.write_unit("/observables/edges", "m/s"), std::invalid_argument);
    Series bad = s;
    bad.time_unit = "s s";
    EXPECT_THROW(w.write_observable("bad", bad), std::invalid_argument);
    w.commit();
  }
  EXPECT_EQ(read_attribute(path, "/h5md/modules/units", "version"), ParameterValue(std::vector<long long>{1, 0}));
  EXPECT_EQ(read_string_attribute(path, "/h5md/modules/units", "system"), "namelist");
  EXPECT_EQ(read_string_attribute(path, "/observables/temperature/time", "unit"), "time");
  EXPECT_EQ(read_string_attribute(path, "/observables/temperature/value", "unit"), "energy");
  EXPECT_EQ(read_string_attribute(path, "/observables/temperature/error", "unit"), "energy");
  EXPECT_EQ(read_string_attribute(path, "/observables/edges", "unit"), "length-1");
  EXPECT_THROW(read_string_attribute(path, "/observables/temperature/step", "unit"), std::runtime_error);
  EXPECT_THROW(read_string_attribute(path, "/observables/plain/value", "unit"), std::runtime_error);
  EXPECT_THROW(read_observable(path, "bad"), std::runtime_error);  // rejected before anything was written
  // The module's form: a scalar variable-length string of the ASCII character set.
  EXPECT_EQ(string_kind(path, "/observables/temperature/value", "unit"), std::make_pair(H5T_CSET_ASCII, true));
  EXPECT_TRUE(string_kind(path, "/h5md/modules/units", "system").second);
}
