#include "ui/settings/SettingsController.hpp"

#include <QDir>
#include <QFileInfo>
#include <QGuiApplication>
#include <QMainWindow>
#include <QScreen>
#include <QSettings>

#include <algorithm>
#include <stdexcept>

#include "core/io/BadFile.hpp"

namespace archipelago::ui {

QRect SettingsController::clampToScreen(const QRect& wanted, const QRect& available) {
  if (!available.isValid()) return wanted;
  QRect r = wanted;
  r.setWidth(std::min(r.width(), available.width()));
  r.setHeight(std::min(r.height(), available.height()));
  if (r.right() > available.right()) r.moveRight(available.right());
  if (r.bottom() > available.bottom()) r.moveBottom(available.bottom());
  if (r.left() < available.left()) r.moveLeft(available.left());
  if (r.top() < available.top()) r.moveTop(available.top());
  return r;
}

QRect SettingsController::firstGeometry(const QRect& available) {
  const QSize size(std::min(available.width(), std::max(1200, available.width() * 9 / 10)),
                   std::min(available.height(), std::max(760, available.height() * 9 / 10)));
  QRect r(QPoint(0, 0), size);
  r.moveCenter(available.center());
  return r;
}

void SettingsController::restoreWindow(QMainWindow& window) {
  QSettings settings;
  const bool restored = window.restoreGeometry(settings.value(QStringLiteral("window/geometry")).toByteArray());
  window.restoreState(settings.value(QStringLiteral("window/state")).toByteArray());
  const QScreen* screen = window.screen() ? window.screen() : QGuiApplication::primaryScreen();
  if (!screen) return;
  const QRect available = screen->availableGeometry();
  if (!restored) {
    window.setGeometry(firstGeometry(available));
    return;
  }
  if (window.isMaximized() || window.isFullScreen()) return;
  const QRect clamped = clampToScreen(window.geometry(), available);
  if (clamped != window.geometry()) window.setGeometry(clamped);
}

void SettingsController::saveWindow(const QMainWindow& window) {
  QSettings settings;
  settings.setValue(QStringLiteral("window/geometry"), window.saveGeometry());
  settings.setValue(QStringLiteral("window/state"), window.saveState());
}

std::optional<RunSpec> SettingsController::lastSpec(QString* error) {
  const QString text = QSettings().value(QStringLiteral("run/spec")).toString();
  if (text.isEmpty()) return std::nullopt;
  try {
    return parseRunSpec(text.toStdString());
  } catch (const io::BadFile& e) {
    if (error) *error = QString::fromStdString(e.what());
    return std::nullopt;
  }
}

void SettingsController::setLastSpec(const RunSpec& spec) {
  QSettings().setValue(QStringLiteral("run/spec"), QString::fromStdString(runSpecJson(spec)));
}

QStringList SettingsController::recentFiles() {
  return QSettings().value(QStringLiteral("recentFiles")).toStringList();
}

void SettingsController::addRecentFile(const QString& path) {
  QSettings settings;
  QStringList files = settings.value(QStringLiteral("recentFiles")).toStringList();
  const QString absolute = QFileInfo(path).absoluteFilePath();
  files.removeAll(absolute);
  files.prepend(absolute);
  while (files.size() > kMaxRecentFiles) files.removeLast();
  settings.setValue(QStringLiteral("recentFiles"), files);
}

QString SettingsController::lastFolder() {
  const QString folder = QSettings().value(QStringLiteral("files/lastFolder")).toString();
  return !folder.isEmpty() && QFileInfo(folder).isDir() ? folder : QDir::homePath();
}

void SettingsController::rememberFolder(const QString& path) {
  if (path.isEmpty()) return;
  const QFileInfo info(path);
  QSettings().setValue(QStringLiteral("files/lastFolder"), info.isDir() ? info.absoluteFilePath() : info.absolutePath());
}

}  // namespace archipelago::ui
