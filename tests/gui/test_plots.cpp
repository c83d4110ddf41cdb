// The statistics plots on their own (issue #13, findings 8, 9 and 13): a placeholder before any run, the
// local exponent's range following its data, t_max kept on the canvas, plain Unicode titles in exported files.
#include <QFile>
#include <QTemporaryDir>

#include <cmath>

#include "GuiTestSupport.hpp"
#include "ui/plots/StatisticsPlot.hpp"

using archipelago::Series;
using archipelago::Statistic;
using archipelago::TheoryCurve;
using archipelago::ui::StatisticsPlot;

namespace {
/// value(t) at t = 1 … n, with error e.
Series series(int n, double (*value)(double), double error) {
  Series s;
  for (int t = 1; t <= n; ++t) {
    s.x.push_back(t);
    s.value.push_back(value(t));
    s.error.push_back(error);
  }
  return s;
}
}  // namespace

class TestPlots : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  // Bug: before any run the plots spanned 10⁻¹⁰⁰ … 1 with a legend and a crosshair readout.
  void emptyPlotsShowAPlaceholderOverSensibleAxes() {
    for (Statistic st : {Statistic::f, Statistic::C, Statistic::S, Statistic::localExponent}) {
      StatisticsPlot plot(st);
      plot.resize(400, 300);
      plot.show();
      plot.refresh();
      QVERIFY(plot.isEmpty());
      QVERIFY(plot.placeholderShown());
      QVERIFY(!plot.legendShown());
      QVERIFY(!plot.crosshairEnabled());
      const QwtInterval x = plot.axisInterval(QwtPlot::xBottom), y = plot.axisInterval(QwtPlot::yLeft);
      QCOMPARE(x.maxValue(), 1e4);
      // At most 7 decades on a log axis (it was 100), 0 … 3 for the exponent.
      const bool sensible = y.maxValue() <= 1e6 && (y.minValue() > 0 ? y.maxValue() / y.minValue() <= 1e7 : y.minValue() == 0);
      QVERIFY2(sensible,
               qPrintable(QStringLiteral("%1 … %2").arg(y.minValue()).arg(y.maxValue())));
    }
    StatisticsPlot plot(Statistic::f);
    plot.setData(series(30, [](double t) { return std::pow(t, -3.0); }, 0), {});
    plot.refresh();
    QVERIFY(!plot.placeholderShown());
    QVERIFY(plot.legendShown());
    QVERIFY(plot.crosshairEnabled());
    QVERIFY(plot.axisInterval(QwtPlot::yLeft).minValue() < 1e-4);  // follows the data: 30⁻³ = 3.7e-5
    plot.clearData();
    plot.resetZoom();
    QVERIFY(plot.placeholderShown());
    QVERIFY(!plot.legendShown());
  }

  // Bug: the exponent plot was fixed at 0 … 3, so K = 0's τ⁻⁵ regime (exponent 5) was off scale.
  void exponentRangeFollowsTheData() {
    StatisticsPlot plot(Statistic::localExponent);
    // Exponent 5 measured to ±0.1, then a noisy tail reaching 40 with large errors (few segments left).
    Series s = series(200, [](double) { return 5.0; }, 0.1);
    for (std::size_t i = 180; i < s.x.size(); ++i) {
      s.value[i] = 40;
      s.error[i] = 20;
    }
    plot.setData(s, {});
    plot.refresh();
    const QwtInterval y = plot.axisInterval(QwtPlot::yLeft);
    QVERIFY2(y.minValue() <= 0 && y.maxValue() > 5 && y.maxValue() < 8,
             qPrintable(QStringLiteral("%1 … %2").arg(y.minValue()).arg(y.maxValue())));
    // K = 0.1: exponent about 0.25 (fig. 5d): the range is the paper's 0 … 2.
    plot.setData(series(200, [](double) { return 0.25; }, 0.05), {});
    plot.resetZoom();
    QCOMPARE(plot.axisInterval(QwtPlot::yLeft).maxValue(), 2.0);
  }

  // Bug: the t_max label was clipped: the data of fig. 3a ended before t_max, the x range with them.
  void tmaxLineStaysOnTheCanvas() {
    StatisticsPlot plot(Statistic::f);
    TheoryCurve line;
    line.statistic = Statistic::f;
    line.kind = TheoryCurve::Kind::verticalLine;
    line.label = "t_max";
    line.labelRich = "t<sub>max</sub> = 5.1454 |K|<sup>−1/4</sup>";
    line.at = 51.454;
    plot.setData(series(37, [](double t) { return std::pow(t, -6.0); }, 0), {line});
    plot.refresh();
    QVERIFY(plot.axisInterval(QwtPlot::xBottom).maxValue() >= 1.2 * 51.454);
  }

  // Bug: the SVG's title held the markup "f<sub>t</sub>".
  void exportedTitlesArePlainText() {
    QTemporaryDir dir;
    StatisticsPlot plot(Statistic::f);
    plot.setData(series(30, [](double t) { return std::pow(t, -3.0); }, 0), {});
    plot.refresh();
    QCOMPARE(plot.plainTitle(), QStringLiteral("fₜ — distribution of trapping times"));
    StatisticsPlot c(Statistic::C);
    QVERIFY2(!c.plainTitle().contains(QLatin1Char('<')), qPrintable(c.plainTitle()));
    const QString svg = dir.filePath(QStringLiteral("f_t.svg"));
    QVERIFY(plot.exportImage(svg));
    QFile file(svg);
    QVERIFY(file.open(QIODevice::ReadOnly));
    const QString text = QString::fromUtf8(file.readAll());
    QVERIFY2(text.contains(QStringLiteral("<title>fₜ — distribution of trapping times</title>")), qPrintable(text.left(600)));
    QVERIFY(!text.contains(QStringLiteral("&lt;sub")));
    QVERIFY(!text.contains(QStringLiteral("<sub>")));
    for (const char* suffix : {"png", "pdf"}) {
      const QString path = dir.filePath(QStringLiteral("f_t.") + QLatin1String(suffix));
      QVERIFY(plot.exportImage(path));
      QVERIFY(QFileInfo(path).size() > 1000);
    }
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestPlots)
#include "test_plots.moc"
