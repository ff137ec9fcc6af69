// Phantom's native dump format (see include/mote/io/phantom_dump.hpp for the layout and its sources).
#include "mote/io/phantom_dump.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace mote::io {

namespace {

constexpr std::size_t kTagLength = 16;
constexpr std::size_t kFileIdLength = 100;
constexpr int kDataTypes = 8;  // default int, int*1, int*2, int*4, int*8, default real, real*4, real*8
constexpr int kInt1 = 1, kReal = 5, kReal4 = 6;

/// One Fortran unformatted record: its byte count (4 bytes) before and after the bytes.
void append_record(std::string& out, const std::string& bytes) {
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw std::length_error("Phantom dump: a record of " + std::to_string(bytes.size()) +
                            " bytes exceeds the 2 GiB of a Fortran record (too many particles for one block)");
  const auto length = static_cast<std::int32_t>(bytes.size());
  std::string marker(sizeof length, '\0');
  std::memcpy(marker.data(), &length, sizeof length);
  out += marker;
  out += bytes;
  out += marker;
}

template <class T>
std::string bytes_of(const T* values, std::size_t count) {
  std::string s(count * sizeof(T), '\0');
  if (count > 0) std::memcpy(s.data(), values, s.size());
  return s;
}

template <class T>
std::string bytes_of(const T& value) {
  return bytes_of(&value, 1);
}

std::string padded(const std::string& text, std::size_t length) {
  return text + std::string(length - text.size(), ' ');
}

void check_tag(const std::string& tag) {
  if (tag.empty() || tag.size() > kTagLength)
    throw std::invalid_argument("Phantom dump: tag '" + tag + "' is not 1 to 16 characters");
}

/// A header block: the count, then (when there are values) the tags and the values.
template <class T>
void append_header_block(std::string& out, const std::vector<std::pair<std::string, std::vector<T>>>& entries) {
  std::string tags, values;
  std::int32_t count = 0;
  for (const auto& [tag, vals] : entries)
    for (const T& v : vals) {
      tags += padded(tag, kTagLength);
      values += bytes_of(v);
      ++count;
    }
  append_record(out, bytes_of(count));
  if (count == 0) return;
  append_record(out, tags);
  append_record(out, values);
}

template <class T>
void append_arrays(std::string& out, const std::vector<std::pair<std::string, std::vector<T>>>& arrays) {
  for (const auto& [tag, values] : arrays) {
    append_record(out, padded(tag, kTagLength));
    append_record(out, bytes_of(values.data(), values.size()));
  }
}

/// A block header: the array length (8 bytes) and the number of arrays of each type.
void append_block_header(std::string& out, std::int64_t length, const std::int32_t (&counts)[kDataTypes]) {
  append_record(out, bytes_of(length) + bytes_of(counts, kDataTypes));
}

}  // namespace

PhantomDump::PhantomDump(const std::string& file_id) : file_id_("FT:" + file_id) {
  if (file_id_.size() > kFileIdLength || file_id_.find("Phantom") == std::string::npos)
    throw std::invalid_argument("Phantom dump: the file identifier must name \"Phantom\" in at most 97 characters");
}

template <class T>
void PhantomDump::set(Entries<T>& entries, const std::string& tag, const std::vector<T>& values) {
  check_tag(tag);
  for (auto& entry : entries)
    if (entry.first == tag) {
      entry.second = values;
      return;
    }
  entries.emplace_back(tag, values);
}

void PhantomDump::header_int(const std::string& tag, const std::vector<std::int32_t>& values) {
  set(header_ints_, tag, values);
}

void PhantomDump::header_real(const std::string& tag, const std::vector<double>& values) {
  set(header_reals_, tag, values);
}

void PhantomDump::header_real8(const std::string& tag, const std::vector<double>& values) {
  set(header_real8s_, tag, values);
}

template <class T>
void PhantomDump::add_array(Entries<T>& arrays, const std::string& tag, std::vector<T> values) {
  check_tag(tag);
  const auto n = static_cast<long long>(values.size());
  if (n_ >= 0 && n != n_)
    throw std::invalid_argument("Phantom dump: array '" + tag + "' has " + std::to_string(n) + " values, not " +
                                std::to_string(n_));
  n_ = n;
  arrays.emplace_back(tag, std::move(values));
}

void PhantomDump::int1_array(const std::string& tag, std::vector<std::int8_t> values) {
  add_array(int1_arrays_, tag, std::move(values));
}

void PhantomDump::real_array(const std::string& tag, std::vector<double> values) {
  add_array(real_arrays_, tag, std::move(values));
}

void PhantomDump::real4_array(const std::string& tag, std::vector<float> values) {
  add_array(real4_arrays_, tag, std::move(values));
}

std::string PhantomDump::encode() const {
  static_assert(sizeof(double) == 8 && sizeof(float) == 4,
                "Phantom dump: real*8 and real*4 must be IEEE doubles and floats");
  constexpr std::int32_t kVersion = 1;
  std::string out;
  append_record(out, bytes_of(std::int32_t{60769}) + bytes_of(60878.0) + bytes_of(std::int32_t{60878}) +
                         bytes_of(kVersion) + bytes_of(std::int32_t{690706}));
  append_record(out, padded(file_id_, kFileIdLength));
  append_header_block(out, header_ints_);
  for (int type = 1; type < kReal; ++type) append_header_block(out, Entries<std::int32_t>{});  // int*1 to int*8: none
  append_header_block(out, header_reals_);
  append_header_block(out, Entries<float>{});  // real*4: none
  append_header_block(out, header_real8s_);

  std::int32_t particle_counts[kDataTypes] = {}, sink_counts[kDataTypes] = {};
  particle_counts[kInt1] = static_cast<std::int32_t>(int1_arrays_.size());
  particle_counts[kReal] = static_cast<std::int32_t>(real_arrays_.size());
  particle_counts[kReal4] = static_cast<std::int32_t>(real4_arrays_.size());
  append_record(out, bytes_of(std::int32_t{2}));  // array blocks: particles, sinks
  append_block_header(out, std::max<long long>(n_, 0), particle_counts);
  append_block_header(out, 0, sink_counts);
  append_arrays(out, int1_arrays_);
  append_arrays(out, real_arrays_);
  append_arrays(out, real4_arrays_);
  return out;
}

}  // namespace mote::io
