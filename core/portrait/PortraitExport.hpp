#pragma once
/// \file PortraitExport.hpp
/// \brief Writes rasters as NumPy .npy files (format version 1.0) with a JSON sidecar.
///
/// The .npy format (numpy.lib.format): the magic "\x93NUMPY", version 1.0, a little-endian uint16 header
/// length, an ASCII dict {'descr': '<u4', 'fortran_order': False, 'shape': (rows, cols), } padded with
/// spaces and ended by '\n' so that the data starts at a multiple of 64 bytes, then the data, little-endian,
/// C order.  Written byte by byte, so the files are the same on any host.
///
/// The sidecar (FILE.json next to FILE.npy) records what numpy.load cannot: the viewport (exact centre in
/// unit coordinates, physical bounds with 19 significant digits), the map (K, xmin, xmax and the exact
/// integers A, B, C, m), the request and the totals; `"rows": "row 0 is the top (largest y)"`.

#include <cstdint>
#include <string>
#include <vector>

#include "portrait/PortraitRenderer.hpp"
#include "portrait/StochasticArea.hpp"

namespace archipelago {

/// The header (magic through '\n') of a 2-D .npy array; descr is "<u4", "<u8" or "<f8".
[[nodiscard]] std::string npyHeader(const std::string& descr, std::size_t rows, std::size_t cols);

/// Writes a rows × cols array, row-major.  Throws std::runtime_error naming the file when it cannot be
/// written, std::invalid_argument when data.size() != rows·cols.
void writeNpy(const std::string& path, const std::vector<std::uint32_t>& data, std::size_t rows, std::size_t cols);
void writeNpy(const std::string& path, const std::vector<std::uint64_t>& data, std::size_t rows, std::size_t cols);
void writeNpy(const std::string& path, const std::vector<double>& data, std::size_t rows, std::size_t cols);

/// The sidecar's path: FILE.npy → FILE.json (any other name: name + ".json").
[[nodiscard]] std::string sidecarPath(const std::string& npyPath);

/// The JSON text of the sidecar (pretty-printed).
[[nodiscard]] std::string portraitMetadataJson(const PortraitRequest& request, const PortraitRaster& raster,
                                               const std::string& arrayName);

/// Writes the raster's main array — counts (<u8) in Density mode, labels (<u4) in Orbits mode, mean segment
/// lengths in steps (<f8) in Stickiness mode — to npyPath and the sidecar to sidecarPath(npyPath).
void exportPortraitNpy(const std::string& npyPath, const PortraitRequest& request, const PortraitRaster& raster);

/// The convergence curve of b₂ as JSON text.
[[nodiscard]] std::string stochasticAreaJson(const StochasticAreaRequest& request, const StochasticAreaResult& result);

}  // namespace archipelago
