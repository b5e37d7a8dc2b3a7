#include "tests/footage/track_accuracy.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "common/error.h"
#include "tracking/io/frame_source.h"
#include "tracking/run_track.h"

namespace dimer::footage {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<std::string> Split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) cells.push_back(cell);
  return cells;
}

double Number(const std::string& s, const std::string& where) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0') throw InputError(where + ": '" + s + "' is not a number");
  return v;
}

SphereAccuracy Summarise(const std::vector<Eigen::Vector2d>& errors, size_t good) {
  SphereAccuracy a;
  a.good = good;
  a.found = errors.size();
  a.found_fraction = good > 0 ? double(a.found) / double(good) : 0.0;
  if (errors.empty()) {
    a.bias = Eigen::Vector2d(kNaN, kNaN);
    a.scatter = a.max_error = kNaN;
    return a;
  }
  for (const auto& e : errors) a.bias += e;
  a.bias /= double(errors.size());
  Eigen::Vector2d var(0, 0);
  for (const auto& e : errors) {
    var += (e - a.bias).cwiseAbs2();
    a.max_error = std::max(a.max_error, (e - a.bias).norm());
  }
  const double n = double(errors.size());
  a.scatter = std::sqrt(var.sum() / n);
  a.bias_sampling = (var / n / n).cwiseSqrt();
  return a;
}

std::string Fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

std::vector<TruthRow> ReadTruthCsv(const std::string& path, double* radius_px) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read truth file");
  if (radius_px) *radius_px = kNaN;
  std::vector<TruthRow> rows;
  std::string line;
  bool header = false;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string where = path + ": line " + std::to_string(number);
    if (line.empty()) continue;
    if (line[0] == '#') {
      const size_t p = line.find("radius_px=");
      if (p != std::string::npos && radius_px) *radius_px = std::atof(line.c_str() + p + 10);
      continue;
    }
    if (!header) {
      if (line.rfind("frame,file,t,left_col,left_row,right_col,right_row,plate_row", 0) != 0) {
        throw InputError(where + ": expected the header "
                                 "frame,file,t,left_col,left_row,right_col,right_row,plate_row");
      }
      header = true;
      continue;
    }
    const auto c = Split(line);
    if (c.size() < 8) throw InputError(where + ": expected 8 columns");
    TruthRow r;
    r.frame = size_t(Number(c[0], where));
    r.file = c[1];
    r.t = Number(c[2], where);
    r.centre[0] = {Number(c[3], where), Number(c[4], where)};
    r.centre[1] = {Number(c[5], where), Number(c[6], where)};
    r.plate_row = Number(c[7], where);
    rows.push_back(r);
  }
  if (rows.empty()) throw InputError(path + ": no frames");
  return rows;
}

bool TrackAccuracy::MeetsTargets(std::string* why) const {
  std::string bad;
  auto need = [&](bool ok, const std::string& what) {
    if (!ok) bad += (bad.empty() ? "" : "; ") + what;
  };
  const char* names[2] = {"left", "right"};
  for (int k = 0; k < 2; ++k) {
    const SphereAccuracy& s = sphere[k];
    const std::string n = names[k];
    need(s.found_fraction >= kFoundTarget,
         n + " found " + Fmt("%.1f", 100 * s.found_fraction) + " % < 99 %");
    need(s.bias.norm() <= kBiasTargetPx, n + " |bias| " + Fmt("%.3f", s.bias.norm()) + " px > 0.1");
    need(s.scatter <= kScatterTargetPx, n + " scatter " + Fmt("%.3f", s.scatter) + " px > 0.05");
  }
  need(identity_swaps == 0, std::to_string(identity_swaps) + " identity swaps");
  need(plate_found == frames, "plate row missing in " + std::to_string(frames - plate_found) +
                                  " frames");
  need(plate_max_error <= kPlateTargetPx,
       "plate row off by up to " + Fmt("%.3f", plate_max_error) + " px > 0.3");
  if (why) *why = bad;
  return bad.empty();
}

TrackAccuracy MeasureTrackAccuracy(const std::string& folder, const std::string& method,
                                   int threads, bool scale_given, const TrackerKnobs& knobs,
                                   const std::string& input) {
  double radius = kNaN;
  const std::vector<TruthRow> truth = ReadTruthCsv(folder + "/truth.csv", &radius);
  std::map<std::string, const TruthRow*> by_file;
  for (const auto& r : truth) by_file[r.file] = &r;

  tracking::SequenceOptions opt;
  opt.follower.method = tracking::ParseMethod(method);
  opt.threads = threads;
  if (knobs.ecc) opt.follower.ecc = *knobs.ecc;
  if (knobs.follow) opt.follower.follow = *knobs.follow;
  opt.learn_passes = knobs.learn_passes;
  opt.jackknife_groups = knobs.jackknife_groups;
  opt.seed_agreement_px = knobs.seed_agreement_px;
  if (scale_given) opt.contact_radius_px = radius;
  if (!knobs.lens.empty()) {
    opt.lens = std::make_shared<const tracking::LensCalibration>(
        tracking::ReadLensCalibration(knobs.lens));
  }
  auto source = tracking::OpenFrameSource(input.empty() ? folder : input);
  const auto start = std::chrono::steady_clock::now();
  const tracking::SequenceResult res = tracking::TrackSequence(*source, opt);
  TrackAccuracy a;
  a.method = method;
  a.frames = truth.size();
  a.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::array<std::vector<Eigen::Vector2d>, 2> errors;
  std::array<size_t, 2> good{0, 0};
  double plate_sum = 0;
  auto inside = [&](const Eigen::Vector2d& c) {
    const double r = std::isnan(radius) ? 0.0 : radius;
    return c.x() - r >= 0 && c.x() + r <= res.width - 1 && c.y() - r >= 0 &&
           c.y() + r <= res.height - 1;
  };
  std::map<std::string, const tracking::FrameTrack*> tracked;
  for (size_t i = 0; i < res.frames.size(); ++i) tracked[res.names[i]] = &res.frames[i];
  if (!input.empty()) {  // truth row k is the input's frame k
    tracked.clear();
    for (const tracking::FrameTrack& f : res.frames) {
      if (f.index < truth.size()) tracked[truth[f.index].file] = &f;
    }
  }
  for (const TruthRow& row : truth) {
    const bool is_good = inside(row.centre[0]) && inside(row.centre[1]);
    good[0] += is_good;
    good[1] += is_good;
    const auto it = tracked.find(row.file);
    if (it == tracked.end()) continue;  // unreadable frame: counts as not found
    const tracking::FrameTrack& f = *it->second;
    if (f.found[0] && f.found[1]) {
      const double straight = (f.centre[0] - row.centre[0]).norm() +
                              (f.centre[1] - row.centre[1]).norm();
      const double crossed = (f.centre[0] - row.centre[1]).norm() +
                             (f.centre[1] - row.centre[0]).norm();
      if (crossed < straight) ++a.identity_swaps;
    }
    if (is_good) {
      for (int k = 0; k < 2; ++k) {
        if (f.found[k]) errors[k].push_back(f.centre[k] - row.centre[k]);
      }
    }
    if (std::isfinite(f.plate_row)) {
      ++a.plate_found;
      plate_sum += f.plate_row - row.plate_row;
      a.plate_max_error = std::max(a.plate_max_error, std::abs(f.plate_row - row.plate_row));
    }
  }
  for (int k = 0; k < 2; ++k) a.sphere[k] = Summarise(errors[k], good[k]);
  a.template_run = res.method == tracking::Method::kTemplate;
  if (a.template_run) {
    // The tracker's own bound (run_track.h, precision_bound): its first readable frame's noise in
    // the levels of the appearance (16-bit levels of fewer bits scaled, level_scale.h).
    for (int k = 0; k < 2; ++k) {
      SphereAccuracy& s = a.sphere[k];
      s.scatter_bound = res.precision_bound[k].norm();
      s.stated_err = Eigen::Vector2d(res.offsets.col[k].err, res.offsets.row[k].err);
      for (int c = 0; c < 2; ++c) {
        s.bias_sigmas(c) = std::abs(s.bias(c)) / std::hypot(s.stated_err(c), s.bias_sampling(c));
      }
    }
  }
  a.plate_bias = a.plate_found > 0 ? plate_sum / double(a.plate_found) : kNaN;
  if (a.plate_found == 0) a.plate_max_error = kNaN;
  return a;
}

std::string AccuracyHeader() {
  return "| method | found L / R (%) | bias L / R (px) | scatter L / R (px) | scatter bound L / R "
         "(px) | bias / stated σ L / R | swaps | plate bias / max (px) | meets targets |\n"
         "|---|---|---|---|---|---|---|---|---|\n";
}

std::string AccuracyRow(const TrackAccuracy& a) {
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "| %s | %.1f / %.1f | %.3f / %.3f | %.3f / %.3f | %.3f / %.3f | %.1f / %.1f | %zu "
                "| %+.3f / %.3f | %s |\n",
                a.method.c_str(), 100 * a.sphere[0].found_fraction,
                100 * a.sphere[1].found_fraction, a.sphere[0].bias.norm(),
                a.sphere[1].bias.norm(), a.sphere[0].scatter, a.sphere[1].scatter,
                a.sphere[0].scatter_bound, a.sphere[1].scatter_bound,
                std::fmax(a.sphere[0].bias_sigmas(0), a.sphere[0].bias_sigmas(1)),
                std::fmax(a.sphere[1].bias_sigmas(0), a.sphere[1].bias_sigmas(1)),
                a.identity_swaps, a.plate_bias, a.plate_max_error,
                a.MeetsTargets() ? "yes" : "no");
  return buf;
}

}  // namespace dimer::footage
