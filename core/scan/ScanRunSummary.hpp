#pragma once
/// \file ScanRunSummary.hpp
/// \brief What a K scan (§5; ScanBox.hpp) reports per K: what its summary files (ScanSummary.hpp) and the heat map
/// of its local exponent (ScanHeatMap.hpp) are made of.

#include "core/stats/TrappingStatistics.hpp"
#include "core/scan/ScanPoint.hpp"
#include "core/run/TrappingRun.hpp"

namespace archipelago {

/// One K of a scan: its parameters (the box of scanBox(K) and the scan's common settings), the scan point and
/// the statistics.
struct ScanRunSummary {
  TrappingParameters params;
  ScanPoint point;
  TrappingStatistics statistics;
};

}  // namespace archipelago
