#include "ui/window/Resources.hpp"

#include <QtGlobal>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

// Q_INIT_RESOURCE must be used outside any namespace.
static void initArchipelagoResources() { Q_INIT_RESOURCE(archipelago); }

namespace archipelago::ui {

void initResources() {
  static const bool done = (initArchipelagoResources(), true);
  (void)done;
}

void configureProcessMemory() {
#if defined(__GLIBC__)
  // Setting either threshold turns off glibc's dynamic adjustment of both (mallopt(3)).
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  mallopt(M_TRIM_THRESHOLD, 4 << 20);
#endif
}

}  // namespace archipelago::ui
