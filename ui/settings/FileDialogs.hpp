#pragma once
/// \file FileDialogs.hpp
/// \brief The file dialogs of the window's File menu: each starts in the folder the last one used and remembers the
/// folder chosen (SettingsController::lastFolder, rememberFolder).  Each returns the path chosen, empty when cancelled.

#include <QString>

class QWidget;

namespace archipelago::ui {

/// An existing file to open.
[[nodiscard]] QString askOpenFile(QWidget* parent, const QString& title, const QString& filter);
/// A file to write, offered as `name` in the last folder.
[[nodiscard]] QString askSaveFile(QWidget* parent, const QString& title, const QString& name, const QString& filter);
/// A folder to write into.
[[nodiscard]] QString askFolder(QWidget* parent, const QString& title);

}  // namespace archipelago::ui
