// Where an output came from (issue 42): the program's version (project() in CMakeLists.txt), the commit it was
// built from, the map, and numbers written as the shortest text that reads back exactly.
#include <gtest/gtest.h>

#include <cstdlib>
#include <regex>
#include <string>

#include "core/provenance/Provenance.hpp"
#include "core/view/ViewExport.hpp"

using namespace archipelago;

TEST(Provenance, ProgramVersionAndCommit) {
  EXPECT_EQ(programVersion(), ARCHIPELAGO_VERSION);
  const std::string commit(programCommit());
  EXPECT_TRUE(std::regex_match(commit, std::regex("[0-9a-f]{12}(-dirty)?|unknown"))) << commit;
  EXPECT_EQ(programDescription(), std::string("archipelago ") + ARCHIPELAGO_VERSION + " (commit " + commit + ")");
  const Provenance p = programProvenance();
  ASSERT_EQ(p.fields.size(), 3u);
  EXPECT_EQ(*p.find("Software"), std::string("archipelago ") + ARCHIPELAGO_VERSION);
  EXPECT_EQ(*p.find("Version"), ARCHIPELAGO_VERSION);
  EXPECT_EQ(*p.find("Commit"), commit);
  EXPECT_EQ(p.find("K"), nullptr);
}

TEST(Provenance, MapAndViewAreExact) {
  const MapParameters map{0.05, -0.6, 0.4};
  Provenance p = mapProvenance(map);
  EXPECT_EQ(*p.find("K"), "0.05");
  EXPECT_EQ(*p.find("xmin"), "-0.6");
  EXPECT_EQ(*p.find("xmax"), "0.4");
  // A deep view's edges: long doubles that differ from their double roundings, read back exactly.
  const Viewport view = Viewport::fromPhysical(map, {-0.3L + 1e-13L, -0.3L + 3e-12L, 0.1L, 0.1L + 2e-12L});
  addView(p, map, view);
  const PhysicalRect b = view.physical(map);
  EXPECT_EQ(std::strtold(p.find("View x0")->c_str(), nullptr), b.x0);
  EXPECT_EQ(std::strtold(p.find("View x1")->c_str(), nullptr), b.x1);
  EXPECT_EQ(std::strtold(p.find("View y0")->c_str(), nullptr), b.y0);
  EXPECT_EQ(std::strtold(p.find("View y1")->c_str(), nullptr), b.y1);
  EXPECT_NE(b.x0, static_cast<long double>(static_cast<double>(b.x0)));  // the view needs the long double digits
  EXPECT_EQ(shortestDecimal(0.1L), "0.1");
  EXPECT_EQ(shortestDecimal(-2.5L), "-2.5");
}
