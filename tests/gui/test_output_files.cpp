// ui/files/OutputFiles and the report's PDF (issue #23, finding 3): on a full disk the report once exited 0 with
// its PDF cut short, and a killed or failing PNG write left a truncated figure.  Every image and document is now
// rendered in memory, checked whole and published atomically: a write that fails leaves the old file (or none)
// and says why.  A full disk is simulated with RLIMIT_FSIZE (a write past it fails with EFBIG, as with ENOSPC).
#include <QImage>
#include <QTemporaryDir>
#include <QtTest>

#include <sys/resource.h>

#include <csignal>
#include <fstream>

#include "ui/files/OutputFiles.hpp"
#include "ui/report/ReportFigures.hpp"

using namespace archipelago::ui;

namespace {
/// Files this process writes may not exceed `bytes` while it lives.
class SmallDisk {
 public:
  explicit SmallDisk(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &previous_);
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{bytes, previous_.rlim_max};
    ::setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~SmallDisk() { ::setrlimit(RLIMIT_FSIZE, &previous_); }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;

 private:
  rlimit previous_{};
};

QByteArray contents(const QString& path) {
  QFile f(path);
  return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}
}  // namespace

class OutputFilesTest : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void pdfOnAFullDisk_Issue23_FailsAndKeepsTheOldFile() {
    QTemporaryDir dir;
    const QString pdf = dir.filePath(QStringLiteral("report.pdf"));
    QString html = QStringLiteral("<h1>Report</h1>");
    for (int i = 0; i < 200; ++i) html += QStringLiteral("<p>Paragraph %1 of a long report.</p>").arg(i);
    QString error;
    QVERIFY2(report::writePdf(html, dir.path(), {}, pdf, &error), qPrintable(error));
    const QByteArray whole = contents(pdf);
    QVERIFY(isCompletePdf(whole));
    {
      const SmallDisk disk(static_cast<rlim_t>(whole.size() / 2));
      error.clear();
      QVERIFY(!report::writePdf(html + QStringLiteral("<p>more</p>"), dir.path(), {}, pdf, &error));
    }
    QVERIFY2(error.contains(pdf), qPrintable(error));
    QCOMPARE(contents(pdf), whole);  // the old, complete file
    QCOMPARE(QDir(dir.path()).entryList(QDir::Hidden | QDir::Files).filter(QStringLiteral(".report.pdf.")).size(), 0);
  }

  void pngOnAFullDisk_Issue23_FailsWithOneReasonAndNoFile() {
    QTemporaryDir dir;
    const QString png = dir.filePath(QStringLiteral("fig.png"));
    QImage image(600, 400, QImage::Format_RGB32);
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) image.setPixel(x, y, qRgb(x * 37 % 256, y * 91 % 256, (x ^ y) % 256));
    QString error;
    {
      const SmallDisk disk(1000);
      QVERIFY(!writePngFile(image, png, &error));
    }
    QVERIFY2(error.contains(png), qPrintable(error));
    QVERIFY(!QFile::exists(png));
    QVERIFY(writePngFile(image, png, &error));
    QCOMPARE(QImage(png).convertToFormat(QImage::Format_RGB32), image);
  }

  void completenessChecks_DetectCutDocuments() {
    QVERIFY(isCompletePdf(QByteArray("%PDF-1.4\n...\n%%EOF\n")));
    QVERIFY(!isCompletePdf(QByteArray("%PDF-1.4\n...\n")));
    QVERIFY(!isCompletePdf(QByteArray("<svg></svg>")));
    QVERIFY(isCompleteSvg(QByteArray("<?xml?><svg width='1'></svg>\n")));
    QVERIFY(!isCompleteSvg(QByteArray("<?xml?><svg width='1'>")));
  }
};

QTEST_MAIN(OutputFilesTest)
#include "test_output_files.moc"
