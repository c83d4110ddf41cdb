#pragma once
/// \file ReportFigures.hpp
/// \brief The figures of the reproduction report (app/reproduce), drawn with the GUI's own plot code
/// (StatisticsPlot, Qwt) offscreen, and the report's PDF.  No maths: the values come from core.

#include <QString>
#include <QStringList>

#include <functional>
#include <vector>

#include "core/portrait/ColourMap.hpp"
#include "core/stats/StatisticsTable.hpp"
#include "core/theory/TheoryCurves.hpp"

namespace archipelago::ui::report {

/// Draws one statistic of a run as the GUI does and writes `base`.png and `base`.svg.  Returns false (with
/// `error`) when a file cannot be written.
bool writeStatisticFigure(Statistic statistic, const TrappingStatistics& stats, const std::vector<TheoryCurve>& theory,
                          const QString& base, QString* error);

/// Fig. 5: T(X0) (a) and F(T) (b) of the small-K theory for K < 0 (core's smallk functions sampled), written as
/// `base`a.png/.svg and `base`b.png/.svg.
bool writeTrappingTimeFigures(const QString& base, QString* error);

/// A portrait (core's colourized raster, as the GUI colours it) with its physical axes, as `base`.png/.svg.
bool writePortraitFigure(const RasterImage& image, double x0, double x1, double y0, double y1, const QString& title,
                         const QString& base, QString* error);

/// A plain curve y(x) on linear axes (the Markov model's ε(τ)), as `base`.png/.svg.
bool writeCurveFigure(const std::vector<double>& x, const std::vector<double>& y, const QString& title,
                      const QString& xLabel, const QString& yLabel, const QString& base, QString* error);

/// Fig. 4: level curves of z(x, y) on [x0, x1] × [y0, y1] (sampled on a grid), at the given levels.
bool writeLevelCurveFigure(const std::function<double(double, double)>& z, double x0, double x1, double y0, double y1,
                           const std::vector<double>& levels, const QString& title, const QString& base,
                           QString* error);

/// Writes `html` (with its images, given as file names relative to `dir`) as a PDF at `pdfPath`.
bool writePdf(const QString& html, const QString& dir, const QStringList& images, const QString& pdfPath,
              QString* error);

}  // namespace archipelago::ui::report
