#pragma once
/// \file Presets.hpp
/// \brief The paper's cases as ready-made parameter sets, read from resources/presets/*.json.
///
/// Each preset file holds {"name", "description", "K", "xmin", "xmax", "Xr", "q", "T", "M", "seed", "subsets"}.
/// They reproduce Karney (1983): figure 3's small-K runs (K = −10⁻⁴, 0, 10⁻⁴ in a small box around the
/// origin, q = 1) and figure 5's long K = 0.1 run (M = 1600 orbits of qT = 2·10⁹ steps), plus a K = 0.1 run of
/// modest size that the application starts with (under a minute on two cores, seconds with AVX-512).

#include <QList>
#include <QString>

#include "trapping/TrappingParameters.hpp"

namespace archipelago::ui {

struct Preset {
  QString name;
  QString description;
  TrappingParameters parameters;
};

/// Registers the application's Qt resources (presets, icon); the ui library is static, so they must be
/// initialised explicitly.  Idempotent.
void initResources();

/// The presets in resource order (file names sort them); the first one is the start-up default.
[[nodiscard]] QList<Preset> loadPresets();

}  // namespace archipelago::ui
