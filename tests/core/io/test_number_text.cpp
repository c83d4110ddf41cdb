// core/io/NumberText: the one strict reader of typed numbers (issue #24: "2e7" is an integer everywhere or
// nowhere; issue #12: never a wrapped value) and locale-free formatting (issue #23: a decimal comma once broke
// sessions and the report's CSV).
#include <gtest/gtest.h>

#include <string>

#include "core/io/NumberText.hpp"
#include "tests/core/DecimalCommaLocale.hpp"

namespace archipelago::io {
namespace {

TEST(NumberText, IntegersAreExactlyWholeDecimals) {
  EXPECT_EQ(toNumber<std::uint64_t>("20000000"), 20000000u);
  EXPECT_EQ(toNumber<std::uint64_t>("2e7"), 20000000u);
  EXPECT_EQ(toNumber<std::uint64_t>("2E+7"), 20000000u);
  EXPECT_EQ(toNumber<std::uint64_t>("2.5e3"), 2500u);
  EXPECT_EQ(toNumber<std::uint64_t>("20.0"), 20u);
  EXPECT_EQ(toNumber<std::uint64_t>("+5"), 5u);
  EXPECT_EQ(toNumber<std::uint64_t>("1.8446744073709551615e19"), 18446744073709551615u);
  EXPECT_EQ(toNumber<std::uint64_t>("18446744073709551615"), 18446744073709551615u);
  EXPECT_EQ(toNumber<std::uint64_t>("-0"), 0u);
  EXPECT_EQ(toNumber<std::int32_t>("-2147483648"), -2147483647 - 1);
  EXPECT_EQ(toNumber<std::int64_t>("-9.223372036854775808e18"), INT64_MIN);
  EXPECT_EQ(toNumber<std::uint32_t>("4294967295"), 4294967295u);
  // Not whole, not decimal, not in range, not only a number: refused, never rounded or wrapped.
  for (const char* bad : {"2.5", "1e-3", "0x10", "2e7.5", "", " 5", "5 ", "5x", "++5", "+-5", "-5", "e5", ".", "1e",
                          "18446744073709551616", "1.8446744073709551616e19", "1e20", "1e99999999", "nan", "inf",
                          "1,5", "2e7 "})
    EXPECT_FALSE(toNumber<std::uint64_t>(bad).has_value()) << '"' << bad << '"';
  EXPECT_FALSE(toNumber<std::int32_t>("2147483648").has_value());
  EXPECT_FALSE(toNumber<std::int32_t>("-2147483649").has_value());
  EXPECT_FALSE(toNumber<std::uint32_t>("4294967296").has_value());
  // 0.000…0001e30 with enough zeros is exactly 10^k: evaluated exactly, not through a double.
  EXPECT_EQ(toNumber<std::uint64_t>("0.000000000000000000001e30"), 1000000000u);
  EXPECT_FALSE(toNumber<std::uint64_t>("9007199254740993.5").has_value());
  EXPECT_EQ(toNumber<std::uint64_t>("9007199254740993"), 9007199254740993u);  // 2^53 + 1: no double holds it
}

TEST(NumberText, RealsAreFiniteAndWholeText) {
  EXPECT_EQ(toNumber<double>("0.1"), 0.1);
  EXPECT_EQ(toNumber<double>("-8e-1"), -0.8);
  EXPECT_EQ(toNumber<double>("0x1p-3"), 0.125);
  EXPECT_EQ(toNumber<double>("+2"), 2.0);
  for (const char* bad : {"nan", "inf", "-inf", "1e400", "0,5", "", " 1", "1 ", "1..2", "--1"})
    EXPECT_FALSE(toNumber<double>(bad).has_value()) << '"' << bad << '"';
  EXPECT_EQ(toNumber<long double>("0.1"), 0.1L);
}

TEST(NumberText, MessagesNameTheInputShortly) {
  try {
    (void)parseNumber<std::uint32_t>("--M", std::string(1000, '9'));
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_LT(std::string(e.what()).size(), 120u) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("--M = 9999", 0), 0u) << e.what();
  }
}

// Issue 36 class 6: ARCHIPELAGO_KERNEL='scalar\n' was quoted with its newline raw, breaking the one-line message.
TEST(NumberText, QuotedTextStaysOnOneLine) {
  EXPECT_EQ(shortText("scalar\n"), "scalar\\n");
  EXPECT_EQ(shortText(std::string("a\tb\rc\x01\x7F", 7)), "a\\tb\\rc\\x01\\x7F");
  EXPECT_EQ(shortText("d\u00e9j\u00e0 vu"), "d\u00e9j\u00e0 vu");  // UTF-8 is text, not a control character
  EXPECT_EQ(shortText(std::string(50, '\n'), 4), "\\n\\n\\n\\n\u2026");
}

using testing::DecimalCommaLocale;

TEST_F(DecimalCommaLocale, FormatAndParseIgnoreIt_Issue23) {
  EXPECT_EQ(formatC("%.1f|%g|%.3Lf", 0.5, 1e-4, 0.25L), "0.5|0.0001|0.250");
  EXPECT_EQ(toNumber<double>("0.5"), 0.5);
  EXPECT_FALSE(toNumber<double>("0,5").has_value());
  EXPECT_EQ(parseLongDoubleC("4503599627370.5"), 4503599627370.5L);
  EXPECT_EQ(toNumber<std::uint64_t>("2.5e3"), 2500u);
}

}  // namespace
}  // namespace archipelago::io
