#pragma once
// Usage errors that CLI11 reports too vaguely: a mistyped subcommand (CLI11 says only "A
// subcommand is required") and a mistyped option (CLI11 lists the words it did not expect).
// Both messages name the word and suggest the nearest valid one (edit distance).
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace dimer::app {

// Levenshtein distance: insertions, deletions and substitutions of one character each.
size_t EditDistance(const std::string& a, const std::string& b);

// The candidate nearest to `word`, if it is close enough to be a likely typo (at most a third of
// the word's letters, and at least 2, edited); "" otherwise.
std::string NearestName(const std::string& word, const std::vector<std::string>& candidates);

// When the command line names no subcommand, or one that does not exist, the message to print
// (naming the word and the nearest subcommand); nullopt when the subcommand is known or the line
// only asks for --help or --version.
std::optional<std::string> CheckSubcommand(const CLI::App& app,
                                           const std::vector<std::string>& args);

// For CLI11's ExtrasError: names each unknown option of the subcommand used, with the nearest
// option of that subcommand; falls back to CLI11's own text when no unknown option is found
// (e.g. a surplus positional argument).
std::string ExtrasMessage(const CLI::App& app, const std::vector<std::string>& args,
                          const std::string& cli11_message);

// For options whose unset value is NaN ("not given"): refuses the text "nan" and infinities, so
// that `--fps nan` is an error and not the default (cli.exit_codes).
const CLI::Validator& FiniteNumber();

}  // namespace dimer::app
