#pragma once
/// \file Sha256.hpp
/// \brief SHA-256 (FIPS 180-4), for the content checksums of run files: any edit of a file is detected.

#include <string>
#include <string_view>

namespace archipelago::io {

/// The SHA-256 digest of `data` as 64 lower-case hexadecimal digits.
[[nodiscard]] std::string sha256Hex(std::string_view data);

}  // namespace archipelago::io
