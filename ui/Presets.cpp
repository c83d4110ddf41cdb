#include "Presets.hpp"

#include <QDir>
#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>

// Q_INIT_RESOURCE must be used outside any namespace.
static void initArchipelagoResources() { Q_INIT_RESOURCE(archipelago); }

namespace archipelago::ui {

void initResources() {
  static const bool done = (initArchipelagoResources(), true);
  (void)done;
}

namespace {
// Integers are written as JSON numbers; sizes such as T = 2e7 are exact in a double.
std::uint64_t integerOf(const QJsonObject& o, const char* key, std::uint64_t fallback) {
  const QJsonValue v = o.value(QLatin1String(key));
  return v.isDouble() ? static_cast<std::uint64_t>(v.toDouble()) : fallback;
}
}  // namespace

QList<Preset> loadPresets() {
  initResources();
  QList<Preset> presets;
  const QDir dir(QStringLiteral(":/presets"));
  const QStringList files = dir.entryList({QStringLiteral("*.json")}, QDir::Files, QDir::Name);
  for (const QString& name : files) {
    QFile file(dir.filePath(name));
    if (!file.open(QIODevice::ReadOnly)) continue;
    const QJsonObject o = QJsonDocument::fromJson(file.readAll()).object();
    if (o.isEmpty()) continue;
    Preset p;
    TrappingParameters defaults;
    p.name = o.value(QStringLiteral("name")).toString(name);
    p.description = o.value(QStringLiteral("description")).toString();
    p.parameters.map.K = o.value(QStringLiteral("K")).toDouble(defaults.map.K);
    p.parameters.map.xmin = o.value(QStringLiteral("xmin")).toDouble(defaults.map.xmin);
    p.parameters.map.xmax = o.value(QStringLiteral("xmax")).toDouble(defaults.map.xmax);
    p.parameters.Xr = o.value(QStringLiteral("Xr")).toDouble(defaults.Xr);
    p.parameters.q = static_cast<std::uint32_t>(integerOf(o, "q", defaults.q));
    p.parameters.T = integerOf(o, "T", defaults.T);
    p.parameters.M = integerOf(o, "M", defaults.M);
    p.parameters.seed = integerOf(o, "seed", defaults.seed);
    p.parameters.subsets = static_cast<std::uint32_t>(integerOf(o, "subsets", defaults.subsets));
    presets.append(p);
  }
  return presets;
}

}  // namespace archipelago::ui
