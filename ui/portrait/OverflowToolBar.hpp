#pragma once
/// \file OverflowToolBar.hpp
/// \brief A one-row tool bar whose items that do not fit go behind a » button that opens a menu of them.
///
/// QToolBar's own extension button only works inside a QMainWindow's tool-bar area: in a plain layout (the
/// portrait's controls above the portrait) it did nothing, and Export PNG…, Export .npy… and b₂… could not be
/// reached (issue 25, finding 1).  This bar lays its items out left to right; those past its width are hidden
/// and the » button (shown only then) opens a menu holding, for each hidden item, the action or submenu that
/// does the same.  Its minimum width is that of the » button: it never sets the window's minimum width.

#include <QPointer>
#include <QWidget>

#include <vector>

class QAction;
class QMenu;
class QToolButton;

namespace archipelago::ui {

class OverflowToolBar : public QWidget {
  Q_OBJECT
 public:
  explicit OverflowToolBar(QWidget* parent = nullptr);

  /// Adds `widget` (the bar takes it over); when it does not fit, the » menu offers `equivalent` instead: an
  /// action, or a submenu's menuAction() (may be null: then nothing replaces it, e.g. a label).
  void addItem(QWidget* widget, QAction* equivalent);
  /// A tool button for `action` (its text, enabled state and tool tip follow the action).
  QToolButton* addAction(QAction* action);
  /// A thin vertical line between groups.
  void addSeparator();

  /// The » button (shown only when some item is hidden) and the actions its menu offers now.
  [[nodiscard]] QToolButton* overflowButton() const noexcept { return overflow_; }
  [[nodiscard]] std::vector<QAction*> overflowActions() const;

  [[nodiscard]] QSize sizeHint() const override;
  [[nodiscard]] QSize minimumSizeHint() const override;

 protected:
  void resizeEvent(QResizeEvent* event) override;
  bool event(QEvent* event) override;

 private:
  struct Item {
    QPointer<QWidget> widget;
    QPointer<QAction> equivalent;
    bool separator = false;
  };
  void relayout();
  void fillMenu();

  std::vector<Item> items_;
  QToolButton* overflow_ = nullptr;
  QMenu* menu_ = nullptr;
  int spacing_ = 2;
};

}  // namespace archipelago::ui
