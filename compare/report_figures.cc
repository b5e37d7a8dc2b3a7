// The track's figures (heights, positions, slip_phase, modes) and the figures step of the
// report. Each figure is planned as a table plus a script (gnuplot.h), so the numbers drawn are
// exactly those written to NAME.dat.
#include <algorithm>
#include <array>
#include <cmath>

#include "compare/report_parts.h"

namespace dimer::compare {
namespace {

constexpr double kMm = 1e3;  // m -> mm (also m/s -> mm/s)
constexpr double kMs = 1e3;  // s -> ms
constexpr int kCurvePointsPerPeriod = 200;  // fitted sinusoids drawn smooth
constexpr int kPlatePhasePoints = 200;      // the reference plate curve of slip_phase
// The paper's energy estimates for A_r >> 1 (in g T^2): drift 1/8, jump 1/4, flutter 1.
constexpr std::array<std::pair<double, const char*>, 3> kPaperEnergies = {
    {{0.125, "E_d = gT²/8"}, {0.25, "E_j = gT²/4"}, {1.0, "E_f = gT²"}}};
constexpr double kReferenceSpan = 1.5;  // draw a reference level up to this times the data max
const std::array<const char*, 2> kTipColour = {"#1f77b4", "#d62728"};
const std::array<const char*, 2> kSide = {"left", "right"};

std::string DriveText(const PlateDrive& p) {
  return Format("f = %.4g Hz, Γ = %.3g", p.freq_hz, p.gamma);
}

std::string RestingText(const SlipResult& s) {
  return s.resting_sphere >= 0 ? std::string(kSide[s.resting_sphere]) : "none";
}

PlannedFigure PlanHeights(const Analysis& a) {
  PlannedFigure p;
  p.outcome = {"heights", "tip heights and plate over the first 4 periods of the settled window "
               "(the paper's Fig. 2)", false, ""};
  const ModeWindow& w = a.periods.settled;
  if (w.count == 0 || !(w.t_end > w.t_start)) {
    p.outcome.note = "no settled window (no whole plate period)";
    return p;
  }
  const double period = a.periods.period_s;
  const double t1 = std::min(w.t_start + kDetailPeriods * period, w.t_end);
  size_t i0 = 0, i1 = 0;
  FramesIn(a.run, w.t_start, t1, &i0, &i1);
  DataBlock frames{"tip centres and tracked plate surface per frame",
                   {"t_ms", "z_left_mm", "z_right_mm", "plate_mm"}, {}};
  std::array<bool, 3> has{};
  for (size_t i = i0; i < i1; ++i) {
    const std::array<double, 3> z = {a.run.z[0][i], a.run.z[1][i],
                                     i < a.run.plate_z.size() ? a.run.plate_z[i] : kNaN};
    for (int c = 0; c < 3; ++c) has[c] = has[c] || std::isfinite(z[c]);
    frames.rows.push_back({a.run.Time(i) * kMs, z[0] * kMm, z[1] * kMm, z[2] * kMm});
  }
  if (!has[0] && !has[1]) {
    p.outcome.note = "no tip position in the first periods of the settled window";
    return p;
  }
  std::vector<std::string> plot;
  for (int s = 0; s < 2; ++s) {
    if (!has[s]) continue;
    plot.push_back(Format("datafile index 0 using 1:%d with points pt %d ps 0.7 lc rgb \"%s\" "
                          "title \"%s tip\"", 2 + s, s == 0 ? 6 : 8, kTipColour[s], kSide[s]));
  }
  if (has[2]) {
    plot.push_back("datafile index 0 using 1:4 with points pt 7 ps 0.3 lc rgb \"gray50\" "
                   "title \"plate (tracked)\"");
  }
  p.figure.blocks.push_back(std::move(frames));
  const PlateDrive& d = a.plate;
  if (std::isfinite(d.amp_m) && std::isfinite(d.phase_rad) && std::isfinite(d.freq_hz)) {
    DataBlock fit{"plate drive z_p(t) = offset + amp sin(2 pi f t + phase), source " + d.source,
                  {"t_ms", "plate_fit_mm"}, {}};
    const int n = static_cast<int>(std::ceil((t1 - w.t_start) / period * kCurvePointsPerPeriod));
    for (int k = 0; k <= n; ++k) {
      const double t = w.t_start + (t1 - w.t_start) * k / std::max(n, 1);
      fit.rows.push_back({t * kMs, d.Z(t) * kMm});
    }
    p.figure.blocks.push_back(std::move(fit));
    plot.push_back("datafile index 1 using 1:2 with lines lw 2 lc rgb \"black\" "
                   "title \"plate drive (" + d.source + ")\"");
  }
  p.figure.script = "set title " +
                    GnuplotQuote("Tip heights, first periods of the settled window (" +
                                 w.summary.label + "); " + DriveText(d)) +
                    "\nset xlabel \"time t (ms)\"\nset ylabel \"height z (mm)\"\n" +
                    Format("set xrange [%.9g:%.9g]\n", w.t_start * kMs, t1 * kMs) +
                    "set grid\nset key below horizontal\nplot " + Join(plot);
  p.figure.height_px = kFigureHeightPx;
  p.ready = true;
  return p;
}

PlannedFigure PlanPositions(const Analysis& a) {
  PlannedFigure p;
  p.outcome = {"positions", "tips' horizontal positions over the settled window and the resting "
               "sphere's slip velocity (the paper's Fig. 3)", false, ""};
  const ModeWindow& w = a.periods.settled;
  size_t i0 = 0, i1 = 0;
  if (w.count > 0) FramesIn(a.run, w.t_start, w.t_end, &i0, &i1);
  std::array<double, 2> x0 = {kNaN, kNaN};
  for (int s = 0; s < 2; ++s) {
    for (size_t i = i0; i < i1 && std::isnan(x0[s]); ++i) x0[s] = a.run.x[s][i];
  }
  if (std::isnan(x0[0]) && std::isnan(x0[1])) {
    p.outcome.note = "no tip position in the settled window";
    return p;
  }
  DataBlock b{"tips' x relative to their first value in the settled window; slip U of the "
              "resting sphere (+ toward the bouncing end)",
              {"t_ms", "dx_left_mm", "dx_right_mm", "U_mm_s"}, {}};
  bool has_u = false;
  for (size_t i = i0; i < i1; ++i) {
    const double u = i < a.slip.U.size() ? a.slip.U[i] : kNaN;
    has_u = has_u || std::isfinite(u);
    b.rows.push_back({a.run.Time(i) * kMs, (a.run.x[0][i] - x0[0]) * kMm,
                      (a.run.x[1][i] - x0[1]) * kMm, u * kMm});
  }
  p.figure.blocks.push_back(std::move(b));
  std::vector<std::string> plot;
  for (int s = 0; s < 2; ++s) {
    if (std::isnan(x0[s])) continue;
    plot.push_back(Format("datafile index 0 using 1:%d with lines lw 1.5 lc rgb \"%s\" "
                          "title \"%s tip\"", 2 + s, kTipColour[s], kSide[s]));
  }
  std::string& sc = p.figure.script;
  const std::string title = "Horizontal motion in the settled window (" + w.summary.label +
                            "); " + DriveText(a.plate);
  sc = "set grid\nset lmargin 12\nset rmargin 4\nset key top left\n" +
       Format("set xrange [%.9g:%.9g]\n", w.t_start * kMs, w.t_end * kMs);
  if (has_u) sc += "set multiplot layout 2,1 title " + GnuplotQuote(title) + "\n";
  else sc += "set title " + GnuplotQuote(title) + "\n";
  sc += "set xlabel \"time t (ms)\"\nset ylabel \"x - x(window start) (mm)\"\nplot " + Join(plot);
  if (has_u) {
    const int r = a.slip.resting_sphere;
    sc += "set title " +
          GnuplotQuote("slip velocity U of the resting " + RestingText(a.slip) +
                       " sphere (+ toward the bouncing end), filter half-width " +
                       std::to_string(a.slip.half_window) + " frames") +
          "\nset ylabel \"U (mm/s)\"\nplot datafile index 0 using 1:4 with lines lc rgb \"" +
          std::string(kTipColour[r < 0 ? 0 : r]) + "\" notitle, 0 with lines dt 2 " +
          "lc rgb \"gray40\" notitle\nunset multiplot\n";
  } else {
    p.outcome.note = "slip panel omitted: no resting sphere";
  }
  p.figure.height_px = kPanelsFigureHeightPx;
  p.ready = true;
  return p;
}

PlannedFigure PlanSlipPhase(const Analysis& a, const Comparison* c) {
  PlannedFigure p;
  p.outcome = {"slip_phase", "phase-averaged slip velocity of the resting sphere over the plate "
               "period, in the settled window", false, ""};
  const SlipResult& s = a.slip;
  if (s.resting_sphere < 0 || !AnyFinite(s.profile)) {
    p.outcome.note = "no resting sphere (settled mode " + a.periods.settled.summary.label +
                     "), so no slip profile";
    return p;
  }
  auto profile_block = [](const SlipResult& r, const std::string& what) {
    DataBlock b{what + ": mean slip per plate-phase bin and its standard error",
                {"phase", "U_mm_s", "U_err_mm_s", "count"}, {}};
    auto at = [](const auto& v, size_t k) { return k < v.size() ? double(v[k]) : kNaN; };
    for (size_t k = 0; k < r.phase.size(); ++k) {
      b.rows.push_back({r.phase[k], at(r.profile, k) * kMm, at(r.profile_err, k) * kMm,
                        at(r.profile_count, k)});
    }
    return b;
  };
  std::vector<std::string> plot;
  p.figure.blocks.push_back(profile_block(s, "track"));
  plot.push_back(Format("datafile index 0 using 1:2:3 with yerrorlines pt 7 ps 0.8 lc rgb \"%s\" "
                        "title \"track (%s sphere)\"", kTipColour[s.resting_sphere],
                        kSide[s.resting_sphere]));
  if (c != nullptr && AnyFinite(c->sim.slip.profile)) {
    p.figure.blocks.push_back(profile_block(c->sim.slip, "simulation"));
    plot.push_back("datafile index 1 using 1:2:3 with yerrorlines pt 4 ps 0.8 dt 2 "
                   "lc rgb \"#2ca02c\" title \"simulation\"");
  }
  DataBlock plate{"plate height relative to its amplitude, sin(2 pi phase)",
                  {"phase", "plate_rel"}, {}};
  for (int k = 0; k <= kPlatePhasePoints; ++k) {
    const double ph = double(k) / kPlatePhasePoints;
    plate.rows.push_back({ph, std::sin(2 * M_PI * ph)});
  }
  p.figure.blocks.push_back(std::move(plate));
  plot.push_back(Format("datafile index %zu using 1:2 axes x1y2 with lines lw 2 "
                        "lc rgb \"gray60\" title \"plate (right axis)\"",
                        p.figure.blocks.size() - 1));
  plot.push_back("0 with lines dt 3 lc rgb \"gray40\" notitle");
  p.figure.script =
      "set title " +
      GnuplotQuote(Format("Phase-averaged slip, %zu bins; after impact %.3g ± %.2g mm/s, "
                          "before %.3g ± %.2g mm/s", s.phase.size(), s.after * kMm,
                          s.after_err * kMm, s.before * kMm, s.before_err * kMm)) +
      "\nset xlabel \"plate phase (0 = plate at mid-height, rising)\"\n"
      "set ylabel \"slip velocity U (mm/s), + toward the bouncing end\"\n"
      "set y2label \"plate height / amplitude\"\nset xrange [0:1]\nset y2range [-1.1:1.1]\n"
      "set ytics nomirror\nset y2tics\nset grid\nset key below horizontal\nplot " +
      Join(plot);
  p.figure.height_px = kFigureHeightPx;
  p.ready = true;
  return p;
}

int ModeIndex(Mode m) {
  const auto& names = ModeNames();
  for (size_t k = 0; k < names.size(); ++k)
    if (names[k].second == m) return static_cast<int>(k);
  return static_cast<int>(names.size()) - 1;
}

// Coloured bands for runs of windows with the same label, labelled in the top panel.
std::string ModeBands(const Periods& periods, double t_span) {
  std::string sc;
  const auto& tl = periods.timeline;
  int object = 1;
  for (size_t k = 0; k < tl.size();) {
    size_t e = k + 1;
    while (e < tl.size() && tl[e].summary.mode == tl[k].summary.mode &&
           std::abs(tl[e].t_start - tl[e - 1].t_end) < 0.5 * periods.period_s)
      ++e;
    const double t0 = tl[k].t_start, t1 = tl[e - 1].t_end;
    sc += Format("set object %d rect from %.9g, graph 0 to %.9g, graph 1 fc rgb \"%s\" "
                 "fs transparent solid 0.18 noborder behind\n",
                 object++, t0, t1, ModeColour(tl[k].summary.mode).c_str());
    if (t1 - t0 > 0.06 * t_span) {
      sc += Format("set label \"%s\" at %.9g, graph 0.05 center front\n",
                   tl[k].summary.label.c_str(), 0.5 * (t0 + t1));
    }
    k = e;
  }
  return sc;
}

PlannedFigure PlanModes(const Analysis& a) {
  PlannedFigure p;
  p.outcome = {"modes", "energy measure and impacts per period with the mode timeline", false,
               ""};
  const Periods& per = a.periods;
  if (per.rows.empty()) {
    p.outcome.note = "no whole plate period";
    return p;
  }
  DataBlock rows{"per period: the paper's energy measure (sum of both spheres' highest "
                 "elevation / (g T^2)), impacts and rest fraction per sphere; complete 1/0",
                 {"t_start_s", "t_mid_s", "energy_gT2", "impacts_left", "impacts_right",
                  "rest_fraction_left", "rest_fraction_right", "complete"}, {}};
  double e_max = 0, i_max = 0;
  for (const PeriodRow& r : per.rows) {
    if (std::isfinite(r.energy_gT2)) e_max = std::max(e_max, r.energy_gT2);
    i_max = std::max({i_max, double(r.stats.impacts[0]), double(r.stats.impacts[1])});
    rows.rows.push_back({r.t_start, r.t_start + 0.5 * per.period_s, r.energy_gT2,
                         double(r.stats.impacts[0]), double(r.stats.impacts[1]),
                         r.stats.rest_time[0] / per.period_s, r.stats.rest_time[1] / per.period_s,
                         r.complete ? 1.0 : 0.0});
  }
  p.figure.blocks.push_back(std::move(rows));
  std::string mode_list;
  for (size_t k = 0; k < ModeNames().size(); ++k)
    mode_list += Format("%s%zu %s", k ? ", " : "", k, ModeNames()[k].first.c_str());
  DataBlock windows{"mode timeline windows; mode: " + mode_list + "; bouncing sphere -1 none",
                    {"t_start_s", "t_end_s", "mode", "bouncing_sphere", "first_period",
                     "periods"}, {}};
  for (const ModeWindow& w : per.timeline) {
    windows.rows.push_back({w.t_start, w.t_end, double(ModeIndex(w.summary.mode)),
                            double(w.summary.bouncing_sphere), double(w.first), double(w.count)});
  }
  if (!windows.rows.empty()) p.figure.blocks.push_back(std::move(windows));

  const double t_span = per.rows.back().t_start + per.period_s - per.rows.front().t_start;
  std::string& sc = p.figure.script;
  // Fixed margins keep the two panels' time axes aligned with the keys outside on the right.
  sc = Format("set grid\nset lmargin 12\nset rmargin 26\nset key outside right top\n"
              "set xrange [%.9g:%.9g]\n", per.rows.front().t_start,
              per.rows.front().t_start + t_span);
  sc += ModeBands(per, t_span);
  std::vector<std::string> top = {"datafile index 0 using 2:3 with linespoints pt 7 ps 0.5 lw 1 "
                                  "lc rgb \"black\" title \"energy per period\""};
  const bool incomplete = std::any_of(per.rows.begin(), per.rows.end(),
                                      [](const PeriodRow& r) { return !r.complete; });
  if (incomplete) {
    top.push_back("datafile index 0 using 2:($8 == 0 ? $3 : NaN) with points pt 2 ps 1.5 "
                  "lc rgb \"#d62728\" title \"incomplete period\"");
  }
  for (size_t k = 0; k < kPaperEnergies.size(); ++k) {
    const auto& [level, name] = kPaperEnergies[k];
    if (level <= kReferenceSpan * e_max) {
      top.push_back(Format("%g with lines dt %zu lw 1.5 lc rgb \"gray30\" title \"%s (paper)\"",
                           level, k + 2, name));
    }
  }
  std::vector<bool> shown(ModeNames().size(), false);
  for (const ModeWindow& w : per.timeline) shown[ModeIndex(w.summary.mode)] = true;
  for (size_t k = 0; k < shown.size(); ++k) {
    if (!shown[k]) continue;
    top.push_back(Format("keyentry with boxes fs transparent solid 0.18 noborder fc rgb \"%s\" "
                         "title \"%s\"", ModeColour(ModeNames()[k].second).c_str(),
                         ModeNames()[k].first.c_str()));
  }
  const ModeWindow& st = per.settled;
  if (st.count > 0) {
    sc += Format("set arrow 1 from %.9g, graph 0.9 to %.9g, graph 0.9 heads size screen 0.008,90 "
                 "lw 2 front\nset label 100 \"settled window: %s\" at %.9g, graph 0.94 center "
                 "front\n", st.t_start, st.t_end, st.summary.label.c_str(),
                 0.5 * (st.t_start + st.t_end));
  }
  sc += "set multiplot layout 2,1 title " +
        GnuplotQuote("Modes over time; " + DriveText(a.plate)) +
        "\nset title \"energy measure per period\"\nset xlabel \"time t (s)\"\n"
        "set ylabel \"Σ max elevation / (g T²)\"\nset yrange [0:*]\n"
        "set offsets 0, 0, graph 0.2, 0\nplot " + Join(top);
  sc += "unset label\nunset arrow\nset offsets 0, 0, 0, 0\nset title \"impacts per period\"\n"
        "set ylabel \"impacts in the period\"\n" +
        Format("set yrange [-0.3:%g]\nset ytics 1\n", i_max + 0.8) +
        Format("plot datafile index 0 using 2:4 with points pt 6 ps 1.0 lc rgb \"%s\" "
               "title \"left\", \\\n     datafile index 0 using 2:5 with points pt 9 ps 0.8 "
               "lc rgb \"%s\" title \"right\"\nunset multiplot\n", kTipColour[0], kTipColour[1]);
  p.figure.height_px = kPanelsFigureHeightPx;
  p.ready = true;
  return p;
}

}  // namespace

void FramesIn(const SampledRun& run, double t_begin, double t_end, size_t* first, size_t* last) {
  *first = *last = 0;
  if (run.n == 0 || !(run.dt > 0)) return;
  // Half a nanosecond of slack (in frames) so a boundary on a frame time includes that frame.
  const double eps = 1e-6;
  const double a = std::ceil((t_begin - run.t0) / run.dt - eps);
  const double b = std::ceil((t_end - run.t0) / run.dt - eps);
  *first = static_cast<size_t>(std::clamp(a, 0.0, double(run.n)));
  *last = static_cast<size_t>(std::clamp(b, double(*first), double(run.n)));
}

bool AnyFinite(const std::vector<double>& v) {
  return std::any_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

std::vector<FigureOutcome> WriteFigures(const std::string& figures_dir, const ReportInputs& in) {
  std::vector<PlannedFigure> plans = {PlanHeights(*in.track), PlanPositions(*in.track),
                                      PlanSlipPhase(*in.track, in.comparison),
                                      PlanModes(*in.track)};
  if (in.comparison != nullptr) plans.push_back(PlanSimVsTrack(*in.track, *in.comparison));
  if (in.fit != nullptr) plans.push_back(PlanFitProfile(*in.fit));
  std::vector<FigureOutcome> out;
  for (PlannedFigure& p : plans) {
    p.figure.name = p.outcome.name;
    p.figure.width_px = kFigureWidthPx;
    if (p.ready) {
      const std::string warnings = DrawFigure(figures_dir, p.figure);
      p.outcome.drawn = true;
      if (!warnings.empty()) {
        p.outcome.note += (p.outcome.note.empty() ? "" : "; ") + ("gnuplot: " + warnings);
      }
    }
    out.push_back(p.outcome);
  }
  return out;
}

}  // namespace dimer::compare
