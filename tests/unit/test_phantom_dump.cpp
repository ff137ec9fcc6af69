// Phantom's dump format (include/mote/io/phantom_dump.hpp): the records of a
// small dump, walked here by their Fortran length markers, against the layout
// of "The phantom native binary format" (Phantom's docs/dumpfile.rst).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "mote/io/phantom_dump.hpp"

using mote::io::PhantomDump;

namespace {

/// The records of a Fortran unformatted file; fails the test on a marker mismatch.
std::vector<std::string> records_of(const std::string& bytes) {
  std::vector<std::string> records;
  std::size_t pos = 0;
  while (pos < bytes.size()) {
    std::int32_t head = 0, tail = 0;
    std::memcpy(&head, bytes.data() + pos, 4);
    EXPECT_LE(pos + 8 + head, bytes.size());
    std::memcpy(&tail, bytes.data() + pos + 4 + head, 4);
    EXPECT_EQ(head, tail) << "record at byte " << pos;
    records.push_back(bytes.substr(pos + 4, head));
    pos += 8 + head;
  }
  return records;
}

template <class T>
T value_at(const std::string& record, std::size_t offset) {
  T v;
  std::memcpy(&v, record.data() + offset, sizeof v);
  return v;
}

PhantomDump small_dump() {
  PhantomDump d("Phantom format, unit test");
  d.header_int("npartoftype", {2, 0});
  d.header_real("time", {0.5});
  d.header_real8("udist", {1.5e13});
  d.real4_array("h", {0.25f, 0.5f});
  d.int1_array("itype", {1, 7});
  d.real_array("x", {-1.0, 2.0});
  return d;
}

}  // namespace

TEST(PhantomDump, RecordsFollowTheFormatDescription) {
  const auto r = records_of(small_dump().encode());
  // magic numbers, file id, 8 header types (3 with values: count, tags, values), block count,
  // 2 block headers, 3 arrays (tag, values)
  ASSERT_EQ(r.size(), 2u + (8u + 3u * 2u) + 1u + 2u + 3u * 2u);
  ASSERT_EQ(r[0].size(), 4u * 4 + 8);
  EXPECT_EQ(value_at<std::int32_t>(r[0], 0), 60769);
  EXPECT_EQ(value_at<double>(r[0], 4), 60878.0);
  EXPECT_EQ(value_at<std::int32_t>(r[0], 12), 60878);
  EXPECT_EQ(value_at<std::int32_t>(r[0], 16), 1);  // iversion
  EXPECT_EQ(value_at<std::int32_t>(r[0], 20), 690706);
  EXPECT_EQ(r[1], "FT:Phantom format, unit test" + std::string(100 - 28, ' '));
  EXPECT_EQ(value_at<std::int32_t>(r[2], 0), 2);  // default int: npartoftype twice
  EXPECT_EQ(r[3], "npartoftype     npartoftype     ");
  EXPECT_EQ(value_at<std::int32_t>(r[4], 4), 0);
  for (int k = 5; k <= 8; ++k) EXPECT_EQ(value_at<std::int32_t>(r[k], 0), 0) << "int*1 to int*8";
  EXPECT_EQ(r[10], "time            ");
  EXPECT_EQ(value_at<double>(r[11], 0), 0.5);
  EXPECT_EQ(value_at<std::int32_t>(r[12], 0), 0);  // real*4
  EXPECT_EQ(r[14], "udist           ");
  EXPECT_EQ(value_at<double>(r[15], 0), 1.5e13);
  EXPECT_EQ(value_at<std::int32_t>(r[16], 0), 2);  // blocks: particles, sinks
  ASSERT_EQ(r[17].size(), 8u + 8 * 4);
  EXPECT_EQ(value_at<std::int64_t>(r[17], 0), 2);
  const std::int32_t counts[8] = {0, 1, 0, 0, 0, 1, 1, 0};
  for (int k = 0; k < 8; ++k) EXPECT_EQ(value_at<std::int32_t>(r[17], 8 + 4 * k), counts[k]) << "type " << k;
  EXPECT_EQ(value_at<std::int64_t>(r[18], 0), 0);  // no sinks
  // arrays by type: int*1, default real, real*4, whatever the order they were given in
  EXPECT_EQ(r[19], "itype           ");
  EXPECT_EQ(r[20], std::string("\x01\x07", 2));
  EXPECT_EQ(r[21], "x               ");
  EXPECT_EQ(value_at<double>(r[22], 8), 2.0);
  EXPECT_EQ(r[23], "h               ");
  EXPECT_EQ(value_at<float>(r[24], 4), 0.5f);
}

TEST(PhantomDump, SettingAHeaderTagAgainReplacesItsValues) {
  PhantomDump d = small_dump();
  d.header_int("npartoftype", {1, 1, 0});
  const auto r = records_of(d.encode());
  EXPECT_EQ(value_at<std::int32_t>(r[2], 0), 3);
}

TEST(PhantomDump, RejectsWhatTheFormatCannotHold) {
  EXPECT_THROW(PhantomDump("no code name"), std::invalid_argument);
  EXPECT_THROW(PhantomDump("Phantom" + std::string(91, 'x')), std::invalid_argument);
  PhantomDump d = small_dump();
  EXPECT_THROW(d.real_array("y", {1.0}), std::invalid_argument);  // not the particle count
  EXPECT_THROW(d.header_real("a_tag_of_17_chars", {1.0}), std::invalid_argument);
}
