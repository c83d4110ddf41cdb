// Rotation profiles (core/measures/RotationProfile.hpp): a plateau at the chain's p/q across an island of the six,
// the points' measures equal to single-orbit ones, the CSV, and the exports of indicator maps
// (core/measures/MeasureExport.hpp).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/io/Npy.hpp"
#include "core/measures/MeasureExport.hpp"
#include "core/measures/RotationProfile.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/view/ViewExport.hpp"

namespace archipelago {
namespace {

const MapParameters kBox{0.1, -0.8, 0.5};

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(RotationProfile, CrossesAnIslandOfTheSixOnThePlateauOneSixth) {
  // A horizontal segment through the elliptic period-6 orbit's member (§5: the six islands around the centre).
  PeriodicOrbitSearch s;
  s.period = 6;
  s.near = {0.0509L, 0.0974L};
  s.stableOnly = true;
  const PhysicalPoint p = findPeriodicOrbit(0.1L, s).points[0];
  RotationProfileRequest r;
  r.measure.map = kBox;
  r.measure.iterations = 3000;
  r.from = {p.x - 0.04L, p.y};
  r.to = {p.x + 0.04L, p.y};
  r.points = 41;
  const RotationProfile profile = computeRotationProfile(r);
  ASSERT_EQ(profile.points.size(), 41u);
  EXPECT_FALSE(profile.cancelled);
  const RotationProfilePoint& middle = profile.points[20];  // at the island's centre
  EXPECT_EQ(middle.measure.verdict, OrbitVerdict::Regular);
  ASSERT_TRUE(middle.rational.has_value());
  EXPECT_EQ(*middle.rational, (Rational{1, 6}));
  // Every point is measured as a single orbit (the Rotation indicator), in the same order.
  MeasureSettings settings = r.measure;
  settings.kind = IndicatorKind::Rotation;
  const OrbitMeasurer measurer(settings);
  std::size_t sixth = 0;
  for (const RotationProfilePoint& q : profile.points) {
    const OrbitMeasure m = measurer.measure(q.start);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(q.measure.value), std::bit_cast<std::uint64_t>(m.value));
    EXPECT_EQ(q.measure.verdict, m.verdict);
    sixth += q.rational == Rational{1, 6};
  }
  EXPECT_GE(sixth, 5u);  // a plateau, not a point
  EXPECT_LT(sixth, 41u);  // the segment leaves the island
}

TEST(RotationProfile, WritesACsvThatReadsBack) {
  RotationProfileRequest r;
  r.measure.map = kBox;
  r.measure.iterations = 500;
  r.from = {-0.31L, 0};
  r.to = {0.2L, 0.1L};
  r.points = 9;
  const RotationProfile profile = computeRotationProfile(r);
  const std::string path = ::testing::TempDir() + "/archipelago_profile.csv";
  writeRotationProfileCsv(path, r, profile);
  std::istringstream in(readFile(path));
  std::string line;
  std::size_t comments = 0, rows = 0;
  while (std::getline(in, line)) {
    if (line.rfind("#", 0) == 0) {
      ++comments;
      continue;
    }
    if (line == "index,x,y,rotation,digits,verdict,rational") continue;
    const std::size_t c1 = line.find(','), c2 = line.find(',', c1 + 1), c3 = line.find(',', c2 + 1),
                      c4 = line.find(',', c3 + 1);
    const RotationProfilePoint& p = profile.points[rows];
    const std::string rotation = line.substr(c3 + 1, c4 - c3 - 1);
    if (p.measure.verdict == OrbitVerdict::Regular) {
      EXPECT_EQ(std::strtod(rotation.c_str(), nullptr), p.measure.value);  // 17 digits: the same double
    } else {
      EXPECT_TRUE(rotation.empty());
    }
    ++rows;
  }
  EXPECT_EQ(rows, 9u);
  EXPECT_GE(comments, 8u);
  std::filesystem::remove(path);
  EXPECT_THROW(writeRotationProfileCsv("/nonexistent-dir/p.csv", r, profile), std::runtime_error);
}

TEST(RotationProfile, RejectsInvalidRequests) {
  RotationProfileRequest r;
  r.measure.map = kBox;
  r.from = {-0.3L, 0};
  r.to = {0.6L, 0};  // x ≥ xmax
  EXPECT_TRUE(validationError(r));
  r.to = {0.2L, std::nanl("")};
  EXPECT_TRUE(validationError(r));
  r.to = {0.2L, 0};
  EXPECT_FALSE(validationError(r));
  r.points = 0;
  EXPECT_TRUE(validationError(r));
  r.points = 10;
  r.maxDenominator = 0;
  EXPECT_TRUE(validationError(r));
}

TEST(MeasureExport, NpyValuesVerdictsAndSidecar) {
  IndicatorRequest r;
  r.measure.map = kBox;
  r.measure.kind = IndicatorKind::Rotation;
  r.measure.iterations = 200;
  r.width = 5;
  r.height = 3;
  const IndicatorResult result = computeIndicatorMap(r);
  const std::string dir = ::testing::TempDir();
  const std::string path = dir + "/archipelago_indicator.npy", verdicts = dir + "/archipelago_indicator_v.npy";
  exportIndicatorNpy(path, r, result, verdicts);
  const std::string bytes = readFile(path), header = npyHeader("<f8", 3, 5);
  ASSERT_EQ(bytes.size(), header.size() + 15 * 8);
  EXPECT_EQ(bytes.substr(0, header.size()), header);
  for (std::size_t i = 0; i < 15; ++i) {
    std::uint64_t v = 0;
    for (int b = 7; b >= 0; --b) v = (v << 8) | static_cast<unsigned char>(bytes[header.size() + 8 * i + static_cast<std::size_t>(b)]);
    EXPECT_EQ(v, std::bit_cast<std::uint64_t>(result.raster.values[i]));  // NaN where there is no number
  }
  const std::string codes = readFile(verdicts);
  EXPECT_EQ(codes.size(), npyHeader("<u4", 3, 5).size() + 15 * 4);
  EXPECT_EQ(static_cast<unsigned char>(codes[npyHeader("<u4", 3, 5).size()]),
            static_cast<unsigned char>(result.raster.verdicts[0]));
  const auto j = nlohmann::json::parse(readFile(sidecarPath(path)));
  EXPECT_EQ(j["kind"], "rotation");
  EXPECT_EQ(j["shape"][0], 3);
  EXPECT_EQ(j["shape"][1], 5);
  EXPECT_EQ(j["map"]["coefficients"]["A"], 2927339757790823);
  EXPECT_EQ(j["request"]["iterations"], 200);
  EXPECT_EQ(j["request"]["steps_per_orbit"], 400);
  EXPECT_EQ(j["verdicts"]["file"], "archipelago_indicator_v.npy");
  std::size_t counted = 0;
  for (const auto& [name, count] : j["verdicts"]["counts"].items()) counted += count.get<std::size_t>();
  EXPECT_EQ(counted, 15u);
  EXPECT_EQ(j["verdicts"]["codes"]["4"], "escaping");
  for (const std::string& f : {path, verdicts, sidecarPath(path)}) std::filesystem::remove(f);
  EXPECT_THROW(exportIndicatorNpy("/nonexistent-dir/i.npy", r, result), std::runtime_error);
}

TEST(MeasureExport, ColoursPixelsWithoutANumberByTheirVerdict) {
  IndicatorRaster raster;
  raster.width = 3;
  raster.height = 1;
  raster.kind = IndicatorKind::Rotation;
  raster.values = {0.18, std::nan(""), std::nan("")};
  raster.digits = {14, 2, 3};
  raster.verdicts = {OrbitVerdict::Regular, OrbitVerdict::Chaotic, OrbitVerdict::Escaping};
  const RasterImage image = colourizeIndicator(raster, ColourMapName::Viridis);
  ASSERT_EQ(image.rgb.size(), 9u);
  EXPECT_EQ((Rgb{image.rgb[3], image.rgb[4], image.rgb[5]}), kChaoticColour);
  EXPECT_EQ((Rgb{image.rgb[6], image.rgb[7], image.rgb[8]}), kEscapingColour);
  EXPECT_NE((Rgb{image.rgb[0], image.rgb[1], image.rgb[2]}), (Rgb{0, 0, 0}));
}

}  // namespace
}  // namespace archipelago
