#include "tracking/io/library_messages.h"

#include <iostream>
#include <mutex>
#include <sstream>
#include <streambuf>
#include <vector>

namespace dimer::tracking {
namespace {

thread_local std::string* t_sink = nullptr;

// std::cerr's buffer from the first CerrToString on: a thread inside a scope writes into its
// string, every other write goes on to the buffer std::cerr had (unbuffered here, so that a
// character never waits in a buffer another thread would flush).
class ThreadRoutingBuf : public std::streambuf {
 public:
  explicit ThreadRoutingBuf(std::streambuf* original) : original_(original) {}

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    if (t_sink) {
      t_sink->push_back(traits_type::to_char_type(c));
      return c;
    }
    return original_->sputc(traits_type::to_char_type(c));
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (t_sink) {
      t_sink->append(s, size_t(n));
      return n;
    }
    return original_->sputn(s, n);
  }
  int sync() override { return t_sink ? 0 : original_->pubsync(); }

 private:
  std::streambuf* original_;
};

void RouteCerr() {
  static std::once_flag once;
  // Never deleted: std::cerr may be written to until the process ends.
  std::call_once(once, [] { std::cerr.rdbuf(new ThreadRoutingBuf(std::cerr.rdbuf())); });
}

std::string Trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r\n") - a + 1);
}

}  // namespace

CerrToString::CerrToString(std::string* sink) : previous_(t_sink) {
  RouteCerr();
  t_sink = sink;
}

CerrToString::~CerrToString() { t_sink = previous_; }

std::string OneLineLibraryMessage(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    line = Trim(line);
    if (!line.empty()) lines.push_back(line);
  }
  if (lines.empty()) return "";
  const std::string& first = lines[0];
  const size_t opencv = first.find("OpenCV(");
  if (opencv == std::string::npos) {
    std::string joined;
    for (const std::string& l : lines) joined += (joined.empty() ? "" : "; ") + l;
    return joined;
  }
  // "imcount_('stack.tif'): can't read header: OpenCV(4.6.0) FILE:LINE: error: (-2:Unspecified
  // error) in function 'f'": what OpenCV was doing (the call and its file are the caller's to
  // name), then the reason: the first "> " line of a check, else the error's own text.
  std::string doing = Trim(first.substr(0, opencv));
  if (const size_t call = doing.find("): "); call != std::string::npos) {
    doing = doing.substr(call + 3);
  }
  while (!doing.empty() && doing.back() == ':') doing.pop_back();
  std::string why;
  for (size_t i = 1; i < lines.size(); ++i) {
    if (lines[i].rfind(">", 0) != 0) continue;
    const std::string l = Trim(lines[i].substr(1));
    if (why.empty()) {
      why = l;
      while (!why.empty() && why.back() == ':') why.pop_back();
    } else if (l.rfind("'", 0) == 0 && l.find("' is ") != std::string::npos) {
      why += " (" + l + ")";  // the value the check failed on: "'channels' is 5"
      break;
    }
  }
  if (why.empty()) {
    const size_t error = first.find("error: (", opencv);
    const size_t close = error == std::string::npos ? error : first.find(')', error);
    why = close == std::string::npos ? Trim(first.substr(opencv)) : Trim(first.substr(close + 1));
    if (const size_t in_function = why.find(" in function "); in_function != std::string::npos) {
      why = Trim(why.substr(0, in_function));
    }
    if (why.empty() && error != std::string::npos && close != std::string::npos) {
      why = first.substr(error + 8, close - error - 8);  // "-2:Unspecified error"
    }
  }
  // A check's reason ends with its condition: "(expected: 'ncn == 1'), where".
  if (const size_t expected = why.find(" (expected:"); expected != std::string::npos) {
    why = why.substr(0, expected);
  }
  return "OpenCV: " + (doing.empty() ? why : doing + ": " + why);
}

}  // namespace dimer::tracking
