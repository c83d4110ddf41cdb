#include "ui/Resources.hpp"

#include <QtGlobal>

// Q_INIT_RESOURCE must be used outside any namespace.
static void initArchipelagoResources() { Q_INIT_RESOURCE(archipelago); }

namespace archipelago::ui {

void initResources() {
  static const bool done = (initArchipelagoResources(), true);
  (void)done;
}

}  // namespace archipelago::ui
