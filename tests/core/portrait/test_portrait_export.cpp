// NumPy .npy writing and the JSON sidecar.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/portrait/PortraitExport.hpp"

namespace archipelago {
namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(PortraitExport, NpyHeaderFollowsFormatVersion1) {
  const std::string h = npyHeader("<u8", 3, 5);
  ASSERT_EQ(h.size() % 64, 0u);
  EXPECT_EQ(h.substr(0, 6), "\x93NUMPY");
  EXPECT_EQ(h[6], 1);
  EXPECT_EQ(h[7], 0);
  const std::size_t len = static_cast<unsigned char>(h[8]) | (static_cast<std::size_t>(static_cast<unsigned char>(h[9])) << 8);
  EXPECT_EQ(len + 10, h.size());
  EXPECT_EQ(h.back(), '\n');
  EXPECT_NE(h.find("{'descr': '<u8', 'fortran_order': False, 'shape': (3, 5), }"), std::string::npos);
}

TEST(PortraitExport, WritesLittleEndianDataAndSidecar) {
  const std::string dir = ::testing::TempDir();
  const std::string path = dir + "/archipelago_portrait_test.npy";
  PortraitRequest req;
  req.width = 3;
  req.height = 2;
  req.points = 1000;
  req.orbits = 8;
  const PortraitRaster raster = renderPortrait(req).raster;
  exportPortraitNpy(path, req, raster);
  const std::string bytes = readFile(path);
  const std::string header = npyHeader("<u8", 2, 3);
  ASSERT_EQ(bytes.size(), header.size() + 6 * 8);
  EXPECT_EQ(bytes.substr(0, header.size()), header);
  for (std::size_t i = 0; i < 6; ++i) {
    std::uint64_t v = 0;
    for (int b = 7; b >= 0; --b) v = (v << 8) | static_cast<unsigned char>(bytes[header.size() + 8 * i + static_cast<std::size_t>(b)]);
    EXPECT_EQ(v, raster.counts[i]);
  }
  EXPECT_EQ(sidecarPath(path), dir + "/archipelago_portrait_test.json");
  const auto j = nlohmann::json::parse(readFile(sidecarPath(path)));
  EXPECT_EQ(j["mode"], "density");
  EXPECT_EQ(j["shape"][0], 2);
  EXPECT_EQ(j["shape"][1], 3);
  EXPECT_EQ(j["map"]["coefficients"]["A"], 2927339757790823);  // the exact map (test_fixed_point_map.cpp)
  EXPECT_EQ(j["viewport"]["centre_unit"]["X"], FixedPointMap::kHalf);
  EXPECT_EQ(j["counts"]["points_iterated"], 1000);
  EXPECT_EQ(j["counts"]["points_binned"], raster.pointsBinned);
  std::filesystem::remove(path);
  std::filesystem::remove(sidecarPath(path));
}

TEST(PortraitExport, FloatAndLabelArrays) {
  const std::string path = ::testing::TempDir() + "/archipelago_f8.npy";
  writeNpy(path, std::vector<double>{1.5, -2.0}, 1, 2);
  const std::string bytes = readFile(path);
  const std::string header = npyHeader("<f8", 1, 2);
  ASSERT_EQ(bytes.size(), header.size() + 16);
  // 1.5 = 0x3FF8000000000000, little-endian: the last byte is 0x3F.
  EXPECT_EQ(static_cast<unsigned char>(bytes[header.size() + 7]), 0x3F);
  EXPECT_EQ(static_cast<unsigned char>(bytes[header.size() + 6]), 0xF8);
  EXPECT_THROW(writeNpy(path, std::vector<std::uint32_t>{1, 2, 3}, 2, 2), std::invalid_argument);
  EXPECT_THROW(writeNpy("/nonexistent-dir/x.npy", std::vector<std::uint32_t>{1}, 1, 1), std::runtime_error);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace archipelago
