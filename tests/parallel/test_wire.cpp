// The farm's byte codec (wire.hpp): every primitive, string and vector of doubles comes back
// bit for bit, in little-endian fixed widths, and a truncated or malformed byte string is
// refused with WireError before anything is read or allocated.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "vibromap/parallel/wire.hpp"

using namespace vibromap;

namespace {
std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }
}  // namespace

TEST(Wire, IntegersRoundTripAtTheirExtremes) {
  ByteWriter w;
  w.put(std::numeric_limits<std::int8_t>::min());
  w.put(std::numeric_limits<std::uint8_t>::max());
  w.put(std::numeric_limits<std::int32_t>::min());
  w.put(std::numeric_limits<std::uint32_t>::max());
  w.put(std::numeric_limits<std::int64_t>::min());
  w.put(std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(w.size(), 1u + 1 + 4 + 4 + 8 + 8);
  ByteReader r(w.bytes());
  EXPECT_EQ(r.get<std::int8_t>(), std::numeric_limits<std::int8_t>::min());
  EXPECT_EQ(r.get<std::uint8_t>(), std::numeric_limits<std::uint8_t>::max());
  EXPECT_EQ(r.get<std::int32_t>(), std::numeric_limits<std::int32_t>::min());
  EXPECT_EQ(r.get<std::uint32_t>(), std::numeric_limits<std::uint32_t>::max());
  EXPECT_EQ(r.get<std::int64_t>(), std::numeric_limits<std::int64_t>::min());
  EXPECT_EQ(r.get<std::uint64_t>(), std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(r.remaining(), 0u);
}

TEST(Wire, LayoutIsLittleEndian) {
  ByteWriter w;
  w.put(std::uint32_t{0x04030201});
  ASSERT_EQ(w.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(w.bytes()[static_cast<std::size_t>(i)], static_cast<char>(i + 1));
}

TEST(Wire, DoublesKeepEveryBit) {
  const std::vector<double> values = {0.0, -0.0, 1.0 / 3.0, std::numeric_limits<double>::denorm_min(),
                                      std::numeric_limits<double>::max(), -std::numeric_limits<double>::infinity(),
                                      std::numeric_limits<double>::quiet_NaN(),
                                      std::bit_cast<double>(std::uint64_t{0x7ff0000000000123}),  // a signalling NaN's payload
                                      std::bit_cast<double>(std::uint64_t{0xfff8000000000001})};
  ByteWriter w;
  for (double x : values) w.put(x);
  w.put(values);
  ByteReader r(w.bytes());
  for (double x : values) EXPECT_EQ(bits(r.get<double>()), bits(x));
  const std::vector<double> back = r.get_doubles();
  ASSERT_EQ(back.size(), values.size());
  for (std::size_t i = 0; i < values.size(); ++i) EXPECT_EQ(bits(back[i]), bits(values[i]));
  EXPECT_EQ(r.remaining(), 0u);
}

TEST(Wire, StringsAndVectorsIncludingEmptyOnes) {
  const std::string with_nul("a\0b\xff", 4);
  ByteWriter w;
  w.put(std::string_view{});
  w.put(std::string_view(with_nul));
  w.put(std::vector<double>{});
  EXPECT_EQ(w.size(), 8u + 8 + 4 + 8);  // each a uint64 length, then the bytes
  ByteReader r(w.bytes());
  EXPECT_EQ(r.get_string(), "");
  EXPECT_EQ(r.get_string(), with_nul);
  EXPECT_TRUE(r.get_doubles().empty());
  EXPECT_EQ(r.remaining(), 0u);
}

TEST(Wire, TruncatedInputIsRefused) {
  ByteWriter w;
  w.put(std::int64_t{42});
  ByteReader r(w.bytes().data(), 7);
  EXPECT_THROW(r.get<std::int64_t>(), WireError);
  ByteReader empty(nullptr, 0);
  EXPECT_THROW(empty.get<std::int8_t>(), WireError);
}

TEST(Wire, LengthBeyondTheBytesLeftIsRefusedWithoutAllocating) {
  // A damaged length (2^62 doubles) must not be believed.
  ByteWriter w;
  w.put(std::uint64_t{1} << 62);
  w.put(1.0);
  ByteReader doubles(w.bytes());
  EXPECT_THROW(doubles.get_doubles(), WireError);
  ByteReader chars(w.bytes());
  EXPECT_THROW(chars.get_string(), WireError);
  // A string one byte longer than what follows it.
  ByteWriter s;
  s.put(std::uint64_t{4});
  s.put_bytes("abc", 3);
  ByteReader r(s.bytes());
  EXPECT_THROW(r.get_string(), WireError);
}
