cmake_minimum_required(VERSION 3.21)
# The one table of limits (issue 35, item 2; core/limits/Limits.hpp), checked on the sources (ctest
# architecture.limits): outside core/limits no source bounds a thread count, a raster side or an orbit's length by a
# number of its own.  Each pattern is one way a copy was written before the table (`r.threads > 1024`,
# `width > 16384`, `steps > (std::uint64_t{1} << 28)`, `steps > 100'000'000`); a planted copy fails the test.
# -DROOT=<project source dir> [-DEXTRA=<file>: one more file to scan, for the test's own check that it can fail]
set(patterns
  "threads[ \t]*[<>]=?[ \t]*[1-9][0-9]"
  "[^0-9]16384[^0-9]"
  "steps[^;]*([^0-9']100'000'000[^0-9']|[^0-9]100000000[^0-9]|<<[ \t]*28)"
  "kMaxThreads[ \t]*=[ \t]*[0-9]")
file(GLOB_RECURSE sources "${ROOT}/core/*.hpp" "${ROOT}/core/*.cpp" "${ROOT}/core/*.inl" "${ROOT}/app/*.hpp"
  "${ROOT}/app/*.cpp" "${ROOT}/ui/*.hpp" "${ROOT}/ui/*.cpp" "${ROOT}/python/*.hpp" "${ROOT}/python/*.cpp")
if(EXTRA)
  list(APPEND sources "${EXTRA}")
endif()
set(offenders "")
foreach(f IN LISTS sources)
  if(f MATCHES "/core/limits/")
    continue()
  endif()
  foreach(p IN LISTS patterns)
    file(STRINGS "${f}" lines REGEX "${p}")
    foreach(line IN LISTS lines)
      if(NOT line MATCHES "^[ \t]*(//|///|\\*)")  # a comment may quote a number
        list(APPEND offenders "${f}: ${line}")
      endif()
    endforeach()
  endforeach()
endforeach()
if(offenders)
  list(JOIN offenders "\n  " text)
  message(FATAL_ERROR "limits written outside the one table (core/limits/Limits.hpp):\n  ${text}")
endif()
list(LENGTH sources n)
message(STATUS "${n} sources: no limit outside core/limits")
