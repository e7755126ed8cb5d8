// H5MD 1.1 output through the HDF5 C API; layout and guarantees are described in h5md.hpp.
#include "io/h5md.hpp"

#include <hdf5.h>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <utility>

namespace gdsmc::io::h5md {
namespace {

namespace fs = std::filesystem;

static_assert(sizeof(long long) == 8, "the int64 datasets are read and written as long long");

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// C++20 deduces this for aggregates, but clang 14 does not implement that (P1816): the guide keeps
// the code building with both compilers.
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

/// Keeps HDF5 from printing its error stack to stderr while a function of this module runs: the
/// module reports errors itself, by exception. The previous handler is restored so that the rest
/// of the program keeps whatever setting it chose.
class ErrorSilencer {
 public:
  ErrorSilencer() {
    if (H5Eget_auto2(H5E_DEFAULT, &func_, &data_) >= 0)
      restore_ = H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0;
  }
  ~ErrorSilencer() {
    if (restore_) H5Eset_auto2(H5E_DEFAULT, func_, data_);
  }
  ErrorSilencer(const ErrorSilencer&) = delete;
  ErrorSilencer& operator=(const ErrorSilencer&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
  bool restore_ = false;
};

/// One entry of HDF5's error stack on one line. A failed system call is described over several
/// lines ("file write failed: time = ..., filename = ..., errno = 28, error message = 'No space left
/// on device', buf = ..."): only what failed and the system's message are kept.
std::string one_line(const std::string& description) {
  const std::size_t details = description.find(": time = ");
  const std::size_t quote = description.find("error message = '");
  if (details != std::string::npos && quote != std::string::npos) {
    const std::size_t begin = quote + 17, end = description.find('\'', begin);
    return description.substr(0, details) + ": " +
           description.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
  }
  std::string out = description;
  std::replace(out.begin(), out.end(), '\n', ' ');
  return out;
}

/// HDF5's own explanation of the last failure: the outermost entry of its error stack (what the API
/// function could not do) and the innermost one (why, often with errno and its text), on one line.
std::string hdf5_detail() {
  const hid_t stack = H5Eget_current_stack();  // takes the stack, so the next call starts clean
  if (stack < 0) return "no details from HDF5";
  std::vector<std::string> descriptions;
  H5Ewalk2(
      stack, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t* error, void* out) -> herr_t {
        if (error != nullptr && error->desc != nullptr)
          static_cast<std::vector<std::string>*>(out)->emplace_back(one_line(error->desc));
        return 0;
      },
      &descriptions);
  H5Eclose_stack(stack);
  if (descriptions.empty()) return "no details from HDF5";
  if (descriptions.size() == 1 || descriptions.front() == descriptions.back())
    return descriptions.front();
  return descriptions.front() + ": " + descriptions.back();
}

/// Throws without naming the file: the public functions add "cannot write/read output file '...'".
[[noreturn]] void fail(const char* call, const std::string& object) {
  throw std::runtime_error(std::string(call) + " failed for '" + object + "': " + hdf5_detail());
}

/// For herr_t and htri_t results (negative = failure); returns the value so htri_t stays usable.
int check(int status, const char* call, const std::string& object) {
  if (status < 0) fail(call, object);
  return status;
}

/// Owns one hid_t and closes it with the matching H5?close, so no exit path leaks an identifier.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept
      : id_(std::exchange(other.id_, invalid)), closer_(other.closer_) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, invalid);
      closer_ = other.closer_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  bool is_open() const { return id_ >= 0; }
  /// For the one place where a failing close matters: the file, before it is renamed.
  herr_t close() {
    const herr_t status = is_open() ? closer_(id_) : 0;
    id_ = invalid;
    return status;
  }
  void reset() noexcept {
    if (is_open()) closer_(id_);  // a destructor cannot report; the explicit paths use close()
    id_ = invalid;
  }

 private:
  static constexpr hid_t invalid = -1;
  hid_t id_ = invalid;
  Closer closer_ = nullptr;
};

Handle make(hid_t id, Handle::Closer closer, const char* call, const std::string& object) {
  if (id < 0) fail(call, object);
  return Handle(id, closer);
}

/// Runs `body` with HDF5's error printing off and prefixes a runtime_error with `context`.
/// Argument errors (std::logic_error) pass unchanged: they are the caller's bug, not the file's.
template <class Body>
auto with_context(const std::string& context, Body&& body) -> decltype(body()) {
  const ErrorSilencer silence;
  try {
    return body();
  } catch (const std::runtime_error& error) {
    throw std::runtime_error(context + ": " + error.what());
  }
}

std::string write_context(const std::string& path) {
  return "cannot write output file '" + path + "'";
}
std::string read_context(const std::string& path) {
  return "cannot read output file '" + path + "'";
}

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  while (begin <= path.size()) {
    const std::size_t end = std::min(path.find('/', begin), path.size());
    if (end > begin) parts.push_back(path.substr(begin, end - begin));
    begin = end + 1;
  }
  return parts;
}

std::string join_path(const std::vector<std::string>& parts, std::size_t count);

/// Where an observable lives: /observables/NAME, or NAME itself when it is an absolute path
/// (e.g. /sweep/point_1/observables/temperature for the points of a parameter sweep).
std::string observable_path(const std::string& name, const std::vector<std::string>& parts) {
  return (name.front() == '/' ? std::string() : std::string("/observables")) +
         join_path(parts, parts.size());
}

std::string join_path(const std::vector<std::string>& parts, std::size_t count) {
  std::string path;
  for (std::size_t i = 0; i < count; ++i) path += "/" + parts[i];
  return path.empty() ? "/" : path;
}

/// File access shared by writer and readers. The 1.8 format bounds give the superblock version 2
/// that H5MD recommends and dense attribute storage (so a long vector parameter cannot overflow the
/// 64 KiB object header), while keeping the file readable by HDF5 1.8. STRONG close degree makes
/// H5Fclose really close the file even if some object were still open, so the rename that follows
/// never moves a file HDF5 is still writing.
Handle file_access(const std::string& object) {
  Handle fapl = make(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate(H5P_FILE_ACCESS)", object);
  check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), "H5Pset_fclose_degree", object);
#if H5_VERSION_GE(1, 10, 2)
  check(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_V18), "H5Pset_libver_bounds",
        object);
#else
  check(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_LATEST, H5F_LIBVER_LATEST),
        "H5Pset_libver_bounds", object);
#endif
  return fapl;
}

Handle utf8_string_type(const std::string& object) {
  Handle type = make(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy(H5T_C_S1)", object);
  check(H5Tset_size(type.get(), H5T_VARIABLE), "H5Tset_size", object);
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset", object);
  return type;
}

void put_attribute(hid_t object, const std::string& where, const std::string& name, hid_t file_type,
                   hid_t memory_type, const hsize_t* dims, const void* data, int rank = 1);

/// The `unit` attribute of H5MD's units module: a scalar variable-length ASCII string.
void put_unit(hid_t dataset, const std::string& dataset_path, const std::string& unit) {
  const std::string where = dataset_path + "@unit";
  if (!is_unit_string(unit))
    throw std::invalid_argument("h5md: '" + unit + "' is not a unit string of H5MD's units module (" + where + ")");
  if (check(H5Aexists(dataset, "unit"), "H5Aexists", where) > 0)
    check(H5Adelete(dataset, "unit"), "H5Adelete", where);
  Handle type = make(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy(H5T_C_S1)", where);
  check(H5Tset_size(type.get(), H5T_VARIABLE), "H5Tset_size", where);
  check(H5Tset_cset(type.get(), H5T_CSET_ASCII), "H5Tset_cset", where);
  const char* text = unit.c_str();
  put_attribute(dataset, where, "unit", type.get(), type.get(), nullptr, &text);
}

/// Opens every group along `path`, creating the missing ones, and returns the last.
Handle ensure_group(hid_t file, const std::string& path) {
  const std::vector<std::string> parts = split_path(path);
  Handle group = make(H5Gopen2(file, "/", H5P_DEFAULT), H5Gclose, "H5Gopen2", "/");
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string where = join_path(parts, i + 1);
    const char* name = parts[i].c_str();
    if (check(H5Lexists(group.get(), name, H5P_DEFAULT), "H5Lexists", where) > 0)
      group = make(H5Gopen2(group.get(), name, H5P_DEFAULT), H5Gclose, "H5Gopen2", where);
    else {
      // No modification times in object headers: the same run gives the same bytes.
      Handle gcpl = make(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, "H5Pcreate(H5P_GROUP_CREATE)", where);
      check(H5Pset_obj_track_times(gcpl.get(), false), "H5Pset_obj_track_times", where);
      group = make(H5Gcreate2(group.get(), name, H5P_DEFAULT, gcpl.get(), H5P_DEFAULT), H5Gclose,
                   "H5Gcreate2", where);
    }
  }
  return group;
}

/// One attribute; `dims` = nullptr gives a scalar dataspace.
void put_attribute(hid_t object, const std::string& where, const std::string& name, hid_t file_type,
                   hid_t memory_type, const hsize_t* dims, const void* data, int rank) {
  Handle space =
      dims == nullptr
          ? make(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate", where)
          : make(H5Screate_simple(rank, dims, nullptr), H5Sclose, "H5Screate_simple", where);
  Handle attribute =
      make(H5Acreate2(object, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
           H5Aclose, "H5Acreate2", where);
  if (dims == nullptr || std::all_of(dims, dims + rank, [](hsize_t d) { return d > 0; }))
    check(H5Awrite(attribute.get(), memory_type, data), "H5Awrite", where);
}

/// `replace` = false makes a second value for the same name an error (a duplicate parameter is a
/// bug upstream that should not pass silently); true is for explicit annotations. A non-empty
/// `shape` writes an array value in that shape (row-major) instead of 1-D.
void put_value(hid_t object, const std::string& object_path, const std::string& name,
               const ParameterValue& value, bool replace, const std::vector<std::size_t>& shape = {}) {
  const std::string where = object_path + "@" + name;
  if (replace && check(H5Aexists(object, name.c_str()), "H5Aexists", where) > 0)
    check(H5Adelete(object, name.c_str()), "H5Adelete", where);
  const std::vector<hsize_t> dims(shape.begin(), shape.end());
  auto put = [&](hid_t file_type, hid_t memory_type, const hsize_t* length, const void* data) {
    if (length != nullptr && !dims.empty())
      put_attribute(object, where, name, file_type, memory_type, dims.data(), data, static_cast<int>(dims.size()));
    else
      put_attribute(object, where, name, file_type, memory_type, length, data);
  };
  std::visit(
      Overloaded{
          [&](bool v) {
            const std::int8_t flag = v ? 1 : 0;
            put(H5T_STD_I8LE, H5T_NATIVE_INT8, nullptr, &flag);
          },
          [&](long long v) { put(H5T_STD_I64LE, H5T_NATIVE_LLONG, nullptr, &v); },
          [&](double v) { put(H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, nullptr, &v); },
          [&](const std::string& v) {
            const Handle type = utf8_string_type(where);
            const char* text = v.c_str();
            put(type.get(), type.get(), nullptr, &text);
          },
          [&](const std::vector<long long>& v) {
            const hsize_t n = v.size();
            put(H5T_STD_I64LE, H5T_NATIVE_LLONG, &n, v.data());
          },
          [&](const std::vector<double>& v) {
            const hsize_t n = v.size();
            put(H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &n, v.data());
          },
          [&](const std::vector<std::string>& v) {
            const Handle type = utf8_string_type(where);
            std::vector<const char*> texts;
            texts.reserve(v.size());
            for (const std::string& s : v) texts.push_back(s.c_str());
            const hsize_t n = v.size();
            put(type.get(), type.get(), &n, texts.data());
          },
      },
      value);
}

/// `extensible` makes the first dimension H5S_UNLIMITED (H5MD's "[variable]"), which needs
/// chunked storage; chunks of about 256 KiB keep partial reads cheap without many tiny chunks.
void put_dataset(hid_t group, const std::string& group_path, const std::string& name,
                 hid_t file_type, hid_t memory_type, const std::vector<hsize_t>& dims,
                 bool extensible, const void* data) {
  const std::string where = (group_path == "/" ? "" : group_path) + "/" + name;
  const int rank = static_cast<int>(dims.size());
  std::vector<hsize_t> max_dims = dims;
  Handle dcpl = make(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "H5Pcreate(H5P_DATASET_CREATE)",
                     where);
  check(H5Pset_obj_track_times(dcpl.get(), false), "H5Pset_obj_track_times", where);  // as for groups
  if (extensible) {
    max_dims[0] = H5S_UNLIMITED;
    hsize_t row = 1;
    for (std::size_t i = 1; i < dims.size(); ++i) row *= std::max<hsize_t>(dims[i], 1);
    std::vector<hsize_t> chunk = dims;
    for (std::size_t i = 1; i < chunk.size(); ++i) chunk[i] = std::max<hsize_t>(chunk[i], 1);
    chunk[0] = std::clamp<hsize_t>(dims[0], 1, std::max<hsize_t>(1, (hsize_t{1} << 15) / row));
    check(H5Pset_chunk(dcpl.get(), rank, chunk.data()), "H5Pset_chunk", where);
  }
  Handle space = make(H5Screate_simple(rank, dims.data(), max_dims.data()), H5Sclose,
                      "H5Screate_simple", where);
  Handle dataset = make(H5Dcreate2(group, name.c_str(), file_type, space.get(), H5P_DEFAULT,
                                   dcpl.get(), H5P_DEFAULT),
                        H5Dclose, "H5Dcreate2", where);
  hsize_t count = 1;
  for (const hsize_t d : dims) count *= d;
  if (count > 0)  // HDF5 rejects a null buffer even when there is nothing to write
    check(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "H5Dwrite",
          where);
}

void sync_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0)
    throw std::runtime_error("cannot open '" + path + "' to sync it: " + std::strerror(errno));
  if (::fsync(fd) != 0) {
    const int error = errno;
    ::close(fd);
    throw std::runtime_error("fsync of '" + path + "' failed: " + std::strerror(error));
  }
  ::close(fd);
}

/// Makes the rename itself durable. Best effort: some filesystems cannot sync a directory, and the
/// file is already complete under its final name either way.
void sync_directory(const std::string& path) noexcept {
  const int fd = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

std::string parent_directory(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

// ---- reading ----

Handle open_for_reading(const std::string& file) {
  std::error_code ec;
  if (!fs::exists(file, ec)) throw std::runtime_error("no such file");
  // The writer's close degree (file_access), so that a file a Writer of this process still has open
  // (its temporary file, read back by --compare before the commit) can be opened again: HDF5 refuses
  // a second open with another degree. Objects are closed before the file in every reader.
  Handle fapl = make(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate(H5P_FILE_ACCESS)", file);
  check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), "H5Pset_fclose_degree", file);
  return make(H5Fopen(file.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose, "H5Fopen", file);
}

std::vector<std::size_t> extent(hid_t space, const std::string& where, hssize_t& count) {
  const int rank = check(H5Sget_simple_extent_ndims(space), "H5Sget_simple_extent_ndims", where);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  check(H5Sget_simple_extent_dims(space, dims.data(), nullptr), "H5Sget_simple_extent_dims", where);
  count = H5Sget_simple_extent_npoints(space);
  if (count < 0) fail("H5Sget_simple_extent_npoints", where);
  return {dims.begin(), dims.end()};
}

template <class T>
std::vector<T> read_numbers(hid_t group, const std::string& group_path, const std::string& name,
                            hid_t memory_type, std::vector<std::size_t>* shape = nullptr) {
  const std::string where = (group_path == "/" ? "" : group_path) + "/" + name;
  Handle dataset = make(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose, "H5Dopen2", where);
  Handle space = make(H5Dget_space(dataset.get()), H5Sclose, "H5Dget_space", where);
  hssize_t count = 0;
  const std::vector<std::size_t> dims = extent(space.get(), where, count);
  std::vector<T> data(static_cast<std::size_t>(count));
  if (count > 0)
    check(H5Dread(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
          "H5Dread", where);
  if (shape != nullptr) *shape = dims;
  return data;
}

std::vector<std::string> read_strings(hid_t attribute, hid_t file_type, hid_t space,
                                      std::size_t count, const std::string& where) {
  std::vector<std::string> texts;
  if (count == 0) return texts;
  const H5T_cset_t cset = H5Tget_cset(file_type);
  if (cset < 0) fail("H5Tget_cset", where);
  Handle memory_type = make(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy(H5T_C_S1)", where);
  check(H5Tset_cset(memory_type.get(), cset), "H5Tset_cset", where);
  if (check(H5Tis_variable_str(file_type), "H5Tis_variable_str", where) > 0) {
    check(H5Tset_size(memory_type.get(), H5T_VARIABLE), "H5Tset_size", where);
    std::vector<char*> pointers(count, nullptr);
    check(H5Aread(attribute, memory_type.get(), pointers.data()), "H5Aread", where);
    // HDF5 allocated the strings; give them back even if copying throws.
    struct Reclaim {
      hid_t type, space;
      std::vector<char*>& buffer;
      ~Reclaim() {
#if H5_VERSION_GE(1, 12, 0)
        H5Treclaim(type, space, H5P_DEFAULT, buffer.data());
#else
        H5Dvlen_reclaim(type, space, H5P_DEFAULT, buffer.data());
#endif
      }
    } reclaim{memory_type.get(), space, pointers};
    for (const char* p : pointers) texts.emplace_back(p == nullptr ? "" : p);
  } else {
    const std::size_t size = H5Tget_size(file_type);
    if (size == 0) fail("H5Tget_size", where);
    // One byte more than stored, so a NULLPAD string of full length keeps its last character.
    check(H5Tset_size(memory_type.get(), size + 1), "H5Tset_size", where);
    check(H5Tset_strpad(memory_type.get(), H5T_STR_NULLTERM), "H5Tset_strpad", where);
    std::vector<char> buffer(count * (size + 1), '\0');
    check(H5Aread(attribute, memory_type.get(), buffer.data()), "H5Aread", where);
    for (std::size_t i = 0; i < count; ++i) texts.emplace_back(buffer.data() + i * (size + 1));
  }
  return texts;
}

ParameterValue read_attribute_value(hid_t file, const std::string& object_path,
                                    const std::string& name) {
  const std::string where = object_path + "@" + name;
  Handle attribute = make(H5Aopen_by_name(file, object_path.c_str(), name.c_str(), H5P_DEFAULT,
                                          H5P_DEFAULT),
                          H5Aclose, "H5Aopen_by_name", where);
  Handle type = make(H5Aget_type(attribute.get()), H5Tclose, "H5Aget_type", where);
  Handle space = make(H5Aget_space(attribute.get()), H5Sclose, "H5Aget_space", where);
  const H5S_class_t space_class = H5Sget_simple_extent_type(space.get());
  if (space_class < 0) fail("H5Sget_simple_extent_type", where);
  hssize_t count = 0;
  const bool scalar = space_class == H5S_SCALAR;
  if (!scalar) {  // an array of any rank is read flat, row-major (pair matrices of /parameters)
    if (space_class != H5S_SIMPLE || extent(space.get(), where, count).empty())
      throw std::runtime_error("attribute '" + where + "' is neither a scalar nor an array");
  } else {
    count = 1;
  }
  const auto n = static_cast<std::size_t>(count);

  auto numbers = [&]<class T>(hid_t memory_type, T) {
    std::vector<T> data(n);
    if (n > 0) check(H5Aread(attribute.get(), memory_type, data.data()), "H5Aread", where);
    return data;
  };
  const H5T_class_t type_class = H5Tget_class(type.get());
  switch (type_class) {
    case H5T_INTEGER: {
      if (scalar && H5Tget_size(type.get()) == 1)
        return numbers(H5T_NATIVE_INT8, std::int8_t{})[0] != 0;
      std::vector<long long> data = numbers(H5T_NATIVE_LLONG, 0LL);
      if (scalar) return data[0];
      return data;
    }
    case H5T_FLOAT: {
      std::vector<double> data = numbers(H5T_NATIVE_DOUBLE, 0.0);
      if (scalar) return data[0];
      return data;
    }
    case H5T_STRING: {
      std::vector<std::string> texts =
          read_strings(attribute.get(), type.get(), space.get(), n, where);
      if (scalar) return std::move(texts[0]);
      return texts;
    }
    case H5T_NO_CLASS:
      fail("H5Tget_class", where);
    default:
      throw std::runtime_error("attribute '" + where +
                               "' is not an integer, float or string (HDF5 type class " +
                               std::to_string(static_cast<int>(type_class)) + ")");
  }
}

}  // namespace

bool is_unit_string(const std::string& unit) {
  // Factors separated by single spaces: no empty factor, no leading or trailing space.
  std::vector<std::string> symbols;
  std::size_t start = 0, index = 0;
  if (unit.empty()) return false;
  for (;; ++index) {
    const std::size_t space = unit.find(' ', start);
    const std::string factor = unit.substr(start, space == std::string::npos ? std::string::npos : space - start);
    if (factor.empty()) return false;
    auto is_digit = [](char c) { return c >= '0' && c <= '9'; };
    auto is_letter = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); };
    std::size_t i = 0;
    if (is_digit(factor[0])) {  // a number: digits, optionally '.' and digits; only the first factor
      if (index != 0) return false;
      while (i < factor.size() && is_digit(factor[i])) ++i;
      if (i < factor.size() && factor[i] == '.') {
        ++i;
        const std::size_t fraction = i;
        while (i < factor.size() && is_digit(factor[i])) ++i;
        if (i == fraction) return false;
      }
    } else if (is_letter(factor[0])) {  // a symbol: letters, each symbol once
      while (i < factor.size() && is_letter(factor[i])) ++i;
      const std::string symbol = factor.substr(0, i);
      if (std::find(symbols.begin(), symbols.end(), symbol) != symbols.end()) return false;
      symbols.push_back(symbol);
    } else {
      return false;
    }
    if (i < factor.size()) {  // a power: a sign and a non-zero integer without leading zeros
      if (factor[i] != '+' && factor[i] != '-') return false;
      ++i;
      if (i >= factor.size() || factor[i] < '1' || factor[i] > '9') return false;
      while (i < factor.size() && is_digit(factor[i])) ++i;
      if (i != factor.size()) return false;
    }
    if (space == std::string::npos) return true;
    start = space + 1;
  }
}

void skip_library_shutdown() {
  // Only a flag before the library starts; once it has, the call fails and nothing changes.
  H5dont_atexit();
}

// ---- Writer ----

struct Writer::Impl {
  std::string final_path;
  std::string temp_path;
  Handle file;
  bool created = false;    // the temporary file is ours to remove
  bool committed = false;
  bool keep_temp = false;  // set when only the rename failed: the file holds a complete run
  bool replace_any = false;  // replace_any_file()
  std::string creator;       // /h5md/creator@name

  // In Impl rather than Writer so that a constructor failing after H5Fcreate also cleans up.
  ~Impl() {
    const ErrorSilencer silence;
    file.reset();
    if (created && !committed && !keep_temp) {
      std::error_code ignored;
      fs::remove(temp_path, ignored);
    }
  }

  std::string context() const { return write_context(final_path); }

  hid_t open_file() const {
    if (committed)
      throw std::logic_error("h5md::Writer for '" + final_path + "' used after commit()");
    if (!file.is_open())
      throw std::logic_error("h5md::Writer for '" + final_path + "' used after a failed commit()");
    return file.get();
  }
};

namespace {
/// Whether process `pid` is alive: it exists and is not a zombie (a process killed a moment ago whose
/// parent has not yet collected it still answers kill(pid, 0)).
bool process_alive(long pid) {
  if (::kill(static_cast<pid_t>(pid), 0) == -1 && errno == ESRCH) return false;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return true;  // (no /proc: taken as alive)
  const std::size_t name_end = line.rfind(')');  // "pid (name) S ...": the name may hold spaces and ')'
  return !(name_end != std::string::npos && name_end + 2 < line.size() &&
           (line[name_end + 2] == 'Z' || line[name_end + 2] == 'X'));
}

/// Removes the `<path>.tmp.<pid>` files of other processes; with `only_dead`, only those whose process is
/// no longer alive (a temporary of a process still running, another run writing the same file, is left).
void remove_temporaries(const std::string& path, bool only_dead) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string prefix = target.filename().string() + ".tmp.";
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::stol(digits);
    if (pid <= 0 || pid == static_cast<long>(::getpid())) continue;
    if (!only_dead || !process_alive(pid)) {
      std::error_code removed;
      fs::remove(it->path(), removed);
    }
  }
}

/// Creates `path` as an empty regular file of this process, exclusively and not through a link: a
/// link planted at the name, or a leftover of a killed process with this pid, is removed first (only
/// the link: never its target). Returns 0, or the errno of a failure (a name still there after its
/// removal: EEXIST, left to H5Fcreate to report).
int create_exclusively(const std::string& path) {
  for (int attempt = 0; attempt < 2; ++attempt) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd >= 0) {
      ::close(fd);
      return 0;
    }
    if (errno != EEXIST) return errno;
    std::error_code ec;
    if (!fs::remove(path, ec) && ec) return ec.value();  // (a leftover that cannot be removed: its reason)
  }
  return EEXIST;
}

/// Why a file cannot be created in the folder of `path`: the folder missing or not one, else the
/// system's reason (`error`, an errno), one line without HDF5's internals.
std::string cannot_create(const std::string& path, int error) {
  const std::string directory = parent_directory(path);
  std::error_code ec;
  if (!fs::exists(directory, ec)) return "directory '" + directory + "' does not exist";
  if (!fs::is_directory(directory, ec)) return "'" + directory + "' is not a directory";
  // (ENOENT for a folder that exists: one of the system's own, as /proc, that takes no file)
  if (error == ENOENT) return "cannot create a file in '" + directory + "': the folder takes no new files";
  return "cannot create a file in '" + directory + "': " + std::strerror(error);
}

/// `<final stem>.kept-<pid>.h5`: where commit() keeps a complete file it must not rename onto the final path.
std::string kept_path(const std::string& final_path) {
  std::string stem = final_path;
  if (stem.size() > 3 && stem.compare(stem.size() - 3, 3, ".h5") == 0) stem.resize(stem.size() - 3);
  return stem + ".kept-" + std::to_string(::getpid()) + ".h5";
}
}  // namespace

void remove_others_temporaries(const std::string& path) { remove_temporaries(path, false); }

bool written_by(const std::string& path, const std::string& creator) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return false;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return false;
  char signature[8] = {};
  const bool hdf5 = std::fread(signature, 1, 8, f) == 8 && std::memcmp(signature, "\x89HDF\r\n\x1a\n", 8) == 0;
  std::fclose(f);
  if (!hdf5) return false;
  try {
    return read_string_attribute(path, "/h5md/creator", "name") == creator;
  } catch (const std::exception&) {
    return false;
  }
}

void Writer::replace_any_file() { impl_->replace_any = true; }

Writer::Writer(std::string final_path, std::string author, std::string creator_name,
               std::string creator_version)
    : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.final_path = std::move(final_path);
  remove_temporaries(d.final_path, true);  // what a run killed with SIGKILL (or a power cut) left behind
  d.temp_path = d.final_path + ".tmp." + std::to_string(::getpid());
  d.creator = creator_name;
  with_context(d.context(), [&] {
    if (d.final_path.empty()) throw std::runtime_error("the path is empty");
    if (const int error = create_exclusively(d.temp_path); error != 0 && error != EEXIST)
      throw std::runtime_error(cannot_create(d.temp_path, error));
    Handle fapl = file_access(d.temp_path);
    // TRUNC, not EXCL: a leftover from a killed run with the same pid (common in containers)
    // must not block the next run; HDF5 itself refuses a file this process still has open.
    Handle fcpl = make(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "H5Pcreate(H5P_FILE_CREATE)", "/");
    check(H5Pset_obj_track_times(fcpl.get(), false), "H5Pset_obj_track_times", "/");  // the root group
    const hid_t id = H5Fcreate(d.temp_path.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get());
    if (id < 0) {
      const std::string detail = hdf5_detail();
      // HDF5 may have created the file before it failed (a full disk): it is ours (our pid), remove it.
      std::error_code removed;
      fs::remove(d.temp_path, removed);
      const std::string directory = parent_directory(d.temp_path);
      std::error_code ec;
      if (!fs::exists(directory, ec) || !fs::is_directory(directory, ec))
        throw std::runtime_error(cannot_create(d.temp_path, ENOENT));
      throw std::runtime_error("H5Fcreate failed for '" + d.temp_path + "': " + detail);
    }
    d.file = Handle(id, H5Fclose);
    d.created = true;

    const hid_t file = d.file.get();
    const Handle h5md = ensure_group(file, "/h5md");
    const std::int32_t version[2] = {1, 1};
    const hsize_t two = 2;
    put_attribute(h5md.get(), "/h5md@version", "version", H5T_STD_I32LE, H5T_NATIVE_INT32, &two,
                  version);
    put_value(ensure_group(file, "/h5md/author").get(), "/h5md/author", "name", author, false);
    const Handle creator = ensure_group(file, "/h5md/creator");
    put_value(creator.get(), "/h5md/creator", "name", creator_name, false);
    put_value(creator.get(), "/h5md/creator", "version", creator_version, false);
  });
}

Writer::~Writer() = default;

void Writer::write_parameters(const std::vector<Parameter>& parameters,
                              const std::string& namelist_text) {
  for (const Parameter& p : parameters) {
    if (p.group.empty() || p.group.find('/') != std::string::npos)
      throw std::invalid_argument("h5md: invalid namelist group name '" + p.group +
                                  "' for parameter '" + p.name + "'");
    if (p.shape.empty()) continue;
    const std::size_t length = std::visit(
        []<class T>(const T& v) -> std::size_t {
          if constexpr (requires { v.size(); } && !std::is_same_v<T, std::string>) return v.size();
          else return 0;  // a scalar has no shape
        },
        p.value);
    std::size_t cells = 1;
    for (std::size_t d : p.shape) cells *= d;
    if (cells != length || length == 0)
      throw std::invalid_argument("h5md: parameter '" + p.group + "/" + p.name + "': a shape of " +
                                  std::to_string(cells) + " values for " + std::to_string(length));
  }
  const hid_t file = impl_->open_file();
  with_context(impl_->context(), [&] {
    const Handle root = ensure_group(file, "/parameters");
    put_value(root.get(), "/parameters", "namelist", namelist_text, false);
    for (const Parameter& p : parameters) {
      const std::string path = "/parameters/" + p.group;
      put_value(ensure_group(file, path).get(), path, p.name, p.value, false, p.shape);
    }
  });
}

void Writer::write_observable(const std::string& name, const Series& series) {
  const std::vector<std::string> parts = split_path(name);
  const std::size_t nt = series.time.size();
  const std::string what = "h5md: observable '" + name + "': ";
  if (parts.empty()) throw std::invalid_argument(what + "empty name");
  if (series.columns == 0) throw std::invalid_argument(what + "columns must be at least 1");
  if (series.step.size() != nt)
    throw std::invalid_argument(what + std::to_string(series.step.size()) + " steps but " +
                                std::to_string(nt) + " times");
  if (series.value.size() != nt * series.columns)
    throw std::invalid_argument(what + std::to_string(series.value.size()) + " values, expected " +
                                std::to_string(nt) + " times x " + std::to_string(series.columns) +
                                " columns");
  if (!series.error.empty() && series.error.size() != series.value.size())
    throw std::invalid_argument(what + std::to_string(series.error.size()) + " errors but " +
                                std::to_string(series.value.size()) + " values");
  for (const std::string* unit : {&series.time_unit, &series.value_unit})
    if (!unit->empty() && !is_unit_string(*unit))
      throw std::invalid_argument(what + "'" + *unit + "' is not a unit string of H5MD's units module");

  const hid_t file = impl_->open_file();
  with_context(impl_->context(), [&] {
    const std::string path = observable_path(name, parts);
    const Handle group = ensure_group(file, path);
    const std::vector<hsize_t> times = {nt};
    const std::vector<hsize_t> dims =
        series.columns == 1 ? times : std::vector<hsize_t>{nt, series.columns};
    put_dataset(group.get(), path, "step", H5T_STD_I64LE, H5T_NATIVE_LLONG, times, true,
                series.step.data());
    put_dataset(group.get(), path, "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, times, true,
                series.time.data());
    put_dataset(group.get(), path, "value", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dims, true,
                series.value.data());
    if (!series.error.empty())
      put_dataset(group.get(), path, "error", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dims, true,
                  series.error.data());
    auto unit_of = [&](const char* dataset, const std::string& unit) {
      const std::string where = path + "/" + dataset;
      const Handle d = make(H5Dopen2(group.get(), dataset, H5P_DEFAULT), H5Dclose, "H5Dopen2", where);
      put_unit(d.get(), where, unit);
    };
    if (!series.time_unit.empty()) unit_of("time", series.time_unit);
    if (!series.value_unit.empty()) {
      unit_of("value", series.value_unit);
      if (!series.error.empty()) unit_of("error", series.value_unit);
    }
  });
}

void Writer::declare_units_module(const std::string& system) {
  const hid_t file = impl_->open_file();
  with_context(impl_->context(), [&] {
    const std::string path = "/h5md/modules/units";
    const Handle module = ensure_group(file, path);
    const std::int32_t version[2] = {kUnitsModuleVersion[0], kUnitsModuleVersion[1]};
    const hsize_t two = 2;
    if (check(H5Aexists(module.get(), "version"), "H5Aexists", path + "@version") > 0)
      check(H5Adelete(module.get(), "version"), "H5Adelete", path + "@version");
    put_attribute(module.get(), path + "@version", "version", H5T_STD_I32LE, H5T_NATIVE_INT32, &two, version);
    put_value(module.get(), path, "system", system, true);
  });
}

void Writer::write_unit(const std::string& dataset_path, const std::string& unit) {
  if (!is_unit_string(unit))
    throw std::invalid_argument("h5md: '" + unit + "' is not a unit string of H5MD's units module (" +
                                dataset_path + "@unit)");
  const hid_t file = impl_->open_file();
  with_context(impl_->context(), [&] {
    const Handle d = make(H5Dopen2(file, dataset_path.c_str(), H5P_DEFAULT), H5Dclose, "H5Dopen2", dataset_path);
    put_unit(d.get(), dataset_path, unit);
  });
}

void Writer::write_attribute(const std::string& object_path, const std::string& name,
                             const ParameterValue& value) {
  const hid_t file = impl_->open_file();
  with_context(impl_->context(), [&] {
    const Handle object =
        make(H5Oopen(file, object_path.c_str(), H5P_DEFAULT), H5Oclose, "H5Oopen", object_path);
    put_value(object.get(), object_path, name, value, true);
  });
}

void Writer::write_hard_link(const std::string& target, const std::string& link_path) {
  const hid_t file = impl_->open_file();
  with_context(impl_->context(), [&] {
    const auto slash = link_path.find_last_of('/');
    if (slash != std::string::npos && slash > 0) ensure_group(file, link_path.substr(0, slash));
    check(H5Lcreate_hard(file, target.c_str(), file, link_path.c_str(), H5P_DEFAULT, H5P_DEFAULT), "H5Lcreate_hard",
          link_path);
  });
}

void Writer::write_group(const std::string& path) {
  const hid_t file = impl_->open_file();
  with_context(impl_->context(), [&] { ensure_group(file, path); });
}

void Writer::write_dataset(const std::string& path, const std::vector<double>& data,
                           std::vector<std::size_t> shape) {
  const std::vector<std::string> parts = split_path(path);
  if (parts.empty())
    throw std::invalid_argument("h5md: dataset path '" + path + "' names no dataset");
  if (shape.empty()) shape = {data.size()};
  std::size_t count = 1;
  for (const std::size_t d : shape) count *= d;
  if (count != data.size())
    throw std::invalid_argument("h5md: dataset '" + path + "': " + std::to_string(data.size()) +
                                " values do not fill its shape (" + std::to_string(count) +
                                " elements)");
  const hid_t file = impl_->open_file();
  with_context(impl_->context(), [&] {
    const std::string parent = join_path(parts, parts.size() - 1);
    const Handle group = ensure_group(file, parent);
    const std::vector<hsize_t> dims(shape.begin(), shape.end());
    put_dataset(group.get(), parent, parts.back(), H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dims, false,
                data.data());
  });
}

namespace {

/// A 1-D integer dataset at absolute `path` of `file` (intermediate groups created).
void put_integers(hid_t file, const std::string& path, hid_t file_type, hid_t memory_type, std::size_t n,
                  const void* data) {
  const std::vector<std::string> parts = split_path(path);
  const std::string parent = join_path(parts, parts.size() - 1);
  const Handle group = ensure_group(file, parent);
  const std::vector<hsize_t> dims{n};
  put_dataset(group.get(), parent, parts.back(), file_type, memory_type, dims, false, data);
}

}  // namespace

void Writer::write_integers(const std::string& path, const std::vector<std::uint64_t>& data) {
  if (split_path(path).empty()) throw std::invalid_argument("h5md: dataset path '" + path + "' names no dataset");
  const hid_t file = impl_->open_file();
  with_context(impl_->context(),
               [&] { put_integers(file, path, H5T_STD_U64LE, H5T_NATIVE_UINT64, data.size(), data.data()); });
}

void Writer::write_integers(const std::string& path, const std::vector<std::int64_t>& data) {
  if (split_path(path).empty()) throw std::invalid_argument("h5md: dataset path '" + path + "' names no dataset");
  const hid_t file = impl_->open_file();
  with_context(impl_->context(),
               [&] { put_integers(file, path, H5T_STD_I64LE, H5T_NATIVE_INT64, data.size(), data.data()); });
}

void Writer::commit() {
  Impl& d = *impl_;
  const hid_t file = d.open_file();
  with_context(d.context(), [&] {
    check(H5Fflush(file, H5F_SCOPE_GLOBAL), "H5Fflush", d.temp_path);
    check(d.file.close(), "H5Fclose", d.temp_path);
    sync_file(d.temp_path);  // otherwise a crash right after the rename could leave an empty file
    std::error_code ec;
    // The final path again, just before the rename: a file someone put there during the run stays.
    if (!d.replace_any && fs::exists(fs::symlink_status(d.final_path, ec)) && !written_by(d.final_path, d.creator)) {
      const std::string kept = kept_path(d.final_path);
      fs::rename(d.temp_path, kept, ec);
      d.keep_temp = true;
      throw std::runtime_error("'" + d.final_path + "' appeared during the run and is not a file of " + d.creator +
                               ": it is left as it is, and the complete output is in '" +
                               (ec ? d.temp_path : kept) + "'");
    }
    fs::rename(d.temp_path, d.final_path, ec);
    if (ec) {
      d.keep_temp = true;
      throw std::runtime_error("renaming '" + d.temp_path + "' failed (" + ec.message() +
                               "); the complete output is kept in '" + d.temp_path + "'");
    }
    d.committed = true;
    sync_directory(parent_directory(d.final_path));
  });
}

const std::string& Writer::temporary_path() const { return impl_->temp_path; }
const std::string& Writer::final_path() const { return impl_->final_path; }

// ---- reading ----

ObservableData read_observable(const std::string& file, const std::string& name) {
  std::string path;
  ObservableData out = with_context(read_context(file), [&] {
    const std::vector<std::string> parts = split_path(name);
    if (parts.empty()) throw std::runtime_error("empty observable name");
    const Handle f = open_for_reading(file);
    path = observable_path(name, parts);
    const Handle group =
        make(H5Gopen2(f.get(), path.c_str(), H5P_DEFAULT), H5Gclose, "H5Gopen2", path);
    ObservableData read;
    read.time = read_numbers<double>(group.get(), path, "time", H5T_NATIVE_DOUBLE);
    read.step = read_numbers<long long>(group.get(), path, "step", H5T_NATIVE_LLONG);
    read.value = read_numbers<double>(group.get(), path, "value", H5T_NATIVE_DOUBLE, &read.shape);
    if (check(H5Lexists(group.get(), "error", H5P_DEFAULT), "H5Lexists", path + "/error") > 0)
      read.error = read_numbers<double>(group.get(), path, "error", H5T_NATIVE_DOUBLE);
    return read;
  });
  // A time series as Writer::write_observable writes it, or none: its readers index value and error by the
  // rows of time (a dataset cut or reshaped by hand crashed --table, or printed memory past its end).
  const std::size_t rows = out.shape.empty() ? 0 : out.shape[0];
  if (out.shape.empty() || out.shape.size() > 2 || rows != out.time.size() || out.step.size() != out.time.size() ||
      (!out.error.empty() && out.error.size() != out.value.size()))
    throw NotAsWritten(read_context(file) + ": " + path + " is not a time series as granular-dsmc writes it: " +
                       std::to_string(out.time.size()) + " times, " + std::to_string(out.step.size()) + " steps, a value of " +
                       std::to_string(out.shape.size()) + " dimensions and " + std::to_string(rows) + " rows, " +
                       std::to_string(out.error.size()) + " errors for " + std::to_string(out.value.size()) + " values");
  return out;
}

namespace {
/// The dataset at `path` of `file`; with `optional`, nothing when its group has no such link (else
/// HDF5's failure to open it is the error).
std::optional<ArrayData> read_array(const std::string& file, const std::string& path, bool optional) {
  return with_context(read_context(file), [&]() -> std::optional<ArrayData> {
    const std::vector<std::string> parts = split_path(path);
    if (parts.empty()) throw std::runtime_error("dataset path '" + path + "' names no dataset");
    const Handle f = open_for_reading(file);
    const std::string parent = join_path(parts, parts.size() - 1);
    const Handle group = make(H5Gopen2(f.get(), parent.c_str(), H5P_DEFAULT), H5Gclose, "H5Gopen2", parent);
    if (optional && check(H5Lexists(group.get(), parts.back().c_str(), H5P_DEFAULT), "H5Lexists", path) <= 0)
      return std::nullopt;
    ArrayData out;
    out.data = read_numbers<double>(group.get(), parent, parts.back(), H5T_NATIVE_DOUBLE, &out.shape);
    return out;
  });
}
}  // namespace

ArrayData read_dataset(const std::string& file, const std::string& path) { return *read_array(file, path, false); }

std::optional<ArrayData> read_dataset_if_present(const std::string& file, const std::string& path) {
  return read_array(file, path, true);
}

std::vector<std::uint64_t> read_integers(const std::string& file, const std::string& path) {
  return with_context(read_context(file), [&] {
    const std::vector<std::string> parts = split_path(path);
    if (parts.empty()) throw std::runtime_error("dataset path '" + path + "' names no dataset");
    const Handle f = open_for_reading(file);
    const std::string parent = join_path(parts, parts.size() - 1);
    const Handle group = make(H5Gopen2(f.get(), parent.c_str(), H5P_DEFAULT), H5Gclose, "H5Gopen2", parent);
    return read_numbers<std::uint64_t>(group.get(), parent, parts.back(), H5T_NATIVE_UINT64);
  });
}

ParameterValue read_attribute(const std::string& file, const std::string& object_path,
                              const std::string& name) {
  return with_context(read_context(file), [&] {
    const Handle f = open_for_reading(file);
    return read_attribute_value(f.get(), object_path, name);
  });
}

bool has_attribute(const std::string& file, const std::string& object_path, const std::string& name) {
  return with_context(read_context(file), [&] {
    const Handle f = open_for_reading(file);
    const htri_t exists = H5Aexists_by_name(f.get(), object_path.c_str(), name.c_str(), H5P_DEFAULT);
    if (exists < 0) fail("H5Aexists_by_name", object_path + "@" + name);
    return exists > 0;
  });
}

std::string read_string_attribute(const std::string& file, const std::string& object_path,
                                  const std::string& name) {
  ParameterValue value = read_attribute(file, object_path, name);
  if (auto* text = std::get_if<std::string>(&value)) return std::move(*text);
  throw std::runtime_error(read_context(file) + ": attribute '" + object_path + "@" + name +
                           "' is not a scalar string");
}

double read_double_attribute(const std::string& file, const std::string& object_path,
                             const std::string& name) {
  const ParameterValue value = read_attribute(file, object_path, name);
  if (const auto* v = std::get_if<double>(&value)) return *v;
  if (const auto* v = std::get_if<long long>(&value)) return static_cast<double>(*v);
  if (const auto* v = std::get_if<bool>(&value)) return *v ? 1.0 : 0.0;
  if (const auto* v = std::get_if<std::vector<double>>(&value); v && v->size() == 1) return (*v)[0];
  if (const auto* v = std::get_if<std::vector<long long>>(&value); v && v->size() == 1)
    return static_cast<double>((*v)[0]);
  throw std::runtime_error(read_context(file) + ": attribute '" + object_path + "@" + name +
                           "' is not a single number");
}

}  // namespace gdsmc::io::h5md
