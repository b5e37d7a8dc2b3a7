#include "app/usage.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace dimer::app {
namespace {

bool LooksLikeOption(const std::string& word) {
  // "-5" or "-0.1,0,..." are values, not options: an option's first letter is a letter.
  if (word.size() >= 3 && word[0] == '-' && word[1] == '-') return std::isalpha(word[2]) != 0;
  return word.size() >= 2 && word[0] == '-' && std::isalpha(word[1]) != 0;
}

std::vector<std::string> SubcommandNames(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    names.push_back(sub->get_name());
  }
  return names;
}

const CLI::App* FindSubcommand(const CLI::App& app, const std::string& name) {
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (sub->get_name() == name) return sub;
  }
  return nullptr;
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// Every spelling of every option of `sub`, with its dashes ("--fps", "-o").
std::vector<std::string> OptionSpellings(const CLI::App& sub) {
  std::vector<std::string> names;
  for (const CLI::Option* opt : sub.get_options()) {
    for (const auto& l : opt->get_lnames()) names.push_back("--" + l);
    for (const auto& s : opt->get_snames()) names.push_back("-" + s);
  }
  return names;
}

}  // namespace

size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string NearestName(const std::string& word, const std::vector<std::string>& candidates) {
  const size_t limit = std::max<size_t>(2, word.size() / 3);
  std::string best;
  size_t best_d = limit + 1;
  for (const auto& c : candidates) {
    const size_t d = EditDistance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

std::optional<std::string> CheckSubcommand(const CLI::App& app,
                                           const std::vector<std::string>& args) {
  const std::vector<std::string> names = SubcommandNames(app);
  for (const std::string& word : args) {
    if (word == "-h" || word == "--help" || word == "--version") return std::nullopt;
    if (!word.empty() && word[0] == '-') continue;  // CLI11 reports unknown top-level options
    if (std::find(names.begin(), names.end(), word) != names.end()) return std::nullopt;
    std::string msg = "unknown subcommand '" + word + "'";
    const std::string near = NearestName(word, names);
    if (!near.empty()) msg += "; did you mean '" + near + "'?";
    return msg + " (subcommands: " + JoinNames(names) + ")";
  }
  return "a subcommand is required: " + JoinNames(names) + " (dimerlab --help)";
}

std::string ExtrasMessage(const CLI::App& app, const std::vector<std::string>& args,
                          const std::string& cli11_message) {
  const CLI::App* sub = nullptr;
  std::string msg;
  for (const std::string& word : args) {
    if (!sub) {
      if (word.empty() || word[0] == '-') continue;
      sub = FindSubcommand(app, word);
      if (!sub) return cli11_message;
      continue;
    }
    if (!LooksLikeOption(word)) continue;
    const std::string name = word.substr(0, word.find('='));
    if (sub->get_option_no_throw(name) != nullptr || name == "-h" || name == "--help") continue;
    msg += (msg.empty() ? "" : "; ") + (sub->get_name() + ": unknown option '" +
                                        name + "'");
    const std::string near = NearestName(name, OptionSpellings(*sub));
    if (!near.empty()) msg += "; did you mean '" + near + "'?";
  }
  if (msg.empty()) return cli11_message;
  return msg + " (dimerlab " + sub->get_name() + " --help lists them)";
}

const CLI::Validator& FiniteNumber() {
  static const CLI::Validator v(
      [](std::string& text) -> std::string {
        double x = 0;
        try {
          size_t used = 0;
          x = std::stod(text, &used);
          if (used != text.size()) return "";  // not a number: the option's own parse says so
        } catch (const std::exception&) {
          return "";
        }
        return std::isfinite(x) ? "" : "'" + text + "' is not a finite number";
      },
      "FINITE");
  return v;
}

}  // namespace dimer::app
