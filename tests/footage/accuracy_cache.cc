#include "tests/footage/accuracy_cache.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>
#include <vector>

namespace dimer::footage {
namespace {

constexpr const char* kMagic = "dimerlab-track-accuracy 1";

// %a: every bit of the double, NaN as "nan"; strtod reads both back.
std::string Exact(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

bool ReadDouble(std::istream& in, double* v) {
  std::string tok;
  if (!(in >> tok)) return false;
  char* end = nullptr;
  *v = std::strtod(tok.c_str(), &end);
  return end == tok.c_str() + tok.size();
}

bool ReadSize(std::istream& in, size_t* v) {
  double d = 0;
  if (!ReadDouble(in, &d) || d < 0) return false;
  if (d != static_cast<double>(static_cast<size_t>(d))) return false;
  *v = static_cast<size_t>(d);
  return true;
}

// Reads "key" then its value(s) with `read`, false unless the key is exactly `key`.
template <typename F>
bool Field(std::istream& in, const char* key, F read) {
  std::string k;
  return (in >> k) && k == key && read();
}

std::string Request(const std::string& folder, const std::string& method, int threads) {
  std::ostringstream s;
  s << kMagic << "\nfolder " << std::filesystem::absolute(folder).lexically_normal().string()
    << "\nrequest " << method << " " << threads << "\n";
  return s.str();
}

// The cache file is older than what it was made from: the footage's truth or this program.
bool Stale(const std::string& cache_file, const std::string& folder) {
  std::error_code ec;
  const auto cached = std::filesystem::last_write_time(cache_file, ec);
  if (ec) return true;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", ec);
  for (const std::filesystem::path& from : {std::filesystem::path(folder) / "truth.csv", program}) {
    if (ec) return true;
    const auto t = std::filesystem::last_write_time(from, ec);
    if (ec || t >= cached) return true;
  }
  return false;
}

}  // namespace

std::string SerializeAccuracy(const TrackAccuracy& a) {
  std::ostringstream s;
  s << "method " << a.method << "\ntemplate_run " << (a.template_run ? 1 : 0) << "\nframes "
    << a.frames << "\nidentity_swaps " << a.identity_swaps << "\nplate_found " << a.plate_found
    << "\nplate_bias " << Exact(a.plate_bias) << "\nplate_max_error " << Exact(a.plate_max_error)
    << "\nseconds " << Exact(a.seconds) << "\n";
  for (const SphereAccuracy& p : a.sphere) {
    s << "sphere " << p.good << " " << p.found;
    for (double v : {p.found_fraction, p.bias.x(), p.bias.y(), p.scatter, p.max_error,
                     p.scatter_bound, p.bias_sampling.x(), p.bias_sampling.y(), p.stated_err.x(),
                     p.stated_err.y(), p.bias_sigmas.x(), p.bias_sigmas.y()}) {
      s << " " << Exact(v);
    }
    s << "\n";
  }
  s << "end\n";
  return s.str();
}

bool ParseAccuracy(const std::string& text, TrackAccuracy* out) {
  std::istringstream in(text);
  TrackAccuracy a;
  size_t template_run = 0;
  const bool head =
      Field(in, "method", [&] { return static_cast<bool>(in >> a.method); }) &&
      Field(in, "template_run", [&] { return ReadSize(in, &template_run) && template_run <= 1; }) &&
      Field(in, "frames", [&] { return ReadSize(in, &a.frames); }) &&
      Field(in, "identity_swaps", [&] { return ReadSize(in, &a.identity_swaps); }) &&
      Field(in, "plate_found", [&] { return ReadSize(in, &a.plate_found); }) &&
      Field(in, "plate_bias", [&] { return ReadDouble(in, &a.plate_bias); }) &&
      Field(in, "plate_max_error", [&] { return ReadDouble(in, &a.plate_max_error); }) &&
      Field(in, "seconds", [&] { return ReadDouble(in, &a.seconds); });
  if (!head) return false;
  a.template_run = template_run == 1;
  for (SphereAccuracy& p : a.sphere) {
    const bool ok = Field(in, "sphere", [&] {
      if (!ReadSize(in, &p.good) || !ReadSize(in, &p.found)) return false;
      for (double* v : {&p.found_fraction, &p.bias.x(), &p.bias.y(), &p.scatter, &p.max_error,
                        &p.scatter_bound, &p.bias_sampling.x(), &p.bias_sampling.y(),
                        &p.stated_err.x(), &p.stated_err.y(), &p.bias_sigmas.x(),
                        &p.bias_sigmas.y()}) {
        if (!ReadDouble(in, v)) return false;
      }
      return true;
    });
    if (!ok) return false;
  }
  std::string end, extra;
  if (!(in >> end) || end != "end" || (in >> extra)) return false;
  *out = a;
  return true;
}

TrackAccuracy CachedTrackAccuracy(const std::string& folder, const std::string& method,
                                  int threads, const std::string& cache_file,
                                  const std::string& lens) {
  TrackerKnobs knobs;
  knobs.lens = lens;
  if (cache_file.empty()) return MeasureTrackAccuracy(folder, method, threads, true, knobs);
  const std::string request =
      Request(folder, method, threads) + (lens.empty() ? "" : "lens " + lens + "\n");
  if (!Stale(cache_file, folder)) {
    std::ifstream in(cache_file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    const std::string s = text.str();
    TrackAccuracy a;
    if (s.compare(0, request.size(), request) == 0 && ParseAccuracy(s.substr(request.size()), &a)) {
      return a;
    }
  }
  const TrackAccuracy a = MeasureTrackAccuracy(folder, method, threads, true, knobs);
  const std::filesystem::path dir = std::filesystem::path(cache_file).parent_path();
  std::error_code made;
  if (!dir.empty()) std::filesystem::create_directories(dir, made);
  // Aside under a name of this process, then renamed over the entry in one step.
  const std::string aside = cache_file + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream o(aside, std::ios::binary | std::ios::trunc);
    o << request << SerializeAccuracy(a);
    if (!o.flush()) {
      std::error_code ec;
      std::filesystem::remove(aside, ec);
      return a;  // an unwritable cache costs time, not the result
    }
  }
  std::error_code ec;
  std::filesystem::rename(aside, cache_file, ec);
  if (ec) std::filesystem::remove(aside, ec);
  return a;
}

}  // namespace dimer::footage
