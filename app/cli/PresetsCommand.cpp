#include "PresetsCommand.hpp"

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/runspec/RunSpec.hpp"

namespace archipelago::cli {

namespace {
/// `text` padded with spaces to `width` characters (UTF-8: continuation bytes take no column).
std::string padded(const std::string& text, std::size_t width) {
  std::size_t columns = 0;
  for (const char c : text) columns += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return text + std::string(columns < width ? width - columns : 1, ' ');
}

int presetsCommand(const std::string& id) {
  if (!id.empty()) {  // one preset, as a spec file to start from: archipelago-cli presets ID > mine.json
    const Preset* p = findPreset(id);
    if (!p) throw std::invalid_argument("no preset '" + id + "' (archipelago-cli presets lists them)");
    std::fputs(runSpecJson(p->spec).c_str(), stdout);
    return 0;
  }
  std::printf("%s%srun\n", padded("id", 19).c_str(), padded("name", 33).c_str());
  for (const Preset& p : presets()) {
    const TrappingParameters& q = p.spec.parameters;
    const double steps = static_cast<double>(q.M) * static_cast<double>(q.T) * q.q;
    std::printf("%s%sK = %g, box [%g, %g), q = %u, T = %llu, M = %llu: %.3g steps\n", padded(p.id, 19).c_str(),
                padded(p.spec.name, 33).c_str(), q.map.K, q.map.xmin, q.map.xmax, q.q, static_cast<unsigned long long>(q.T),
                static_cast<unsigned long long>(q.M), steps);
  }
  std::printf("\nrun one:       archipelago-cli run --preset ID [--M …]\n"
              "edit one:      archipelago-cli presets ID > spec.json; archipelago-cli run --spec spec.json\n");
  return 0;
}
}  // namespace

void addPresetsCommand(CLI::App& app, int& status) {
  auto id = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("presets", "the paper's presets: list them, or print one as a run spec (JSON)");
  cmd->add_option("id", *id, "print this preset's run spec");
  cmd->callback([id, &status] { status = presetsCommand(*id); });
}

}  // namespace archipelago::cli
