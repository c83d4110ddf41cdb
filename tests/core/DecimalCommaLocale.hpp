#pragma once
// A test fixture that switches the process to a locale with a decimal comma (de_DE.UTF-8), made with localedef
// in a folder of the test's own, so that the test does not depend on the machine's locales (Debian: the
// locales package provides localedef's sources).  Issue #23: files written under such a locale must be the
// same bytes as under "C".
#include <gtest/gtest.h>

#include <unistd.h>

#include <clocale>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace archipelago::testing {

class DecimalCommaLocale : public ::testing::Test {
 protected:
  std::filesystem::path localeDir =
      std::filesystem::temp_directory_path() / ("archipelago-locale-" + std::to_string(::getpid()));
  std::string previous;

  void SetUp() override {
    std::filesystem::create_directories(localeDir);
    const std::string command =
        "localedef -i de_DE -f UTF-8 " + (localeDir / "de_DE.UTF-8").string() + " >/dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << "localedef failed (Debian: install the locales package)";
    ::setenv("LOCPATH", localeDir.c_str(), 1);
    previous = std::setlocale(LC_ALL, nullptr);
    ASSERT_NE(std::setlocale(LC_ALL, "de_DE.UTF-8"), nullptr);
    char text[16];
    std::snprintf(text, sizeof text, "%.1f", 0.5);
    ASSERT_STREQ(text, "0,5") << "the locale really writes a decimal comma";
  }

  void TearDown() override {
    std::setlocale(LC_ALL, previous.c_str());
    ::unsetenv("LOCPATH");
    std::filesystem::remove_all(localeDir);
  }
};

}  // namespace archipelago::testing
