#pragma once
/// \file Png.hpp
/// \brief A minimal PNG encoder for the programs that link no Qt (archipelago-cli): 8-bit RGB, no interlace, and
/// text chunks, which carry where the image came from (core/provenance/Provenance.hpp; issue 42).
/// IDAT is compressed with zlib when the build found it (ARCHIPELAGO_HAVE_ZLIB); otherwise it is written as
/// stored (uncompressed) deflate blocks, which every PNG reader accepts.  CRC-32 and Adler-32 are computed
/// here in both cases.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace archipelago::io {

/// Key/value text of a PNG, in order: a tEXt chunk each when the value is ASCII, an iTXt chunk (UTF-8, not
/// compressed) otherwise.  A key is 1–79 printable ASCII characters with no leading, trailing or double space.
using PngText = std::vector<std::pair<std::string, std::string>>;

/// The PNG file's bytes for a width × height RGB image (3 bytes per pixel, row-major, row 0 on top), with `text`
/// before the image data.  Throws std::invalid_argument when rgb.size() != 3·width·height, a size is not
/// positive, a key breaks the rule above or a value holds a NUL.
[[nodiscard]] std::vector<std::uint8_t> encodePng(int width, int height, const std::vector<std::uint8_t>& rgb,
                                                  const PngText& text = {});

/// Writes encodePng(...) to `path` atomically; throws std::runtime_error naming the file when that fails.
void writePng(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb,
              const PngText& text = {});

/// The tEXt and iTXt (uncompressed) chunks of a PNG file's bytes, in order (what a test or a reader of the
/// files checks); throws std::invalid_argument when the bytes are not a PNG whose chunks end with IEND.
[[nodiscard]] PngText readPngText(const std::vector<std::uint8_t>& png);

}  // namespace archipelago::io
