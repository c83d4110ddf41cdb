// The atlas read back from its JSON (core/atlas/AtlasExport.hpp, atlasFromJson; issue 38, deliverable 3: a session
// keeps its atlas this way): atlasJson → atlasFromJson → atlasJson gives the same text for a hand-built tree, and
// truncated, edited, NaN, huge and negative documents are refused with a std::runtime_error naming the key — never
// a crash, never another exception.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "core/atlas/AtlasExport.hpp"
#include "core/io/BadFile.hpp"
#include "core/io/Json.hpp"

namespace archipelago {
namespace {

using ojson = nlohmann::ordered_json;

PeriodicOrbit orbitAt(PhysicalPoint p, int period, long double residue) {
  PeriodicOrbit o;
  o.K = 0.1L;
  o.period = period;
  o.points = {p};
  o.residue = residue;
  return o;
}

/// An island's area as computeAtlas() fills it: the proven circle's polygon area and convergence, and the interval
/// that holds the true area (issue 50).
void withInterval(AtlasNode& n, long double area, long double polygon, long double upper) {
  n.area = n.circleArea = area;
  n.polygonError = polygon;
  n.areaLower = area - polygon;
  n.areaUpper = upper;
  n.areaError = std::max(n.area - n.areaLower, n.areaUpper - n.area);
}

/// A small tree as computeAtlas() would fill it (its numbers doubles, as the JSON keeps them): the centre, the chain
/// of six with the 138-chain below it (its boundary not found), the chain of 13 (its flux refused, with a partner),
/// every flux found with a partner's digits all agreeing (infinity: null in the JSON).
Atlas handBuilt() {
  Atlas a;
  a.request.depth = 2;
  a.request.maxPeriod = 200;
  a.request.scanSteps = 0;
  a.cancelled = true;
  a.stopReason = "stopped";
  a.request.timeBudget = 600;
  a.seconds = 12.5;

  AtlasNode centre;
  centre.centre = {-0.31622776601683794, 0};
  centre.orbit = orbitAt(centre.centre, 1, 0.31622776601683794L);
  centre.scanRange = 0.63245553203367588;
  centre.boundaryFound = true;
  centre.boundaryPoint = {-0.0770813, 0};
  centre.boundaryRotation = 0.1668;
  centre.boundaryDigits = 14.25;
  centre.gap = 1.2e-9;
  withInterval(centre, 0.2391965, 2.2e-7, 0.2406);
  centre.areaPoints = 8192;
  centre.flux.found = true;
  centre.flux.flux = 3.843389e-3;
  centre.flux.zoneArea = 0.5135965;
  centre.flux.fluxDigits = std::numeric_limits<long double>::infinity();
  centre.flux.zoneDigits = 9.5;
  centre.flux.enclosedIslands = 0.2391965;
  centre.flux.layerArea = centre.flux.zoneArea - centre.flux.enclosedIslands;  // the reader checks both (issue 54)
  centre.flux.residence = static_cast<double>(centre.flux.layerArea / centre.flux.flux);
  centre.internal = {{2, 11}, {3, 17}};
  centre.children = {1, 2};
  centre.measured = true;

  AtlasNode six;
  six.parent = 0;
  six.level = 1;
  six.period = 6;
  six.aboutParent = Rational{1, 6};
  six.centre = {0.0157, 0};
  six.orbit = orbitAt(six.centre, 6, 0.25);
  six.sense = -1;
  six.scanRange = 0.16;
  six.boundaryFound = true;
  six.boundaryPoint = {0.05, 0};
  six.boundaryRotation = 0.0912;
  six.boundaryDigits = 13.5;
  six.gap = 3e-10;
  withInterval(six, 6.704824e-3, 2.4e-9, 7.1e-3);
  six.areaPoints = 8192;
  six.flux.found = true;
  six.flux.partner = orbitAt({0.2, -0.1}, 6, -0.5);
  six.flux.flux = 2.040311e-5;
  six.flux.zoneArea = 0.3112;
  six.flux.fluxDigits = 8.25;
  six.flux.zoneDigits = 7.5;
  six.flux.enclosedIslands = 0.2391965;
  six.flux.layerArea = six.flux.zoneArea - six.flux.enclosedIslands;
  six.flux.residence = static_cast<double>(six.flux.layerArea / six.flux.flux);
  six.children = {3};
  six.measured = true;

  AtlasNode thirteen;
  thirteen.parent = 0;
  thirteen.level = 1;
  thirteen.period = 13;
  thirteen.aboutParent = Rational{2, 13};
  thirteen.centre = {0.11, 0.0925};
  thirteen.onS1 = true;
  thirteen.orbit = orbitAt(thirteen.centre, 13, std::numeric_limits<long double>::quiet_NaN());
  thirteen.scanRange = 0.02;
  thirteen.boundaryFound = true;
  thirteen.boundaryPoint = {0.111, 0.0931};
  thirteen.boundaryRotation = 0.03;
  thirteen.boundaryDigits = 12;
  withInterval(thirteen, 2.822e-5, 8e-12, 6e-5);
  thirteen.areaPoints = 8192;
  thirteen.flux.failure = "lobe area 0.478 is not small against the area it encloses, 0.516";
  thirteen.flux.partner = orbitAt({0.12, 0.09}, 13, -0.01);
  thirteen.note = "not followed: area below 1e-4";

  AtlasNode chain138;
  chain138.parent = 1;
  chain138.level = 2;
  chain138.period = 138;
  chain138.aboutParent = Rational{2, 23};
  chain138.centre = {0.09437, 0.09109};
  chain138.onS1 = true;
  chain138.orbit = orbitAt(chain138.centre, 138, 0.125);
  chain138.boundaryFailure = "no invariant circle about the centre within the scan's first step";
  chain138.flux.failure = "no hyperbolic partner found between the islands";
  chain138.note = "not followed: no boundary circle";

  a.nodes = {centre, six, thirteen, chain138};
  return a;
}

/// atlasFromJson() of `text` must throw std::runtime_error (and nothing else); returns its message.
std::string refusal(const std::string& text) {
  try {
    (void)atlasFromJson(text);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted:\n" << text.substr(0, 400);
  return {};
}

/// `j` signed again after an edit (io::jsonChecksum, as the writer signs): the edit then meets the rule it tests.
std::string signedAgain(ojson j) {
  if (!j.is_object()) return j.dump(2);
  j.erase("checksum");
  if (j.contains("format_version")) j["checksum"] = io::jsonChecksum(nlohmann::json::parse(j.dump()));
  return j.dump(2);
}

std::string edited(const std::function<void(ojson&)>& edit) {
  ojson j = ojson::parse(atlasJson(handBuilt()));
  edit(j);
  return signedAgain(j);
}

TEST(AtlasJson, ReadsBackToTheSameText) {
  const Atlas a = handBuilt();
  const std::string text = atlasJson(a);
  const Atlas b = atlasFromJson(text);
  EXPECT_EQ(atlasJson(b), text);
  ASSERT_EQ(b.nodes.size(), a.nodes.size());
  EXPECT_TRUE(b.cancelled);
  EXPECT_EQ(b.stopReason, "stopped");
  EXPECT_EQ(b.request.timeBudget, 600);
  EXPECT_EQ(b.seconds, 12.5);
  EXPECT_EQ(b.request.map, a.request.map);
  EXPECT_EQ(b.request.depth, 2);
  EXPECT_EQ(b.request.maxPeriod, 200u);
  EXPECT_EQ(atlasPath(b, 3), "6 > 138");
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const AtlasNode& x = a.nodes[i];
    const AtlasNode& y = b.nodes[i];
    EXPECT_EQ(y.parent, x.parent);
    EXPECT_EQ(y.level, x.level);
    EXPECT_EQ(y.period, x.period);
    EXPECT_EQ(y.aboutParent, x.aboutParent);
    EXPECT_EQ(y.children, x.children);
    EXPECT_EQ(y.measured, x.measured);
    EXPECT_EQ(y.internal, x.internal);
    EXPECT_EQ(y.centre.x, x.centre.x);
    EXPECT_EQ(y.boundaryFound, x.boundaryFound);
    EXPECT_EQ(y.boundaryFailure, x.boundaryFailure);
    EXPECT_EQ(y.area, x.area);
    EXPECT_EQ(y.flux.found, x.flux.found);
    EXPECT_EQ(y.flux.failure, x.flux.failure);
    EXPECT_EQ(y.flux.partner.has_value(), x.flux.partner.has_value());
    EXPECT_EQ(y.note, x.note);
    // The orbit the JSON keeps: its centre, period and residue (refinePeriodicOrbit finds the rest).
    ASSERT_EQ(y.orbit.points.size(), 1u);
    EXPECT_EQ(y.orbit.period, static_cast<int>(x.period));
    EXPECT_EQ(y.orbit.points[0].y, x.centre.y);
  }
  EXPECT_TRUE(std::isinf(b.nodes[0].flux.fluxDigits));  // null: every digit agrees
  EXPECT_TRUE(std::isnan(b.nodes[2].orbit.residue));    // null: no residue
  EXPECT_EQ(b.nodes[1].flux.partner->points[0].x, static_cast<long double>(0.2));
  EXPECT_EQ(b.nodes[1].flux.partner->period, 6);
}

TEST(AtlasJson, AnAtlasOfTheCentreAloneReadsBack) {
  Atlas a = handBuilt();
  a.nodes.resize(1);
  a.nodes[0].children.clear();
  const std::string text = atlasJson(a);
  EXPECT_EQ(atlasJson(atlasFromJson(text)), text);
}

TEST(AtlasJson, RefusesTruncatedDocuments) {
  const std::string text = atlasJson(handBuilt());
  for (std::size_t n = 0; n < text.size() - 2; n += 37) EXPECT_FALSE(refusal(text.substr(0, n)).empty()) << n;
  EXPECT_NE(refusal("").find("JSON"), std::string::npos);
  EXPECT_FALSE(refusal("[]").empty());
  EXPECT_FALSE(refusal("\"archipelago atlas\"").empty());
  EXPECT_FALSE(refusal("{}").empty());
}

TEST(AtlasJson, RefusesNaNInfinitiesAndNulls) {
  std::string text = atlasJson(handBuilt());
  const std::string area = "\"area\": 0.006704824";
  ASSERT_NE(text.find(area), std::string::npos);
  for (const char* bad : {"NaN", "nan", "Infinity", "-Infinity", "1e999", "null", "\"0.0067\""}) {
    std::string t = text;
    t.replace(t.find(area), area.size(), std::string("\"area\": ") + bad);
    EXPECT_FALSE(refusal(t).empty()) << bad;
  }
  EXPECT_NE(refusal(edited([](ojson& j) { j["nodes"][1]["centre"][0] = nullptr; })).find("nodes[1].centre[0]"),
            std::string::npos);
  EXPECT_NE(refusal(edited([](ojson& j) { j["seconds"] = nullptr; })).find("seconds"), std::string::npos);
  EXPECT_NE(refusal(edited([](ojson& j) { j["nodes"][0]["flux"]["residence"] = nullptr; })).find("residence"),
            std::string::npos);
}

TEST(AtlasJson, RefusesHugeAndNegativeValuesNamingTheKey) {
  const auto says = [](const std::function<void(ojson&)>& edit, const std::string& key) {
    const std::string message = refusal(edited(edit));
    EXPECT_NE(message.find(key), std::string::npos) << message;
  };
  says([](ojson& j) { j["nodes"][1]["period"] = 1e300; }, "nodes[1].period");
  says([](ojson& j) { j["nodes"][1]["period"] = std::uint64_t{1} << 62; }, "nodes[1].period");
  says([](ojson& j) { j["nodes"][1]["period"] = -6; }, "nodes[1].period");
  says([](ojson& j) { j["nodes"][1]["area"] = -1e-3; }, "nodes[1].area");
  says([](ojson& j) { j["nodes"][1]["area_error"] = -1; }, "nodes[1].area_error");
  says([](ojson& j) { j["nodes"][1]["scan_range"] = -0.5; }, "nodes[1].scan_range");
  says([](ojson& j) { j["nodes"][1]["area_points"] = 1e12; }, "nodes[1].area_points");
  says([](ojson& j) { j["nodes"][1]["parent"] = -5; }, "nodes[1].parent");
  says([](ojson& j) { j["nodes"][1]["parent"] = std::uint64_t{1} << 63; }, "nodes[1].parent");
  says([](ojson& j) { j["nodes"][0]["children"][0] = -1; }, "nodes[0].children[0]");
  says([](ojson& j) { j["nodes"][0]["children"][1] = 1'000'000'000; }, "nodes[0].children[1]");
  says([](ojson& j) { j["nodes"][1]["level"] = 99; }, "nodes[1].level");
  says([](ojson& j) { j["nodes"][1]["sense"] = 7; }, "nodes[1].sense");
  says([](ojson& j) { j["nodes"][1]["flux"]["flux_per_step"] = -2e-5; }, "nodes[1].flux.flux_per_step");
  says([](ojson& j) { j["nodes"][1]["flux"]["zone_area"] = -1; }, "nodes[1].flux.zone_area");
  says([](ojson& j) { j["nodes"][1]["about_parent"] = "1/99999999999999"; }, "nodes[1].about_parent");
  says([](ojson& j) { j["seconds"] = -1; }, "seconds");
  says([](ojson& j) { j["request"]["depth"] = 1000000; }, "request.depth");
  says([](ojson& j) { j["request"]["max_period"] = 0; }, "request.max_period");
  says([](ojson& j) { j["request"]["scan_points"] = 1e9; }, "request");
  says([](ojson& j) { j["request"]["min_area"] = -1; }, "request");
  says([](ojson& j) { j["map"]["K"] = 1e308; }, "request");
  says([](ojson& j) { j["map"]["xmin"] = 0.9; }, "request");
}

TEST(AtlasJson, AnAreaOutsideItsIntervalOrAnErrorThatDoesNotCoverItIsRefused) {
  // Issue 50: the interval [area_lower, area_upper] holds the true area and area ± area_error holds the interval.
  const auto says = [](const std::function<void(ojson&)>& edit, const std::string& words) {
    const std::string message = refusal(edited(edit));
    EXPECT_NE(message.find(words), std::string::npos) << message;
  };
  says([](ojson& j) { j["nodes"][1]["area_upper"] = 6e-3; }, "must lie in [area_lower, area_upper]");
  says([](ojson& j) { j["nodes"][1]["area_lower"] = 6.8e-3; }, "must lie in [area_lower, area_upper]");
  says([](ojson& j) { j["nodes"][1]["area_error"] = 2.4e-9; }, "nodes[1].area_error");
  says([](ojson& j) { j["nodes"][1]["polygon_error"] = -1; }, "nodes[1].polygon_error");
  says([](ojson& j) { j["nodes"][1]["area_upper"] = nullptr; }, "nodes[1].area_error must be null");
}

TEST(AtlasJson, AFileFromBeforeTheIntervalReadsWithItsBoundaryUncertaintyUnknown) {
  // Files of a2e223a and before: area_error was the polygon's convergence (2.4e-9 for the island of six, whose area
  // was low by 3e-3 relative); read back, that number is the polygon's, and the interval's upper end is not known.
  ojson j = ojson::parse(atlasJson(handBuilt()));
  j.erase("format_version");  // and unsigned, as files were then
  j.erase("checksum");
  for (ojson& n : j["nodes"]) {
    n["area_error"] = n["polygon_error"];
    n.erase("area_lower");
    n.erase("area_upper");
    n.erase("polygon_error");
    if (n["flux"].contains("inner")) n["flux"].erase("inner");
    if (n["flux"].contains("outer_by")) n["flux"].erase("outer_by");
  }
  const Atlas a = atlasFromJson(j.dump(2));
  const AtlasNode& six = a.nodes[1];
  EXPECT_EQ(six.polygonError, static_cast<long double>(2.4e-9));
  EXPECT_TRUE(std::isnan(six.areaUpper));
  EXPECT_TRUE(std::isnan(six.areaError));
  EXPECT_EQ(six.area, static_cast<long double>(6.704824e-3));
  // Written again: the unknown upper end and error are null, not the polygon's number under their name.
  const ojson again = ojson::parse(atlasJson(a));
  EXPECT_TRUE(again["nodes"][1]["area_upper"].is_null());
  EXPECT_TRUE(again["nodes"][1]["area_error"].is_null());
  const Atlas b = atlasFromJson(again.dump(2));  // and reads back so (an old atlas resumed)
  EXPECT_TRUE(std::isnan(b.nodes[1].areaUpper));
  EXPECT_EQ(atlasJson(b), atlasJson(a));
}

// Issue 54, item 1: atlas files were trusted as written — an edited about_parent, an area of 1e308, an area doubled
// consistently with its islands_area, a layer above zone − enclosed islands all read back (and resumed, and modelled)
// with exit 0.  They are signed now, and their invariants checked when read.
TEST(AtlasJson, AnEditedFileIsRefusedByItsChecksumAndAForgedOneByItsInvariants) {
  // Any edit, consistent or not, breaks the checksum.
  ojson j = ojson::parse(atlasJson(handBuilt()));
  j["nodes"][0]["area"] = 2 * j["nodes"][0]["area"].get<double>();
  EXPECT_NE(refusal(j.dump(2)).find("checksum does not match"), std::string::npos);
  j.erase("checksum");
  EXPECT_NE(refusal(j.dump(2)).find("checksum"), std::string::npos);
  // Signed again (a forger who knows the checksum's rule), the invariants refuse what no computation writes.
  const auto says = [](const std::function<void(ojson&)>& edit, const std::string& words) {
    const std::string message = refusal(edited(edit));
    EXPECT_NE(message.find(words), std::string::npos) << message;
  };
  says([](ojson& d) { d["nodes"][1]["about_parent"] = "-1/6"; }, "nodes[1].about_parent");
  says([](ojson& d) { d["nodes"][1]["about_parent"] = "2/12"; }, "lowest terms");
  says([](ojson& d) { d["nodes"][1]["about_parent"] = "7/6"; }, "0 < |p| < q");
  says([](ojson& d) {
    d["nodes"][0]["area"] = 1e308;
    d["nodes"][0]["area_upper"] = 1e308;
    d["nodes"][0]["area_error"] = 1e308;
  }, "box's area");
  says([](ojson& d) { d["nodes"][1]["flux"]["layer_area"] = 1.1 * d["nodes"][1]["flux"]["layer_area"].get<double>(); },
       "must be zone_area − enclosed_islands_area");
  says([](ojson& d) { d["nodes"][1]["flux"]["residence"] = 2 * d["nodes"][1]["flux"]["residence"].get<double>(); },
       "layer_area / flux_per_step");
  says([](ojson& d) { d["nodes"][0]["flux"]["zone_area"] = 1e308; }, "box's area");
  says([](ojson& d) { d["format_version"] = 3; }, "format_version");
}

TEST(AtlasJson, RefusesEditedTrees) {
  const auto says = [](const std::function<void(ojson&)>& edit, const std::string& words) {
    const std::string message = refusal(edited(edit));
    EXPECT_NE(message.find(words), std::string::npos) << message;
  };
  says([](ojson& j) { j["format"] = "archipelago run"; }, "not an atlas");
  says([](ojson& j) { j["colour"] = "red"; }, "unknown key 'colour'");
  says([](ojson& j) { j.erase("nodes"); }, "no 'nodes'");
  says([](ojson& j) { j["nodes"] = ojson::array(); }, "central island");
  says([](ojson& j) { j["nodes"][1].erase("period"); }, "nodes[1] has no 'period'");
  says([](ojson& j) { j["nodes"][1]["index"] = 2; }, "nodes[1].index");
  says([](ojson& j) { j["nodes"][1]["about_parent"] = "1/7"; }, "nodes[1].period = 6 must be 7");
  says([](ojson& j) { j["nodes"][1]["about_parent"] = "1/0"; }, "p/q");
  says([](ojson& j) { j["nodes"][1]["about_parent"] = "one sixth"; }, "p/q");
  says([](ojson& j) { j["nodes"][1]["about_parent"] = nullptr; }, "nodes[1].about_parent");
  says([](ojson& j) { j["nodes"][0]["about_parent"] = "1/1"; }, "nodes[0].about_parent");
  says([](ojson& j) { j["nodes"][3]["parent"] = 2; }, "nodes[3].period");
  says([](ojson& j) { j["nodes"][3]["parent"] = 3; }, "nodes[3].parent");
  says([](ojson& j) { j["nodes"][0]["children"] = ojson::array({1}); }, "missing from its parent's children");
  // What a resumed computation relies on: an island is measured only under a measured parent, one not measured has
  // no children yet, and a finished atlas has every island measured.
  says([](ojson& j) { j["nodes"][1]["measured"] = false; }, "nodes[1].children");
  says([](ojson& j) { j["nodes"][3]["measured"] = "yes"; }, "nodes[3].measured");
  says([](ojson& j) {
    j["nodes"][0]["measured"] = false;
    j["nodes"][0]["children"] = ojson::array();
  }, "nodes[1].measured");
  says([](ojson& j) { j["cancelled"] = false; }, "not measured in an atlas not cancelled");
  says([](ojson& j) { j["request"]["time_budget"] = -1; }, "request.time_budget");
  says([](ojson& j) { j["nodes"][0]["children"] = ojson::array({2, 1}); }, "increasing");
  says([](ojson& j) { j["nodes"][0]["children"] = ojson::array({1, 3}); }, "not its child");
  says([](ojson& j) { j["nodes"][1]["symmetry_line"] = "S3"; }, "nodes[1].symmetry_line");
  says([](ojson& j) { j["nodes"][1]["boundary"]["found"] = false; }, "nodes[1].boundary");
  says([](ojson& j) { j["nodes"][1]["flux"].erase("residence"); }, "nodes[1].flux has no 'residence'");
  says([](ojson& j) { j["nodes"][2]["flux"]["found"] = true; }, "nodes[2].flux");
  says([](ojson& j) { j["nodes"][0]["flux"]["partner"] = j["nodes"][1]["flux"]["partner"]; }, "nodes[0].flux.partner");
  says([](ojson& j) { j["nodes"][1]["internal"] = ojson::array({"2/x"}); }, "nodes[1].internal[0]");
  says([](ojson& j) { j["nodes"][1]["note"] = 5; }, "nodes[1].note");
  says([](ojson& j) { j["cancelled"] = "yes"; }, "cancelled");
}

// Random edits (a value replaced by another of any kind, a key removed, an entry duplicated): each document is either
// refused with a std::runtime_error or read into an atlas that writes a text that reads back to itself.
// A barrier whose zone is no larger than the islands found inside it has no layer (found at K = 0.15: the 1/5 chain
// about the island of 21 gave a layer of −4.2e−4 and a residence of −1.5e9 steps, printed as numbers): the rule
// refuses the flux, with the numbers in its reason, in the computation (settleLayers) and in a file read back.
TEST(AtlasJson, ABarrierWhoseZoneIsNoLargerThanItsIslandsIsRefused) {
  AtlasFlux f;
  f.found = true;
  f.flux = 2.7204031581282044e-13L;
  f.zoneArea = 0.00045115427721225407L;
  f.enclosedIslands = 0.0008689337652417415L;
  f.enclosedCount = 126;
  f.layerArea = f.zoneArea - f.enclosedIslands;
  f.residence = static_cast<double>(f.layerArea / f.flux);
  refuseEmptyLayer(f);
  EXPECT_FALSE(f.found);
  EXPECT_NE(f.failure.find("no larger than the 126 islands"), std::string::npos) << f.failure;
  EXPECT_NE(f.failure.find("0.00045115427721225407"), std::string::npos) << f.failure;

  AtlasFlux empty = f;  // a layer of exactly nothing is no layer either
  empty.found = true;
  empty.failure.clear();
  empty.layerArea = 0;
  refuseEmptyLayer(empty);
  EXPECT_FALSE(empty.found);

  AtlasFlux thin = f;  // the smallest positive layer is a layer: the rule refuses no more than it must
  thin.found = true;
  thin.failure.clear();
  thin.layerArea = std::numeric_limits<long double>::denorm_min();
  refuseEmptyLayer(thin);
  EXPECT_TRUE(thin.found);
  EXPECT_TRUE(thin.failure.empty());

  // The file: the chain of six's layer and residence edited negative are read as a refused flux, and written so.
  const Atlas a = atlasFromJson(edited([](ojson& j) {
    ojson& g = j["nodes"][1]["flux"];  // the islands inside exceed the zone, as K = 0.15's 1/5 about 21's did
    g["enclosed_islands_area"] = g["zone_area"].get<double>() + 4.177795e-4;
    g["layer_area"] = g["zone_area"].get<double>() - g["enclosed_islands_area"].get<double>();
    g["residence"] = g["layer_area"].get<double>() / g["flux_per_step"].get<double>();
  }));
  EXPECT_FALSE(a.nodes[1].flux.found);
  EXPECT_NE(a.nodes[1].flux.failure.find("no larger than"), std::string::npos) << a.nodes[1].flux.failure;
  const ojson again = ojson::parse(atlasJson(a));
  EXPECT_EQ(again["nodes"][1]["flux"]["found"], false);
  EXPECT_FALSE(again["nodes"][1]["flux"].contains("residence"));
  EXPECT_TRUE(atlasFromJson(atlasJson(handBuilt())).nodes[1].flux.found);  // the untouched file keeps it
}

// Issue 50: the cantori read back; edited (and signed again) against their
// invariants — a layer that is not its zone less its islands, a flux ≤ 0, a zone above the box's, a found cantorus
// without a flux or with a failure, a fraction that is no fraction — they are refused, naming the field.
TEST(AtlasJson, TheCantoriReadBackAndForgedOnesAreRefused) {
  Atlas a = handBuilt();
  AtlasCantorus c;
  c.outer = {5, 31};
  c.inner = {1, 6};
  c.convergents = {{5, 31}, {6, 37}, {11, 68}};
  c.found = true;
  c.flux = 1.1632e-5L;
  c.fluxUncertainty = 5e-10L;
  c.zoneArea = 0.3189L;
  c.zoneSpread = 1.3e-3L;
  c.enclosedIslands = 0.2794L;
  c.enclosedCount = 7;
  c.layerArea = c.zoneArea - c.enclosedIslands;
  AtlasCantorus refused = c;
  refused.found = false;
  refused.failure = "its layer does not lie between the layers of the barriers about it";
  a.cantori = {c, refused};
  const std::string text = atlasJson(a);
  const Atlas back = atlasFromJson(text);
  ASSERT_EQ(back.cantori.size(), 2u);
  EXPECT_EQ(back.cantori[0].convergents, c.convergents);
  EXPECT_TRUE(back.cantori[0].found);
  EXPECT_FALSE(back.cantori[1].found);
  EXPECT_EQ(back.cantori[1].failure, refused.failure);
  EXPECT_EQ(atlasJson(back), text);
  const auto refusedWith = [&](const std::function<void(ojson&)>& edit, const std::string& word) {
    ojson j = ojson::parse(text);
    edit(j);
    try {
      (void)atlasFromJson(signedAgain(j));
      ADD_FAILURE() << "accepted: " << word;
    } catch (const io::BadFile& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  refusedWith([](ojson& j) { j["cantori"][0]["layer_area"] = 0.05; }, "layer_area");
  refusedWith([](ojson& j) { j["cantori"][0]["flux_per_step"] = -1e-5; }, "flux_per_step");
  refusedWith([](ojson& j) { j["cantori"][0]["zone_area"] = 1e308; }, "zone_area");
  refusedWith([](ojson& j) { j["cantori"][1]["found"] = true; }, "found");
  refusedWith([](ojson& j) { j["cantori"][0]["outer"] = "5/-31"; }, "outer");
  refusedWith([](ojson& j) { j["cantori"][0].erase("flux_per_step"); }, "flux");
}

TEST(AtlasJson, RandomEditsAreRefusedOrReadConsistently) {
  std::mt19937_64 rng(38);
  const ojson base = ojson::parse(atlasJson(handBuilt()));
  const std::vector<ojson> values = {nullptr, true, -1, 0, 1, 2, 3, 6, 1e300, -1e-300, 0.5, "1/6", "S1", "",
                                     ojson::array(), ojson::object(), ojson::array({0.1, 0.2}),
                                     std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::uint64_t>::max()};
  int accepted = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    ojson j = base;
    const int edits = 1 + static_cast<int>(rng() % 3);
    for (int e = 0; e < edits; ++e) {
      // A random path into the document.
      ojson* v = &j;
      while ((v->is_object() || v->is_array()) && !v->empty() && rng() % 4 != 0) {
        const std::size_t k = rng() % v->size();
        auto it = v->begin();
        std::advance(it, static_cast<std::ptrdiff_t>(k));
        v = &*it;
      }
      switch (rng() % 3) {
        case 0: *v = values[rng() % values.size()]; break;
        case 1: if (v->is_object() && !v->empty()) v->erase(v->begin()); break;
        case 2: if (v->is_array() && !v->empty()) v->push_back((*v)[0]); break;
      }
    }
    const std::string text = signedAgain(j);  // past the checksum, to the rules (an unsigned edit is refused whole)
    try {
      const Atlas a = atlasFromJson(text);
      const std::string again = atlasJson(a);
      EXPECT_EQ(atlasJson(atlasFromJson(again)), again);
      ++accepted;
    } catch (const std::runtime_error&) {
    }
  }
  EXPECT_LT(accepted, 3000);  // most edits break something
}

}  // namespace
}  // namespace archipelago
