// archipelago: the desktop application (Qt Widgets + Qwt).
#include <QApplication>

#include "MainWindow.hpp"

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  QApplication::setApplicationName(QStringLiteral("Archipelago"));
  QApplication::setOrganizationName(QStringLiteral("Archipelago"));
  QApplication::setApplicationVersion(QStringLiteral(ARCHIPELAGO_VERSION));
  archipelago::ui::MainWindow window;
  window.show();
  return QApplication::exec();
}
