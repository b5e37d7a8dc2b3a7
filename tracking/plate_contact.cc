#include "tracking/plate_contact.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "common/median.h"
#include "common/parallel_for.h"

namespace dimer::tracking {
namespace {

constexpr int kSubRows = 5;  // sub-rows per pixel row for the covered fraction down a pixel

// The window's grey levels and each row's sums (fixed for every model tried).
struct Window {
  int r0 = 0, c0 = 0, rows = 0, cols = 0;
  std::vector<double> p;             // rows x cols
  std::vector<double> sy, syy;       // per row
};

struct Model {
  double col, row;
};

struct Score {
  double rss = std::numeric_limits<double>::infinity();
  double explained_below = 0;  // variance the model explains in rows wholly below the line
};

// Covered fraction of pixel [x - 1/2, x + 1/2] by the interval [a, b].
inline double Overlap(double a, double b, double x) {
  return std::max(0.0, std::min(b, x + 0.5) - std::max(a, x - 0.5));
}

// Each row's covered columns lie within the chords' span: only there is the cover non-zero,
// and the sums skip the columns outside, where every term is exactly 0 (the same bits; about a
// third of the window at a resting sphere's contact, where the chords are short).
Score Evaluate(const Window& w, const Model& m, double radius, std::vector<double>* cover) {
  cover->assign(size_t(w.rows) * size_t(w.cols), 0.0);
  std::vector<int> lo(size_t(w.rows), w.cols), hi(size_t(w.rows), -1);
  for (int i = 0; i < w.rows; ++i) {
    const double y = w.r0 + i;
    for (int s = 0; s < kSubRows; ++s) {
      const double ys = y - 0.5 + (s + 0.5) / kSubRows;
      // Above the line: the sphere resting on it, centre R above; below: its mirror image.
      const double centre = ys < m.row ? m.row - radius : m.row + radius;
      const double dy = ys - centre;
      if (std::abs(dy) >= radius) continue;
      const double half = std::sqrt(radius * radius - dy * dy);
      const double a = m.col - half, b = m.col + half;
      const int j0 = std::max(0, int(std::floor(a - 0.5 - w.c0)));
      const int j1 = std::min(w.cols - 1, int(std::ceil(b + 0.5 - w.c0)));
      lo[size_t(i)] = std::min(lo[size_t(i)], j0);
      hi[size_t(i)] = std::max(hi[size_t(i)], j1);
      double* c = cover->data() + size_t(i) * size_t(w.cols);
      // Columns wholly inside the chord are covered by exactly 1 (Overlap's own value there).
      int in0 = std::max(j0, int(std::ceil(a + 0.5 - w.c0)));
      int in1 = std::min(j1, int(std::floor(b - 0.5 - w.c0)));
      while (in0 <= in1 && w.c0 + in0 - 0.5 < a) ++in0;  // the rounding of a + 0.5 - c0
      while (in1 >= in0 && w.c0 + in1 + 0.5 > b) --in1;
      if (in0 > in1) {
        for (int j = j0; j <= j1; ++j) c[j] += Overlap(a, b, w.c0 + j) / kSubRows;
        continue;
      }
      for (int j = j0; j < in0; ++j) c[j] += Overlap(a, b, w.c0 + j) / kSubRows;
      for (int j = in0; j <= in1; ++j) c[j] += 1.0 / kSubRows;
      for (int j = in1 + 1; j <= j1; ++j) c[j] += Overlap(a, b, w.c0 + j) / kSubRows;
    }
  }
  Score out;
  out.rss = 0;
  const double n = w.cols;
  for (int i = 0; i < w.rows; ++i) {
    const double* c = cover->data() + size_t(i) * size_t(w.cols);
    const double* p = w.p.data() + size_t(i) * size_t(w.cols);
    double sx = 0, sxx = 0, sxy = 0;
    for (int j = lo[size_t(i)]; j <= hi[size_t(i)]; ++j) {
      sx += c[j];
      sxx += c[j] * c[j];
      sxy += c[j] * p[j];
    }
    const double var_y = w.syy[i] - w.sy[i] * w.sy[i] / n;
    const double var_x = sxx - sx * sx / n;
    const double cov = sxy - sx * w.sy[i] / n;
    // Each row its own levels inside and outside (a straight line in the covered fraction).
    const double explained = var_x > 1e-9 ? cov * cov / var_x : 0.0;
    out.rss += var_y - explained;
    if (w.r0 + i - 0.5 >= m.row) out.explained_below += explained;
  }
  return out;
}

}  // namespace

MirroredContact FitMirroredContact(const cv::Mat& frame, double col_guess, double radius_px,
                                   double plate_row) {
  MirroredContact out;
  if (!std::isfinite(col_guess) || !std::isfinite(plate_row) || !(radius_px > 2)) return out;
  Window w;
  const int half = int(std::ceil(std::min(20.0, 0.85 * radius_px)));
  w.r0 = int(std::floor(plate_row)) - kContactAbovePx;
  w.c0 = int(std::lround(col_guess)) - half;
  w.rows = kContactAbovePx + kContactBelowPx + 1;
  w.cols = 2 * half + 1;
  if (w.r0 < 0 || w.c0 < 0 || w.r0 + w.rows > frame.rows || w.c0 + w.cols > frame.cols) return out;
  w.p.resize(size_t(w.rows) * size_t(w.cols));
  w.sy.assign(w.rows, 0.0);
  w.syy.assign(w.rows, 0.0);
  for (int i = 0; i < w.rows; ++i) {
    for (int j = 0; j < w.cols; ++j) {
      const double v = frame.depth() == CV_8U ? frame.at<uint8_t>(w.r0 + i, w.c0 + j)
                                              : frame.at<uint16_t>(w.r0 + i, w.c0 + j);
      w.p[size_t(i) * size_t(w.cols) + size_t(j)] = v;
      w.sy[i] += v;
      w.syy[i] += v * v;
    }
  }
  std::vector<double> cover;
  Model best{col_guess, plate_row};
  Score best_score;
  // A grid about the current best (deterministic; the residual has local minima where the
  // plate's own edges cross the window, which a descent could settle in).
  auto search = [&](double col0, double col1, double dcol, double row0, double row1, double drow) {
    const Model centre = best;
    for (double col = col0; col <= col1 + 1e-9; col += dcol) {
      for (double row = row0; row <= row1 + 1e-9; row += drow) {
        const Model m{centre.col + col, centre.row + row};
        const Score s = Evaluate(w, m, radius_px, &cover);
        if (s.rss < best_score.rss) best_score = s, best = m;
      }
    }
  };
  // Coarse over the whole range, then fine about the best.
  search(-kContactColSearchPx, kContactColSearchPx, 0.5, -1.0, kContactSearchBelowPx, 0.25);
  search(-0.5, 0.5, 0.125, -0.25, 0.25, 0.025);
  // Between grid rows: the parabola through the residuals at the best row and a step each side.
  const double step = 0.025;
  const double lo = Evaluate(w, {best.col, best.row - step}, radius_px, &cover).rss;
  const double hi = Evaluate(w, {best.col, best.row + step}, radius_px, &cover).rss;
  const double curve = lo + hi - 2 * best_score.rss;
  if (curve > 0) best.row += std::clamp(0.5 * step * (lo - hi) / curve, -step, step);
  // Noise from the fit: each row spends two parameters on its levels, the model two.
  const double dof = double(w.rows) * (w.cols - 2) - 2;
  const double sigma2 = best_score.rss / dof;
  if (!(sigma2 > 0)) return out;
  out.row = best.row;
  out.col = best.col;
  out.reflection_chi2 = best_score.explained_below / sigma2;
  // At the edge of the search: what was found is not a sphere resting near the edge.
  out.ok = best.row < plate_row + kContactSearchBelowPx - 0.25 && best.row > plate_row - 0.75 &&
           std::abs(best.col - col_guess) < kContactColSearchPx - 0.25;
  return out;
}

namespace {

// The contact line less the edge (d) and the edge, of every fit with a mirror image among the
// samples order[from..to), appended in that order. Each sample's two fits on its own: any
// thread count gives the same list.
void ContactShifts(const std::vector<LearningSample>& samples, const std::vector<size_t>& order,
                   size_t from, size_t to, double radius_px, int threads, std::vector<double>* d,
                   std::vector<double>* edges) {
  std::vector<std::array<double, 2>> fits(to - from, {NAN, NAN});
  ParallelFor(to - from, threads, [&](size_t j) {
    const LearningSample& s = samples[order[from + j]];
    if (!std::isfinite(s.plate_row)) return;
    for (int k = 0; k < 2; ++k) {
      if (!s.found[k]) continue;
      const double plate = s.PlateRowAt(s.centre[k].x());
      const MirroredContact c = FitMirroredContact(s.image, s.centre[k].x(), radius_px, plate);
      if (c.ok && c.reflection_chi2 >= kMinReflectionChi2) fits[j][k] = c.row - plate;
    }
  });
  for (size_t j = 0; j < fits.size(); ++j) {
    for (int k = 0; k < 2; ++k) {
      if (!std::isfinite(fits[j][k])) continue;
      d->push_back(fits[j][k]);
      edges->push_back(samples[order[from + j]].plate_row);
    }
  }
}

}  // namespace

PlateShift EstimatePlateShift(const std::vector<LearningSample>& samples, double radius_px,
                              int threads) {
  PlateShift out;
  // A probe first, every stride-th sample (spread over the sequence), then the rest only where
  // the probe sees a plate to move: each fit costs ~2 ms, and footage whose plate edge is the
  // contact line (most) should not pay for 96 of them. The median does not depend on the order,
  // so a sequence that goes on gets the same answer as from all samples at once.
  const size_t stride = std::max<size_t>(1, samples.size() / kProbeSamples);
  std::vector<size_t> order;
  for (size_t i = 0; i < samples.size(); i += stride) order.push_back(i);
  const size_t probe = order.size();
  for (size_t i = 0; i < samples.size(); ++i) {
    if (i % stride != 0) order.push_back(i);
  }
  std::vector<double> d, edges;
  ContactShifts(samples, order, 0, probe, radius_px, threads, &d, &edges);
  bool probe_only = false;
  if (probe < order.size()) {
    probe_only = d.size() < kMinContactFits ||
                 std::abs(MedianOf(d)) < kProbeShiftFraction * kMinPlateShiftPx;
    if (!probe_only) {
      ContactShifts(samples, order, probe, order.size(), radius_px, threads, &d, &edges);
    }
  }
  out.fits = d.size();
  if (d.size() < kMinContactFits) {
    out.reason = "the plate shows no mirror image of the spheres: its edge is the contact line";
    return out;
  }
  out.value = MedianOf(d);
  out.edge_ref = MedianOf(edges);
  std::vector<double> dev;
  for (double v : d) dev.push_back(std::abs(v - out.value));
  // Standard error of a median: 1.2533 sigma / sqrt(n), sigma = 1.4826 MAD.
  out.err = 1.2533 * 1.4826 * MedianOf(dev) / std::sqrt(double(d.size()));
  // kMinPlateShiftPx: a fit on a plate that mirrors nothing can still find some contrast below
  // the line (a shadow, the plate's own band): +0.10 and +0.15 px on the POV-Ray
  // bright-background and backlit footage, where the edge is right to 0.04 px.
  out.applied = std::abs(out.value) >= kMinPlateShiftPx &&
                std::abs(out.value) >= kPlateShiftSigmas * out.err;
  char text[320];
  if (out.applied) {
    std::snprintf(text, sizeof text,
                  "the spheres' mirror images put the contact line %+.2f +- %.2f px from the "
                  "plate's visible edge (%zu sphere-frames): the plate row is moved there (its "
                  "top surface is in view)",
                  out.value, out.err, d.size());
  } else {
    std::snprintf(text, sizeof text,
                  "the sphere-and-image fits put the contact line %+.2f +- %.2f px from the "
                  "plate's edge (%zu sphere-frames): the edge is kept (a shift under %.1f px or "
                  "%.0f standard errors is not taken)",
                  out.value, out.err, d.size(), kMinPlateShiftPx, kPlateShiftSigmas);
  }
  out.reason = text;
  if (probe_only) out.reason += " (from a probe of " + std::to_string(probe) + " sample frames)";
  return out;
}

namespace {

// The first band's allowance for the scale itself: (scale - 1) x the edge's range, 0.15 x 2 px
// on the POV-Ray mirror plate.
constexpr double kScaleSpreadAllowancePx = 0.3;

// Least squares row = a + b edge over `use`.
RestingLine FitLine(const std::vector<double>& edge, const std::vector<double>& row,
                    const std::vector<uint8_t>& use) {
  RestingLine l;
  double se = 0, sr = 0;
  for (size_t i = 0; i < edge.size(); ++i) {
    if (use[i]) se += edge[i], sr += row[i], ++l.n;
  }
  if (l.n < 3) return l;
  const double me = se / double(l.n), mr = sr / double(l.n);
  double see = 0, ser = 0;
  for (size_t i = 0; i < edge.size(); ++i) {
    if (!use[i]) continue;
    see += (edge[i] - me) * (edge[i] - me);
    ser += (edge[i] - me) * (row[i] - mr);
  }
  if (!(see > 0)) return l;
  l.b = ser / see;
  l.a = mr - l.b * me;
  double rss = 0;
  for (size_t i = 0; i < edge.size(); ++i) {
    if (use[i]) rss += std::pow(row[i] - l.a - l.b * edge[i], 2);
  }
  l.b_err = std::sqrt(rss / double(l.n - 2) / see);
  l.edge_sd = std::sqrt(see / double(l.n));
  return l;
}

}  // namespace

RestingLine FitRestingLine(const std::vector<double>& edge, const std::vector<double>& row,
                           std::vector<uint8_t>* resting) {
  RestingLine l;
  if (row.size() != edge.size()) return l;
  std::vector<uint8_t> valid(edge.size(), 0), use(edge.size(), 0);
  std::vector<double> gap;  // edge - row: smallest where the sphere rests (its row largest)
  for (size_t i = 0; i < edge.size(); ++i) {
    valid[i] = std::isfinite(edge[i]) && std::isfinite(row[i]);
    if (valid[i]) gap.push_back(edge[i] - row[i]);
  }
  if (gap.size() < 3) return l;
  // Lower envelope first: within a band of its 5th percentile (not its minimum: one noisy
  // frame) wide enough for the scale's own spread over the edge's range.
  std::sort(gap.begin(), gap.end());
  const double low = gap[gap.size() / 20];
  for (size_t i = 0; i < edge.size(); ++i) {
    use[i] = valid[i] && edge[i] - row[i] <= low + kRestBandPx + kScaleSpreadAllowancePx;
  }
  l = FitLine(edge, row, use);
  // Then the frames near the line (twice: the first line may lean on a few flight frames).
  for (int pass = 0; pass < 2 && l.n >= 3; ++pass) {
    for (size_t i = 0; i < edge.size(); ++i) {
      use[i] = valid[i] && row[i] >= l.a + l.b * edge[i] - kRestBandPx;
    }
    l = FitLine(edge, row, use);
  }
  l.valid = gap.size();
  if (resting) *resting = use;
  return l;
}

PlateMotionScale FitPlateMotionScale(const std::vector<double>& edge,
                                     const std::array<std::vector<double>, 2>& rows,
                                     const PlateShift& shift) {
  PlateMotionScale best;
  for (int k = 0; k < 2; ++k) {
    const RestingLine l = FitRestingLine(edge, rows[k]);
    if (l.valid < kMinScaleFrames || l.n < kMinScaleFrames || l.edge_sd < kMinScaleSpreadPx ||
        !std::isfinite(l.b_err)) {
      continue;
    }
    if (l.n > best.frames) {
      best.fitted = true;
      best.scale = l.b;
      best.err = l.b_err;
      best.frames = l.n;
      best.sphere = k;
    }
  }
  best.edge_ref = shift.edge_ref;
  return best;
}

PlateMotionScale GivenPlateMotionScale(double scale, const std::vector<double>& edge,
                                       const PlateShift& shift) {
  PlateMotionScale m;
  m.given = true;
  m.scale = scale;
  m.err = 0;
  if (shift.applied) {
    m.edge_ref = shift.edge_ref;
  } else {
    std::vector<double> found;
    for (double e : edge) {
      if (std::isfinite(e)) found.push_back(e);
    }
    m.edge_ref = found.empty() ? 0.0 : MedianOf(found);
  }
  return m;
}

}  // namespace dimer::tracking
