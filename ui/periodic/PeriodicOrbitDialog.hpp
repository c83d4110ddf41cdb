#pragma once
/// \file PeriodicOrbitDialog.hpp
/// \brief "Find periodic orbit": K, period n, a point near the orbit, stable only → the orbit's points, its
/// residue, stability and rotation number (Karney 1983, §6; Greene's residue R = (2 − trace DQⁿ)/4).
///
/// The search is core's findPeriodicOrbit() (periodic/PeriodicOrbitFinder.hpp), run as a job of ui/jobs (BackgroundJobs) and
/// tagged with a request id: the latest search wins, a newer search drops the answer of an older one.  "Overlay" hands the orbit to whoever
/// listens (the main window draws it on the phase portrait).

#include <QDialog>

#include <memory>
#include <optional>

#include "core/periodic/PeriodicOrbit.hpp"

class QCheckBox;
class QDialogButtonBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QSpinBox;
class QTableWidget;

namespace archipelago::ui {

class BackgroundJobs;

class PeriodicOrbitDialog : public QDialog {
  Q_OBJECT
 public:
  explicit PeriodicOrbitDialog(QWidget* parent = nullptr);
  ~PeriodicOrbitDialog() override;

  void setK(double K);
  void setPeriod(int period);
  void setNear(double x, double y);
  void setStableOnly(bool on);
  [[nodiscard]] double K() const;

  /// Starts a search with the values in the form (also the "Find" button).
  void find();
  /// Finds the hyperbolic partner of the elliptic orbit shown (core's findHyperbolicPartner): the unstable orbit
  /// between its islands, whose manifolds are the chain's separatrices.  (The "Hyperbolic Partner" button.)
  void findPartner();
  /// The note on coordinates shown above the form (tests).
  [[nodiscard]] QString coordinatesNote() const;
  /// The orbit found by the last search that succeeded (nothing before, or after a failed search).
  [[nodiscard]] const std::optional<PeriodicOrbit>& orbit() const noexcept { return orbit_; }
  /// True while a search runs.
  [[nodiscard]] bool searching() const noexcept { return searching_; }

 Q_SIGNALS:
  /// A search ended: found or not (then the result label says why).
  void searchFinished(bool found);
  /// The user asked to draw this orbit on the portrait.
  void overlayRequested(const archipelago::PeriodicOrbit& orbit);
  /// The user asked for the manifolds of this hyperbolic orbit on the portrait (issue #28).
  void manifoldsRequested(const archipelago::PeriodicOrbit& orbit);

 private:
  void onResult(quint64 requestId, const std::optional<PeriodicOrbit>& orbit, const QString& error);
  void showOrbit();
  void updateButtons();

  QLineEdit* kEdit_ = nullptr;
  QSpinBox* periodBox_ = nullptr;
  QLineEdit* xEdit_ = nullptr;
  QLineEdit* yEdit_ = nullptr;
  QDoubleSpinBox* radiusBox_ = nullptr;
  QCheckBox* stableBox_ = nullptr;
  QPushButton* findButton_ = nullptr;
  QPushButton* overlayButton_ = nullptr;
  QPushButton* partnerButton_ = nullptr;
  QPushButton* manifoldsButton_ = nullptr;
  QLabel* note_ = nullptr;
  QLabel* summary_ = nullptr;
  QTableWidget* points_ = nullptr;
  std::unique_ptr<BackgroundJobs> jobs_;
  quint64 request_ = 0;
  bool searching_ = false;
  std::optional<PeriodicOrbit> orbit_;
};

}  // namespace archipelago::ui

Q_DECLARE_METATYPE(archipelago::PeriodicOrbit)
