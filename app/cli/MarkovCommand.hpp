#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli markov`: the Markov model of Karney (1983), appendix C (core/markov/MarkovModel.hpp).
/// Prints D by the matrix formula and by eq. (dmark) with D_is, and writes τ, C(τ), C_is(τ), ε(τ) as CSV.
///
/// Options (each checked before any work; one line "ERROR: --name = value must be ..." otherwise):
///   --m LIST     trapped-segment lengths m_k, comma-separated whole numbers 1 ... 10^6, total m ≤ 10^6
///   --N N        number of points, a whole number m + M + 1 ... 2^53
///   --tau-max T  largest lag, a whole number 0 ... 5·10^8/(m + 1) − 1 (a few seconds) (default 4m)
///   --csv FILE   write the CSV there (default: stdout after the '#' header lines)
/// The observable is the paper's: h = 1 on the trapped points, 0 on the pre-images, −m/n′ on the rest.
void addMarkovCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
