#include "ui/plots/LogScaleDraw.hpp"

#include <qwt_text.h>

#include <cmath>

namespace archipelago::ui {

QwtText LogScaleDraw::label(double value) const {
  if (!(value > 0)) return QwtText(QString::number(value, 'g', 3));
  const double decade = std::round(std::log10(value));
  if (std::abs(std::log10(value) - decade) > 1e-9) return QwtText(QString::number(value, 'g', 3));
  const int n = static_cast<int>(decade);
  if (n == 0) return QwtText(QStringLiteral("1"));
  if (n == 1) return QwtText(QStringLiteral("10"));
  return QwtText(QStringLiteral("10<sup>%1</sup>").arg(n), QwtText::RichText);
}

}  // namespace archipelago::ui
