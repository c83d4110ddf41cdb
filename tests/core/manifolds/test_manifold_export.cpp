// The files of core/manifolds (ManifoldExport.hpp): the CSV's header and columns, its pieces, atomic writing, the
// JSON's fields.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/manifolds/ManifoldExport.hpp"

namespace archipelago {
namespace {

TEST(ManifoldExport, CsvHasItsHeaderColumnsAndPieces) {
  ManifoldCurveRequest r;
  r.K = 0.1L;
  r.length = 30;
  const ManifoldCurve c = computeManifoldCurve(r);
  ASSERT_GT(c.pieces.size(), 1u);
  std::ostringstream out;
  writeManifoldCsv(out, r, c);
  std::istringstream in(out.str());
  std::string line;
  bool header = false;
  std::size_t rows = 0, pieces = 1;
  double lastS = -1;
  while (std::getline(in, line)) {
    if (line.rfind("# piece ", 0) == 0) {
      ++pieces;
      continue;
    }
    if (line[0] == '#') {
      EXPECT_FALSE(header) << "metadata after the column header: " << line;
      continue;
    }
    if (!header) {
      EXPECT_EQ(line, "s,x,y");
      header = true;
      continue;
    }
    double s = 0, x = 0, y = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf", &s, &x, &y), 3) << line;
    EXPECT_GE(s, lastS);
    lastS = s;
    ++rows;
  }
  EXPECT_EQ(rows, c.points);
  EXPECT_EQ(pieces, c.pieces.size());
  for (const char* key : {"# K: 0.1", "# branch: unstable", "# side: inward", "# length_requested: 30", "# map: Q in the plane"})
    EXPECT_NE(out.str().find(key), std::string::npos) << key;
}

TEST(ManifoldExport, CsvIsWrittenAtomically) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "archipelago_manifold_export_test";
  std::filesystem::create_directories(dir);
  ManifoldCurveRequest r;
  r.length = 1;
  writeManifoldCsv(dir / "m.csv", r, computeManifoldCurve(r));
  EXPECT_TRUE(std::filesystem::exists(dir / "m.csv"));
  for (const auto& entry : std::filesystem::directory_iterator(dir)) EXPECT_EQ(entry.path().filename(), "m.csv");
  EXPECT_THROW(writeManifoldCsv(dir / "missing" / "m.csv", r, computeManifoldCurve(r)), std::runtime_error);
  std::filesystem::remove_all(dir);
}

TEST(ManifoldExport, JsonCarriesBothMethodsAndTheZone) {
  TurnstileRequest r;
  r.K = 0.1L;
  const TurnstileFlux f = computeTurnstileFlux(r);
  const nlohmann::json j = nlohmann::json::parse(turnstileJson(r, f));
  EXPECT_EQ(j["homoclinic_points"].size(), 2u);
  EXPECT_NEAR(j["lobe_area"]["action"].get<double>(), j["lobe_area"]["polygon"].get<double>(), 1e-16);
  EXPECT_GT(j["lobe_area"]["agreeing_digits"].get<double>(), 13);
  EXPECT_GT(j["zone_area"]["action"].get<double>(), 0.5);
  EXPECT_EQ(j["lobe_area"]["action_text"].get<std::string>().substr(0, 12), "0.0038433893");
  EXPECT_EQ(quadText(quad(1) / 3, 10), "0.3333333333");
  EXPECT_EQ(quadText(-quad(12345) / 100, 6), "-123.450");
}

}  // namespace
}  // namespace archipelago
