// The PNG encoder's text chunks (issue 42: where an image came from): ASCII values as tEXt, others as iTXt, read
// back in order by readPngText; chunk layout and CRC checked against the PNG specification's bytes.
#include <gtest/gtest.h>

#include <stdexcept>

#include "core/io/Png.hpp"

using namespace archipelago::io;

namespace {
std::string chunkTypes(const std::vector<std::uint8_t>& png) {
  std::string types;
  for (std::size_t pos = 8; pos + 12 <= png.size();) {
    const std::size_t length = (std::size_t{png[pos]} << 24) | (std::size_t{png[pos + 1]} << 16) |
                               (std::size_t{png[pos + 2]} << 8) | png[pos + 3];
    types += std::string(reinterpret_cast<const char*>(&png[pos + 4]), 4) + " ";
    pos += length + 12;
  }
  return types;
}
}  // namespace

TEST(Png, TextChunksRoundTripInOrder) {
  const std::vector<std::uint8_t> rgb(2 * 3 * 3, 200);
  const PngText text = {{"Software", "archipelago 0.1.0"}, {"K", "0.1"}, {"Title", "Q\xE2\x88\x97 (UTF-8)"}};
  const auto png = encodePng(2, 3, rgb, text);
  EXPECT_EQ(chunkTypes(png), "IHDR tEXt tEXt iTXt IDAT IEND ");
  EXPECT_EQ(readPngText(png), text);
  // The first tEXt chunk byte for byte: length 26, "tEXt", "Software\0archipelago 0.1.0", then its CRC-32
  // (zlib's crc32 of "tEXtSoftware\0archipelago 0.1.0", computed with Python's zlib.crc32: 0x5C043579).
  const std::vector<std::uint8_t> first(png.begin() + 33, png.begin() + 33 + 4 + 4 + 26 + 4);
  std::vector<std::uint8_t> expected = {0, 0, 0, 26, 't', 'E', 'X', 't'};
  const std::string body = std::string("Software") + '\0' + "archipelago 0.1.0";
  expected.insert(expected.end(), body.begin(), body.end());
  expected.insert(expected.end(), {0x5C, 0x04, 0x35, 0x79});
  EXPECT_EQ(first, expected);
  EXPECT_TRUE(readPngText(encodePng(2, 3, rgb)).empty());
}

TEST(Png, BadKeywordsAndTruncatedFilesAreRefused) {
  const std::vector<std::uint8_t> rgb(3, 0);
  for (const std::string& key : {std::string(), std::string(80, 'k'), std::string(" K"), std::string("K "),
                                std::string("a  b"), std::string("K\n")})
    EXPECT_THROW((void)encodePng(1, 1, rgb, {{key, "v"}}), std::invalid_argument) << key;
  EXPECT_THROW((void)encodePng(1, 1, rgb, {{"K", std::string("a\0b", 3)}}), std::invalid_argument);
  auto png = encodePng(1, 1, rgb, {{"K", "0.1"}});
  png.resize(png.size() - 6);
  EXPECT_THROW((void)readPngText(png), std::invalid_argument);
  EXPECT_THROW((void)readPngText({1, 2, 3}), std::invalid_argument);
}
