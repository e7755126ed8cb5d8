/**
 * \file h5md.hpp
 * \brief The output file of granular-dsmc: an H5MD 1.1 file (https://www.nongnu.org/h5md/) with
 *        the resolved input and the time series of the observables, plus readers for tests and
 *        validation.
 *
 * Layout (the contract with external scripts, \ref output_h5md "docs/output.md"):
 * \verbatim
 * /
 * +-- h5md                              +-- version: int32 [2] = {1, 1}
 * |   +-- author                        +-- name: string
 * |   +-- creator                       +-- name: string, +-- version: string
 * |   \-- modules/units                 +-- version: int32 [2] = {1, 0}, +-- system: string
 * |                                         (only when declare_units_module() was called)
 * +-- parameters                        +-- namelist: string (the input file as given)
 * |   +-- system                        +-- <variable>: one attribute per resolved variable
 * |   \-- <namelist group> ...              (defaults included)
 * \-- observables
 *     +-- temperature                   (H5MD time-dependent data element)
 *     |   +-- step: int64 [Nt]
 *     |   +-- time: float64 [Nt]        +-- unit: string (Series::time_unit, when given)
 *     |   +-- value: float64 [Nt] or [Nt][S]  +-- unit (Series::value_unit, when given)
 *     |   \-- error: float64, shape of value (only when there are several replicas), +-- unit
 *     +-- histogram
 *     |   \-- species_1 ...             (names may nest: "histogram/species_1")
 *     \-- ...
 * \endverbatim
 * The first dimension of step, time and value is extensible (H5S_UNLIMITED), which is what H5MD
 * means by "[variable]"; the datasets are written in one piece all the same. `step` holds an integer
 * step of the simulation (granular-dsmc: the cumulative collision events of a replica, the mean over
 * replicas rounded; run/simulation.cpp), `time` the simulation time.
 * A sweep point /sweep/point_K is an H5MD root of its own (the specification allows the root of the
 * H5MD structure to be any group): /sweep/point_K/h5md is a hard link to /h5md, beside its
 * observables. Checked against the specification by tests/h5md_spec_test.cpp.
 *
 * Units (H5MD's units module 1.0, \ref output_units "docs/output.md"): declare_units_module() declares
 * the module and its unit system; a `unit` attribute (Series::time_unit and Series::value_unit, or
 * write_unit() for a time-independent dataset) is a scalar variable-length ASCII string whose text
 * follows the module's grammar (is_unit_string()); an invalid one throws std::invalid_argument.
 *
 * Attribute types: strings are variable-length UTF-8 (h5py returns them as str); logicals are
 * 8-bit signed integers 0/1, because HDF5 has no boolean class and a plain integer reads the same
 * in every tool (h5py's bool is an enum convention other readers do not share); integers are
 * int64, reals float64; vectors are 1-D attributes, scalars have a scalar dataspace, so a
 * one-element vector and a scalar stay distinguishable.
 *
 * Atomic write guarantee: everything goes to `<final path>.tmp.<pid>` in the same directory, and
 * only Writer::commit() renames it onto the final path (rename(2) within one filesystem is atomic,
 * and the data are fsync'ed first). A reader therefore sees either the previous file or the
 * complete new one, never a truncated one. A Writer destroyed without commit (an exception, a
 * failed run) deletes its temporary file, so a failed run leaves no half-written output behind;
 * only a killed process can leave a `.tmp.<pid>` file, and never under the final name; the next Writer of
 * that path removes it when its process is gone (remove_others_temporaries() whatever the process). The temporary
 * is created exclusively and not through a link (O_EXCL | O_NOFOLLOW): a link planted at its name is
 * removed, never written through. Just before the rename the final path is looked at again: a file
 * that is not this creator's (written_by()) and appeared there during the run is not replaced (unless
 * replace_any_file()); the new file is then kept beside it as `<stem>.kept-<pid>.h5` and named in the
 * exception.
 *
 * Errors: every HDF5 call is checked; a failure throws std::runtime_error naming the output file,
 * the HDF5 call, the object, and HDF5's own description. HDF5's automatic printing of its error
 * stack is switched off while a function of this module runs and restored afterwards, so other
 * HDF5 users in the program keep their setting. Inconsistent arguments (e.g. a Series whose sizes
 * disagree) throw std::invalid_argument; using a Writer after commit() throws std::logic_error.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace gdsmc::io::h5md {

/// Value of one resolved namelist variable, or of any attribute this module writes or reads.
using ParameterValue = std::variant<bool, long long, double, std::string, std::vector<long long>,
                                    std::vector<double>, std::vector<std::string>>;

/// One resolved namelist variable; group = namelist group name, e.g. "system".
struct Parameter {
  std::string group;     ///< namelist group, e.g. "system"
  std::string name;      ///< variable name
  ParameterValue value;  ///< its resolved value
  /// Shape of an array value (row-major), e.g. {S, S} for a pair matrix; empty: a scalar, or 1-D of
  /// the value's length. The product must equal the value's length.
  std::vector<std::size_t> shape = {};
};

/// One time series: value is row-major [time][column]; columns = 1 writes a 1-D dataset of shape
/// (Nt), else (Nt, columns). time and step have Nt entries, value Nt * columns.
struct Series {
  std::vector<double> time;      ///< sample times (Nt)
  std::vector<long long> step;   ///< H5MD step of each sample (Nt)
  std::vector<double> value;     ///< row-major [time][column]
  std::size_t columns = 1;       ///< 1: a 1-D dataset
  std::vector<double> error;  ///< empty = no error dataset; else same size as value
  /// The `unit` attribute of `time` (H5MD units module); empty = none. Must pass is_unit_string().
  std::string time_unit;
  /// The `unit` attribute of `value`, and of `error` (the same quantity); empty = none.
  std::string value_unit;
};

/// Version {major, minor} of H5MD's units module that declare_units_module() declares.
inline constexpr int kUnitsModuleVersion[2] = {1, 0};

/// Whether `unit` is a unit string of H5MD's units module (\ref output_units "docs/output.md"):
/// unit factors separated by one space each; a factor is a number (an integer or a decimal
/// fraction) or a unit symbol (letters), either optionally followed by a signed non-zero integer
/// power ("m+2", "s-1", "10+3"); at most one number, and only as the first factor; no symbol twice.
/// "1" (a single number) is the unit of a dimensionless quantity.
bool is_unit_string(const std::string& unit);

/// Call first in main, before any other function of this module: HDF5 then does not run its own
/// shutdown at exit. HDF5 1.10 segfaults there after a file failed to close (a write error: a full
/// disk, a file size limit), and there is nothing for it to do otherwise: every file this module
/// opens it closes itself (and a temporary file that failed is removed).
void skip_library_shutdown();

/// Writes one H5MD file through a temporary file; see the file comment for the guarantees.
class Writer {
 public:
  /// Creates `<final_path>.tmp.<pid>` and writes /h5md. Throws std::runtime_error("cannot write
  /// output file '<final_path>': <reason>") if the temporary file cannot be created.
  Writer(std::string final_path, std::string author, std::string creator_name,
         std::string creator_version);
  /// Without a successful commit(): closes and removes the temporary file.
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  /// `/parameters/GROUP@NAME` for every parameter (in its shape) and `/parameters@namelist` =
  /// namelist_text. A group name must be non-empty and free of '/'; a duplicate (group, name) or a
  /// shape that does not hold the value is an error.
  void write_parameters(const std::vector<Parameter>& parameters, const std::string& namelist_text);

  /// `/observables/NAME/{step,time,value[,error]}`; `name` may contain '/' for nested groups.
  /// A `name` starting with '/' is an absolute path instead (points of a sweep). The units of the
  /// series (when given) become the `unit` attributes of time, value and error.
  void write_observable(const std::string& name, const Series& series);

  /// Declares H5MD's units module: group `/h5md/modules/units` with `version` int32[2] =
  /// kUnitsModuleVersion and `system` (scalar variable-length string) naming the unit system of
  /// every `unit` attribute of the file. Further attributes of the module group (the meaning of the
  /// system's symbols) can be added with write_attribute().
  void declare_units_module(const std::string& system);

  /// Attaches (or replaces) the `unit` attribute of the existing dataset `dataset_path`: a scalar
  /// variable-length ASCII string, as the units module prescribes. Throws std::invalid_argument
  /// if `unit` is not a unit string (is_unit_string()).
  void write_unit(const std::string& dataset_path, const std::string& unit);

  /// Attaches (or replaces) attribute `name` on the existing group or dataset `object_path`.
  void write_attribute(const std::string& object_path, const std::string& name,
                       const ParameterValue& value);
  /// Keeps a string literal a string also with standard libraries older than P0608/P1957, where
  /// "energy" converts to the variant's bool.
  void write_attribute(const std::string& object_path, const std::string& name, const char* value) {
    write_attribute(object_path, name, ParameterValue(std::string(value)));
  }

  /// A second name `link_path` (absolute; parents created) for the existing object `target` (an HDF5
  /// hard link: one object, two paths), e.g. /sweep/point_K/h5md for /h5md.
  void write_hard_link(const std::string& target, const std::string& link_path);
  /// Group at absolute `path` (and its parents), if it does not exist yet.
  void write_group(const std::string& path);

  /// Plain float64 dataset at absolute `path`, creating intermediate groups. An empty shape means
  /// 1-D of data.size(); otherwise the product of shape must equal data.size().
  void write_dataset(const std::string& path, const std::vector<double>& data,
                     std::vector<std::size_t> shape);

  /// Plain uint64 dataset (exact integers: generator states, counters), as write_dataset above.
  void write_integers(const std::string& path, const std::vector<std::uint64_t>& data);
  /// Plain int64 dataset (H5MD's species and step), as write_dataset above, 1-D.
  void write_integers(const std::string& path, const std::vector<std::int64_t>& data);

  /// Flushes, closes, fsyncs and renames the temporary file onto the final path. If the rename
  /// itself fails, the complete temporary file is kept (and named in the exception), because it
  /// holds a finished run. A file at the final path that is not written_by() this creator is not
  /// replaced (header): the new one is kept as `<stem>.kept-<pid>.h5` and std::runtime_error names both.
  void commit();
  /// commit() replaces whatever is at the final path (granular-dsmc --force).
  void replace_any_file();

  /// The file written until commit(): `<final path>.tmp.<pid>`.
  const std::string& temporary_path() const;
  /// The output file as requested.
  const std::string& final_path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// ---- Reading back (tests, validation programs). All throw std::runtime_error("cannot read output
// ---- file '<file>': ...") on failure, including a type that does not fit the request.

/// One observable as read back.
struct ObservableData {
  std::vector<double> time;               ///< sample times
  std::vector<double> value;              ///< row-major, shape as below
  std::vector<double> error;              ///< empty if the file has no error dataset
  std::vector<std::size_t> shape;         ///< shape of value: {Nt} or {Nt, S}
  std::vector<long long> step;            ///< H5MD step of each sample
};
/// A file's dataset is there but not as granular-dsmc writes it (a damaged or hand-edited file): unlike a
/// missing one, not to be taken for "not measured".
struct NotAsWritten : std::runtime_error {
  using std::runtime_error::runtime_error;
};
/// `name` as for Writer::write_observable: relative to /observables, or an absolute path. Throws NotAsWritten
/// when its time, step, value and error do not make one time series (rows of value = times = steps, error
/// as value).
ObservableData read_observable(const std::string& file, const std::string& name);

/// A float64 (or any numeric) dataset, flattened row-major, with its shape.
struct ArrayData {
  std::vector<double> data;        ///< the values, row-major
  std::vector<std::size_t> shape;  ///< the dataset's dimensions
};
/// The dataset at `path` of `file`.
ArrayData read_dataset(const std::string& file, const std::string& path);
/// The dataset at `path` of `file`, or nothing when its group has no such link (a dataset left out,
/// as a standard error of one replica is).
std::optional<ArrayData> read_dataset_if_present(const std::string& file, const std::string& path);
/// A uint64 dataset written by Writer::write_integers, flattened.
std::vector<std::uint64_t> read_integers(const std::string& file, const std::string& path);

/// Reads any attribute this module writes (and fixed-length strings, int32, ...): integer class of
/// size 1 with scalar dataspace -> bool, other integers -> long long, floats -> double, strings ->
/// std::string; an array dataspace gives the vector alternative (flattened, row-major, for the pair
/// matrices of /parameters).
ParameterValue read_attribute(const std::string& file, const std::string& object_path,
                              const std::string& name);
/// Removes every `<path>.tmp.<pid>` file of another process, alive or not: for the holder of the lock that
/// keeps other runs off `path` (file_lock.hpp), to whom any such file is what a killed run left (its
/// process id possibly reused since, or of another node). A Writer removes only those of processes no
/// longer alive.
void remove_others_temporaries(const std::string& path);
/// Whether `path` is a regular HDF5 file whose `/h5md/creator@name` is `creator` (an earlier output of
/// the program that may replace it); false for anything else, without opening a FIFO or a device.
bool written_by(const std::string& path, const std::string& creator);

/// Whether the object at `object_path` of `file` has an attribute `name` (a missing object or an unreadable
/// file throws, as read_attribute).
bool has_attribute(const std::string& file, const std::string& object_path, const std::string& name);
/// A string attribute (read_attribute holding a std::string; anything else throws).
std::string read_string_attribute(const std::string& file, const std::string& object_path,
                                  const std::string& name);
/// Any scalar (or one-element) numeric attribute, converted to double.
double read_double_attribute(const std::string& file, const std::string& object_path,
                             const std::string& name);

}  // namespace gdsmc::io::h5md
