#include "ui/settings/FileDialogs.hpp"

#include <QDir>
#include <QFileDialog>

#include "ui/settings/SettingsController.hpp"

namespace archipelago::ui {

namespace {
/// `path` (empty: cancelled), its folder remembered.
QString remembered(const QString& path) {
  if (!path.isEmpty()) SettingsController::rememberFolder(path);
  return path;
}
}  // namespace

QString askOpenFile(QWidget* parent, const QString& title, const QString& filter) {
  return remembered(QFileDialog::getOpenFileName(parent, title, SettingsController::lastFolder(), filter));
}

QString askSaveFile(QWidget* parent, const QString& title, const QString& name, const QString& filter) {
  return remembered(
      QFileDialog::getSaveFileName(parent, title, QDir(SettingsController::lastFolder()).filePath(name), filter));
}

QString askFolder(QWidget* parent, const QString& title) {
  return remembered(QFileDialog::getExistingDirectory(parent, title, SettingsController::lastFolder()));
}

}  // namespace archipelago::ui
