#pragma once
/// \file LogScaleDraw.hpp
/// \brief Tick labels of a logarithmic axis as powers of ten (10⁶ rather than 1,000,000 or 1e+06), so that
/// labels over many decades stay short and never overlap.

#include <qwt_scale_draw.h>

namespace archipelago::ui {

class LogScaleDraw : public QwtScaleDraw {
 public:
  [[nodiscard]] QwtText label(double value) const override;
};

}  // namespace archipelago::ui
