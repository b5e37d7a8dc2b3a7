// The report's figures of a comparison with a simulation (sim_vs_track) and of a fit of the
// contact coefficients (fit_profile).
#include <algorithm>
#include <array>
#include <cmath>

#include "compare/report_parts.h"

namespace dimer::compare {
namespace {

constexpr double kMm = 1e3;  // m -> mm
constexpr double kUm = 1e6;  // m -> um
constexpr double kMs = 1e3;  // s -> ms
const std::array<const char*, 2> kTipColour = {"#1f77b4", "#d62728"};
const std::array<const char*, 2> kResColour = {"#ff7f0e", "#9467bd"};  // x, z residuals
const std::array<const char*, 2> kSide = {"left", "right"};
constexpr double kZoomThresholds = 10;  // fit_profile's y range: chi2_min + this many thresholds
// A constrained range narrower than this fraction of its bounds is drawn zoomed: x from a range's
// width below it to one above (the profile's points there are its ends' bisections, fit.cc).
constexpr double kZoomRangeFraction = 0.1;

double At(const std::vector<double>& v, size_t i) { return i < v.size() ? v[i] : kNaN; }

// The panel title of a fit parameter: a value only when the slice constrains it.
std::string ParameterTitle(const FitParameter& p) {
  std::string t = p.name + ": ";
  if (p.status == "constrained") t += Format("%.4g ± %.2g", p.value, p.err);
  else if (p.status == "bounded_below") t += Format("≥ %.4g", p.range_lo);
  else if (p.status == "bounded_above") t += Format("≤ %.4g", p.range_hi);
  else t += Format("unconstrained (range %.4g–%.4g)", p.lo, p.hi);
  return p.fitted ? t : t + " (slice only, not fitted)";
}

}  // namespace

int FitProfileHeightPx(int parameters) {
  const int rows = (std::max(parameters, 1) + 1) / 2;
  return std::max(kFigureHeightPx, rows * kFitPanelHeightPx);
}

PlannedFigure PlanSimVsTrack(const Analysis& a, const Comparison& c) {
  PlannedFigure p;
  p.outcome = {"sim_vs_track", "tip heights of the track and the aligned simulation over the "
               "first 4 periods of the settled window, and the residuals", false, ""};
  const ModeWindow& w = a.periods.settled;
  size_t i0 = 0, i1 = 0;
  const double t1 = std::min(w.t_start + kDetailPeriods * a.periods.period_s, w.t_end);
  if (w.count > 0) FramesIn(a.run, w.t_start, t1, &i0, &i1);
  DataBlock b{"track and aligned simulation (track frame) per track frame; residual = track - sim",
              {"t_ms", "z_left_track_mm", "z_right_track_mm", "z_left_sim_mm", "z_right_sim_mm",
               "res_x_left_um", "res_x_right_um", "res_z_left_um", "res_z_right_um"}, {}};
  std::array<bool, 2> has_sim{}, has_track{};
  for (size_t i = i0; i < i1; ++i) {
    std::vector<double> row = {a.run.Time(i) * kMs};
    for (int s = 0; s < 2; ++s) row.push_back(a.run.z[s][i] * kMm);
    for (int s = 0; s < 2; ++s) row.push_back(At(c.sim_z[s], i) * kMm);
    for (int s = 0; s < 2; ++s) row.push_back(At(c.res_x[s], i) * kUm);
    for (int s = 0; s < 2; ++s) row.push_back(At(c.res_z[s], i) * kUm);
    for (int s = 0; s < 2; ++s) {
      has_track[s] = has_track[s] || std::isfinite(row[1 + s]);
      has_sim[s] = has_sim[s] || std::isfinite(row[3 + s]);
    }
    b.rows.push_back(std::move(row));
  }
  if (!has_sim[0] && !has_sim[1]) {
    p.outcome.note = "the aligned simulation does not cover the first periods of the settled "
                     "window";
    return p;
  }
  p.figure.blocks.push_back(std::move(b));
  std::vector<std::string> top, bottom;
  for (int s = 0; s < 2; ++s) {
    if (has_track[s]) {
      top.push_back(Format("datafile using 1:%d with points pt %d ps 0.6 lc rgb \"%s\" "
                           "title \"%s tip, track\"", 2 + s, s == 0 ? 6 : 8, kTipColour[s],
                           kSide[s]));
    }
    if (has_sim[s]) {
      top.push_back(Format("datafile using 1:%d with lines lw 2 lc rgb \"%s\" "
                           "title \"%s tip, simulation\"", 4 + s, kTipColour[s], kSide[s]));
      for (int k = 0; k < 2; ++k) {
        bottom.push_back(Format("datafile using 1:%d with lines lw 1.5 dt %d lc rgb \"%s\" "
                                "title \"%s tip, %s\"", 6 + 2 * k + s, s == 0 ? 1 : 2,
                                kResColour[k], kSide[s], k == 0 ? "x" : "z"));
      }
    }
  }
  const std::string title =
      Format("Track vs simulation: time offset %.4g ms, x offset %.4g mm%s", c.time_offset_s * kMs,
             c.x_offset_m * kMm, c.mirrored ? ", simulation mirrored" : "");
  p.figure.script = "set grid\nset lmargin 12\nset rmargin 4\nset key below horizontal\n" +
                    Format("set xrange [%.9g:%.9g]\n", w.t_start * kMs, t1 * kMs) +
                    "set multiplot layout 2,1 title " + GnuplotQuote(title) + "\n" +
                    "set title " + GnuplotQuote("tip heights (simulation: " + c.sim_path + ")") +
                    "\nset xlabel \"time t (ms, track)\"\nset ylabel \"height z (mm)\"\nplot " +
                    Join(top) +
                    "set title \"residuals, track - simulation\"\nset ylabel \"residual (µm)\"\n"
                    "set offsets 0, 0, graph 0.1, graph 0.1\n"
                    "plot " + Join(bottom) + "unset multiplot\n";
  p.figure.height_px = kPanelsFigureHeightPx;
  p.ready = true;
  return p;
}

PlannedFigure PlanFitProfile(const FitResult& fit) {
  PlannedFigure p;
  p.outcome = {"fit_profile", "chi2 profile through the optimum along each parameter (the others "
               "re-optimised; a plain slice when no fit is acceptable), with the "
               "threshold that defines its range", false, ""};
  std::vector<const FitParameter*> sliced;
  for (const FitParameter& q : fit.params) {
    if (!q.slice_x.empty() && q.slice_x.size() == q.slice_chi2.size() && AnyFinite(q.slice_chi2))
      sliced.push_back(&q);
  }
  if (sliced.empty()) {
    p.outcome.note = "no chi2 slice in the fit result";
    return p;
  }
  const int n = static_cast<int>(sliced.size());
  std::string& sc = p.figure.script;
  sc = Format("set grid\nset multiplot layout %d,%d title ", (n + 1) / 2, n == 1 ? 1 : 2) +
       GnuplotQuote(Format("chi2 profiles through the optimum: chi2 = %.4g, dof %d", fit.chi2,
                           fit.dof)) + "\nset key inside top right opaque box\n"
       "set offsets 0, 0, graph 0.05, graph 0.05\n";
  for (int k = 0; k < n; ++k) {
    const FitParameter& q = *sliced[k];
    DataBlock b{"chi2 along " + q.name + " (dimensionless) with the other parameters at the "
                "optimum; status " + q.status, {q.name, "chi2"}, {}};
    for (size_t j = 0; j < q.slice_x.size(); ++j) b.rows.push_back({q.slice_x[j], q.slice_chi2[j]});
    p.figure.blocks.push_back(std::move(b));
    sc += "unset object\nunset arrow\n";
    const bool bounded = std::isfinite(q.lo) && std::isfinite(q.hi) && q.hi > q.lo;
    const double width = q.range_hi - q.range_lo;
    const bool zoom = bounded && q.status == "constrained" && width > 0 &&
                      width < kZoomRangeFraction * (q.hi - q.lo);
    if (zoom)
      sc += Format("set xrange [%.9g:%.9g]\n", std::max(q.lo, q.range_lo - width),
                   std::min(q.hi, q.range_hi + width));
    else if (bounded)
      sc += Format("set xrange [%.9g:%.9g]\n", q.lo, q.hi);
    else
      sc += "set xrange [*:*]\n";
    // Zoom on the minimum: the range is read where the slice crosses chi2 + threshold.
    const double top = *std::max_element(q.slice_chi2.begin(), q.slice_chi2.end());
    if (std::isfinite(fit.chi2) && fit.threshold > 0 &&
        top > fit.chi2 + kZoomThresholds * fit.threshold) {
      sc += Format("set yrange [%.9g:%.9g]\n", fit.chi2 - 0.5 * fit.threshold,
                   fit.chi2 + kZoomThresholds * fit.threshold);
    } else {
      sc += "set yrange [*:*]\n";
    }
    if (q.status != "unconstrained" && std::isfinite(q.range_lo) && std::isfinite(q.range_hi)) {
      sc += Format("set object 1 rect from %.9g, graph 0 to %.9g, graph 1 fc rgb \"#2ca02c\" "
                   "fs transparent solid 0.15 noborder behind\n", q.range_lo, q.range_hi);
    }
    if (q.status == "constrained" && std::isfinite(q.value)) {
      sc += Format("set arrow 1 from %.9g, graph 0 to %.9g, graph 1 nohead lw 2 "
                   "lc rgb \"#2ca02c\" front\n", q.value, q.value);
    }
    std::vector<std::string> plot = {
        Format("datafile index %d using 1:2 with linespoints pt 7 ps 0.7 lc rgb \"black\" "
               "title \"chi2\"", k)};
    const double level = fit.chi2 + fit.threshold;
    if (std::isfinite(level)) {
      plot.push_back(Format("%.9g with lines dt 2 lw 1.5 lc rgb \"#d62728\" title "
                            "\"chi2_min + %.3g\"", level, fit.threshold));
    }
    if (q.status == "constrained" && std::isfinite(q.value)) {
      plot.push_back("keyentry with lines lw 2 lc rgb \"#2ca02c\" title \"optimum\"");
    }
    if (q.status != "unconstrained" && std::isfinite(q.range_lo) && std::isfinite(q.range_hi)) {
      plot.push_back("keyentry with boxes fs transparent solid 0.15 noborder fc rgb \"#2ca02c\" "
                     "title \"range\"");
    }
    sc += "set title " + GnuplotQuote(ParameterTitle(q) + (zoom ? " (zoomed on the range)" : "")) +
          "\nset xlabel " + GnuplotQuote(q.name) + "\nset ylabel \"chi2\"\nplot " + Join(plot);
  }
  sc += "unset multiplot\n";
  p.figure.height_px = FitProfileHeightPx(n);
  p.ready = true;
  return p;
}

}  // namespace dimer::compare
