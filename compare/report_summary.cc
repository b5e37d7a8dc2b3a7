// summary.md: the report's text. Numbers carry their units; a value with an error is printed
// to the error's second significant digit; unknown values print as "n/a" (never "nan").
#include <algorithm>
#include <cmath>
#include <sstream>

#include "compare/goodness_of_fit.h"
#include "compare/report_parts.h"

namespace dimer::compare {
namespace {

constexpr double kMm = 1e3, kUm = 1e6, kMs = 1e3;  // from m, m/s, s
constexpr size_t kMaxGapRows = 50;                   // per sphere; the rest are counted
constexpr int kMaxSignificant = 6;                   // digits of a value with a tiny error
const char* const kSide[2] = {"left", "right"};

std::string NumOrNa(double v, const char* fmt = "%.4g") {
  return std::isfinite(v) ? Format(fmt, v) : "n/a";
}

// v ± err (both times `scale`) with the error's two significant digits, then the unit.
std::string Pm(double v, double err, double scale = 1, const std::string& unit = "") {
  if (!std::isfinite(v)) return "n/a";
  const std::string u = unit.empty() ? "" : " " + unit;
  v *= scale;
  err *= scale;
  if (!std::isfinite(err) || err <= 0) return Format("%.4g", v) + u;
  const int decimals = std::max(0, 1 - static_cast<int>(std::floor(std::log10(err))));
  // A tiny error (a noise-free simulation) would ask for many digits: the value keeps
  // kMaxSignificant, the error is shown in exponent form.
  const int max_decimals =
      v == 0 ? decimals
             : kMaxSignificant - 1 - static_cast<int>(std::floor(std::log10(std::abs(v))));
  if (decimals > max_decimals) {
    return Format("%.*f ± %.1g", std::max(0, max_decimals), v, err) + u;
  }
  return Format("%.*f ± %.*f", decimals, v, decimals, err) + u;
}

std::string Percent(double fraction) {
  return std::isfinite(fraction) ? Format("%.2g %%", fraction * 100) : "n/a";
}

std::string Side(int s) { return s == 0 || s == 1 ? kSide[s] : "none"; }

std::string ModeText(const ModeSummary& m) {
  return m.mode == Mode::kDrift ? m.label + " (bouncing " + Side(m.bouncing_sphere) + " end)"
                                : m.label;
}

// Where a track's scale came from: what its lengths, speeds and Γ rest on.
std::string ScaleRow(const SampledRun& r) {
  if (r.kind != "track" || r.scale_source.empty()) return "";
  const std::string scale = NumOrNa(r.m_per_px * 1e3, "%.6g") + " mm/px";
  const std::string from =
      r.scale_source == "--m-per-px" ? "given (track --m-per-px)"
      : r.scale_source == "--ar"
          ? "from the dimer's length and A_r (track --ar): to ~0.2 %"
          : "from the sphere diameter over the measured radius (on mirror steel ~2 % large, more "
            "where one side is dark; track --ar or --m-per-px fixes it)";
  return "| scale | " + scale + ", " + from + " |\n";
}

// How the tracked plate's motion became metres: a Γ read off a plate edge that is not in the
// dimer's plane is off by the ratio of the two scales, so the summary says which was used.
std::string PlateScaleRow(const Analysis& a) {
  const SampledRun& r = a.run;
  if (r.kind != "track" || a.plate.source != "fit" || r.plate_scale_source.empty()) return "";
  std::string text;
  if (r.plate_scale_source == "--plate-m-per-px") {
    text = "the edge's own (--plate-m-per-px): its motion × " + NumOrNa(r.plate_motion_scale, "%.6g");
  } else if (r.plate_scale_source == "fitted") {
    text = "fitted on a resting sphere (polished plate): its motion × " +
           NumOrNa(r.plate_motion_scale, "%.4g");
  } else {
    text = "the dimer plane's: an edge nearer the camera (a deep plate's front edge) reads Γ "
           "high by D / (D − Δ); track --plate-m-per-px gives its own";
  }
  return "| plate edge's scale | " + text + " |\n";
}

void Drive(const Analysis& a, std::ostringstream& o) {
  const PlateDrive& d = a.plate;
  const SampledRun& r = a.run;
  o << "## Input and drive\n\n| quantity | value |\n|---|---|\n"
    << "| input | `" << r.path << "` (" << r.kind << ") |\n"
    << "| frames | " << r.n << Format(" at %.6g fps, t = %.4f … %.4f s", r.fps(), r.Time(0),
                                      r.n ? r.Time(r.n - 1) : r.t0) << " |\n"
    << "| drive source | " << d.source << " |\n"
    << "| drive frequency f | " << Pm(d.freq_hz, d.freq_err, 1, "Hz") << " |\n"
    << "| Γ" << (std::isfinite(d.gamma_plate) ? " (--gamma)" : "") << " | " << Pm(d.gamma, d.gamma_err) << " |\n"
    << (std::isfinite(d.gamma_plate) ? "| Γ of the tracked plate | " + Pm(d.gamma_plate, d.gamma_plate_err) + " |\n" : "")
    << PlateScaleRow(a)
    << "| plate amplitude | " << Pm(d.amp_m, d.amp_err, kMm, "mm") << " |\n"
    << "| plate phase at t = 0 | " << Pm(d.phase_rad, d.phase_err, 1, "rad") << " |\n"
    << "| plate fit residual (rms) | " << NumOrNa(d.residual_rms_m * kUm, "%.3g") << " µm |\n"
    << "| harmonics 2f, 3f, 4f (of the amplitude) | " << Percent(d.harmonic_rel[0]) << ", "
    << Percent(d.harmonic_rel[1]) << ", " << Percent(d.harmonic_rel[2]) << " |\n"
    << "| sphere diameter d | " << NumOrNa(r.diameter_m * kMm) << " mm |\n"
    << ScaleRow(r)
    << (r.scale_source == "--ar" ? "| A_r (given to track --ar, which set the scale by it) | "
                                 : "| A_r (measured) | ")
    << NumOrNa(r.ar, "%.3f") << " |\n\n";
}

void Settled(const Analysis& a, std::ostringstream& o) {
  const ModeWindow& w = a.periods.settled;
  const ModeSummary& m = w.summary;
  o << "## Settled mode\n\n";
  if (w.count == 0) {
    o << "No settled window: the run has no whole plate period.\n\n";
    return;
  }
  o << "**" << ModeText(m) << "** over " << Format("t = %.4f … %.4f s (%d periods)", w.t_start,
                                                    w.t_end, w.count)
    << "; orbit period: "
    << (m.orbit_periods > 0 ? std::to_string(m.orbit_periods) + " plate period" + (m.orbit_periods > 1 ? "s" : "")
                            : "none up to " + std::to_string(kMaxOrbitPeriods) + " plate periods")
    << ".\n\n| per sphere | left | right |\n|---|---|---|\n"
    << "| impacts per period | " << NumOrNa(m.impacts_per_period[0], "%.3f") << " | "
    << NumOrNa(m.impacts_per_period[1], "%.3f") << " |\n"
    << "| rest fraction | " << NumOrNa(m.rest_fraction[0], "%.3f") << " | "
    << NumOrNa(m.rest_fraction[1], "%.3f") << " |\n";
  const auto& sp = a.contacts.sphere;
  o << "| position noise of the gap | " << NumOrNa(sp[0].noise_m * kUm, "%.3g") << " µm | "
    << NumOrNa(sp[1].noise_m * kUm, "%.3g") << " µm |\n"
    << "| contact level | " << NumOrNa(sp[0].level_m * kUm, "%.3g") << " µm | "
    << NumOrNa(sp[1].level_m * kUm, "%.3g") << " µm |\n"
    << "| contact threshold | " << NumOrNa(sp[0].threshold_m * kUm, "%.3g") << " µm | "
    << NumOrNa(sp[1].threshold_m * kUm, "%.3g") << " µm |\n"
    << "| impacts found (whole run) | " << sp[0].impacts.size() << " | " << sp[1].impacts.size()
    << " |\n\n";
}

void DriftAndFall(const Analysis& a, std::ostringstream& o) {
  const Drift& d = a.drift;
  // One period has no period-to-period scatter: its error is not zero but unknown.
  const std::string one = d.periods < 2 ? " ± n/a (one period)" : "";
  // "Toward the bouncing end" only in drift; in any other mode the plain mean of lab x.
  const std::string sign = d.bouncing_sphere >= 0
                               ? "positive toward the bouncing end, " + Side(d.bouncing_sphere)
                               : "the mean along +x: no bouncing end in the " +
                                     a.periods.settled.summary.label + " mode";
  o << "## Drift\n\n- ⟨u⟩ = " << Pm(d.speed, d.speed_err, kMm, "mm/s") << one << " (" << sign
    << "), over the settled window's " << d.periods << (d.periods == 1 ? " whole period" : " whole periods")
    << " (the transient before it "
    << "excluded)\n- ⟨u⟩ f / g = " << Pm(d.scaled, d.scaled_err) << one << "\n";
  if (std::isfinite(d.travel_time_s)) {
    o << "- travel over " << NumOrNa(d.travel_mm, "%.3g") << " mm (the paper's measure): "
      << NumOrNa(d.travel_time_s, "%.4g") << " s, " << NumOrNa(d.travel_speed * kMm, "%.4g")
      << " mm/s\n";
  } else {
    o << "- travel over " << NumOrNa(d.travel_mm, "%.3g") << " mm: not measured"
      << (d.travel_note.empty() ? "" : " (" + d.travel_note + ")") << "\n";
  }
  const FreeFall& f = a.free_fall;
  o << "\n## Free fall (calibration check)\n\n";
  if (std::isfinite(f.g_fit)) {
    o << "g_fit / g = " << Pm(f.g_fit / kGravity, f.g_fit_err / kGravity) << " from "
      << f.flights << " flights (" << f.frames << " frames); the flights fall "
      << Pm(f.tilt_deg, f.tilt_deg_err) << "° from the normal of the plate as tracked "
      << "(a plate tilted against gravity, > 0 rising toward +x; 0 for a level plate, whatever "
         "the camera's roll).\n\n";
  } else {
    o << "g_fit not measured" << (f.note.empty() ? "" : ": " + f.note) << ".\n\n";
  }
}

void Slip(const Analysis& a, std::ostringstream& o) {
  const SlipResult& s = a.slip;
  o << "## Slip of the resting sphere\n\n";
  if (s.resting_sphere < 0) {
    o << "No resting sphere in the settled mode (" << a.periods.settled.summary.label
      << "): no slip analysis.\n\n";
    return;
  }
  o << "- resting sphere: " << Side(s.resting_sphere) << "; U positive toward the bouncing end\n"
    << "- averaged over the settled window, " << s.window_periods
    << (s.window_periods == 1 ? " period" : " periods") << " from t = " << NumOrNa(s.window_t_start, "%.4f")
    << " s (the transient before it excluded; the whole run's profile is /slip/whole_profile)\n"
    << "- filter half-width h = " << s.half_window << " frames, predicted velocity noise "
    << NumOrNa(s.velocity_noise * kMm, "%.3g") << " mm/s\n"
    << "- U after the bouncing end's impact: " << Pm(s.after, s.after_err, kMm, "mm/s") << "\n"
    << "- U before the next impact: " << Pm(s.before, s.before_err, kMm, "mm/s") << "\n"
    << "- impact intervals averaged: " << s.intervals << "\n\n";
}

void Timeline(const Analysis& a, std::ostringstream& o) {
  const auto& tl = a.periods.timeline;
  o << "## Mode timeline\n\n";
  if (tl.empty()) {
    o << "No complete window of " << a.options.window_periods << " periods.\n\n";
    return;
  }
  o << "| t_start (s) | t_end (s) | mode | impacts/period L | impacts/period R | rest fraction L "
       "| rest fraction R | drift speed (mm/s) |\n|---|---|---|---|---|---|---|---|\n";
  for (const ModeWindow& w : tl) {
    const ModeSummary& m = w.summary;
    o << Format("| %.4f | %.4f | ", w.t_start, w.t_end) << ModeText(m) << " | "
      << NumOrNa(m.impacts_per_period[0], "%.2f") << " | " << NumOrNa(m.impacts_per_period[1], "%.2f")
      << " | " << NumOrNa(m.rest_fraction[0], "%.2f") << " | " << NumOrNa(m.rest_fraction[1], "%.2f")
      << " | " << Pm(m.drift_speed, m.drift_speed_err, kMm) << " |\n";
  }
  o << "\n### Switches between modes\n\n";
  int switches = 0;
  for (size_t k = 1; k < tl.size(); ++k) {
    if (tl[k].summary.label == tl[k - 1].summary.label) continue;
    o << Format("- t = %.4f s: ", tl[k].t_start) << tl[k - 1].summary.label << " → "
      << tl[k].summary.label << "\n";
    ++switches;
  }
  if (switches == 0) o << "None: one mode throughout.\n";
  o << "\n";
}

void WarningsAndGaps(const ReportInputs& in, std::ostringstream& o) {
  const Analysis& a = *in.track;
  o << "## Warnings\n\n";
  std::vector<std::string> all = a.warnings;
  all.insert(all.end(), in.extra_warnings.begin(), in.extra_warnings.end());
  for (const auto& w : all) o << "- " << w << "\n";
  if (all.empty()) o << "None.\n";
  o << "\n## Missing frames\n\n";
  bool any = false;
  for (int s = 0; s < 2; ++s) {
    const auto& gaps = a.run.gaps[s];
    if (gaps.empty()) continue;
    any = true;
    o << "### " << kSide[s] << " tip: " << gaps.size() << (gaps.size() == 1 ? " gap" : " gaps")
      << "\n\n"
      << "| first frame | frames | time (s) | duration (ms) |\n|---|---|---|---|\n";
    for (size_t k = 0; k < gaps.size() && k < kMaxGapRows; ++k) {
      o << Format("| %zu | %zu | %.4f | %.3g |\n", gaps[k].first, gaps[k].count,
                  a.run.Time(gaps[k].first), double(gaps[k].count) * a.run.dt * kMs);
    }
    if (gaps.size() > kMaxGapRows) o << "\n… and " << gaps.size() - kMaxGapRows << " more.\n";
    o << "\n";
  }
  if (!any) o << "None: every frame has both tips.\n\n";
  if (a.outliers.empty()) return;
  o << "### Tracking outliers (rejected, part of the gaps above): " << a.outliers.size()
    << "\n\n| frame | tip | time (s) | distance from the local median (µm) |\n|---|---|---|---|\n";
  for (size_t k = 0; k < a.outliers.size() && k < kMaxGapRows; ++k) {
    const Outlier& x = a.outliers[k];
    o << Format("| %zu | %s | %.4f | %.4g |\n", x.frame, Side(x.sphere).c_str(),
                a.run.Time(x.frame), x.deviation_m * kUm);
  }
  if (a.outliers.size() > kMaxGapRows)
    o << "\n… and " << a.outliers.size() - kMaxGapRows << " more.\n";
  o << "\n";
}

void Comparing(const Analysis& t, const Comparison& c, std::ostringstream& o) {
  const Analysis& s = c.sim;
  o << "## Comparison with the simulation\n\n- simulation: `" << c.sim_path << "`\n"
    << "- time offset (t_sim = t_track + offset): " << NumOrNa(c.time_offset_s * kMs, "%.5g")
    << " ms\n- x offset: " << NumOrNa(c.x_offset_m * kMm, "%.5g") << " mm; simulation mirrored: "
    << (c.mirrored ? "yes" : "no") << "\n- frames compared: " << c.frames_compared
    << "; settled modes agree: " << (c.modes_agree ? "yes" : "no") << "\n\n"
    << "| RMS residual over the settled window | left | right |\n|---|---|---|\n"
    << "| x | " << NumOrNa(c.rms_x[0] * kUm, "%.3g") << " µm | " << NumOrNa(c.rms_x[1] * kUm, "%.3g")
    << " µm |\n| z | " << NumOrNa(c.rms_z[0] * kUm, "%.3g") << " µm | "
    << NumOrNa(c.rms_z[1] * kUm, "%.3g") << " µm |\n\n"
    << "| quantity | track | simulation |\n|---|---|---|\n";
  auto row = [&o](const std::string& q, const std::string& a, const std::string& b) {
    o << "| " << q << " | " << a << " | " << b << " |\n";
  };
  row("settled mode", ModeText(t.periods.settled.summary), ModeText(s.periods.settled.summary));
  row("drift ⟨u⟩ (mm/s)", Pm(t.drift.speed, t.drift.speed_err, kMm),
      Pm(s.drift.speed, s.drift.speed_err, kMm));
  row("⟨u⟩ f / g", Pm(t.drift.scaled, t.drift.scaled_err), Pm(s.drift.scaled, s.drift.scaled_err));
  row("g_fit / g", Pm(t.free_fall.g_fit / kGravity, t.free_fall.g_fit_err / kGravity),
      Pm(s.free_fall.g_fit / kGravity, s.free_fall.g_fit_err / kGravity));
  row("plate tilt from the flights (°)", Pm(t.free_fall.tilt_deg, t.free_fall.tilt_deg_err),
      Pm(s.free_fall.tilt_deg, s.free_fall.tilt_deg_err));
  row("slip after impact (mm/s)", Pm(t.slip.after, t.slip.after_err, kMm),
      Pm(s.slip.after, s.slip.after_err, kMm));
  row("slip before impact (mm/s)", Pm(t.slip.before, t.slip.before_err, kMm),
      Pm(s.slip.before, s.slip.before_err, kMm));
  o << "\n";
}

// A parameter's value cell: a number only when the chi2 profile constrains it.
std::string ParameterValue(const FitParameter& p) {
  if (p.status == "constrained") return Pm(p.value, p.err);
  if (p.status == "bounded_below") return "≥ " + NumOrNa(p.range_lo);
  if (p.status == "bounded_above") return "≤ " + NumOrNa(p.range_hi);
  if (p.status == "no_acceptable_fit") return "none (best point " + NumOrNa(p.value) + ", which fails)";
  return "unconstrained (range " + NumOrNa(p.lo) + "–" + NumOrNa(p.hi) + ")";
}

// The correlations of the constrained parameters (fit_correlation.h), when two or more are.
void Correlations(const FitResult& f, std::ostringstream& o) {
  const size_t n = f.params.size();
  std::vector<size_t> c;
  for (size_t k = 0; k < n; ++k)
    if (f.params[k].status == "constrained") c.push_back(k);
  if (c.size() < 2 || f.correlation.size() != n * n) return;
  o << "Correlations of the constrained parameters (from their chi2 profiles: how far each moves "
       "when another is held off its optimum):\n\n|   |";
  for (size_t k : c) o << " " << f.params[k].name << " |";
  o << "\n|---|";
  for (size_t k = 0; k < c.size(); ++k) o << "---|";
  o << "\n";
  for (size_t j : c) {
    o << "| " << f.params[j].name << " |";
    for (size_t k : c) o << " " << NumOrNa(f.correlation[j * n + k], "%+.2f") << " |";
    o << "\n";
  }
  o << "\n";
}

// The tracker's error that repeats with the drive's phase (compare/locked_error.h), as chi2
// holds it.
void LockedErrorNote(const LockedError& e, std::ostringstream& o) {
  if (e.phase_bins == 0) return;
  o << "The tracker's error that repeats with the drive's phase (averaging periods does not shrink it): ";
  if (e.col_m == 0 && e.row_m == 0) {
    o << "none measured (the dimer's length and the resting sphere's height keep their phase averages "
         "within their noise), so chi2 has no term for it.\n\n";
    return;
  }
  o << NumOrNa(e.col_m * 1e6, "%.2f") << " um per column, from the dimer's length over " << e.length_bins
    << " of " << e.phase_bins << " phase bins, and " << NumOrNa(e.row_m * 1e6, "%.2f") << " um per row, ";
  if (e.row_source == "resting_height") {
    o << "from the resting sphere's height above the plate over " << e.rest_bins << " bins of steady contact";
  } else {
    o << "taken from the columns (no sphere rests long enough to measure the rows)";
  }
  o << ". Its covariance over the observables (from the track analysed again with such errors drawn) is in "
       "chi2, and in each observable's error below.\n\n";
}

void Fitting(const FitResult& f, std::ostringstream& o) {
  o << "## Fit of the contact coefficients\n\n| parameter | fitted | status | value |\n"
       "|---|---|---|---|\n";
  for (const FitParameter& p : f.params) {
    o << "| " << p.name << " | " << (p.fitted ? "yes" : "no (slice only)") << " | "
      << (p.status.empty() ? "unknown" : p.status) << " | " << ParameterValue(p) << " |\n";
  }
  o << "\nchi2 = " << NumOrNa(f.chi2) << " with " << f.dof << " degrees of freedom (chi2/dof "
    << NumOrNa(f.chi2 / f.dof, "%.3g") << ", p-value " << NumOrNa(f.p_value, "%.3g") << ")";
  if (!f.acceptable) {
    o << ": **no acceptable fit** (p < " << NumOrNa(kMinFitPValue, "%g")
      << "): the best simulation of this scene the search found does not reproduce the track, "
         "so no coefficient is given (a start nearer the truth, --eps etc., may find one). "
         "Furthest off at the best point:\n\n";
    for (const std::string& line : f.off) o << "- " << line << "\n";
    o << "\n";
  } else {
    if (f.floor_scale < 1) {
      o << ", with the analysis floors scaled by " << NumOrNa(f.floor_scale, "%.3g")
        << ": at the floors as set chi2/dof was " << NumOrNa(f.chi2_per_dof_at_floors, "%.3g")
        << ", so they overstate this track's scatter";
    }
    o << ". A parameter's range is where its chi2 profile (the others re-optimised) stays within "
         "chi2 + "
      << NumOrNa(f.threshold) << " = " << NumOrNa(f.chi2 + f.threshold) << ".";
  }
  o << " " << f.evaluations
    << " simulations (their wall time is on stderr, so that reports are identical on rerun).\n\n";
  LockedErrorNote(f.locked, o);
  Correlations(f, o);
  if (f.observable_names.empty()) return;
  o << "| observable | track | simulation at the optimum |\n|---|---|---|\n";
  for (size_t k = 0; k < f.observable_names.size(); ++k) {
    auto at = [k](const std::vector<double>& v) { return k < v.size() ? v[k] : kNaN; };
    o << "| " << f.observable_names[k] << " | " << Pm(at(f.observed), at(f.observed_err))
      << " | " << NumOrNa(at(f.simulated)) << " |\n";
  }
  o << "\n";
}

void Figures(const std::vector<FigureOutcome>& figures, std::ostringstream& o) {
  o << "## Figures\n\nEach figure is drawn by gnuplot from `figures/NAME.dat` by "
       "`figures/NAME.gp` (replot: `cd figures && gnuplot NAME.gp`).\n\n";
  for (const FigureOutcome& f : figures) {
    if (f.drawn) {
      o << "- [" << f.name << ".png](figures/" << f.name << ".png): " << f.caption
        << (f.note.empty() ? "" : " (" + f.note + ")") << "\n";
    } else {
      o << "- " << f.name << ": not drawn, " << f.note << "\n";
    }
  }
  o << "\n";
}

}  // namespace

std::string SummaryMarkdown(const ReportInputs& in, const std::vector<FigureOutcome>& figures) {
  const Analysis& a = *in.track;
  std::ostringstream o;
  o << "# dimerlab report: " << a.run.path << "\n\n";
  Drive(a, o);
  Settled(a, o);
  DriftAndFall(a, o);
  Slip(a, o);
  Timeline(a, o);
  WarningsAndGaps(in, o);
  if (in.comparison != nullptr) Comparing(a, *in.comparison, o);
  if (in.fit != nullptr) Fitting(*in.fit, o);
  Figures(figures, o);
  o << "## Commands\n\n```\n";
  for (const auto& c : in.commands) o << c << "\n";
  o << "```\n";
  return o.str();
}

}  // namespace dimer::compare
