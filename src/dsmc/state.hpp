/**
 * \file state.hpp
 * \brief What a module saves of itself for a checkpoint: named arrays of reals and of exact
 *        integers, read back by name (\ref output_checkpoint "docs/output.md").
 *
 * Every module that evolves during a run (the particles, the collider, the cluster gas, each forcing,
 * the replica's own progress and partial results) writes its state into a Record under names of its
 * own, prefixed by the module ("collider/time", "thermostat/scale", ...), and reads it back by the
 * same names; whoever stores the Record (run/checkpoint.hpp: an HDF5 file with a checksum) knows
 * nothing of what is in it. A name a reader needs and does not find, or one of the wrong length, is
 * a StateError naming it: a checkpoint is read, not trusted.
 *
 * The layout of the records is versioned as a whole (`layout`, written with every checkpoint): a
 * module that changes what it saves raises it and says in run/checkpoint.cpp how an older record is
 * read (or that it is refused).
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace gdsmc::state {

/// The layout of the records this build writes: 2 (named values; 1 was the positional layout of the
/// checkpoints written before 2026-11-29, which run/checkpoint.cpp reads by translating it).
inline constexpr int layout = 2;

/// A record that lacks a name its reader needs, or holds it with the wrong length or a value out of range.
struct StateError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A whole record that another build's rules wrote (another number of cache blocks for the same gas, say):
/// refused as a StateError is, in words of its own.
struct StateMismatch : StateError {
  using StateError::StateError;
};

/// Named arrays of reals and of exact integers: one module's state, or many modules' under their prefixes.
struct Record {
  std::map<std::string, std::vector<double>> reals;           ///< name -> values
  std::map<std::string, std::vector<std::uint64_t>> integers;  ///< name -> values

  /// Stores one real under `name`.
  void put(const std::string& name, double x) { reals[name] = {x}; }
  /// Stores one integer under `name`.
  void put_integer(const std::string& name, std::uint64_t x) { integers[name] = {x}; }
  /// Stores an array of reals under `name`.
  void put(const std::string& name, std::vector<double> x) { reals[name] = std::move(x); }
  /// Stores an array of integers under `name`.
  void put(const std::string& name, std::vector<std::uint64_t> x) { integers[name] = std::move(x); }

  /// Whether `name` holds reals.
  bool has(const std::string& name) const { return reals.count(name) > 0; }
  /// Whether `name` holds integers.
  bool has_integers(const std::string& name) const { return integers.count(name) > 0; }

  /// The array of reals `name`; with `size`, it must have exactly that many. Throws StateError.
  const std::vector<double>& array(const std::string& name, std::size_t size = npos) const {
    const auto it = reals.find(name);
    if (it == reals.end()) throw StateError("'" + name + "' is missing");
    if (size != npos && it->second.size() != size) throw StateError(wrong_length(name, it->second.size(), size));
    return it->second;
  }
  /// The array of integers `name`, as array().
  const std::vector<std::uint64_t>& integer_array(const std::string& name, std::size_t size = npos) const {
    const auto it = integers.find(name);
    if (it == integers.end()) throw StateError("'" + name + "' is missing");
    if (size != npos && it->second.size() != size) throw StateError(wrong_length(name, it->second.size(), size));
    return it->second;
  }
  /// The real `name` (an array of one).
  double real(const std::string& name) const { return array(name, 1)[0]; }
  /// The integer `name` (an array of one).
  std::uint64_t integer(const std::string& name) const { return integer_array(name, 1)[0]; }
  /// The integer `name` as a flag (0 or 1).
  bool flag(const std::string& name) const {
    const std::uint64_t x = integer(name);
    if (x > 1) throw StateError("'" + name + "' is " + std::to_string(x) + ", not 0 or 1");
    return x == 1;
  }

  static constexpr std::size_t npos = static_cast<std::size_t>(-1);  ///< any length

 private:
  static std::string wrong_length(const std::string& name, std::size_t has, std::size_t needs) {
    return "'" + name + "' holds " + std::to_string(has) + " values, not " + std::to_string(needs);
  }
};

}  // namespace gdsmc::state
