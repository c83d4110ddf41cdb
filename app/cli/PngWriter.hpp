#pragma once
// A minimal PNG encoder for archipelago-cli (which links no Qt): 8-bit RGB, no interlace.
// IDAT is compressed with zlib when the build found it (ARCHIPELAGO_HAVE_ZLIB); otherwise it is written as
// stored (uncompressed) deflate blocks, which every PNG reader accepts.  CRC-32 and Adler-32 are computed
// here in both cases.

#include <cstdint>
#include <string>
#include <vector>

namespace archipelago::cli {

/// The PNG file's bytes for a width × height RGB image (3 bytes per pixel, row-major, row 0 on top).
/// Throws std::invalid_argument when rgb.size() != 3·width·height or a size is not positive.
[[nodiscard]] std::vector<std::uint8_t> encodePng(int width, int height, const std::vector<std::uint8_t>& rgb);

/// Writes encodePng(...) to `path`; throws std::runtime_error naming the file when that fails.
void writePng(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb);

}  // namespace archipelago::cli
