#include "core/report/ReportPlan.hpp"

#include <array>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/paper/PaperTable.hpp"

namespace archipelago::report {

namespace {
// Every statement of core/paper/PaperTable.hpp and the part that computes it (tests/core/report checks that the two
// lists name the same statements).
constexpr std::array<std::pair<std::string_view, Need>, 37> kNeeds{{
    {"cos-alpha", Need::theory},      {"pd-first", Need::theory},        {"pd-accumulation", Need::theory},
    {"tmax", Need::theory},           {"tmax-X0", Need::theory},         {"F-smallT", Need::theory},
    {"F-cutoff", Need::theory},       {"A-const", Need::theory},         {"t7", Need::smallK},
    {"decay-0.0001", Need::smallK},   {"decay-0.001", Need::smallK},     {"decay-0.01", Need::smallK},
    {"tmax-measured", Need::smallK},  {"alpha-quarter", Need::k01},      {"p-five-quarters", Need::k01},
    {"alpha-min", Need::k01},         {"alpha-max", Need::k01},          {"S-superdiffusive", Need::k01},
    {"D", Need::k01},                 {"b2", Need::b2},                  {"b2D", Need::b2},
    {"kscan", Need::scan},            {"longest", Need::k01},            {"factor056", Need::b2},
    {"enhancement", Need::b2},        {"chain138-x", Need::theory},      {"chain138-y", Need::theory},
    {"tail-gamma", Need::k01},        {"tail-forecast", Need::k01},      {"tail-splitting", Need::k01},
    {"markov-tree", Need::atlas},     {"tail-gamma-K", Need::tailScan},
    {"cray-ns", Need::timing},
    {"cray-hours", Need::timing},     {"markov-dmark", Need::theory},    {"markov-eps", Need::theory},
    {"markov-period", Need::theory},
}};
}  // namespace

Need needOf(std::string_view id) {
  for (const auto& [name, need] : kNeeds)
    if (name == id) return need;
  throw std::out_of_range("--only '" + std::string(id) + "': no such statement (archipelago-reproduce --table lists them)");
}

std::set<Need> allNeeds() {
  return {Need::theory, Need::smallK, Need::k01, Need::b2, Need::atlas, Need::scan, Need::tailScan, Need::timing};
}

}  // namespace archipelago::report
