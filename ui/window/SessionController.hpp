#pragma once
/// \file SessionController.hpp
/// \brief File ▸ Save Session / Open Session: the window as it is, in a `.archipelago` file (core/session's codec).
///
/// A session holds the parameters, the run (referenced when it is saved in a file and unchanged since, else
/// embedded), the portrait's exact view with its history, mode, colour map, points budget, launched orbits and
/// periodic-orbit overlays, the selected long segment with its replay position, the plots the user zoomed, the
/// active tab and the page beside the portrait, the Atlas page's atlas (of the session's map; while it computes, the
/// islands finished so far) with its Markov tree's α and b₂ (computed again on opening), and the tail file drawn on
/// P_t (read again once the run's statistics are back; issue 53, finding 3).  Opening reads and validates the whole file first (core), then checks what only the window
/// knows (plot and tab names): a bad or foreign file changes nothing and the reason is returned.  Discarding
/// unsaved work asks (the run controller).  What depends on the run (the segment table, plot ranges) is applied
/// when its analysis has come back.
///
/// The controller sees the window's parts (SessionParts), never the window itself: MainWindow creates it and
/// includes this header, and this file includes none of MainWindow's (no include cycle between the two).

#include <QObject>
#include <QString>

#include <functional>
#include <optional>

#include "core/session/SessionFile.hpp"

class QTabWidget;

namespace archipelago::ui {

class LongSegmentsPanel;
class ParameterPanel;
class PortraitPanel;
class RunController;
class StatisticsView;
class TailEstimateController;

/// What a session captures and restores: the window's parts (none may be null) and two of its actions.
struct SessionParts {
  ParameterPanel* parameters = nullptr;
  RunController* run = nullptr;
  StatisticsView* statistics = nullptr;
  PortraitPanel* portrait = nullptr;
  LongSegmentsPanel* segments = nullptr;
  QTabWidget* tabs = nullptr;
  /// The tail file whose estimate P_t shows, and drawing one again.
  TailEstimateController* tailEstimates = nullptr;
  /// Shows the run's newest snapshot now (plots, segment table), instead of at the window's next refresh.
  std::function<void()> refreshNow;
  /// Selects the long segment of this rank as soon as the segment table has it (the window raises its dock).
  std::function<void(int rank)> showSegment;
};

class SessionController : public QObject {
  Q_OBJECT
 public:
  SessionController(SessionParts parts, QObject* parent);

  /// The window as it is now.  The run is embedded unless it is in `currentFile` unchanged; a referenced run's
  /// path is written relative to `sessionPath`'s folder when it lies inside it.
  [[nodiscard]] Session capture(const QString& sessionPath) const;
  bool save(const QString& path, QString* error = nullptr);
  /// Opens a session file.  False with the reason in `error` when it cannot (nothing changed), or when the user
  /// cancelled (error "Cancelled").
  bool open(const QString& path, QString* error = nullptr);
  /// Restores `session` (already validated by core).
  bool apply(const Session& session, QString* error = nullptr);
  /// True while parts of an opened session wait for its run's analysis.
  [[nodiscard]] bool restoring() const noexcept { return pending_.has_value(); }

 Q_SIGNALS:
  /// Everything of an opened session is on screen.
  void restored();

 private:
  [[nodiscard]] std::optional<QString> windowError(const Session& session) const;
  void applyViews(const Session& session);
  void applyRunDependent(const Session& session);
  void selectTab(const std::string& tab);
  void selectSidePage(const std::string& page);
  /// The Markov tree's and the tail estimate's curves, from their inputs (once the run's statistics are shown).
  void redrawModels(const Session& session);

  SessionParts parts_;
  std::optional<Session> pending_;
};

}  // namespace archipelago::ui
