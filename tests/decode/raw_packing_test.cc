// Raw pixel packing: the published bit layouts, exact round trips on random data of every length, and size checks.

#include "lfsp/decode/raw_packing.h"

#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "lfsp/core/error.h"

namespace lfsp::decode {
namespace {

std::vector<std::uint16_t> RandomPixels(std::size_t n, RawPacking packing, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> value(0, MaxPixelValue(packing));
  std::vector<std::uint16_t> pixels(n);
  for (auto& p : pixels) p = static_cast<std::uint16_t>(value(rng));
  return pixels;
}

constexpr RawPacking kAllPackings[] = {RawPacking::kBits12BigEndian, RawPacking::kBits10Illum,
                                       RawPacking::kBits16LittleEndian};

TEST(RawPacking, F01TwelveBitLayoutMatchesTheReference) {
  // lytro-format.md: FFF,000 -> FF F0 00; p0 = b0<<4 | b1>>4, p1 = (b1&0x0F)<<8 | b2.
  const std::vector<std::uint16_t> pixels = {0xFFF, 0x000, 0xABC, 0x123};
  const std::vector<std::uint8_t> expected = {0xFF, 0xF0, 0x00, 0xAB, 0xC1, 0x23};
  EXPECT_EQ(PackRaw(RawPacking::kBits12BigEndian, pixels, "test"), expected);
  EXPECT_EQ(UnpackRaw(RawPacking::kBits12BigEndian, expected, 4, "test"), pixels);
}

TEST(RawPacking, IllumTenBitLayoutIsFourMsbBytesThenOneLsbByte) {
  // p_i = b_i<<2 | (b4 >> 2i)&3.  1023 = 0xFF<<2|3, 0, 512 = 0x80<<2|0, 6 = 0x01<<2|2.
  const std::vector<std::uint16_t> pixels = {1023, 0, 512, 6};
  const std::vector<std::uint8_t> expected = {0xFF, 0x00, 0x80, 0x01, 0b10'00'00'11};
  EXPECT_EQ(PackRaw(RawPacking::kBits10Illum, pixels, "test"), expected);
  EXPECT_EQ(UnpackRaw(RawPacking::kBits10Illum, expected, 4, "test"), pixels);
}

TEST(RawPacking, SixteenBitIsLittleEndian) {
  const std::vector<std::uint16_t> pixels = {0x1234, 0xFFFF};
  const std::vector<std::uint8_t> expected = {0x34, 0x12, 0xFF, 0xFF};
  EXPECT_EQ(PackRaw(RawPacking::kBits16LittleEndian, pixels, "test"), expected);
  EXPECT_EQ(UnpackRaw(RawPacking::kBits16LittleEndian, expected, 2, "test"), pixels);
}

TEST(RawPacking, RealSensorBufferSizes) {
  // The component sizes of real files (lytro-format.md §1.3).
  EXPECT_EQ(PackedByteCount(RawPacking::kBits12BigEndian, 3280u * 3280u), 16'137'600u);
  EXPECT_EQ(PackedByteCount(RawPacking::kBits10Illum, 7728u * 5368u), 51'854'880u);
  EXPECT_EQ(PackedByteCount(RawPacking::kBits16LittleEndian, 7u * 5u), 70u);
}

TEST(RawPacking, TrailingPartialGroupIsPaddedToAWholeGroup) {
  EXPECT_EQ(PackedByteCount(RawPacking::kBits12BigEndian, 3), 6u);  // 2 groups of 3 bytes
  EXPECT_EQ(PackedByteCount(RawPacking::kBits10Illum, 5), 10u);     // 2 groups of 5 bytes
  EXPECT_EQ(PackedByteCount(RawPacking::kBits10Illum, 0), 0u);
  // The missing pixels are packed as 0.
  const auto packed = PackRaw(RawPacking::kBits10Illum, std::vector<std::uint16_t>{1023}, "test");
  EXPECT_EQ(packed, (std::vector<std::uint8_t>{0xFF, 0, 0, 0, 0x03}));
}

TEST(RawPacking, RoundTripIsExactForRandomDataOfEveryLength) {
  for (const RawPacking packing : kAllPackings) {
    for (std::size_t n = 0; n <= 41; ++n) {
      const auto pixels = RandomPixels(n, packing, static_cast<std::uint32_t>(n));
      const auto packed = PackRaw(packing, pixels, "test");
      ASSERT_EQ(packed.size(), PackedByteCount(packing, n));
      EXPECT_EQ(UnpackRaw(packing, packed, n, "test"), pixels) << ToString(packing) << " n=" << n;
    }
  }
}

TEST(RawPacking, OddWidthImagesRoundTripAsOneContinuousStream) {
  // Lytro rows are not padded: a 7x5 (or 1001x3) image is packed as 35 (3003) consecutive pixels.
  for (const RawPacking packing : kAllPackings) {
    for (const auto& [width, height] : {std::pair{7, 5}, std::pair{1001, 3}, std::pair{3, 1}}) {
      const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
      const auto pixels = RandomPixels(n, packing, 7u * static_cast<std::uint32_t>(n));
      const auto packed = PackRaw(packing, pixels, "test");
      const RawImage image = UnpackRawImage(packing, packed, width, height, "test");
      ASSERT_EQ(image.width, width);
      ASSERT_EQ(image.height, height);
      EXPECT_EQ(image.pixels, pixels);
      EXPECT_EQ(image.at(height - 1, width - 1), pixels.back());
    }
  }
}

TEST(RawPacking, LargeBufferRoundTripUsesEveryValue) {
  // Every 10- and 12-bit value appears (parallel path with many groups).
  for (const RawPacking packing : {RawPacking::kBits12BigEndian, RawPacking::kBits10Illum}) {
    std::vector<std::uint16_t> pixels(1'000'003);
    for (std::size_t i = 0; i < pixels.size(); ++i) {
      pixels[i] = static_cast<std::uint16_t>((i * 2654435761u) % (MaxPixelValue(packing) + 1u));
    }
    EXPECT_EQ(UnpackRaw(packing, PackRaw(packing, pixels, "test"), pixels.size(), "test"), pixels);
  }
}

// The streamed sum (a white image's mean level) over more than one block and a partial last group equals the sum
// over the unpacked pixels; a stream that ends early is an error naming the source.
TEST(RawPacking, StreamedSumOfLevelsEqualsTheUnpackedSum) {
  const std::size_t n = (std::size_t{1} << 16) * 2 + 3;  // two whole blocks and a partial group
  for (const RawPacking packing : kAllPackings) {
    const std::vector<std::uint16_t> pixels = RandomPixels(n, packing, 5);
    const std::vector<std::uint8_t> packed = PackRaw(packing, pixels, "test");
    std::uint64_t expected = 0;
    for (const std::uint16_t p : pixels) expected += p;
    std::istringstream in(std::string(packed.begin(), packed.end()));
    EXPECT_EQ(SumPackedLevels(packing, in, n, "test"), expected) << ToString(packing);
    std::istringstream short_stream(std::string(packed.begin(), packed.end() - 1));
    try {
      (void)SumPackedLevels(packing, short_stream, n, "white.RAW");
      ADD_FAILURE() << "a short stream was summed";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("white.RAW: raw data ends after"), std::string::npos) << error.what();
    }
  }
}

TEST(RawPacking, WrongBufferSizeNamesSourceAndByteCounts) {
  const std::vector<std::uint8_t> bytes(100);
  try {
    (void)UnpackRaw(RawPacking::kBits10Illum, bytes, 81, "capture.lfr raw image");  // 81 px need 105 B
    FAIL() << "expected lfsp::Error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("capture.lfr raw image"), std::string::npos) << message;
    EXPECT_NE(message.find("100 bytes"), std::string::npos) << message;
    EXPECT_NE(message.find("expected 105"), std::string::npos) << message;
  } catch (...) {
    FAIL() << "wrong exception type";
  }
}

TEST(RawPacking, WrongSizesThrow) {
  const std::vector<std::uint8_t> bytes(99);
  EXPECT_THROW((void)UnpackRaw(RawPacking::kBits10Illum, bytes, 80, "x"), Error);         // needs 100
  EXPECT_THROW((void)UnpackRaw(RawPacking::kBits12BigEndian, bytes, 80, "x"), Error);     // needs 120
  EXPECT_THROW((void)UnpackRaw(RawPacking::kBits16LittleEndian, bytes, 49, "x"), Error);  // needs 98
  EXPECT_THROW((void)UnpackRawImage(RawPacking::kBits10Illum, bytes, 0, 5, "x"), Error);
  EXPECT_THROW((void)UnpackRawImage(RawPacking::kBits10Illum, bytes, 4, -1, "x"), Error);
  // A hostile pixel count must fail on the size check, not try to allocate it.
  EXPECT_THROW((void)UnpackRaw(RawPacking::kBits16LittleEndian, bytes, std::size_t{1} << 40, "x"), Error);
}

TEST(RawPacking, ValuesAboveTheBitDepthAreRejectedWhenPacking) {
  EXPECT_THROW((void)PackRaw(RawPacking::kBits10Illum, std::vector<std::uint16_t>{0, 1024}, "white.RAW"), Error);
  EXPECT_THROW((void)PackRaw(RawPacking::kBits12BigEndian, std::vector<std::uint16_t>{4096}, "x"), Error);
  EXPECT_NO_THROW((void)PackRaw(RawPacking::kBits16LittleEndian, std::vector<std::uint16_t>{65535}, "x"));
}

}  // namespace
}  // namespace lfsp::decode
