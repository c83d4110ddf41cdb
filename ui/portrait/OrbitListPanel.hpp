#pragma once
/// \file OrbitListPanel.hpp
/// \brief The "Orbits" page beside the portrait: the launched orbits with their colour, start, steps and
/// measures (rotation number, digits, island chain), highlight, undo and clear (issue 25, deliverable 6;
/// issue 27, deliverable 3).
///
/// A view of the PortraitController's list: it shows what the controller holds and asks it to highlight or
/// remove; the orbits themselves (their points, their measures) are computed by the controller's background jobs
/// through core.  Selecting a row highlights that orbit on the portrait and draws its chain's elliptic orbit.

#include <QWidget>

class QCheckBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QSpinBox;
class QTimer;
class QTreeWidget;

namespace archipelago::ui {

class PortraitController;

class OrbitListPanel : public QWidget {
  Q_OBJECT
 public:
  OrbitListPanel(PortraitController* controller, QWidget* parent = nullptr);

  [[nodiscard]] QTreeWidget* list() const noexcept { return list_; }
  /// The details of the selected orbit, as shown under the list (rich text).
  [[nodiscard]] QString detailsText() const;
  [[nodiscard]] QSize sizeHint() const override { return {300, 400}; }
  /// What a click launches, and a typed start (issue 37, finding 15): the steps, N⁻¹, the start's fields.
  [[nodiscard]] QSpinBox* stepsBox() const noexcept { return steps_; }
  [[nodiscard]] QCheckBox* backwardBox() const noexcept { return backward_; }
  [[nodiscard]] QLineEdit* startXField() const noexcept { return startX_; }
  [[nodiscard]] QLineEdit* startYField() const noexcept { return startY_; }
  /// Launches an orbit from the typed start with the steps and direction shown; false (the reason in the status
  /// bar) when a coordinate is not a number or the point is not in the box.
  bool launchTyped();
  /// A line or a grid of orbits (issue 37, finding 15): from the typed start to the "to" point, `columns`
  /// orbits per row and `rows` rows (1: a line).
  [[nodiscard]] QLineEdit* endXField() const noexcept { return endX_; }
  [[nodiscard]] QLineEdit* endYField() const noexcept { return endY_; }
  [[nodiscard]] QSpinBox* columnsBox() const noexcept { return columns_; }
  [[nodiscard]] QSpinBox* rowsBox() const noexcept { return rows_; }
  /// Launches the line or grid with the steps and direction shown; how many were launched (0: refused, the reason
  /// in the status bar: a coordinate not a number, or core's rule of the count).
  int launchFamily();
  /// Writes the selected orbit as CSV (the CLI's `orbit` output; issue 37, finding 20).
  bool exportSelectedCsv(const QString& path, QString* error = nullptr);

 Q_SIGNALS:
  void statusMessage(const QString& text);

 private:
  /// The constructor's steps, in the order the widgets are made (the order of the Tab chain): the list and its
  /// details; Undo, Remove, Clear and CSV; what a click launches (steps, N⁻¹); the typed start and Launch; the line
  /// or grid's other end, its counts and Line/Grid; the list's connections; then the page's layout.
  void createList();
  void createListButtons();
  void createClickControls();
  void createStartFields();
  void createFamilyControls();
  void connectList();
  void layOut();
  void refresh();
  void updateDetails();

  PortraitController* controller_;
  QTreeWidget* list_ = nullptr;
  QLabel* details_ = nullptr;
  QLabel* empty_ = nullptr;
  QPushButton* remove_ = nullptr;
  QPushButton* clear_ = nullptr;
  QPushButton* undo_ = nullptr;
  QPushButton* csv_ = nullptr;
  QSpinBox* steps_ = nullptr;
  QCheckBox* backward_ = nullptr;
  QLineEdit* startX_ = nullptr;
  QLineEdit* startY_ = nullptr;
  QLineEdit* endX_ = nullptr;
  QLineEdit* endY_ = nullptr;
  QSpinBox* columns_ = nullptr;
  QSpinBox* rows_ = nullptr;
  QPushButton* launch_ = nullptr;
  QPushButton* family_ = nullptr;
  QTimer* refreshTimer_ = nullptr;
};

}  // namespace archipelago::ui
