#include "core/io/Npy.hpp"

#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/io/AtomicFile.hpp"

namespace archipelago {

namespace {
template <class T>
void writeArray(const std::string& path, const std::string& descr, const std::vector<T>& data, std::size_t rows,
                std::size_t cols) {
  if (data.size() != rows * cols) {
    std::ostringstream s;
    s << "writeNpy: " << data.size() << " values do not make a " << rows << " x " << cols << " array";
    throw std::invalid_argument(s.str());
  }
  std::string bytes = npyHeader(descr, rows, cols);
  const std::size_t start = bytes.size();
  bytes.resize(start + data.size() * sizeof(T));
  for (std::size_t i = 0; i < data.size(); ++i) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &data[i], sizeof(T));
    for (std::size_t b = 0; b < sizeof(T); ++b)
      bytes[start + i * sizeof(T) + b] = static_cast<char>((bits >> (8 * b)) & 0xff);
  }
  io::writeFileAtomically(path, bytes);
}
}  // namespace

std::string npyHeader(const std::string& descr, std::size_t rows, std::size_t cols) {
  std::ostringstream dict;
  dict << "{'descr': '" << descr << "', 'fortran_order': False, 'shape': (" << rows << ", " << cols << "), }";
  std::string text = dict.str();
  const std::size_t preamble = 10;  // magic (6) + version (2) + header length (2)
  const std::size_t total = (preamble + text.size() + 1 + 63) / 64 * 64;
  text.append(total - preamble - text.size() - 1, ' ');
  text.push_back('\n');
  std::string header = "\x93NUMPY";
  header.push_back('\x01');
  header.push_back('\x00');
  header.push_back(static_cast<char>(text.size() & 0xff));
  header.push_back(static_cast<char>((text.size() >> 8) & 0xff));
  return header + text;
}

void writeNpy(const std::string& path, const std::vector<std::uint32_t>& d, std::size_t rows, std::size_t cols) {
  writeArray(path, "<u4", d, rows, cols);
}
void writeNpy(const std::string& path, const std::vector<std::uint64_t>& d, std::size_t rows, std::size_t cols) {
  writeArray(path, "<u8", d, rows, cols);
}
void writeNpy(const std::string& path, const std::vector<double>& d, std::size_t rows, std::size_t cols) {
  static_assert(std::numeric_limits<double>::is_iec559, "the .npy '<f8' type is IEEE 754 binary64");
  writeArray(path, "<f8", d, rows, cols);
}

}  // namespace archipelago
