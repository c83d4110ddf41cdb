#include "ui/jobs/DurationText.hpp"

namespace archipelago::ui {

QString formatDuration(double seconds) {
  if (!(seconds >= 0) || seconds > 1e9) return QStringLiteral("—");
  const auto s = static_cast<qint64>(seconds + 0.5);
  if (s >= 3600) return QStringLiteral("%1:%2:%3").arg(s / 3600).arg(s / 60 % 60, 2, 10, QLatin1Char('0'))
                                                   .arg(s % 60, 2, 10, QLatin1Char('0'));
  return QStringLiteral("%1:%2").arg(s / 60).arg(s % 60, 2, 10, QLatin1Char('0'));
}

}  // namespace archipelago::ui
