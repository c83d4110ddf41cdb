#pragma once
/// \file QwtCompat.hpp
/// \brief The few names that differ between Qwt 6.1 (Qt 5) and Qwt 6.2 (Qt 5 or 6).

#include <qwt_global.h>
#include <qwt_plot.h>

namespace archipelago::ui {

#if QWT_VERSION >= 0x060200
inline constexpr int kAxisX = QwtAxis::XBottom;  // QwtAxisId is an int in 6.2
inline constexpr int kAxisY = QwtAxis::YLeft;
#else
inline constexpr int kAxisX = QwtPlot::xBottom;
inline constexpr int kAxisY = QwtPlot::yLeft;
#endif

}  // namespace archipelago::ui
