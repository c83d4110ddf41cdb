#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli manifold`: a branch of the stable or unstable manifold of the fixed point (√K, 0) or of a
/// hyperbolic periodic orbit, adaptively refined, as CSV s,x,y with a '#' metadata header
/// (core/manifolds/ManifoldCurve.hpp, ManifoldExport.hpp).
void addManifoldCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
