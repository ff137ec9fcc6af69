// Particle dumps in Phantom's native binary format, which SPLASH
// (`splash -f phantom`) and sarracen (`sarracen.read_phantom`) read. Written
// from the format's description, "The phantom native binary format"
// (docs/dumpfile.rst of github:danieljprice/phantom), and checked against two
// public readers: sarracen's sarracen/readers/read_phantom.py and SPLASH's
// src/read_data_sphNG.f90 (its Phantom reader). The file is a sequence of
// Fortran unformatted records (a 4-byte length before and after the bytes):
//   1. the magic numbers: default int 60769, default real 60878.0, default
//      int 60878, default int iversion = 1, default int 690706;
//   2. a 100-character file identifier: "F" (full dump), "T" (tagged), and
//      "Phantom" somewhere in it (SPLASH takes these to mean a tagged Phantom dump);
//   3. the global header: for each of the 8 types (default int, int*1, int*2,
//      int*4, int*8, default real, real*4, real*8) a record with the 4-byte
//      count nvars and, when nvars > 0, a record of nvars 16-character tags and
//      one of their values (a tag repeated for an array: npartoftype, massoftype);
//   4. the number of array blocks (4-byte int), then for each block a record of
//      its length (8-byte int) and its number of arrays of each of the 8 types
//      (4-byte ints), then for each block its arrays by type, each as a record of
//      its 16-character tag and one of its values.
// Here the default int is 4 bytes and the default real 8 bytes (Phantom built in
// double precision), little-endian as the host writes. There are two array
// blocks, as in a Phantom run without MPI: the particles and an empty block of
// sink particles (SPLASH and sarracen read block 2 as the sinks).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace mote::io {

class PhantomDump {
 public:
  /// `file_id`: the identifier after "FT:" (at most 97 characters; it must name "Phantom").
  explicit PhantomDump(const std::string& file_id);

  /// Header values: one entry per value, all under `tag` (at most 16 characters).
  /// Setting a tag again replaces its values in place.
  void header_int(const std::string& tag, const std::vector<std::int32_t>& values);
  void header_real(const std::string& tag, const std::vector<double>& values);
  void header_real8(const std::string& tag, const std::vector<double>& values);

  /// Arrays over the particles, written in the order given within each type;
  /// every array has the same length (the particle count).
  void int1_array(const std::string& tag, std::vector<std::int8_t> values);
  void real_array(const std::string& tag, std::vector<double> values);
  void real4_array(const std::string& tag, std::vector<float> values);

  /// The file's bytes.
  std::string encode() const;

 private:
  template <class T>
  using Entries = std::vector<std::pair<std::string, std::vector<T>>>;
  template <class T>
  static void set(Entries<T>& entries, const std::string& tag, const std::vector<T>& values);
  template <class T>
  void add_array(Entries<T>& arrays, const std::string& tag, std::vector<T> values);

  std::string file_id_;
  Entries<std::int32_t> header_ints_;
  Entries<double> header_reals_, header_real8s_;
  long long n_ = -1;  // particle count, set by the first array
  Entries<std::int8_t> int1_arrays_;
  Entries<double> real_arrays_;
  Entries<float> real4_arrays_;
};

/// A Simulation whose snapshots can also be written as Phantom dumps (the SPH engine).
class PhantomDumpSource {
 public:
  virtual ~PhantomDumpSource() = default;
  /// Throws core::InputError when the state has no Phantom form (e.g. unequal masses within a particle type).
  virtual void check_phantom_dump() const = 0;
  /// Adds the header values and the particle arrays of the current state (the run loop adds time and units).
  virtual void write_phantom_dump(PhantomDump& dump) const = 0;
};

}  // namespace mote::io
