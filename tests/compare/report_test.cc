// The report and the overlay on a hand-made analysis of a drift-like run (no call to Analyze:
// the structs are filled with designed numbers, so every value drawn is known).
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "compare/gnuplot.h"
#include "compare/overlay.h"
#include "compare/report.h"
#include "tests/common/test_tmpdir.h"
#include "tracking/io/lens_undistortion.h"

namespace dimer::compare {
namespace {

namespace fs = std::filesystem;

// The run: A_r = 3.9, d = 9.5 mm, f = 25 Hz at 1000 frames/s (40 frames a period), 8 periods.
// The left sphere rests on the plate, the right one leaves it once a period; the dimer creeps
// toward its bouncing (right) end at 5 mm/s with a slip oscillating over the plate period.
constexpr double kFreqHz = 25, kFps = 1000, kGamma = 0.9, kDiameterM = 9.5e-3, kAr = 3.9;
constexpr int kPeriods = 8, kFramesPerPeriod = 40, kWindow = 2, kBins = 20;
constexpr double kT0 = 0.1;               // time of frame 0, s
constexpr double kDriftMs = 5e-3;         // m/s
constexpr double kHopM = 0.4e-3;          // the bouncing end's highest elevation, m
constexpr double kXLeft0M = 12e-3;        // left tip at t = 0, m
constexpr double kMPerPx = 1e-3, kRow0Px = 40;  // 64 x 48 frames: the dimer spans 28 px
constexpr int kFrameCols = 64, kFrameRows = 48;
constexpr double kUnconstrainedValue = 0.123456, kUnconstrainedErr = 0.0456;
constexpr double kRel = 1e-8;  // .dat numbers carry 9 significant digits

double Amp() { return kGamma * kGravity / (4 * M_PI * M_PI * kFreqHz * kFreqHz); }
double Phase(double t) { return t * kFreqHz - std::floor(t * kFreqHz); }
double SlipAt(double phase) { return kDriftMs + 20e-3 * std::cos(2 * M_PI * phase); }

void FillRun(SampledRun* r) {
  r->path = "synthetic_drift.h5";
  r->kind = "track";
  r->t0 = kT0;
  r->dt = 1 / kFps;
  r->n = kPeriods * kFramesPerPeriod;
  r->diameter_m = kDiameterM;
  r->ar = kAr;
  r->m_per_px = kMPerPx;
  r->row0_px = kRow0Px;
  const double radius = kDiameterM / 2, length = (kAr - 1) * kDiameterM;
  for (size_t i = 0; i < r->n; ++i) {
    const double t = r->Time(i), zp = Amp() * std::sin(2 * M_PI * kFreqHz * t);
    const double xl = kXLeft0M + kDriftMs * t + 0.1e-3 * std::sin(2 * M_PI * Phase(t));
    const double zr = radius + zp + kHopM * std::sin(M_PI * Phase(t));
    r->x[0].push_back(xl);
    r->z[0].push_back(radius + zp);
    r->x[1].push_back(xl + std::sqrt(length * length - (zr - radius - zp) * (zr - radius - zp)));
    r->z[1].push_back(zr);
    r->plate_z.push_back(zp);
    r->theta.push_back(std::atan2(zr - radius - zp, length));
    r->frame_files.push_back("frame_" + std::to_string(i) + ".png");
  }
  for (size_t i = 50; i < 53; ++i) r->x[0][i] = r->z[0][i] = kNaN;  // a 3-frame gap
  r->gaps[0].push_back({50, 3});
}

void FillPeriods(const SampledRun& r, Periods* p) {
  const double period = 1 / kFreqHz;
  p->period_s = period;
  for (int k = 0; k < kPeriods; ++k) {
    PeriodRow row;
    row.t_start = kT0 + k * period;
    row.stats.impacts = {0, k == 1 ? 2 : 1};
    row.stats.rest_time = {0.9 * period, 0};
    row.stats.x_start = r.x[1][k * kFramesPerPeriod] - 0.5 * (kAr - 1) * kDiameterM;
    row.elevation_m = {0, kHopM + 1e-5 * k};
    row.energy_gT2 = row.elevation_m[1] / (kGravity * period * period);
    p->rows.push_back(row);
  }
  p->rows[1].complete = false;
  p->rows[1].missing_fraction = 3.0 / kFramesPerPeriod;
  auto window = [&](int first, int count, Mode mode) {
    ModeWindow w;
    w.first = first;
    w.count = count;
    w.t_start = kT0 + first * period;
    w.t_end = w.t_start + count * period;
    w.summary.mode = mode;
    w.summary.label = ToString(mode);
    w.summary.bouncing_sphere = mode == Mode::kDrift ? 1 : -1;
    w.summary.window_periods = count;
    w.summary.impacts_per_period = {0, 1};
    w.summary.rest_fraction = {0.9, 0};
    w.summary.drift_speed = kDriftMs;
    w.summary.drift_speed_err = 2e-4;
    return w;
  };
  p->timeline = {window(0, kWindow, Mode::kJump), window(2, kWindow, Mode::kDrift),
                 window(4, kWindow, Mode::kDrift), window(6, kWindow, Mode::kDrift)};
  p->settled = window(kPeriods / 2, kPeriods / 2, Mode::kDrift);
}

void FillSlip(const SampledRun& r, SlipResult* s) {
  s->resting_sphere = 0;
  s->half_window = 3;
  s->velocity_noise = 1.1e-3;
  for (size_t i = 0; i < r.n; ++i) s->U.push_back(SlipAt(Phase(r.Time(i))));
  for (int k = 0; k < kBins; ++k) {
    const double phase = (k + 0.5) / kBins;
    s->phase.push_back(phase);
    s->profile.push_back(SlipAt(phase));
    s->profile_err.push_back(1e-3 + 1e-5 * k);
    s->profile_count.push_back(16 + k);
  }
  s->after = 12e-3;
  s->after_err = 1e-3;
  s->before = -4e-3;
  s->before_err = 0.8e-3;
  s->intervals = 7;
}

Analysis SyntheticDrift() {
  Analysis a;
  FillRun(&a.run);
  a.options.window_periods = kWindow;
  PlateDrive& d = a.plate;
  d.source = "fit";
  d.freq_hz = kFreqHz;
  d.freq_err = 1e-3;
  d.amp_m = Amp();
  d.amp_err = 1e-6;
  d.phase_rad = 0;
  d.phase_err = 2e-3;
  d.gamma = kGamma;
  d.gamma_err = 4e-3;
  d.residual_rms_m = 3e-6;
  d.harmonic_rel = {0.01, 0.005, 0.002};
  for (int s = 0; s < 2; ++s) {
    a.contacts.sphere[s].noise_m = 5e-6;
    a.contacts.sphere[s].level_m = 1e-6;
    a.contacts.sphere[s].threshold_m = 2e-5;
  }
  FillPeriods(a.run, &a.periods);
  a.drift = {1, kDriftMs, 2e-4, kDriftMs * kFreqHz / kGravity, 2e-4 * kFreqHz / kGravity, 4,
             55, kNaN, kNaN, "the run travels 1.6 mm, less than 55 mm"};
  a.free_fall.note = "no free flight: one end is always on the plate in the drift mode";
  FillSlip(a.run, &a.slip);
  a.warnings = {"synthetic warning: hand-made analysis"};
  a.outliers = {{52, 0, 1.5e-3}};  // the last frame of the gap was a tracker failure
  return a;
}

// The simulation: the same run lifted by 20 um (so the residuals are known), a smaller slip.
Comparison SyntheticComparison(const Analysis& track) {
  Comparison c;
  c.sim_path = "sim_drift.h5";
  c.time_offset_s = 0.0123;
  c.x_offset_m = 1e-3;
  c.sim = track;
  for (double& u : c.sim.slip.profile) u *= 0.9;
  for (size_t i = 0; i < track.run.n; ++i) {
    c.t.push_back(track.run.Time(i));
    for (int s = 0; s < 2; ++s) {
      c.sim_x[s].push_back(track.run.x[s][i] - 5e-6);
      c.sim_z[s].push_back(track.run.z[s][i] + 20e-6);
      c.res_x[s].push_back(track.run.x[s][i] - c.sim_x[s][i]);
      c.res_z[s].push_back(track.run.z[s][i] - c.sim_z[s][i]);
    }
  }
  c.rms_x = {5e-6, 5e-6};
  c.rms_z = {20e-6, 20e-6};
  c.frames_compared = static_cast<int>(track.run.n);
  c.modes_agree = true;
  return c;
}

FitParameter Param(const std::string& name, const std::string& status, double value, double err,
                   double lo, double hi, double curvature) {
  FitParameter p;
  p.name = name;
  p.fitted = true;
  p.status = status;
  p.value = value;
  p.err = err;
  p.lo = lo;
  p.hi = hi;
  p.range_lo = status == "constrained" ? value - err : lo;
  p.range_hi = status == "constrained" ? value + err : hi;
  for (int k = 0; k < 15; ++k) {
    const double x = lo + (hi - lo) * k / 14;
    p.slice_x.push_back(x);
    p.slice_chi2.push_back(3.2 + curvature * (x - value) * (x - value));
  }
  return p;
}

FitResult SyntheticFit() {
  FitResult f;
  f.params = {Param("eps", "constrained", 0.65, 0.03, 0.3, 0.95, 1 / (0.03 * 0.03)),
              Param("mu", "unconstrained", kUnconstrainedValue, kUnconstrainedErr, 0.05, 0.6,
                    0.5)};
  f.chi2 = 3.2;
  f.dof = 5;
  f.p_value = 0.669;  // P(chi2_5 >= 3.2)
  f.acceptable = true;
  f.threshold = 1;
  f.evaluations = 42;
  f.seconds = 12.5;
  f.observable_names = {"drift_scaled"};
  f.observed = {0.0127};
  f.observed_err = {0.0005};
  f.simulated = {0.0129};
  return f;
}

struct Block {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
};

// NAME.dat back: blocks split at blank lines, the last comment line of each naming its columns.
std::vector<Block> ReadDat(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << path;
  std::vector<Block> blocks;
  std::string line;
  bool in_block = false;
  while (std::getline(in, line)) {
    if (line.empty()) {
      in_block = false;
      continue;
    }
    if (!in_block) blocks.emplace_back();
    in_block = true;
    std::istringstream words(line[0] == '#' ? line.substr(1) : line);
    std::vector<std::string> cells;
    for (std::string w; words >> w;) cells.push_back(w);
    if (line[0] == '#') {
      blocks.back().columns = cells;
    } else {
      std::vector<double> row;
      for (const auto& c : cells) row.push_back(std::stod(c));  // stod reads "NaN"
      blocks.back().rows.push_back(row);
    }
  }
  return blocks;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Width and height from the PNG's IHDR chunk; {0, 0} when the file is not a PNG.
std::pair<int, int> PngSize(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char h[24] = {};
  in.read(reinterpret_cast<char*>(h), sizeof h);
  const unsigned char magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!in || !std::equal(magic, magic + 8, h) || std::string(h + 12, h + 16) != "IHDR")
    return {0, 0};
  auto be32 = [&h](int at) {
    return int(uint32_t(h[at]) << 24 | uint32_t(h[at + 1]) << 16 | uint32_t(h[at + 2]) << 8 |
               uint32_t(h[at + 3]));
  };
  return {be32(16), be32(20)};
}

void ExpectNear(double expected, double actual, const std::string& what) {
  if (std::isnan(expected)) {
    EXPECT_TRUE(std::isnan(actual)) << what;
  } else {
    EXPECT_NEAR(actual, expected, kRel * std::max(1.0, std::abs(expected))) << what;
  }
}

class ReportTest : public ::testing::Test {
 protected:
  void Write() {
    ReportInputs in;
    in.track = &track_;
    in.comparison = &comparison_;
    in.fit = &fit_;
    in.commands = {"dimerlab compare synthetic_drift.h5 --sim sim_drift.h5 -o report"};
    in.extra_warnings = {"extra warning from the caller"};
    WriteReport(dir_.path().string(), in);
  }
  std::string Figure(const std::string& file) const { return dir_ / ("figures/" + file); }

  testing::TempDir dir_;
  Analysis track_ = SyntheticDrift();
  Comparison comparison_ = SyntheticComparison(track_);
  FitResult fit_ = SyntheticFit();
};

TEST_F(ReportTest, EveryFigureIsAPngOfItsSizeWithItsTableAndScript) {
  Write();
  const std::vector<std::pair<std::string, int>> figures = {
      {"heights", kFigureHeightPx},       {"positions", kPanelsFigureHeightPx},
      {"slip_phase", kFigureHeightPx},    {"modes", kPanelsFigureHeightPx},
      {"sim_vs_track", kPanelsFigureHeightPx}, {"fit_profile", FitProfileHeightPx(2)}};
  for (const auto& [name, height] : figures) {
    EXPECT_TRUE(fs::exists(Figure(name + ".dat"))) << name;
    EXPECT_TRUE(fs::exists(Figure(name + ".gp"))) << name;
    const auto size = PngSize(Figure(name + ".png"));
    EXPECT_EQ(size.first, kFigureWidthPx) << name;
    EXPECT_EQ(size.second, height) << name;
    EXPECT_NE(ReadText(dir_ / "summary.md").find("](figures/" + name + ".png)"),
              std::string::npos) << name;
  }
}

TEST_F(ReportTest, TablesHoldTheNumbersDrawn) {
  Write();
  const auto slip = ReadDat(Figure("slip_phase.dat"));
  ASSERT_EQ(slip.size(), 3u);  // track, simulation, plate reference
  EXPECT_EQ(slip[0].columns, (std::vector<std::string>{"phase", "U_mm_s", "U_err_mm_s", "count"}));
  ASSERT_EQ(slip[0].rows.size(), size_t(kBins));
  for (int k = 0; k < kBins; ++k) {
    ExpectNear(track_.slip.phase[k], slip[0].rows[k][0], "phase bin");
    ExpectNear(track_.slip.profile[k] * 1e3, slip[0].rows[k][1], "slip profile");
    ExpectNear(track_.slip.profile_err[k] * 1e3, slip[0].rows[k][2], "slip error");
    ExpectNear(comparison_.sim.slip.profile[k] * 1e3, slip[1].rows[k][1], "sim slip profile");
  }
  const auto modes = ReadDat(Figure("modes.dat"));
  ASSERT_EQ(modes.size(), 2u);
  EXPECT_EQ(modes[0].columns[2], "energy_gT2");
  ASSERT_EQ(modes[0].rows.size(), size_t(kPeriods));
  for (int k = 0; k < kPeriods; ++k) {
    const PeriodRow& row = track_.periods.rows[k];
    ExpectNear(row.t_start, modes[0].rows[k][0], "period start");
    ExpectNear(row.energy_gT2, modes[0].rows[k][2], "energy per period");
    ExpectNear(row.stats.impacts[1], modes[0].rows[k][4], "right impacts");
    ExpectNear(row.complete ? 1 : 0, modes[0].rows[k][7], "complete");
  }
  ASSERT_EQ(modes[1].rows.size(), track_.periods.timeline.size());
  EXPECT_EQ(modes[1].rows[0][2], 2);  // jump, the third of ModeNames()
  EXPECT_EQ(modes[1].rows[1][2], 1);  // drift
  // heights: the first 4 periods of the settled window (periods 4..7), frame by frame.
  const auto heights = ReadDat(Figure("heights.dat"));
  ASSERT_EQ(heights[0].rows.size(), size_t(4 * kFramesPerPeriod));
  const size_t first = kPeriods / 2 * kFramesPerPeriod;
  for (size_t j = 0; j < heights[0].rows.size(); ++j) {
    ExpectNear(track_.run.Time(first + j) * 1e3, heights[0].rows[j][0], "time");
    ExpectNear(track_.run.z[1][first + j] * 1e3, heights[0].rows[j][2], "right height");
  }
  const auto fit = ReadDat(Figure("fit_profile.dat"));
  ASSERT_EQ(fit.size(), 2u);
  EXPECT_EQ(fit[1].columns[0], "mu");
  for (size_t j = 0; j < fit_.params[1].slice_x.size(); ++j)
    ExpectNear(fit_.params[1].slice_chi2[j], fit[1].rows[j][1], "chi2 slice");
  const auto sim = ReadDat(Figure("sim_vs_track.dat"));
  ASSERT_FALSE(sim[0].rows.empty());
  ExpectNear(-20, sim[0].rows[0][7], "z residual of the left tip, um");
}

// A constrained range narrower than a tenth of its bounds is drawn zoomed on it (x from a
// range's width below it to one above, the title saying so), a wider one over its bounds: eps's
// range 0.62-0.68 is 0.092 of its bounds 0.3-0.95; 0.60-0.70 is 0.15.
TEST_F(ReportTest, FitProfileZoomsOnARangeNarrowerThanATenthOfItsBounds) {
  Write();
  std::string gp = ReadText(Figure("fit_profile.gp"));
  EXPECT_NE(gp.find("set xrange [0.56:0.74]"), std::string::npos) << gp;
  EXPECT_NE(gp.find("(zoomed on the range)"), std::string::npos) << gp;
  fit_.params[0] = Param("eps", "constrained", 0.65, 0.05, 0.3, 0.95, 1 / (0.05 * 0.05));
  Write();
  gp = ReadText(Figure("fit_profile.gp"));
  EXPECT_NE(gp.find("set xrange [0.3:0.95]"), std::string::npos) << gp;
  EXPECT_EQ(gp.find("zoomed"), std::string::npos) << gp;
}

TEST_F(ReportTest, SummaryNeverPrintsAValueForAnUnconstrainedParameter) {
  Write();
  const std::string md = ReadText(dir_ / "summary.md");
  const size_t row = md.find("| mu |");
  ASSERT_NE(row, std::string::npos);
  const std::string mu_row = md.substr(row, md.find('\n', row) - row);
  EXPECT_NE(mu_row.find("unconstrained (range 0.05–0.6)"), std::string::npos) << mu_row;
  for (const char* value : {"0.123", "0.1235", "0.046", "0.0456"})
    EXPECT_EQ(md.find(value), std::string::npos) << value;
  EXPECT_NE(md.find("| eps | yes | constrained | 0.650 ± 0.030 |"), std::string::npos);
  // The other sections, from the designed numbers.
  EXPECT_NE(md.find("t = 0.1800 s: jump → drift"), std::string::npos);
  EXPECT_NE(md.find("| 50 | 3 | 0.1500 |"), std::string::npos);  // the left tip's gap
  EXPECT_NE(md.find("| 52 | left | 0.1520 | 1500 |"), std::string::npos);  // its outlier
  EXPECT_NE(md.find("synthetic warning"), std::string::npos);
  EXPECT_NE(md.find("extra warning from the caller"), std::string::npos);
  EXPECT_NE(md.find("⟨u⟩ = 5.00 ± 0.20 mm/s"), std::string::npos);
  EXPECT_NE(md.find("U after the bouncing end's impact: 12.0 ± 1.0 mm/s"), std::string::npos);
  EXPECT_NE(md.find("dimerlab compare synthetic_drift.h5"), std::string::npos);
  EXPECT_EQ(md.find("nan"), std::string::npos);
}

// Two constrained parameters: their correlation is printed (fit_correlation.h); an
// unconstrained one gets neither row nor column.
TEST_F(ReportTest, SummaryPrintsTheCorrelationsOfConstrainedParameters) {
  fit_.params.push_back(Param("mu_hat", "constrained", 0.12, 0.01, 0, 0.5, 1e4));
  fit_.correlation = {1, kNaN, -0.83, kNaN, kNaN, kNaN, -0.83, kNaN, 1};
  Write();
  const std::string md = ReadText(dir_ / "summary.md");
  EXPECT_NE(md.find("|   | eps | mu_hat |\n|---|---|---|\n| eps | +1.00 | -0.83 |\n"
                    "| mu_hat | -0.83 | +1.00 |\n"), std::string::npos) << md;
  const size_t table = md.find("Correlations of the constrained");
  ASSERT_NE(table, std::string::npos);
  EXPECT_EQ(md.find("| mu |", table), std::string::npos);
}

// A fit whose goodness fails gives no coefficient: the best point is named as failing, with the
// observables furthest off.
TEST_F(ReportTest, NoAcceptableFitGivesNoCoefficient) {
  fit_.chi2 = 640;
  fit_.p_value = 1.6e-108;
  fit_.acceptable = false;
  for (FitParameter& p : fit_.params) p.status = "no_acceptable_fit", p.err = p.range_lo = p.range_hi = kNaN;
  fit_.off = {"drift_scaled: track 0.0127 +- 0.0005, simulated -0.018 (-61.4 sigma)"};
  Write();
  const std::string md = ReadText(dir_ / "summary.md");
  EXPECT_NE(md.find("(chi2/dof 128, p-value 1.6e-108): **no acceptable fit**"), std::string::npos);
  EXPECT_NE(md.find("- drift_scaled: track 0.0127 +- 0.0005, simulated -0.018 (-61.4 sigma)"), std::string::npos);
  EXPECT_NE(md.find("| eps | yes | no_acceptable_fit | none (best point 0.65, which fails) |"), std::string::npos);
  EXPECT_EQ(md.find("0.650 ± 0.030"), std::string::npos);
  EXPECT_EQ(md.find("range is where"), std::string::npos);
}

// An acceptable fit whose floors overstated the track's scatter (compare/fit.h, kMinFloorScale)
// says by what factor they were scaled and what chi2/dof was before; one whose floors were kept
// says nothing of it.
TEST_F(ReportTest, SummarySaysWhenTheFloorsWereScaled) {
  Write();
  EXPECT_EQ(ReadText(dir_ / "summary.md").find("floors scaled"), std::string::npos);
  fit_.floor_scale = 0.41;
  fit_.chi2_per_dof_at_floors = 0.19;
  fit_.p_value_at_floors = 1;
  Write();
  const std::string md = ReadText(dir_ / "summary.md");
  EXPECT_NE(md.find("(chi2/dof 0.64, p-value 0.669), with the analysis floors scaled by 0.41: at the floors as "
                    "set chi2/dof was 0.19, so they overstate this track's scatter. A parameter's range"),
            std::string::npos)
      << md;
}

// The summary says at which scale the tracked plate's motion became metres: Γ read off an edge
// that is not in the dimer's plane is off by the ratio of the scales (track --plate-m-per-px).
TEST_F(ReportTest, SummarySaysWhichScaleThePlatesMotionWasReadAt) {
  auto row = [&]() {
    ReportInputs in;
    in.track = &track_;
    WriteReport(dir_.path().string(), in);
    const std::string md = ReadText(dir_ / "summary.md");
    const size_t at = md.find("| plate edge's scale |");
    return at == std::string::npos ? std::string() : md.substr(at, md.find('\n', at) - at);
  };
  EXPECT_EQ(row(), "") << "a track file from before the attribute: nothing claimed";
  track_.run.plate_scale_source = "none";
  track_.run.plate_motion_scale = 1;
  EXPECT_NE(row().find("the dimer plane's"), std::string::npos) << row();
  EXPECT_NE(row().find("--plate-m-per-px"), std::string::npos) << row();
  track_.run.plate_scale_source = "--plate-m-per-px";
  track_.run.plate_motion_scale = 0.9714286;
  EXPECT_NE(row().find("the edge's own (--plate-m-per-px): its motion × 0.971429"),
            std::string::npos) << row();
  track_.plate.source = "options";  // no plate tracked: no row
  EXPECT_EQ(row(), "");
}

// The drift line: an error from one settled period is unknown, not zero; outside the drift mode
// there is no bouncing end to sign the speed toward.
TEST_F(ReportTest, DriftLineStatesAnUnknownErrorAndNoBouncingEndOutsideDrift) {
  auto line = [&]() {
    ReportInputs in;
    in.track = &track_;
    WriteReport(dir_.path().string(), in);
    const std::string md = ReadText(dir_ / "summary.md");
    const size_t at = md.find("- ⟨u⟩ = ");
    return at == std::string::npos ? std::string() : md.substr(at, md.find('\n', at) - at);
  };
  EXPECT_EQ(line().find("n/a"), std::string::npos) << line();
  EXPECT_NE(line().find("positive toward the bouncing end, right"), std::string::npos) << line();
  track_.drift.periods = 1;
  track_.drift.speed_err = track_.drift.scaled_err = kNaN;  // ClassifyPeriods over one period
  EXPECT_NE(line().find("mm/s ± n/a (one period)"), std::string::npos) << line();
  EXPECT_NE(line().find("1 whole period "), std::string::npos) << line();
  track_.drift.periods = 20;
  track_.drift.bouncing_sphere = -1;
  track_.periods.settled.summary.label = "jump";
  EXPECT_EQ(line().find("bouncing end, none"), std::string::npos) << line();
  EXPECT_NE(line().find("no bouncing end in the jump mode"), std::string::npos) << line();
}

// The summary says where a track's scale came from (track's m_per_px_given), and that A_r was
// given rather than measured when the scale rests on it (track --ar).
TEST_F(ReportTest, SummarySaysWhereTheScaleCameFrom) {
  auto rows = [&]() {
    ReportInputs in;
    in.track = &track_;
    WriteReport(dir_.path().string(), in);
    const std::string md = ReadText(dir_ / "summary.md");
    const size_t at = md.find("| scale |");
    const size_t ar = md.find("| A_r (");
    return std::make_pair(
        at == std::string::npos ? std::string() : md.substr(at, md.find('\n', at) - at),
        ar == std::string::npos ? std::string() : md.substr(ar, md.find('\n', ar) - ar));
  };
  EXPECT_EQ(rows().first, "") << "a track file from before the attribute: nothing claimed";
  track_.run.m_per_px = 2e-4;
  track_.run.scale_source = "--diameter";
  EXPECT_NE(rows().first.find("0.2 mm/px, from the sphere diameter over the measured radius"),
            std::string::npos) << rows().first;
  EXPECT_NE(rows().second.find("A_r (measured)"), std::string::npos) << rows().second;
  track_.run.scale_source = "--ar";
  EXPECT_NE(rows().first.find("from the dimer's length and A_r (track --ar)"), std::string::npos)
      << rows().first;
  EXPECT_NE(rows().second.find("A_r (given to track --ar"), std::string::npos) << rows().second;
  track_.run.scale_source = "--m-per-px";
  EXPECT_NE(rows().first.find("given (track --m-per-px)"), std::string::npos) << rows().first;
}

TEST_F(ReportTest, FigureWithoutDataIsSkippedAndSaidSo) {
  track_.slip = SlipResult();  // no resting sphere
  ReportInputs in;
  in.track = &track_;
  WriteReport(dir_.path().string(), in);
  EXPECT_FALSE(fs::exists(Figure("slip_phase.png")));
  EXPECT_FALSE(fs::exists(Figure("sim_vs_track.png")));
  EXPECT_EQ(PngSize(Figure("positions.png")).first, kFigureWidthPx);  // without its slip panel
  const std::string md = ReadText(dir_ / "summary.md");
  EXPECT_NE(md.find("slip_phase: not drawn, no resting sphere"), std::string::npos);
  EXPECT_NE(md.find("slip panel omitted: no resting sphere"), std::string::npos);
}

TEST_F(ReportTest, FailingGnuplotIsAnErrorNamingTheScript) {
  std::ofstream(dir_ / "broken.gp") << "plot this_is_not_a_function(x\n";
  try {
    RunGnuplot(dir_.path().string(), "broken.gp");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.gp: gnuplot failed"), std::string::npos)
        << e.what();
  }
}

// Frames of the settled window as the camera would show them: bright discs on a grey plate.
void WriteFrames(const Analysis& a, const std::string& folder, std::vector<size_t> skip) {
  fs::create_directories(folder);
  for (size_t i = kPeriods / 2 * kFramesPerPeriod; i < a.run.n; ++i) {
    if (a.run.frame_files[i].empty() || std::find(skip.begin(), skip.end(), i) != skip.end())
      continue;
    cv::Mat img(kFrameRows, kFrameCols, CV_8UC1, cv::Scalar(60));
    for (int s = 0; s < 2; ++s) {
      const cv::Point c(int(std::lround(a.run.x[s][i] / kMPerPx)),
                        int(std::lround(kRow0Px - a.run.z[s][i] / kMPerPx)));
      cv::circle(img, c, int(std::lround(kDiameterM / 2 / kMPerPx)), cv::Scalar(200), -1);
    }
    ASSERT_TRUE(cv::imwrite(folder + "/" + a.run.frame_files[i], img));
  }
}

TEST_F(ReportTest, OverlayWritesAVideoAndStillsSkippingMissingFrames) {
  const size_t settled = kPeriods / 2 * kFramesPerPeriod;
  track_.run.frame_files[settled + 5] = "";  // not tracked
  WriteFrames(track_, dir_ / "frames", {settled + 11});  // tracked, file gone
  OverlayOptions o;
  o.frames_dir = dir_ / "frames";
  o.max_frames = 40;
  o.stills = 4;
  o.quiet = true;
  fs::create_directories(dir_ / "out");
  ::testing::internal::CaptureStderr();
  WriteOverlay(dir_ / "out", track_, &comparison_, o);
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_GT(fs::file_size(dir_ / "out/overlay.avi"), 1000u);
  EXPECT_NE(err.find("warning: overlay: 2 frames missing"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  for (int k = 0; k < o.stills; ++k) {
    const std::string path = dir_ / ("out/stills/still_" + std::to_string(k) + ".png");
    const cv::Mat still = cv::imread(path, cv::IMREAD_COLOR);
    ASSERT_FALSE(still.empty()) << path;
    EXPECT_EQ(still.cols, kFrameCols);
    EXPECT_EQ(still.rows, kFrameRows);
    // The left tip's cross is drawn in colour over the grey frame.
    const size_t i = settled + size_t(k) * kFramesPerPeriod / o.stills;
    const int row = int(std::lround(kRow0Px - track_.run.z[0][i] / kMPerPx));
    const cv::Vec3b px = still.at<cv::Vec3b>(row, int(std::lround(track_.run.x[0][i] / kMPerPx)));
    EXPECT_FALSE(px[0] == px[1] && px[1] == px[2]) << "still " << k << " has no cross";
  }
}

// A track made through `track --lens` has its centres in the undistorted frames: the overlay
// undistorts the recorded frames alike before drawing (a strong lens here: 13 px at the corners).
TEST_F(ReportTest, OverlayUndistortsTheFramesOfATrackMadeThroughALens) {
  track_.run.lens_camera = {50, 0, 31.5, 0, 50, 23.5, 0, 0, 1};
  track_.run.lens_distortion = {0.5, 0, 0, 0, 0};
  const std::string folder = dir_ / "frames";
  fs::create_directories(folder);
  cv::Mat gradient(kFrameRows, kFrameCols, CV_8UC1);
  for (int r = 0; r < kFrameRows; ++r) {
    for (int c = 0; c < kFrameCols; ++c) gradient.at<uint8_t>(r, c) = uint8_t(3 * c + r);
  }
  for (size_t i = kPeriods / 2 * kFramesPerPeriod; i < track_.run.n; ++i) {
    ASSERT_TRUE(cv::imwrite(folder + "/" + track_.run.frame_files[i], gradient));
  }
  OverlayOptions o;
  o.frames_dir = folder;
  o.max_frames = 4;
  o.stills = 1;
  o.quiet = true;
  fs::create_directories(dir_ / "out");
  WriteOverlay(dir_ / "out", track_, nullptr, o);
  const cv::Mat still = cv::imread(dir_ / "out/stills/still_0.png", cv::IMREAD_COLOR);
  ASSERT_FALSE(still.empty());
  tracking::LensCalibration lens;
  lens.camera = cv::Matx33d(50, 0, 31.5, 0, 50, 23.5, 0, 0, 1);
  lens.distortion = {0.5, 0, 0, 0, 0};
  const cv::Mat undistorted = tracking::LensUndistortion(lens, gradient.size()).Apply(gradient);
  const cv::Point corner(56, 42);  // right of the dimer, below the text: nothing is drawn there
  EXPECT_EQ(int(still.at<cv::Vec3b>(corner)[1]), int(undistorted.at<uint8_t>(corner)));
  EXPECT_GT(std::abs(int(undistorted.at<uint8_t>(corner)) - int(gradient.at<uint8_t>(corner))),
            10);
}

TEST_F(ReportTest, OverlayNeedsACalibratedTrack) {
  track_.run.m_per_px = kNaN;
  OverlayOptions o;
  o.frames_dir = dir_.path().string();
  EXPECT_THROW(WriteOverlay(dir_.path().string(), track_, nullptr, o), InputError);
}

}  // namespace
}  // namespace dimer::compare

namespace dimer::compare {
namespace {

// The overlay draws lab points at the pixels `track` read them from: SampledRun::PixelOf undoes
// docs/FORMATS.md's metres, level and along a sloping plate (x along it, z along its normal,
// turned about (col0, row0)).
TEST(TrackCalibration, PixelOfUndoesTheMetresLevelAndAlongASlopingPlate) {
  for (double slope : {0.0, 0.0087, -0.035}) {
    SampledRun r;
    r.m_per_px = 2e-4;
    r.row0_px = 250.3;
    r.plate_slope = slope;
    r.col0_px = slope == 0 ? 0.0 : 319.5;
    const double a = std::atan(slope), c = std::cos(a), s = std::sin(a);
    for (const auto& [col, row] : {std::pair{12.25, 240.5}, {319.5, 250.3}, {600.75, 180.0}}) {
      const double dc = col - r.col0_px, dr = row - r.row0_px;
      const double x = r.m_per_px * (r.col0_px + dc * c + dr * s);
      const double z = r.m_per_px * (dc * s - dr * c);
      const Eigen::Vector2d p = r.PixelOf(x, z);
      EXPECT_NEAR(p.x(), col, 1e-9) << "slope " << slope;
      EXPECT_NEAR(p.y(), row, 1e-9) << "slope " << slope;
    }
  }
}

}  // namespace
}  // namespace dimer::compare
