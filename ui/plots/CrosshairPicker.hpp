#pragma once
/// \file CrosshairPicker.hpp
/// \brief A crosshair that follows the mouse over a plot canvas and shows the coordinates under it.

#include <qwt_plot_picker.h>

namespace archipelago::ui {

class CrosshairPicker : public QwtPlotPicker {
 public:
  explicit CrosshairPicker(QWidget* canvas);

 protected:
  [[nodiscard]] QwtText trackerTextF(const QPointF& position) const override;
};

}  // namespace archipelago::ui
