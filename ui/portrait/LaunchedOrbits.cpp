#include "ui/portrait/LaunchedOrbits.hpp"

#include <QCoreApplication>

#include <cmath>

namespace archipelago::ui {

namespace {
QString tr(const char* text) { return QCoreApplication::translate("LaunchedOrbits", text); }
}  // namespace

QString rotationText(const OrbitMeasuresResult& m) {
  if (!m.error.isEmpty() || m.chain.levels.empty()) return tr("—");
  const RotationMeasurement& r = m.chain.levels.front().rotation;
  const QString digits = std::isfinite(r.digits) ? QString::number(r.digits, 'f', 1) : QStringLiteral("?");
  switch (r.verdict) {
    case OrbitVerdict::Regular:
      if (const auto& q = m.chain.levels.front().rational)
        return tr("%1 = %2 (%3 digits)").arg(QString::fromStdString(toString(*q))).arg(r.rotation, 0, 'g', 10).arg(digits);
      return tr("%1 (%2 digits)").arg(r.rotation, 0, 'g', 10).arg(digits);
    case OrbitVerdict::Chaotic: return tr("none: chaotic (%1 digits)").arg(digits);
    case OrbitVerdict::Escaping: return tr("none: leaves the box");
    default: return tr("—");
  }
}

QString chainText(const OrbitMeasuresResult& m) {
  if (!m.error.isEmpty()) return m.error;
  if (m.chain.period > 1) {
    QStringList factors;
    for (std::int64_t f : m.chain.factors) factors << QString::number(f);
    return factors.size() > 1 ? tr("chain %1 = %2").arg(factors.join(QStringLiteral(" × "))).arg(m.chain.period)
                              : tr("chain of period %1").arg(m.chain.period);
  }
  return QString::fromStdString(m.chain.ending);
}

}  // namespace archipelago::ui
