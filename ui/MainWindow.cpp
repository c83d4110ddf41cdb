#include "MainWindow.hpp"

#include <QApplication>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QStatusBar>
#include <qwt_global.h>

namespace archipelago::ui {

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
  setWindowTitle(tr("Archipelago"));
  auto* placeholder = new QLabel(tr("Archipelago — stickiness of islands around islands (Karney 1983)"), this);
  placeholder->setAlignment(Qt::AlignCenter);
  setCentralWidget(placeholder);
  createMenus();
  statusBar()->showMessage(tr("Ready"));
  resize(1200, 800);
}

void MainWindow::createMenus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  QAction* quit = file->addAction(tr("&Quit"), this, &QWidget::close);
  quit->setShortcut(QKeySequence::Quit);
  QMenu* help = menuBar()->addMenu(tr("&Help"));
  help->addAction(tr("&About Archipelago"), this, &MainWindow::showAbout);
  help->addAction(tr("About &Qt"), qApp, &QApplication::aboutQt);
}

void MainWindow::showAbout() {
  QMessageBox::about(this, tr("About Archipelago"),
                     tr("<h3>Archipelago %1</h3>"
                        "<p>Exact trapping statistics of the quadratic map Q*.</p>"
                        "<p>Reproduces C. F. F. Karney, <i>Long-time correlations in the stochastic regime</i>, "
                        "Physica D <b>8</b>, 360–380 (1983).</p>"
                        "<p>Qt %2 (built with %3), Qwt %4</p>")
                         .arg(QStringLiteral(ARCHIPELAGO_VERSION), QString::fromLatin1(qVersion()),
                              QStringLiteral(QT_VERSION_STR), QStringLiteral(QWT_VERSION_STR)));
}

}  // namespace archipelago::ui
