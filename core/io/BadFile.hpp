#pragma once
/// \file BadFile.hpp
/// \brief The one exception of a document refused for its content, whichever its format (core/io/Json.hpp).

#include <stdexcept>

namespace archipelago::io {

/// A run file, tail file, session, run spec, manifest or atlas refused for its content: not JSON, or not what its
/// format says.  One line naming the field ("corrupt run file: orbitBegin = -1 must be a whole number in [0, …]").
/// A std::runtime_error, as the failure to read a file is: front ends print it (the CLI's "ERROR:" line), and the
/// Python module raises what it raised for that document before there was one type (OSError for a file it loads,
/// ValueError for a run spec given as text).
struct BadFile : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace archipelago::io
