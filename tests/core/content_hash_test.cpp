// Content hashes: the canonical encoding separates what must differ and joins what must not.
#include "core/content_hash.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "core/error.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

TEST(ContentHash, KnownVectorOfTheLibrary) {
  // XXH3-128 of the empty input, from xxHash's own test vectors (xxhsum -H2 of an empty file).
  const ContentHash empty = hash_bytes({});
  EXPECT_EQ(empty.hex(), "99aa06d3014798d86001c324468d497f");
}

TEST(ContentHash, HexRoundTripsAndRejectsOtherText) {
  const ContentHash h = Hasher().text("road").digest();
  EXPECT_EQ(ContentHash::from_hex(h.hex()), h);
  EXPECT_THROW(ContentHash::from_hex("12"), Error);
  EXPECT_THROW(ContentHash::from_hex(std::string(32, 'g')), Error);
}

TEST(ContentHash, LengthPrefixesSeparateConcatenations) {
  EXPECT_NE(Hasher().text("ab").text("c").digest(), Hasher().text("a").text("bc").digest());
  EXPECT_NE(Hasher().points({{1, 2}}).points({}).digest(),
            Hasher().points({}).points({{1, 2}}).digest());
}

TEST(ContentHash, DoublesByValueWithOneZeroAndOneNaN) {
  EXPECT_EQ(Hasher().real(0.0).digest(), Hasher().real(-0.0).digest());
  EXPECT_EQ(Hasher().real(std::nan("1")).digest(),
            Hasher().real(std::numeric_limits<double>::quiet_NaN()).digest());
  EXPECT_NE(Hasher().real(1.0).digest(), Hasher().real(std::nextafter(1.0, 2.0)).digest());
}

TEST(ContentHash, FilesByBytesAndAbsenceIsDistinct) {
  test::TempDir dir;
  const auto a = dir.path() / "a.bin", b = dir.path() / "b.bin";
  std::ofstream(a, std::ios::binary) << "exemplar";
  std::ofstream(b, std::ios::binary) << "exemplar";
  EXPECT_EQ(hash_file(a), hash_file(b));  // the bytes, not the name
  std::ofstream(b, std::ios::binary) << "exemplaR";
  EXPECT_NE(hash_file(a), hash_file(b));
  EXPECT_NE(hash_file(dir.path() / "missing"), Hasher().bytes({}).digest());
  EXPECT_NE(hash_file(dir.path() / "missing"), hash_file(a));
}

TEST(ContentHash, CopiesContinueIndependently) {
  Hasher base;
  base.text("seed").u64(7);
  Hasher copy = base;
  copy.u64(1);
  EXPECT_EQ(base.digest(), Hasher().text("seed").u64(7).digest());
  EXPECT_EQ(copy.digest(), Hasher().text("seed").u64(7).u64(1).digest());
}

}  // namespace
}  // namespace tw
