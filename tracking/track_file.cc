#include "tracking/track_file.h"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <utility>
#include <vector>

#include "common/h5_file.h"
#include "common/provenance.h"
#include "common/trajectory_io.h"

namespace dimer::tracking {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// TIME64 (seconds since 1970 and 2^-32 s fractions) as ISO 8601 UTC with nanoseconds.
std::string TriggerTimeText(int64_t seconds, int64_t fraction) {
  const std::time_t t = static_cast<std::time_t>(seconds);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char day[32];
  std::strftime(day, sizeof day, "%Y-%m-%dT%H:%M:%S", &tm);
  const long long ns = (static_cast<long long>(fraction) * 1000000000LL) >> 32;
  char out[64];
  std::snprintf(out, sizeof out, "%s.%09lldZ", day, ns);
  return out;
}

// How precisely each sphere was followed, beside the footage's bound (track_precision.h).
void WritePrecisionGroup(H5Writer& w, const SequenceResult& r) {
  std::vector<double> scatter, bound;
  std::vector<int64_t> followed, poor;
  for (int k = 0; k < 2; ++k) {
    const SpherePrecision& p = r.precision[k];
    scatter.insert(scatter.end(), {p.measured.x(), p.measured.y()});
    bound.insert(bound.end(), {p.bound.x(), p.bound.y()});
    followed.push_back(p.followed);
    poor.push_back(p.poor);
  }
  w.WriteDoubles("/precision/scatter", scatter, {2, 2}, "px", "col,row");
  w.SetAttr("/precision/scatter", "rows", "left,right");
  w.SetAttr("/precision/scatter", "description",
            "each sphere's centres' scatter from frame to frame: the median absolute second "
            "difference / 0.6745 / sqrt(6) (NaN: fewer than 3 consecutive found frames)");
  w.WriteDoubles("/precision/bound", bound, {2, 2}, "px", "col,row");
  w.SetAttr("/precision/bound", "rows", "left,right");
  w.SetAttr("/precision/bound", "description",
            "Cramer-Rao bound on placing each sphere's learnt appearance in the first frame's "
            "noise (template method; NaN otherwise)");
  w.SetAttr("/precision/bound", "frame_noise", r.frame_noise);
  w.SetAttr("/precision/bound", "frame_noise_units", "grey levels");
  w.WriteInt64("/precision/followed", followed, {2});
  w.SetAttr("/precision/followed", "codes", "0=not followed as the footage allows,1=followed");
  w.SetAttr("/precision/followed", "rows", "left,right");
  char text[160];
  std::snprintf(text, sizeof text,
                "whether each sphere was followed as the footage allows: not where its scatter "
                "is above %g times the bound and %g px",
                kNotFollowedFactor, kNotFollowedMinPx);
  w.SetAttr("/precision/followed", "description", text);
  w.WriteInt64("/precision/poor_footage", poor, {2});
  std::snprintf(text, sizeof text, "0=no,1=the bound is above %g px", kPoorFootageBoundPx);
  w.SetAttr("/precision/poor_footage", "codes", text);
  w.SetAttr("/precision/poor_footage", "rows", "left,right");
  w.SetAttr("/precision/poor_footage", "description",
            "whether the footage shows each sphere with too little contrast for sub-pixel work");
}

// The template method's learnt appearances and offsets (docs/FORMATS.md).
// auto's trial (method_trial.h): one row per candidate, the template (or, on clean
// silhouettes, the centroid) first.
void WriteMethodTrial(H5Writer& w, const SequenceResult& r) {
  if (r.method_trial.empty()) return;
  std::vector<double> v;
  std::string rows;
  for (const TrialScores& t : r.method_trial) {
    v.insert(v.end(), {double(t.frames), double(t.both_found), t.smooth_px, t.length_px, t.score});
    rows += (rows.empty() ? "" : ",") + ToString(t.method);
  }
  w.WriteDoubles("/method_trial", v, {r.method_trial.size(), 5}, "px (frames: counts)",
                 "frames,both_found,smooth_px,length_px,score");
  w.SetAttr("/method_trial", "rows", rows);
  w.SetAttr("/method_trial", "description",
            "--method auto: each candidate followed over the film's first consecutive frames; "
            "smooth_px is each centre's noise from its third differences, length_px the "
            "dimer's length's, score the larger of smooth_px and length_px / sqrt(2) (NaN: "
            "both spheres found in under 90 % of the frames); the centroid replaces the template "
            "only at half its score or less, or where the template has none; on clean "
            "silhouettes discfit replaces the centroid at 0.9 of its score or less");
}

void WriteTemplateGroup(H5Writer& w, const SequenceResult& r) {
  std::vector<double> offset, err;
  std::vector<int64_t> frames;
  std::vector<std::string> sources;
  for (int k = 0; k < 2; ++k) {
    for (const OffsetEstimate* e : {&r.offsets.col[k], &r.offsets.row[k]}) {
      offset.push_back(e->value);
      err.push_back(e->err);
      frames.push_back(int64_t(e->n));
      sources.push_back(e->source);
    }
  }
  w.WriteDoubles("/template/offset", offset, {2, 2}, "px", "col,row");
  w.SetAttr("/template/offset", "rows", "left,right");
  w.SetAttr("/template/offset", "description",
            "offset from each learnt appearance's reference point to the sphere centre, added to "
            "every located position (already applied to /pixels)");
  // NaN (no row carried over) is written as such: the attribute is always there.
  w.SetAttr("/template/offset", "appearance_mismatch", r.offsets.appearance_mismatch);
  w.WriteDoubles("/template/offset_err", err, {2, 2}, "px", "col,row");
  w.SetAttr("/template/offset_err", "description", "standard uncertainty of /template/offset");
  w.WriteInt64("/template/offset_frames", frames, {2, 2});
  w.SetAttr("/template/offset_frames", "units", "1");
  w.SetAttr("/template/offset_frames", "columns", "col,row");
  w.SetAttr("/template/offset_frames", "description", "frames each offset rests on");
  w.WriteStrings("/template/offset_source", sources);
  w.SetAttr("/template/offset_source", "description",
            "left col, left row, right col, right row: silhouette, plate_contact, "
            "plate_contact_impacts, plate_contact_bounces, "
            "plate_contact_of_other(_outline|_both), limb, "
            "symmetry(_and_whole_outline) or none");
  for (int k = 0; k < 2; ++k) {
    const Appearance& a = r.appearance[k];
    std::vector<double> img(a.image.begin<float>(), a.image.end<float>());
    std::vector<uint8_t> mask(a.mask.begin<uint8_t>(), a.mask.end<uint8_t>());
    const std::string name = std::string("/template/") + (k == 0 ? "left" : "right");
    const size_t size = size_t(a.image.rows);
    std::string columns;  // each column's offset from the reference column, px
    for (int x = -a.half; x <= a.half; ++x) columns += (columns.empty() ? "" : ",") + std::to_string(x);
    w.WriteDoubles(name, img, {size, size}, "grey levels", columns);
    w.SetAttr(name, "description",
              "the learnt appearance, reference point at the centre pixel; frame grey levels");
    w.WriteUint8(name + "_mask", mask, {size, size});
    w.SetAttr(name + "_mask", "columns", columns);
    w.SetAttr(name + "_mask", "codes", "0=not part of the sphere's appearance (rod, plate, unseen),1=used");
    w.SetAttr(name + "_mask", "description", "which pixels of the learnt appearance are used");
  }
}

// One row per tracked frame: the trajectory in metres and the pixel columns beside it.
struct TrackColumns {
  Trajectory traj;
  std::vector<double> px[2], plate_row;
  std::vector<double> cut_err[2];  // a cut sphere's stated uncertainty (col, row), NaN elsewhere
  std::vector<int64_t> index;
  std::vector<uint8_t> found;
};

// t: each frame's own time stamp when the source has them (Recording's frame_times), else
// frame_index / fps.
TrackColumns ColumnsOf(const SequenceResult& r, const Calibration& cal, double fps,
                       const std::vector<double>& times) {
  const size_t n = r.frames.size();
  TrackColumns out;
  Trajectory& traj = out.traj;
  traj.Reserve(n);
  std::vector<double>* px = out.px;
  std::vector<double>& plate_row = out.plate_row;
  std::vector<int64_t>& index = out.index;
  std::vector<uint8_t>& found = out.found;
  plate_row.resize(n);
  index.resize(n);
  found.resize(2 * n);
  for (size_t i = 0; i < n; ++i) {
    const FrameTrack& f = r.frames[i];
    Eigen::Vector2d tip[2];
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d c = f.found[k] ? f.centre[k] : Eigen::Vector2d(kNaN, kNaN);
      px[k].push_back(c.x());
      px[k].push_back(c.y());
      tip[k] = cal.ToMetres(c);
      found[2 * i + k] = f.found[k] ? (f.cut[k] ? 2 : 1) : 0;
      // A cut sphere's own uncertainty with its appearance's offset's, which it shares with
      // every frame of the film (the silhouette methods' cut spheres state theirs in sigma_px).
      Eigen::Vector2d err = Eigen::Vector2d::Constant(kNaN);
      if (f.found[k] && f.cut[k]) {
        const int a = f.appearance[k];
        const Eigen::Vector2d off = r.method == Method::kTemplate
                                        ? Eigen::Vector2d(r.offsets.col[a].err, r.offsets.row[a].err)
                                        : Eigen::Vector2d(0, 0);
        err = (f.sigma_px[k].cwiseProduct(f.sigma_px[k]) + off.cwiseProduct(off)).cwiseSqrt();
      }
      out.cut_err[k].push_back(err.x());
      out.cut_err[k].push_back(err.y());
    }
    const Eigen::Vector2d axis = tip[1] - tip[0];
    // The plate under the dimer: midway between the spheres (where it was read if one is lost).
    const double plate_col = f.found[0] && f.found[1] ? 0.5 * (f.centre[0].x() + f.centre[1].x())
                                                      : f.plate_col;
    plate_row[i] = f.PlateRowAt(plate_col);
    const double t = f.index < times.size() ? times[f.index] : double(f.index) / fps;
    traj.Append(t, tip[0], tip[1],
                cal.ToMetres({plate_col, plate_row[i]}).y(), std::atan2(axis.y(), axis.x()));
    index[i] = int64_t(f.index);
  }
  return out;
}

// What the recording itself says (a video's codec, a .cine header's values), the lens and a
// camera's levels: root attributes after the stages' own.
void RecordingAttributes(const SequenceResult& r, const Recording& rec, AttrList* attrs_out,
                         AttrUnits* units_out) {
  AttrList& attrs = *attrs_out;
  AttrUnits& units = *units_out;
  if (!rec.info.video_codec.empty()) {  // a video file's codec, as its container declares it
    attrs.push_back({"video_codec", rec.info.video_codec});
    attrs.push_back({"video_codec_lossless", int64_t{LosslessVideoCodec(rec.info.video_codec)}});
    units["video_codec_lossless"] = "1";
  }
  attrs.push_back({"lens", r.lens ? r.lens->path : std::string()});
  attrs.push_back({"lens_max_shift_px", r.lens_max_shift_px});
  units["lens_max_shift_px"] = "px";
  attrs.push_back({"level_scale", r.level_scale.factor});
  attrs.push_back({"level_scale_bits", int64_t(r.level_scale.bits)});
  attrs.push_back({"level_scale_clipped_frames", int64_t(r.level_scale.clipped_frames)});
  units["level_scale"] = "1";
  units["level_scale_bits"] = "bit";
  units["level_scale_clipped_frames"] = "1";
  if (rec.info.known) {  // the .cine header's values, exactly as stored
    attrs.push_back({"exposure_ns", rec.info.exposure_ns});
    attrs.push_back({"trigger_time", TriggerTimeText(rec.info.trigger_seconds,
                                                     rec.info.trigger_fraction)});
    attrs.push_back({"trigger_time_seconds", rec.info.trigger_seconds});
    attrs.push_back({"trigger_time_fraction", rec.info.trigger_fraction});
    attrs.push_back({"first_image_no", rec.info.first_image_no});
    attrs.push_back({"real_bpp", int64_t(rec.info.real_bpp)});
    attrs.push_back({"cine_colour", rec.info.colour});
    attrs.push_back({"cine_cfa", rec.info.cfa});
    attrs.push_back({"cine_mosaic_balance", rec.info.mosaic_balance});
    attrs.push_back({"cine_flip_v", int64_t{rec.info.flip_v}});
    attrs.push_back({"cine_header_fps", rec.info.fps});
    units["cine_flip_v"] = "1";
    units["cine_header_fps"] = "1/s";
    units["exposure_ns"] = "ns";
    units["trigger_time_seconds"] = "s";
    units["trigger_time_fraction"] = "2^-32 s";
    units["first_image_no"] = "1";
    units["real_bpp"] = "bit";
    units["cine_cfa"] = "1";
  }
}

// The calibration's attributes and the film's counts: the last root attributes.
AttrList CalibrationAttributes(const TrackArgs& args, const SequenceResult& r,
                               const Calibration& cal) {
  const size_t n = r.frames.size();
  return {
      {"m_per_px", cal.m_per_px}, {"row0", cal.row0}, {"col0", cal.col0},
      {"diameter", args.diameter},
      {"polarity", std::string(r.polarity > 0 ? "bright" : "dark")},
      {"polarity_requested", ToString(args.polarity)},
      {"m_per_px_given",
       int64_t(args.m_per_px ? 1 : args.ar ? 2 : 0)},
      {"ar", args.ar.value_or(0.0)},
      {"ar_length_px", std::isfinite(cal.length_px) ? cal.length_px : 0.0},
      {"ar_length_frames", int64_t(cal.length_frames)},
      {"ar_radius_px", cal.length_scale.ok ? cal.length_scale.radius_px : 0.0},
      {"ar_outline_radius_px", std::isfinite(cal.length_scale.outline_radius_px)
                                   ? cal.length_scale.outline_radius_px
                                   : 0.0},
      {"ar_passes", int64_t(cal.length_scale.passes.size())},
      {"ar_converged", int64_t(cal.length_scale.converged)},
      {"chunk_frames", int64_t(args.sequence.chunk_frames)},
      {"width", int64_t(r.width)}, {"height", int64_t(r.height)},
      {"frames_tracked", int64_t(n)}, {"frames_skipped", int64_t(r.skipped.size())},
      {"complete", int64_t(r.complete)}};
}

struct RootAttrs {
  AttrList attrs;
  AttrUnits units;
};

// The root attributes (docs/FORMATS.md): every parameter that made the file and what each
// stage found, with their units.
// A sphere's resting rows on the plate's (plate_agreement.h) and its error; 0 where too few
// resting frames decided nothing (rest_slope_frames says how many there were).
std::pair<double, double> RestSlope(const PlateAgreement& a) {
  if (!std::isfinite(a.slope) || !std::isfinite(a.slope_err)) return {0.0, 0.0};
  return {a.slope, a.slope_err};
}

RootAttrs RootAttributes(const TrackArgs& args, const SequenceResult& r, const Calibration& cal,
                         const Recording& rec) {
  const bool clip_found = r.plate_clip.level.found();
  AttrList attrs = {{"source", args.input}, {"frames", args.frames.empty() ? "all" : args.frames},
                    {"method", ToString(r.method)}, {"method_requested", ToString(args.method)},
                    {"method_reason", r.method_reason}, {"fps", *args.fps},
                    {"fps_source", rec.fps_from},
                    {"plate_shift", r.plate_shift.applied ? r.plate_shift.value : 0.0},
                    {"plate_shift_err", r.plate_shift.applied ? r.plate_shift.err : 0.0},
                    {"plate_shift_reason", r.plate_shift.reason},
                    {"plate_shift_edge_ref",
                     r.plate_shift.applied || r.plate_scale.given ? r.plate_scale.edge_ref : 0.0},
                    {"plate_motion_scale", r.plate_scale.scale},
                    {"plate_motion_scale_err", r.plate_scale.fitted ? r.plate_scale.err : 0.0},
                    {"plate_motion_scale_source",
                     std::string(r.plate_scale.given    ? "--plate-m-per-px"
                                 : r.plate_scale.fitted ? "fitted"
                                                        : "none")},
                    {"plate_m_per_px", args.plate_m_per_px.value_or(0.0)},
                    {"plate_clipped_frames", int64_t(r.plate_clip.frames)},
                    {"plate_clip_level", clip_found ? r.plate_clip.level.value : 0.0},
                    {"plate_clip_level_err", clip_found ? r.plate_clip.level.err : 0.0},
                    {"plate_clip_refitted", int64_t(r.plate_clip.refitted)},
                    {"plate_psf_sigma", clip_found ? r.plate_clip.level.psf_sigma
                                                   : args.sequence.follower.psf_sigma_px},
                    {"plate_psf_sigma_source", PsfSource(args, r.plate_clip)},
                    {"plate_slope", r.plate_slope.value},
                    {"plate_slope_measured", r.plate_slope.measured},
                    {"plate_slope_err", r.plate_slope.err},
                    {"plate_slope_reason", r.plate_slope.reason},
                    {"stuck_pixels", int64_t(r.defects.at.size())},
                    {"stuck_pixels_frames", int64_t(r.defects.frames)},
                    {"stuck_pixels_reason", r.defects.reason},
                    {"matches_dropped_score_left", int64_t(r.scores.dropped[0])},
                    {"matches_dropped_score_right", int64_t(r.scores.dropped[1])},
                    {"matches_dropped_length_left", int64_t(r.scores.dropped_length[0])},
                    {"matches_dropped_length_right", int64_t(r.scores.dropped_length[1])},
                    {"learnt_again_left", int64_t(r.relearnt[0])},
                    {"learnt_again_right", int64_t(r.relearnt[1])},
                    {"rest_slope_left", RestSlope(r.plate_agreement[0]).first},
                    {"rest_slope_err_left", RestSlope(r.plate_agreement[0]).second},
                    {"rest_slope_frames_left", int64_t(r.plate_agreement[0].frames)},
                    {"rest_slope_right", RestSlope(r.plate_agreement[1]).first},
                    {"rest_slope_err_right", RestSlope(r.plate_agreement[1]).second},
                    {"rest_slope_frames_right", int64_t(r.plate_agreement[1].frames)},
                    {"dimer_length_px", r.scores.length_px},
                    {"dimer_length_noise_px", r.length.noise_px},
                    {"dimer_length_tolerance_px", r.length.tolerance_px},
                    {"dimer_length_departing_frames", int64_t(r.length.departing)},
                    {"dimer_length_worst_px", r.length.worst_px}};
  AttrUnits units = {{"fps", "1/s"}, {"plate_shift", "px"}, {"plate_shift_err", "px"},
                     {"plate_shift_edge_ref", "px"}, {"plate_motion_scale", "1"},
                     {"plate_motion_scale_err", "1"}, {"plate_m_per_px", "m/px"},
                     {"plate_clipped_frames", "1"},
                     {"plate_clip_level", "grey levels"}, {"plate_clip_level_err", "grey levels"},
                     {"plate_clip_refitted", "1"}, {"plate_psf_sigma", "px"},
                     {"plate_slope", "px/px"}, {"plate_slope_measured", "px/px"},
                     {"plate_slope_err", "px/px"}, {"stuck_pixels", "1"},
                     {"stuck_pixels_frames", "1"}, {"matches_dropped_score_left", "1"},
                     {"matches_dropped_score_right", "1"}, {"matches_dropped_length_left", "1"},
                     {"matches_dropped_length_right", "1"}, {"learnt_again_left", "1"},
                     {"learnt_again_right", "1"}, {"rest_slope_left", "px/px"},
                     {"rest_slope_err_left", "px/px"}, {"rest_slope_frames_left", "1"},
                     {"rest_slope_right", "px/px"}, {"rest_slope_err_right", "px/px"},
                     {"rest_slope_frames_right", "1"}, {"dimer_length_px", "px"},
                     {"dimer_length_noise_px", "px"}, {"dimer_length_tolerance_px", "px"},
                     {"dimer_length_departing_frames", "1"}, {"dimer_length_worst_px", "px"},
                     {"m_per_px", "m/px"}, {"row0", "px"}, {"col0", "px"}, {"ar", "1"},
                     {"ar_length_px", "px"}, {"ar_length_frames", "1"}, {"ar_radius_px", "px"},
                     {"ar_outline_radius_px", "px"},
                     {"ar_passes", "1"}, {"ar_converged", "1"},
                     {"diameter", "m"},
                     {"chunk_frames", "1"}, {"width", "px"}, {"height", "px"},
                     {"frames_tracked", "1"}, {"frames_skipped", "1"}};
  RecordingAttributes(r, rec, &attrs, &units);
  const AttrList rest = CalibrationAttributes(args, r, cal);
  attrs.insert(attrs.end(), rest.begin(), rest.end());
  return {std::move(attrs), std::move(units)};
}

// The datasets: trajectory, pixels, frames, found, the template's appearances, precision,
// stuck pixels, the lens and the skipped frames.
void WriteColumns(H5Writer& w, const TrackColumns& columns, const SequenceResult& r) {
  const size_t n = r.frames.size();
  const Trajectory& traj = columns.traj;
  const std::vector<double>* px = columns.px;
  const std::vector<double>& plate_row = columns.plate_row;
  const std::vector<int64_t>& index = columns.index;
  const std::vector<uint8_t>& found = columns.found;
  std::vector<std::string> skipped_names, skipped_reasons;
  for (const auto& s : r.skipped) {
    skipped_names.push_back(s.name);
    skipped_reasons.push_back(s.reason);
  }
  WriteTrajectory(w, traj);
  w.WriteDoubles("/pixels/left", px[0], {n, 2}, "px", "col,row");
  w.SetAttr("/pixels/left", "description",
            "sub-pixel centre of the left sphere: 0-based column and row of pixel centres, rows "
            "growing downward; NaN where not found");
  w.WriteDoubles("/pixels/right", px[1], {n, 2}, "px", "col,row");
  w.SetAttr("/pixels/right", "description",
            "sub-pixel centre of the right sphere: 0-based column and row of pixel centres, rows "
            "growing downward; NaN where not found");
  w.WriteDoubles("/pixels/plate_row", plate_row, {n}, "px");
  w.SetAttr("/pixels/plate_row", "description",
            "row of the plate's top surface under the dimer (at the column midway between the "
            "centres; the edge slopes by the root attribute plate_slope)");
  w.WriteInt64("/frame_index", index, {n});
  w.SetAttr("/frame_index", "units", "1");
  w.SetAttr("/frame_index", "description",
            "0-based index of the frame in the source's sorted frame list");
  w.WriteStrings("/frame_files", r.names);
  w.SetAttr("/frame_files", "description", "file name of each tracked frame (FILE#PAGE in a stack)");
  w.WriteUint8("/found", found, {n, 2});
  w.SetAttr("/found", "columns", "left,right");
  w.SetAttr("/found", "codes",
            "0=not found (its tips and pixels are NaN),1=found,2=found cut by the frame's edge");
  w.SetAttr("/found", "description", "whether each sphere was found in the frame");
  w.WriteDoubles("/pixels/left_cut_err", columns.cut_err[0], {n, 2}, "px", "col,row");
  w.WriteDoubles("/pixels/right_cut_err", columns.cut_err[1], {n, 2}, "px", "col,row");
  for (const char* name : {"/pixels/left_cut_err", "/pixels/right_cut_err"}) {
    w.SetAttr(name, "description",
              "standard uncertainty of a centre found cut by the frame's edge (found = 2): its "
              "registration on the part in view, the shift of the whole sphere beside it cut "
              "alike, the pair's miss of the dimer's length, and the appearance's offset's; NaN "
              "for a whole sphere (its scatter is "
              "/precision/scatter, its offset's uncertainty /template/offset_err)");
  }
  if (r.method == Method::kTemplate) WriteTemplateGroup(w, r);
  WritePrecisionGroup(w, r);
  WriteMethodTrial(w, r);
  std::vector<int64_t> stuck;
  for (const cv::Point& p : r.defects.at) stuck.insert(stuck.end(), {p.x, p.y});
  w.WriteInt64("/stuck_pixels", stuck, {r.defects.at.size(), 2});
  w.SetAttr("/stuck_pixels", "columns", "col,row");
  w.SetAttr("/stuck_pixels", "units", "px");
  w.SetAttr("/stuck_pixels", "description",
            "the sensor's stuck (hot or dead) pixels, found on the frames spread over the first "
            "chunk and replaced in every frame, before tracking, by the mean of their sound "
            "opposite neighbours");
  if (r.lens) {
    const LensCalibration& c = *r.lens;
    w.WriteDoubles("/lens/camera_matrix", std::vector<double>(c.camera.val, c.camera.val + 9),
                   {3, 3}, "px");
    w.SetAttr("/lens/camera_matrix", "description",
              "the lens calibration's camera matrix (fx 0 cx; 0 fy cy; 0 0 1), kept by the "
              "undistortion: every position in this file is in the undistorted frame");
    w.WriteDoubles("/lens/distortion", c.distortion, {c.distortion.size()}, "1");
    w.SetAttr("/lens/distortion", "description",
              "the lens's distortion coefficients in OpenCV's order (k1 k2 p1 p2 k3 ...), taken "
              "out of every frame before tracking");
  }
  w.WriteStrings("/skipped/files", skipped_names);
  w.SetAttr("/skipped/files", "description", "frames that could not be used");
  w.WriteStrings("/skipped/reasons", skipped_reasons);
  w.SetAttr("/skipped/reasons", "description", "why each skipped frame could not be used");
}

}  // namespace

std::string PsfSource(const TrackArgs& args, const PlateClip& clip) {
  if (clip.level.psf_fitted) return "fitted";
  return args.sequence.follower.fit_psf_sigma ? "default" : "--psf-sigma";
}

void WriteTrackFile(const std::string& path, const TrackArgs& args, const SequenceResult& r,
                    const Calibration& cal, const Recording& rec) {
  const TrackColumns columns = ColumnsOf(r, cal, *args.fps, rec.info.frame_times);
  const RootAttrs root = RootAttributes(args, r, cal, rec);
  H5Writer w(path);
  WriteProvenance(w, "track", root.attrs, root.units,
                  {{"m_per_px_given", "0=calibrated from --diameter,1=given by --m-per-px,"
                                      "2=calibrated from --ar (the dimer's length)"},
                   {"complete", "0=interrupted (Ctrl-C): the frames tracked so far,1=complete"}});
  WriteColumns(w, columns, r);
  w.Close();
}

}  // namespace dimer::tracking
