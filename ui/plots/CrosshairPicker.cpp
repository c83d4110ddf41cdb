#include "ui/plots/CrosshairPicker.hpp"

#include <QColor>
#include <QPen>
#include <qwt_picker_machine.h>
#include <qwt_text.h>

#include "ui/plots/QwtCompat.hpp"

namespace archipelago::ui {

CrosshairPicker::CrosshairPicker(QWidget* canvas)
    : QwtPlotPicker(kAxisX, kAxisY, QwtPicker::CrossRubberBand, QwtPicker::AlwaysOn, canvas) {
  setStateMachine(new QwtPickerTrackerMachine);
  setRubberBandPen(QPen(QColor(90, 90, 90, 140), 1, Qt::DashLine));
  setTrackerPen(QPen(QColor(30, 30, 30)));
}

QwtText CrosshairPicker::trackerTextF(const QPointF& p) const {
  QwtText text(QStringLiteral("(%1, %2)").arg(p.x(), 0, 'g', 4).arg(p.y(), 0, 'g', 4));
  text.setBackgroundBrush(QColor(255, 255, 255, 210));
  return text;
}

}  // namespace archipelago::ui
