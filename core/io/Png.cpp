#include "core/io/Png.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#ifdef ARCHIPELAGO_HAVE_ZLIB
#include <zlib.h>
#endif

#include "core/io/AtomicFile.hpp"

namespace archipelago::io {

namespace {
// CRC-32 of ISO 3309 / PNG (polynomial 0xEDB88320, reflected), table-driven.
std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc = 0) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i) crc = table[(crc ^ data[i]) & 0xff] ^ (crc >> 8);
  return ~crc;
}

void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>((v >> s) & 0xff));
}

void chunk(std::vector<std::uint8_t>& out, const char* type, const std::vector<std::uint8_t>& data) {
  put32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put32(out, crc32(out.data() + start, out.size() - start));
}

// A zlib stream (RFC 1950) of stored deflate blocks (RFC 1951, BTYPE = 00) with its Adler-32.
std::vector<std::uint8_t> zlibStored(const std::vector<std::uint8_t>& raw) {
  std::vector<std::uint8_t> z = {0x78, 0x01};
  std::size_t pos = 0;
  do {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - pos);
    const bool last = pos + n == raw.size();
    z.push_back(last ? 1 : 0);
    z.push_back(static_cast<std::uint8_t>(n & 0xff));
    z.push_back(static_cast<std::uint8_t>(n >> 8));
    z.push_back(static_cast<std::uint8_t>(~n & 0xff));
    z.push_back(static_cast<std::uint8_t>((~n >> 8) & 0xff));
    z.insert(z.end(), raw.begin() + static_cast<std::ptrdiff_t>(pos), raw.begin() + static_cast<std::ptrdiff_t>(pos + n));
    pos += n;
  } while (pos < raw.size());
  std::uint32_t a = 1, b = 0;
  for (std::uint8_t v : raw) {
    a = (a + v) % 65521;
    b = (b + a) % 65521;
  }
  put32(z, (b << 16) | a);
  return z;
}

std::vector<std::uint8_t> compress(const std::vector<std::uint8_t>& raw) {
#ifdef ARCHIPELAGO_HAVE_ZLIB
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::vector<std::uint8_t> z(size);
  if (compress2(z.data(), &size, raw.data(), static_cast<uLong>(raw.size()), 9) == Z_OK) {
    z.resize(size);
    return z;
  }
#endif
  return zlibStored(raw);
}

std::uint32_t get32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

void checkKeyword(const std::string& key) {
  const bool printable = std::all_of(key.begin(), key.end(), [](char c) { return c >= 0x20 && c <= 0x7e; });
  if (key.empty() || key.size() > 79 || !printable || key.front() == ' ' || key.back() == ' ' ||
      key.find("  ") != std::string::npos)
    throw std::invalid_argument("encodePng: '" + key + "' is not a PNG keyword (1-79 printable characters)");
}
}  // namespace

std::vector<std::uint8_t> encodePng(int width, int height, const std::vector<std::uint8_t>& rgb,
                                    const PngText& text) {
  if (width < 1 || height < 1 || rgb.size() != 3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    throw std::invalid_argument("encodePng: the RGB data do not match the image size");
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<std::uint8_t> header;
  put32(header, static_cast<std::uint32_t>(width));
  put32(header, static_cast<std::uint32_t>(height));
  header.insert(header.end(), {8, 2, 0, 0, 0});  // 8 bits, truecolour, deflate, adaptive filters, no interlace
  chunk(png, "IHDR", header);
  for (const auto& [key, value] : text) {
    checkKeyword(key);
    if (value.find('\0') != std::string::npos) throw std::invalid_argument("encodePng: the text of '" + key + "' holds a NUL");
    const bool ascii = std::all_of(value.begin(), value.end(), [](char c) { return static_cast<unsigned char>(c) < 0x80; });
    std::vector<std::uint8_t> data(key.begin(), key.end());
    data.push_back(0);
    if (!ascii) data.insert(data.end(), {0, 0, 0, 0});  // iTXt: not compressed, no language, no translated key
    data.insert(data.end(), value.begin(), value.end());
    chunk(png, ascii ? "tEXt" : "iTXt", data);
  }
  // Each row: filter type 1 (Sub) — it helps zlib on smooth colour maps and costs nothing when stored.
  const std::size_t stride = 3 * static_cast<std::size_t>(width);
  std::vector<std::uint8_t> raw;
  raw.reserve((stride + 1) * static_cast<std::size_t>(height));
  for (int row = 0; row < height; ++row) {
    const std::uint8_t* line = rgb.data() + static_cast<std::size_t>(row) * stride;
    raw.push_back(1);
    for (std::size_t i = 0; i < stride; ++i)
      raw.push_back(static_cast<std::uint8_t>(line[i] - (i >= 3 ? line[i - 3] : 0)));
  }
  chunk(png, "IDAT", compress(raw));
  chunk(png, "IEND", {});
  return png;
}

void writePng(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb,
              const PngText& text) {
  const std::vector<std::uint8_t> png = encodePng(width, height, rgb, text);
  io::AtomicOutputFile file(path);  // a full disk or a kill leaves the old image, never a truncated one
  file.stream().write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  file.commit();
}

PngText readPngText(const std::vector<std::uint8_t>& png) {
  static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (png.size() < 8 || !std::equal(kSignature, kSignature + 8, png.begin()))
    throw std::invalid_argument("readPngText: not a PNG (no signature)");
  PngText text;
  std::size_t pos = 8;
  while (pos + 12 <= png.size()) {
    const std::size_t length = get32(&png[pos]);
    if (length > png.size() - pos - 12) break;
    const std::string type(reinterpret_cast<const char*>(&png[pos + 4]), 4);
    const std::string data(reinterpret_cast<const char*>(&png[pos + 8]), length);
    if (type == "IEND") return text;
    const std::size_t nul = data.find('\0');
    if (type == "tEXt" && nul != std::string::npos) {
      text.emplace_back(data.substr(0, nul), data.substr(nul + 1));
    } else if (type == "iTXt" && nul != std::string::npos && nul + 2 < data.size() && data[nul + 1] == 0) {
      const std::size_t language = data.find('\0', nul + 3);
      const std::size_t translated = language == std::string::npos ? language : data.find('\0', language + 1);
      if (translated != std::string::npos) text.emplace_back(data.substr(0, nul), data.substr(translated + 1));
    }
    pos += length + 12;
  }
  throw std::invalid_argument("readPngText: the PNG's chunks do not end with IEND");
}

}  // namespace archipelago::io
