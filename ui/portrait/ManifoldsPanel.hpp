#pragma once
/// \file ManifoldsPanel.hpp
/// \brief The "Manifolds and flux" page beside the portrait: which hyperbolic orbit's manifolds the portrait
/// draws, and the numbers of its turnstile (issue 28, deliverable 5).
///
/// The numbers are core's (core/manifolds, TurnstileFlux): the homoclinic (heteroclinic) points, the lobe area —
/// the flux per step — by the difference of two actions and by the polygon between the manifold arcs, their
/// agreeing digits, the resonance zone's area both ways; the same that `archipelago-cli flux --json` prints,
/// which "Export JSON…" writes (core's turnstileJson).  The PortraitController computes them in the background;
/// this page only shows them.

#include <QWidget>

class QCheckBox;
class QComboBox;
class QLabel;
class QPushButton;

namespace archipelago::ui {

class PortraitController;

class ManifoldsPanel : public QWidget {
  Q_OBJECT
 public:
  ManifoldsPanel(PortraitController* controller, QWidget* parent = nullptr);

  /// The numbers as shown (rich text), and the lobe area displayed (NaN while none).
  [[nodiscard]] QString numbersText() const;
  [[nodiscard]] double displayedLobeArea() const noexcept { return lobeArea_; }
  /// Writes core's JSON of the flux shown (as `archipelago-cli flux --json`).  False with the reason.
  bool exportJson(const QString& path, QString* error = nullptr);

 Q_SIGNALS:
  void statusMessage(const QString& text);

 private:
  void refresh();

  PortraitController* controller_;
  QCheckBox* shown_ = nullptr;
  QComboBox* orbit_ = nullptr;
  QLabel* numbers_ = nullptr;
  QPushButton* export_ = nullptr;
  double lobeArea_;
};

}  // namespace archipelago::ui
