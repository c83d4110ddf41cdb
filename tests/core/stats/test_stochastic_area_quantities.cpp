// b₂ as an area (Karney 1983, appendix A), the box-invariant b₂·D (eq. A3) and the §6 figures, against the
// paper's numbers and the definitions of §6 evaluated here.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "core/stats/StochasticAreaQuantities.hpp"

namespace archipelago {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(StochasticAreaQuantities, AreaIsTheFractionTimesTheBoxArea) {
  const MapParameters paperBox;  // K = 0.1, (−0.8, 0.5): L = 1.3
  const StochasticAreaValue b2 = stochasticAreaOf(paperBox, 0.811);
  EXPECT_DOUBLE_EQ(b2.boxArea, 1.3 * 1.3);
  EXPECT_DOUBLE_EQ(b2.fraction, 0.811);
  EXPECT_NEAR(b2.area, 1.371, 5e-4);  // issue #14: "an area of L²·0.811 ≈ 1.37"
  const MapParameters unitBox{0.1, -0.65, 0.35};
  EXPECT_NEAR(stochasticAreaOf(unitBox, 0.718).area, 0.718, 1e-15);  // L = 1: area and fraction coincide
  EXPECT_DOUBLE_EQ(stochasticAreaOf(paperBox, 1).area, paperBox.width() * paperBox.width());
  EXPECT_EQ(stochasticAreaOf(paperBox, 0).area, 0);
}

TEST(StochasticAreaQuantities, RejectsWhatIsNotAFractionOfAValidBox) {
  const MapParameters box;
  for (const double f : {-0.1, 1.1, std::numeric_limits<double>::quiet_NaN()})
    EXPECT_TRUE(std::isnan(stochasticAreaOf(box, f).area)) << f;
  const MapParameters inverted{0.1, 0.5, -0.8};
  EXPECT_TRUE(std::isnan(stochasticAreaOf(inverted, 0.5).area));
}

// §6: 2h²(γ/A₁)b₂ with h = 2πn, γ = (2/πn)², A₁ = (2π)², for every n.
TEST(StochasticAreaQuantities, AcceleratorFactorFollowsFromTheDefinitionsOfSection6) {
  for (int n = 1; n <= 5; ++n) {
    const double h = 2 * kPi * n, gamma = std::pow(2 / (kPi * n), 2), A1 = std::pow(2 * kPi, 2);
    EXPECT_NEAR(acceleratorModeFactor(0.693), 2 * h * h * gamma / A1 * 0.693, 1e-15) << n;
  }
  EXPECT_NEAR(acceleratorModeFactor(kPaperStochasticArea), 0.56, 0.005);  // the paper: "≈ 0.56"
}

TEST(StochasticAreaQuantities, EnhancementOverQuasiLinearDiffusionIsThePapers) {
  // The paper: with D ≥ 6400 the islands raise the diffusion coefficient over 𝒟_ql = (πn)² by "at least 360/n²".
  const double e1 = acceleratorModeEnhancement(kPaperStochasticArea, kPaperDiffusion, 1);
  EXPECT_GE(e1, 360);
  EXPECT_NEAR(e1, 360, 6);
  EXPECT_NEAR(acceleratorModeEnhancement(kPaperStochasticArea, kPaperDiffusion, 3), e1 / 9, 1e-12);
  EXPECT_TRUE(std::isnan(acceleratorModeEnhancement(0.693, 6400, 0)));
}

TEST(StochasticAreaQuantities, BoxInvariantProductsOfThePaperAndOfThisProject) {
  const MapParameters box;
  // The paper: b₂D = 0.693 × 6400 ≈ 4.4·10³; this project's 3.2·10¹²-step run in the default box: 1.371 × 3140.
  const BoxInvariantQuantities paper = boxInvariantQuantities({0.693, 1, 0.693}, 6400, 800);
  EXPECT_NEAR(paper.b2D, 4.4e3, 0.05e3);
  EXPECT_NEAR(paper.b2DError, 0.693 * 800, 1e-9);
  const BoxInvariantQuantities ours = boxInvariantQuantities(stochasticAreaOf(box, 0.811), 3140, 510);
  EXPECT_NEAR(ours.b2D, 4.3e3, 0.05e3);
  EXPECT_NEAR(ours.enhancementN1, acceleratorModeFactor(ours.b2.area) * 3140 / (kPi * kPi), 1e-9);
}

TEST(StochasticAreaQuantities, ThePaperIsComparedOnlyAtItsK) {
  const MapParameters paperBox;
  const auto at01 = paperStochasticAreaComparison(paperBox, stochasticAreaOf(paperBox, 0.811));
  ASSERT_TRUE(at01.has_value());
  EXPECT_NE(at01->find("0.693"), std::string::npos);
  EXPECT_NE(at01->find("xmin = -0.8, xmax = 0.5"), std::string::npos) << *at01;  // says which box
  EXPECT_NE(at01->find("fig. 6"), std::string::npos) << *at01;
  const MapParameters other{0.2, -1.1, 0.7};
  EXPECT_FALSE(paperStochasticAreaComparison(other, stochasticAreaOf(other, 0.8)).has_value());
  const std::string text = stochasticAreaText(paperBox, stochasticAreaOf(paperBox, 0.811));
  EXPECT_NE(text.find("1.3706 (area; fraction 0.81100"), std::string::npos) << text;
}

}  // namespace
}  // namespace archipelago
