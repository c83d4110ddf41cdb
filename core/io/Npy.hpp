#pragma once
/// \file Npy.hpp
/// \brief NumPy .npy files (format version 1.0) of 2-D arrays, written atomically.
///
/// The format (numpy.lib.format): the magic "\x93NUMPY", version 1.0, a little-endian uint16 header length,
/// an ASCII dict {'descr': '<u4', 'fortran_order': False, 'shape': (rows, cols), } padded with spaces and
/// ended by '\n' so that the data starts at a multiple of 64 bytes, then the data, little-endian, C order.
/// Written byte by byte, so the files are the same on any host.

#include <cstdint>
#include <string>
#include <vector>

namespace archipelago {

/// The header (magic through '\n') of a 2-D .npy array; descr is "<u4", "<u8" or "<f8".
[[nodiscard]] std::string npyHeader(const std::string& descr, std::size_t rows, std::size_t cols);

/// Writes a rows × cols array, row-major, atomically (io/AtomicFile.hpp).  Throws std::runtime_error naming
/// the file when it cannot be written, std::invalid_argument when data.size() != rows·cols.
void writeNpy(const std::string& path, const std::vector<std::uint32_t>& data, std::size_t rows, std::size_t cols);
void writeNpy(const std::string& path, const std::vector<std::uint64_t>& data, std::size_t rows, std::size_t cols);
void writeNpy(const std::string& path, const std::vector<double>& data, std::size_t rows, std::size_t cols);

}  // namespace archipelago
