#pragma once
/// \file ReportFigures.hpp
/// \brief The figures of the reproduction report (app/reproduce), drawn with the GUI's own plot code
/// (StatisticsPlot, Qwt) offscreen, and the report's PDF.  No maths: the values come from core.

#include <QColor>
#include <QPointF>
#include <QString>
#include <QStringList>

#include <functional>
#include <vector>

#include "core/provenance/Provenance.hpp"
#include "core/scan/ScanSummary.hpp"
#include "core/colour/ColourMap.hpp"
#include "core/stats/StatisticsTable.hpp"
#include "core/theory/TheoryCurves.hpp"
#include "core/run/TrappingRun.hpp"

namespace archipelago::ui::report {

/// Every PNG of the report carries the parameters of what it shows as text chunks (issue 54): a statistic the run's
/// (runProvenance, as the GUI's plots; its runParametersLine drawn under the plot), a picture of the plane K and the
/// view, any other figure the `provenance` its caller gives (programProvenance() and what it shows).

/// Draws one statistic of `run` (`stats`: its statistics, or a splice of them) as the GUI does and writes `base`.png
/// and `base`.svg.  Returns false (with `error`) when a file cannot be written.
bool writeStatisticFigure(Statistic statistic, const TrappingState& run, const TrappingStatistics& stats,
                          const std::vector<TheoryCurve>& theory, const QString& base, QString* error);
/// The same, with another method's estimate drawn beside the run's statistic (StatisticsPlot::setEstimate: the tail
/// sampler's P_t, issue #29).
bool writeStatisticFigure(Statistic statistic, const TrappingState& run, const TrappingStatistics& stats,
                          const std::vector<TheoryCurve>& theory, const Series& estimate, const QString& estimateTitle,
                          const QString& base, QString* error);

/// Fig. 5: T(X0) (a) and F(T) (b) of the small-K theory for K < 0 (core's smallk functions sampled), written as
/// `base`a.png/.svg and `base`b.png/.svg.
bool writeTrappingTimeFigures(const QString& base, const Provenance& provenance, QString* error);

/// Points to mark on a figure (e.g. the members of a periodic orbit), drawn as open circles with a legend entry.
struct FigureMarkers {
  std::vector<QPointF> points;
  QString name;
};

/// A portrait (core's colourized raster, as the GUI colours it) with its physical axes and `markers`, as
/// `base`.png/.svg; `provenance`: the portrait's (portraitProvenance: K, the view, the image's parameters).
bool writePortraitFigure(const RasterImage& image, double x0, double x1, double y0, double y1, const QString& title,
                         const QString& base, const Provenance& provenance, QString* error,
                         const FigureMarkers& markers = {});

/// An orbit's points (physical x, y) as black dots on [x0, x1] × [y0, y1] (rasterized at the canvas's
/// resolution, so that a million points make a small SVG), with `markers`, as `base`.png/.svg.
bool writePointsFigure(const std::vector<QPointF>& points, double x0, double x1, double y0, double y1,
                       const QString& title, const QString& base, const Provenance& provenance, QString* error,
                       const FigureMarkers& markers = {});

/// §5's K scan as the GUI's K-scan dialog draws it (ui/scan/KScanPlots, the dialog's plots, fed the summaries):
/// f_t per K, the local exponent's heat map over (K, τ), D(K) with its supported error, the longest segment and
/// the fraction of steps in long segments against K, as `base`-ft, -heatmap, -D, -long (.png/.svg).
bool writeScanFigures(const std::vector<ScanRunSummary>& runs, const QString& base, const Provenance& provenance,
                      QString* error);

/// One curve of writeCurvesFigure().
struct FigureCurve {
  std::vector<double> x, y;
  std::vector<double> error;  ///< one-sigma error bars (empty, or NaN for a point: none)
  QString name;               ///< legend entry (empty: none)
  QColor colour;              ///< invalid: the next colour of the report's palette
  bool dashed = false;        ///< a thin dashed line (reference lines)
  bool symbols = false;       ///< points with symbols and no line
};
struct FigureAxes {
  QString title, xLabel, yLabel;
  bool logX = false, logY = false;  ///< logarithmic axes, labelled as the GUI's (powers of ten)
};
/// Curves y(x) (only points with finite x, y, and > 0 on a logarithmic axis), with a legend when more than one is
/// named, as `base`.png/.svg: the Markov model's ε(τ), the K scan's summaries, the tail's exponents.
bool writeCurvesFigure(const std::vector<FigureCurve>& curves, const FigureAxes& axes, const QString& base,
                       const Provenance& provenance, QString* error);

/// Fig. 4: level curves of z(x, y) on [x0, x1] × [y0, y1] (sampled on a grid), at the given levels.
bool writeLevelCurveFigure(const std::function<double(double, double)>& z, double x0, double x1, double y0, double y1,
                           const std::vector<double>& levels, const QString& title, const QString& base,
                           const Provenance& provenance, QString* error);

/// Writes `html` (with its images, given as file names relative to `dir`) as a PDF at `pdfPath`.
bool writePdf(const QString& html, const QString& dir, const QStringList& images, const QString& pdfPath,
              QString* error);

}  // namespace archipelago::ui::report
