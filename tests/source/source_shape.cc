// The shape of the libraries' sources, checked where a reviewer would otherwise count by hand:
//   source_shape functions MAX_LINES MAX_DECISIONS DIR...   every function body in DIR's .cc/.h
//       files is at most MAX_LINES lines (its opening to its closing brace) and has at most
//       MAX_DECISIONS decision points (if, for, while, case, catch, ?, &&, ||);
//   source_shape includes DIR...   the include graph between DIR's concepts (x.h and x.cc are one
//       concept) has no cycle.
// It reads C++ with a tokenizer, not a compiler: comments, strings, character literals and
// preprocessor lines are skipped; a brace at namespace or class scope opens a function when the
// declaration before it has a parameter list and is not an initialiser (`= {`). Lambdas count
// toward the function they are written in. Exit 0 when every file passes, 1 with one line per
// offender, 2 on bad usage.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct Token {
  std::string text;
  int line = 0;
};

std::string ReadFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Skips a quoted literal starting at s[i] (the opening quote), counting newlines; returns the
// index after its closing quote.
size_t SkipQuoted(const std::string& s, size_t i, int* line) {
  const char q = s[i++];
  while (i < s.size() && s[i] != q) {
    if (s[i] == '\\') ++i;
    else if (s[i] == '\n') ++*line;
    ++i;
  }
  return i + 1;
}

// R"delim( ... )delim" starting at s[i] (the R).
size_t SkipRawString(const std::string& s, size_t i, int* line) {
  const size_t open = s.find('(', i);
  const std::string close = ")" + s.substr(i + 2, open - i - 2) + "\"";
  const size_t end = s.find(close, open);
  const size_t stop = end == std::string::npos ? s.size() : end + close.size();
  *line += int(std::count(s.begin() + long(i), s.begin() + long(stop), '\n'));
  return stop;
}

std::vector<Token> Tokenize(const std::string& s) {
  std::vector<Token> out;
  int line = 1;
  bool line_start = true;
  size_t i = 0;
  while (i < s.size()) {
    const char c = s[i];
    if (c == '\n') {
      ++line;
      line_start = true;
      ++i;
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
      continue;
    }
    if (line_start && c == '#') {  // a preprocessor line, with its continuations
      while (i < s.size() && !(s[i] == '\n' && s[i - 1] != '\\')) {
        if (s[i] == '\n') ++line;
        ++i;
      }
      continue;
    }
    line_start = false;
    if (s.compare(i, 2, "//") == 0) {
      while (i < s.size() && s[i] != '\n') ++i;
      continue;
    }
    if (s.compare(i, 2, "/*") == 0) {
      const size_t end = s.find("*/", i + 2);
      const size_t stop = end == std::string::npos ? s.size() : end + 2;
      line += int(std::count(s.begin() + long(i), s.begin() + long(stop), '\n'));
      i = stop;
      continue;
    }
    if (c == 'R' && s.compare(i, 2, "R\"") == 0) {
      i = SkipRawString(s, i, &line);
      continue;
    }
    if (c == '"' || c == '\'') {
      // A digit separator (1'000) is not a character literal.
      if (c == '\'' && i > 0 && std::isxdigit(static_cast<unsigned char>(s[i - 1]))) {
        ++i;
        continue;
      }
      i = SkipQuoted(s, i, &line);
      continue;
    }
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
      size_t j = i;
      while (j < s.size() && (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '_')) ++j;
      out.push_back({s.substr(i, j - i), line});
      i = j;
      continue;
    }
    for (const char* op : {"&&", "||", "::", "==", "!=", "<=", ">=", "->"}) {
      if (s.compare(i, 2, op) == 0) {
        out.push_back({op, line});
        i += 2;
        goto next;
      }
    }
    out.push_back({std::string(1, c), line});
    ++i;
  next:;
  }
  return out;
}

struct FunctionSize {
  std::string name;
  int line = 0;
  int lines = 0;
  int decisions = 0;
};

enum class Scope { kNamespace, kClass, kFunction, kBlock };

// The kind of scope a `{` opens after `decl` (the tokens since the last ; { or } at namespace
// or class scope).
Scope KindOf(const std::vector<Token>& decl) {
  size_t k = 0;
  if (k < decl.size() && decl[k].text == "template") {  // skip template <...>
    int depth = 0;
    for (++k; k < decl.size(); ++k) {
      if (decl[k].text == "<") ++depth;
      if (decl[k].text == ">" && --depth == 0) {
        ++k;
        break;
      }
    }
  }
  bool paren = false, assigned = false, is_operator = false;
  for (size_t j = k; j < decl.size(); ++j) {
    const std::string& t = decl[j].text;
    if (!paren && (t == "namespace" || t == "extern")) return Scope::kNamespace;
    if (!paren && (t == "class" || t == "struct" || t == "union")) return Scope::kClass;
    if (!paren && t == "enum") return Scope::kBlock;
    if (t == "operator") is_operator = true;
    if (t == "=" && !paren && !is_operator) assigned = true;
    if (t == "(") paren = true;
  }
  return paren && !assigned ? Scope::kFunction : Scope::kBlock;
}

std::string NameOf(const std::vector<Token>& decl) {
  std::string name;
  for (size_t j = 0; j < decl.size(); ++j) {
    if (decl[j].text == "(") break;
    if (decl[j].text == "::" || std::isalpha(static_cast<unsigned char>(decl[j].text[0])) ||
        decl[j].text[0] == '_' || decl[j].text == "~") {
      if (decl[j].text != "::" && !name.empty() && name.back() != ':' && name.back() != '~')
        name.clear();
      name += decl[j].text;
    }
  }
  return name;
}

std::vector<FunctionSize> Functions(const std::vector<Token>& tokens) {
  static const std::set<std::string> kDecisions = {"if", "for", "while", "case", "catch",
                                                   "?",  "&&",  "||"};
  std::vector<FunctionSize> out;
  std::vector<Scope> scopes;
  std::vector<Token> decl;
  FunctionSize current;
  auto in_function = [&] {
    return std::find(scopes.begin(), scopes.end(), Scope::kFunction) != scopes.end();
  };
  for (const Token& t : tokens) {
    const bool outer = !in_function() && (scopes.empty() || scopes.back() != Scope::kBlock);
    if (t.text == "{") {
      Scope kind = Scope::kBlock;
      if (outer) {
        kind = KindOf(decl);
        if (kind == Scope::kFunction) current = {NameOf(decl), t.line, 0, 0};
        decl.clear();
      }
      scopes.push_back(kind);
      continue;
    }
    if (t.text == "}") {
      if (!scopes.empty()) {
        const Scope closed = scopes.back();
        scopes.pop_back();
        if (closed == Scope::kFunction) {
          current.lines = t.line - current.line + 1;
          out.push_back(current);
        }
      }
      decl.clear();
      continue;
    }
    if (in_function()) {
      if (kDecisions.count(t.text)) ++current.decisions;
    } else if (outer) {
      if (t.text == ";") decl.clear();
      else decl.push_back(t);
    }
  }
  return out;
}

std::vector<fs::path> Sources(const std::vector<std::string>& dirs) {
  std::vector<fs::path> files;
  for (const std::string& d : dirs) {
    for (const auto& e : fs::recursive_directory_iterator(d)) {
      const std::string ext = e.path().extension().string();
      if (e.is_regular_file() && (ext == ".cc" || ext == ".h")) files.push_back(e.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

int CheckFunctions(int max_lines, int max_decisions, const std::vector<std::string>& dirs) {
  int offenders = 0, functions = 0;
  const std::vector<fs::path> files = Sources(dirs);
  for (const fs::path& f : files) {
    for (const FunctionSize& fn : Functions(Tokenize(ReadFile(f)))) {
      ++functions;
      if (fn.lines > max_lines || fn.decisions > max_decisions) {
        std::printf("%s:%d: %s: %d lines (at most %d), %d decision points (at most %d)\n",
                    f.string().c_str(), fn.line, fn.name.c_str(), fn.lines, max_lines,
                    fn.decisions, max_decisions);
        ++offenders;
      }
    }
  }
  std::printf("%d of %d functions in %zu files over %d lines or %d decision points\n", offenders,
              functions, files.size(), max_lines, max_decisions);
  return offenders == 0 ? 0 : 1;
}

// The includes of `text` written as "path" (the project's own).
std::vector<std::string> QuotedIncludes(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const size_t hash = line.find_first_not_of(" \t");
    if (hash == std::string::npos || line[hash] != '#') continue;
    const size_t inc = line.find("include", hash);
    const size_t open = line.find('"', inc == std::string::npos ? line.size() : inc);
    if (inc == std::string::npos || open == std::string::npos) continue;
    const size_t close = line.find('"', open + 1);
    if (close != std::string::npos) out.push_back(line.substr(open + 1, close - open - 1));
  }
  return out;
}

// A concept: the file's path from the repository root without its extension.
std::string Concept(const fs::path& p) {
  fs::path c = p;
  return c.replace_extension().lexically_normal().string();
}

int CheckIncludes(const std::vector<std::string>& dirs) {
  std::map<std::string, std::set<std::string>> edges;
  for (const fs::path& f : Sources(dirs)) {
    const std::string from = Concept(f);
    edges[from];
    for (const std::string& inc : QuotedIncludes(ReadFile(f))) {
      const std::string to = Concept(inc);
      if (to != from) edges[from].insert(to);
    }
  }
  // Depth-first search for a back edge; only edges between concepts of DIRs count.
  std::map<std::string, int> state;  // 0 new, 1 on the path, 2 done
  std::vector<std::string> path;
  int cycles = 0;
  std::function<void(const std::string&)> visit = [&](const std::string& n) {
    state[n] = 1;
    path.push_back(n);
    for (const std::string& m : edges[n]) {
      if (!edges.count(m)) continue;
      if (state[m] == 1) {
        std::string text;
        for (auto it = std::find(path.begin(), path.end(), m); it != path.end(); ++it)
          text += *it + " -> ";
        std::printf("include cycle: %s%s\n", text.c_str(), m.c_str());
        ++cycles;
      } else if (state[m] == 0) {
        visit(m);
      }
    }
    path.pop_back();
    state[n] = 2;
  };
  std::vector<std::string> nodes;
  for (const auto& [n, out] : edges) nodes.push_back(n);
  for (const std::string& n : nodes)
    if (state[n] == 0) visit(n);
  std::printf("%d include cycles among %zu concepts\n", cycles, nodes.size());
  return cycles == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string usage =
      "usage: source_shape functions MAX_LINES MAX_DECISIONS DIR... | source_shape includes DIR...";
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.size() >= 4 && args[0] == "functions") {
    return CheckFunctions(std::atoi(args[1].c_str()), std::atoi(args[2].c_str()),
                          std::vector<std::string>(args.begin() + 3, args.end()));
  }
  if (args.size() >= 2 && args[0] == "includes") {
    return CheckIncludes(std::vector<std::string>(args.begin() + 1, args.end()));
  }
  std::fprintf(stderr, "%s\n", usage.c_str());
  return 2;
}
