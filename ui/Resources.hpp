#pragma once
/// \file Resources.hpp
/// \brief The application's Qt resources (icon).  The paper's presets are core data (spec/RunSpec.hpp).

namespace archipelago::ui {

/// Registers the application's Qt resources; the ui library is static, so they must be initialised
/// explicitly.  Idempotent.
void initResources();

}  // namespace archipelago::ui
