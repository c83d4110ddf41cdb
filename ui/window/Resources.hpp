#pragma once
/// \file Resources.hpp
/// \brief The application's Qt resources (icon).  The paper's presets are core data (runspec/RunSpec.hpp).

namespace archipelago::ui {

/// Registers the application's Qt resources; the ui library is static, so they must be initialised
/// explicitly.  Idempotent.
void initResources();

/// Makes memory freed by the GUI go back to the system.  The portrait and run workers allocate buffers of many
/// MiB (rasters copied for each progress update) in their own threads; glibc's malloc raises its mmap threshold
/// after the first such buffer is freed, and from then on keeps their pages in each thread's arena: resident memory
/// grew by ~100 MiB over a 30-minute soak while the live heap did not (scripts/gui-soak.sh prints both).  A fixed
/// threshold keeps every buffer of 1 MiB or more mmapped, returned on free.  Call once, before any thread starts;
/// a no-op on other C libraries.
void configureProcessMemory();

}  // namespace archipelago::ui
