#pragma once
/// \file HelpDialogs.hpp
/// \brief The Help menu's dialogs: Keyboard Shortcuts (every key of every menu, and the mouse) and About.

#include <QList>
#include <QPair>
#include <QString>

class QMenuBar;
class QWidget;

namespace archipelago::ui {

/// Every key of every menu of `bar` (menu path, keys), then the mouse on the portrait and the plots.
[[nodiscard]] QList<QPair<QString, QString>> keyboardShortcuts(const QMenuBar& bar);
/// The table of `rows` in a dialog of `parent` (not modal, deleted on close), sized to the screen.
void showKeyboardShortcuts(QWidget* parent, const QList<QPair<QString, QString>>& rows);
/// About Archipelago: the paper, the versions of Qt and Qwt, and `kernel`, the block kernel in use.
void showAbout(QWidget* parent, const QString& kernel);

}  // namespace archipelago::ui
