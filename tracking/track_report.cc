#include "tracking/track_report.h"

#include <cmath>
#include <string>

#include "common/format.h"
namespace dimer::tracking {
namespace {

// A colour camera's film is tracked grey: said, as the file's cine_colour keeps it; a 10- or
// 12-bit camera's levels, scaled (level_scale.h).
void ReportInput(const TrackArgs& args, const Recording& rec, const SequenceResult& r,
                 Diagnostics* diag) {
  if (rec.info.known && rec.info.colour != "grey") {
    const bool mosaic = rec.info.colour == "mosaic";
    diag->Note("colour",
               Format("%s: %s, tracked in grey (%s)", args.input.c_str(),
                      mosaic ? ("a colour sensor's raw Bayer mosaic (CFA " +
                                std::to_string(rec.info.cfa) + ")").c_str()
                             : "interpolated colour (BGR)",
                      mosaic ? ("the four phases balanced to one grey, " +
                                rec.info.mosaic_balance +
                                "; cells still coloured filtered to (R + 2G + B) / 4 over 3x3")
                                   .c_str()
                             : "OpenCV's BGR to grey"));
  }
  if (r.level_scale.warn) {
    diag->WarnInput("levels", r.level_scale.reason);
  } else if (!r.level_scale.reason.empty()) {
    diag->Note("levels", r.level_scale.reason, "levels");
  }
  if (r.level_scale.clipped_frames > 0) {
    diag->WarnInput("levels_clipped",
                    Format("%zu %s (the first %s) had levels above the %d bits taken for the "
                           "camera and were clipped at the top by the scaling; give the camera's "
                           "bits with --bits (16: as stored)",
                           r.level_scale.clipped_frames,
                           r.level_scale.clipped_frames == 1 ? "frame" : "frames",
                           r.level_scale.first_clipped.c_str(), r.level_scale.bits));
  }
}

// An over-exposed plate: how its rows were found. Both lines belong to the report --quiet
// silences.
void ReportClippedPlate(const TrackArgs& args, const PlateClip& c, Diagnostics* diag) {
  if (c.frames == 0) return;
  if (c.level.found()) {
    diag->Note("plate_clipped",
               Format("over-exposed in %zu frames; its level %.1f +- %.1f grey levels above the "
                      "backdrop and the camera's blur %.2f px (%s), from %zu frames with two "
                      "partly lit rows; %zu rows fitted at them",
                      c.frames, c.level.value, c.level.err, c.level.psf_sigma,
                      PsfSource(args, c).c_str(), c.level.used, c.refitted),
               "plate");
  } else {
    diag->Add({Severity::kWarning, "plate_clip_level_unmeasured", "plate",
               Format("over-exposed in %zu frames, and %zu show two partly lit rows (%zu needed "
                      "to measure its level): a row may be up to the covered part of a pixel "
                      "toward the dark side",
                      c.frames, c.level.informative, kClippedLevelMinFrames),
               false});
  }
}

// What was taken out before or after tracking: matches that were not the sphere
// (match_scores.h), the lens's distortion (lens_undistortion.h), the sensor's stuck pixels
// (defect_pixels.h).
void ReportCleaning(const SequenceResult& r, Diagnostics* diag) {
  const size_t by_score = r.scores.dropped[0] + r.scores.dropped[1];
  const size_t by_length = r.scores.dropped_length[0] + r.scores.dropped_length[1];
  if (by_score + by_length > 0) {
    diag->Note("matches_dropped",
               Format("%zu sphere matches dropped as not the sphere: %zu scoring far below their "
                      "sphere's median, %zu giving the dimer another length than its %.2f px (a "
                      "sphere at the frame's edge, or beside itself); those spheres are not found "
                      "there",
                      by_score + by_length, by_score, by_length, r.scores.length_px));
  }
  if (r.lens) {
    diag->Note("lens",
               Format("every frame undistorted with %s (%zu coefficients, k1 %.4g); it moves "
                      "pixels by up to %.2f px in these frames",
                      r.lens->path.c_str(), r.lens->distortion.size(), r.lens->distortion[0],
                      r.lens_max_shift_px),
               "lens");
  }
  if (!r.defects.at.empty()) {
    diag->Note("stuck_pixels",
               Format("%zu stuck pixels of the sensor (standing out from all their neighbours in "
                      "%zu frames or more of %zu) replaced in every frame by the mean of their "
                      "sound opposite neighbours (/stuck_pixels)",
                      r.defects.at.size(),
                      size_t(std::ceil(kDefectFrameFraction * double(r.defects.frames))),
                      r.defects.frames));
  } else if (!r.defects.reason.empty()) {
    diag->Note("stuck_pixels", r.defects.reason, "note");
  }
}

// The plate found in no frame: heights are then measured from the frame's bottom row, which is
// said (RunTrack.APlateFoundInNoFrameIsSaid); found in part of them, a note.
void ReportPlateFound(const TrackArgs& args, const SequenceResult& r, Diagnostics* diag) {
  size_t found = 0;
  for (const FrameTrack& f : r.frames) found += std::isfinite(f.plate_row);
  if (found == 0) {
    diag->WarnInput("no_plate",
                    Format("%s: no plate edge found in any of the %zu frames: heights are taken "
                           "from the frame's bottom row (give --row0, the row of z = 0)",
                           args.input.c_str(), r.frames.size()));
  } else if (found < r.frames.size()) {
    diag->Note("plate_found", Format("plate edge found in %zu of %zu frames", found,
                                     r.frames.size()));
  }
}

// Where the image's strongest edge is not the plate's (a ruler, a backdrop's band, a reflection,
// the plate's lower face): the plate is the edge the dimer stands on (sphere/detector.h), and
// the film says so, once, with the first frame where it was told apart
// (PlateUnderTheDimer.TrackSaysTheStrongestEdgeIsNotThePlate).
void ReportStrongerEdge(const SequenceResult& r, Diagnostics* diag) {
  size_t frames = 0;
  const FrameTrack* first = nullptr;
  for (const FrameTrack& f : r.frames) {
    if (!f.acquired || !std::isfinite(f.strongest_edge_row) || !std::isfinite(f.plate_row)) {
      continue;
    }
    ++frames;
    if (!first) first = &f;
  }
  if (!first) return;
  diag->Note("plate_not_strongest_edge",
             Format("the image's strongest edge (row %.1f in frame %zu) is not the plate's: the "
                    "plate is the edge the dimer stands on (row %.1f there; told apart in %zu "
                    "of the frames where the spheres were searched afresh)",
                    first->strongest_edge_row, first->index, first->plate_row, frames),
             "plate");
}

// A camera not level (or a tilted plate): the rows are read under each sphere and the metres
// run along the plate. The plate's top in view: its row is the contact line found from the
// mirror images, and its motion scaled to the dimer plane's.
void ReportPlateGeometry(const TrackArgs& args, const SequenceResult& r, Diagnostics* diag) {
  if (r.plate_slope.applied) {
    diag->Note("plate_slope",
               Format("the edge slopes by %.5f +- %.5f px per px (%s): the plate is read under "
                      "each sphere, and x runs along it, z along its normal",
                      r.plate_slope.value, r.plate_slope.err, r.plate_slope.reason.c_str()),
               "plate");
  }
  if (r.plate_shift.applied) diag->Note("plate_shift", r.plate_shift.reason, "plate");
  if (r.plate_scale.given) {
    diag->Note("plate_motion_scale",
               Format("the edge's motion scaled by %.6g to the dimer's plane (--plate-m-per-px "
                      "%.6g / --m-per-px %.6g), about edge row %.3f",
                      r.plate_scale.scale, *args.plate_m_per_px, args.m_per_px.value_or(std::nan("")),
                      r.plate_scale.edge_ref),
               "plate");
  } else if (r.plate_shift.applied && r.plate_scale.fitted) {
    diag->Note("plate_motion_scale",
               Format("the contact line moves %.3f +- %.3f px per px of the visible edge (the %s "
                      "sphere resting, %zu frames)",
                      r.plate_scale.scale, r.plate_scale.err,
                      r.plate_scale.sphere == 0 ? "left" : "right", r.plate_scale.frames),
               "plate");
  } else if (r.plate_shift.applied) {
    diag->Add({Severity::kWarning, "plate_motion_scale_unfitted", "plate",
               Format("the edge's motion is taken as the contact line's (fewer than %zu resting "
                      "frames, or the plate moved under %.1f px in them); the far edge of a deep "
                      "plate moves less than the contact line",
                      kMinScaleFrames, kMinScaleSpreadPx),
               false});
  }
}

// The template's offsets to the centres, and where its radius came from. Its warnings belong
// to the report --quiet silences.
void ReportTemplate(const SequenceResult& r, Diagnostics* diag) {
  if (r.method != Method::kTemplate) return;
  auto warn = [&](const char* code, std::string message) {
    diag->Add({Severity::kWarning, code, "", std::move(message), false});
  };
  for (int k = 0; k < 2; ++k) {
    const OffsetEstimate &c = r.offsets.col[k], &w = r.offsets.row[k];
    diag->Note("offset",
               Format("%s sphere: offset to the centre col %+.3f +- %.3f px (%s), row %+.3f +- "
                      "%.3f px (%s, %zu frames)",
                      k == 0 ? "left" : "right", c.value, c.err, c.source.c_str(), w.value, w.err,
                      w.source.c_str(), w.n));
  }
  // An offset is a constant shift of every frame's centre: it biases absolute positions (a
  // sphere's height above the plate, the tilt) but not velocities, slip or drift. Say so where
  // its uncertainty exceeds the 0.1 px the tracker aims at.
  constexpr double kOffsetWarnPx = 0.1;
  for (int k = 0; k < 2; ++k) {
    for (int axis = 0; axis < 2; ++axis) {
      const OffsetEstimate& e = axis == 0 ? r.offsets.col[k] : r.offsets.row[k];
      const char* side = k == 0 ? "left" : "right";
      const char* what = axis == 0 ? "column" : "row";
      if (std::isnan(e.err)) {  // source "none": nothing on the footage gave it
        warn("offset_unmeasured",
             Format("the %s sphere's %s offset could not be estimated (no outline, symmetry or "
                    "plate contact to measure it on): its absolute position is the learnt "
                    "appearance's reference point, possibly pixels off; its motion is not",
                    side, what));
        continue;
      }
      if (!(e.err > kOffsetWarnPx)) continue;
      warn("offset_uncertain",
           Format("the %s sphere's %s is uncertain by %.2f px (%s): its absolute position may be "
                  "off by as much; its motion is not",
                  side, what, e.err, e.source.c_str()));
    }
  }
  // Rows rest on plate - R: a radius error is a row bias, so say where R came from.
  if (r.radius_source == "outline") {
    diag->Note("radius",
               Format("sphere radius %.2f px from the spheres' outline (no --m-per-px); on mirror "
                      "spheres it can be ~0.5 px short, which lowers every row by as much and "
                      "enlarges the scale by ~2 %%: pass --m-per-px when the scale is known, or "
                      "--ar with the dimer's aspect ratio",
                      r.appearance[0].radius_px));
  } else if (r.radius_source == "silhouette" && !r.method_reason.empty() &&
             r.appearance[0].valid()) {
    warn("radius_from_silhouette",
         Format("sphere radius %.2f px from the silhouette methods, not the outline (the two "
                "spheres' outlines disagree); rows and the scale rest on it: pass --m-per-px, or "
                "--ar with the dimer's aspect ratio",
                r.appearance[0].radius_px));
  }
}

// Each sphere's frame-to-frame scatter beside the footage's bound; a warning where the tracker
// did not follow a sphere as the footage allows (track_precision.h): its positions are then not
// what a sub-pixel tracker gives, whatever "found" says.
void ReportPrecision(const TrackArgs& args, const SequenceResult& r, Diagnostics* diag) {
  for (int k = 0; k < 2; ++k) {
    const SpherePrecision& p = r.precision[k];
    const char* side = k == 0 ? "left" : "right";
    if (p.measured.allFinite()) {
      if (p.bound.allFinite()) {
        diag->Note("precision",
                   Format("%s sphere: centres scatter %.3f / %.3f px (col / row) from frame to "
                          "frame; the footage allows %.3f / %.3f (noise %.2f grey levels)",
                          side, p.measured.x(), p.measured.y(), p.bound.x(), p.bound.y(),
                          r.frame_noise));
      } else {
        diag->Note("precision",
                   Format("%s sphere: centres scatter %.3f / %.3f px (col / row) from frame to "
                          "frame",
                          side, p.measured.x(), p.measured.y()));
      }
    }
    if (p.poor) {
      diag->Warn("poor_footage",
                 Format("%s: the footage places the %s sphere to %.2f / %.2f px (col / row) at "
                        "best: too little contrast for sub-pixel work; its offset to the centre, "
                        "estimated on the same footage, may be off by more than it states; more "
                        "light or a larger image of the spheres helps",
                        args.input.c_str(), side, p.bound.x(), p.bound.y()));
    }
    if (p.uneven_motion) {
      diag->Note("uneven_motion",
                 Format("%s sphere: centres move unevenly from frame to frame (%.2f / %.2f px, "
                        "col / row) while the dimer's length holds to %.3f px: the motion "
                        "(separate poses, a jolt), not the tracking",
                        side, p.measured.x(), p.measured.y(), p.length_measured));
    }
    if (!p.followed && !p.bound.allFinite()) {
      diag->Warn("not_followed",
                 Format("%s: the %s sphere's centres scatter %.2f / %.2f px from frame to frame, "
                        "and the dimer's length %.2f px (a rigid rod's is constant): it is not "
                        "followed as a sub-pixel tracker should, and many frames may be pixels "
                        "off; on steel that is not a clean silhouette the silhouette methods "
                        "can find a reflection instead of the sphere: compare the track with the "
                        "frames, or track the frames where the template follows (--frames)",
                        args.input.c_str(), side, p.measured.x(), p.measured.y(),
                        p.length_measured));
    } else if (!p.followed) {
      diag->Warn("not_followed",
                 Format("%s: the %s sphere's centres scatter %.2f / %.2f px from frame to frame, "
                        "more than %.0f times what the footage allows (%.3f / %.3f px): it is not "
                        "followed as a sub-pixel tracker should, and many frames may be pixels "
                        "off; more light, a larger image of the spheres or --method "
                        "centroid/discfit may help",
                        args.input.c_str(), side, p.measured.x(), p.measured.y(),
                        kNotFollowedFactor, p.bound.x(), p.bound.y()));
    }
  }
}

// A sphere whose rows neither moved with the plate under it nor fell (held_rows.h).
void ReportHeldRows(const TrackArgs& args, const SequenceResult& r, Diagnostics* diag) {
  for (int k = 0; k < 2; ++k) {
    const HeldRows& h = r.held_rows[k];
    if (h.held == 0) continue;
    const size_t first = r.frames[h.first].index;
    const size_t last = r.frames[h.first + h.window_frames - 1].index;
    diag->Warn("rows_held",
               Format("%s: the %s sphere's rows stood within %.2f px over frames %zu-%zu while "
                      "the plate under it moved %.2f px, and a free fall would move them by "
                      "%.0f px or more (%zu of %zu windows of %zu frames): neither resting nor "
                      "falling, they are held by something that stands still behind it (a "
                      "ruler's or a backdrop's edge), and its rows, with the offset measured on "
                      "them, may be pixels off; a plain background behind the dimer helps",
                      args.input.c_str(), k == 0 ? "left" : "right", h.row_range, first, last,
                      h.plate_range, kHeldFallPx, h.held, h.windows,
                      h.window_frames));
  }
}

// Frames whose two centres part from the dimer's length by more than its noise allows
// (length_constancy.h): one sphere or both are off there, whatever the other referees said.
void ReportLengthConstancy(const TrackArgs& args, const SequenceResult& r, Diagnostics* diag) {
  const LengthConstancy& c = r.length;
  if (c.departing == 0) return;
  diag->Warn("length_departs",
             Format("%s: the dimer's length (the two centres' distance) departs from its median "
                    "%.2f px by up to %.2f px in %zu of %zu frames (frames %zu-%zu), while from "
                    "frame to frame it scatters %.3f px: a rigid rod's is constant, so there one "
                    "sphere or both are off by at least half that (held by something behind "
                    "it, or a lens's distortion as the dimer crosses the field: track --lens); "
                    "compare the track with those frames",
                    args.input.c_str(), c.median_px, c.worst_px, c.departing, c.frames,
                    r.frames[c.first].index, r.frames[c.last].index, c.noise_px));
}

// A sphere whose learnt appearance did not move with its detections on the learning frames
// (detection_agreement.h): its positions may be held by something that does not move with it.
// Where it was learnt again without that (learn_method.h, RelearnHeldSpheres), a note says so.
void ReportDetectionAgreement(const TrackArgs& args, const SequenceResult& r, Diagnostics* diag) {
  if (r.method != Method::kTemplate) return;
  for (int k = 0; k < 2; ++k) {
    const DetectionAgreement& a = r.detection_agreement[k];
    if (r.relearnt_by_length[k]) {
      diag->Note("learnt_again",
                 Format("%s: followed over the film's first frames, the dimer's length departed "
                        "from its median by more than its noise allows (a rigid rod's is "
                        "constant): the %s sphere's appearance was held by something standing "
                        "still behind it (a ruler's or a backdrop's edge), and it was learnt "
                        "again from its highlights without the pixels that stand still, with "
                        "which the length holds better (method_reason gives the figures)",
                        args.input.c_str(), k == 0 ? "left" : "right"));
    } else if (r.relearnt_by_plate[k]) {
      const PlateAgreement& p = r.plate_agreement[k];
      diag->Note("learnt_again",
                 Format("%s: the %s sphere's rows did not move with the plate it rests on "
                        "(something standing still behind it, a ruler's or a backdrop's edge, "
                        "held them); it was learnt again without the pixels that stand still, "
                        "and its rows then moved %.2f +- %.2f px per px of the plate's over %zu "
                        "resting learning frames (1 for rows that move with it; the rows' stated "
                        "uncertainty includes how far they part from that)",
                        args.input.c_str(), k == 0 ? "left" : "right", p.slope, p.slope_err,
                        p.frames));
    } else if (r.relearnt[k]) {
      diag->Note("learnt_again",
                 Format("%s: the %s sphere's first appearance did not move as its detections "
                        "did (something standing still behind it, a ruler's or a backdrop's "
                        "edge, held it); it was learnt again from its highlights without the "
                        "pixels that stand still, and then moved with them",
                        args.input.c_str(), k == 0 ? "left" : "right"));
    }
    const PlateAgreement& p = r.plate_agreement[k];
    if (!p.agrees) {
      diag->Warn("not_with_plate",
                 Format("%s: the %s sphere's rows moved %.2f +- %.2f px per px of the plate's "
                        "over %zu learning frames where it rests, not with the plate: something "
                        "that stands still behind it (a ruler's or a backdrop's edge) may hold "
                        "them, and learnt again without it they still did not move with it; its "
                        "rows may be off by a fraction of the plate's motion; a plain background "
                        "behind the dimer helps",
                        args.input.c_str(), k == 0 ? "left" : "right", p.slope, p.slope_err,
                        p.frames));
    }
    if (a.agrees) continue;
    const char* axis = a.axis == 0 ? "columns" : "rows";
    diag->Warn("not_with_detections",
               Format("%s: the %s sphere's learnt appearance did not move as its detections did "
                      "over the learning frames (its %s spread %.2f px, theirs %.2f px): "
                      "something that stands still behind it (a ruler's or a backdrop's edge) "
                      "may hold its positions; its stated uncertainty includes the %.2f px by "
                      "which the two parted, and it may be off by more; a plain background "
                      "behind the dimer helps",
                      args.input.c_str(), k == 0 ? "left" : "right", axis, a.learnt_sd,
                      a.rough_sd, a.residual_sd));
  }
}

}  // namespace

void ReportFilm(const TrackArgs& args, const Recording& rec, const SequenceResult& r,
                Diagnostics* diag) {
  ReportInput(args, rec, r, diag);
  // The choice and its evidence (also in the file); -q keeps stderr empty on success.
  if (!r.method_reason.empty()) {
    diag->Note("method", Format("method %s -> %s (reason: %s)", ToString(args.method).c_str(),
                                ToString(r.method).c_str(), r.method_reason.c_str()));
  }
  ReportClippedPlate(args, r.plate_clip, diag);
  ReportCleaning(r, diag);
  ReportPlateFound(args, r, diag);
  ReportStrongerEdge(r, diag);
  ReportPlateGeometry(args, r, diag);
  ReportTemplate(r, diag);
  ReportDetectionAgreement(args, r, diag);
  ReportPrecision(args, r, diag);
  ReportHeldRows(args, r, diag);
  ReportLengthConstancy(args, r, diag);
}

void ReportLengthScale(const TrackArgs& args, const Calibration& cal, Diagnostics* diag) {
  const double ar = *args.ar;  // called with --ar given
  if (!args.m_per_px) {
    const LengthScale& ls = cal.length_scale;
    diag->Note("length_scale",
               Format("scale %.6g m/px from the dimer's length %.3f px (median of %zu frames, "
                      "--ar %g, --diameter %g m); tracked with a sphere radius of %.3f px, "
                      "settled in %zu passes over the first frames",
                      cal.m_per_px, cal.length_px, cal.length_frames, ar, args.diameter,
                      ls.radius_px, ls.passes.size()));
    const double outline = ls.outline_radius_px;
    if (std::abs(ls.radius_px / outline - 1.0) > kOutlineRadiusCheck) {
      diag->Warn("length_scale_outline",
                 Format("the spheres' outline gives a radius of %.2f px, the dimer's length with "
                        "--ar %g one of %.2f px (%+.0f %%): check --ar (the length over the "
                        "diameter, not the centre distance over it)",
                        outline, ar, ls.radius_px, 100.0 * (ls.radius_px / outline - 1.0)));
    }
    if (!ls.converged) {
      diag->Warn("length_scale_unsettled",
                 Format("the radius had not settled to %.2f px after %d passes (last %.3f -> "
                        "%.3f px); rows rest on it",
                        kLengthScaleTolPx, int(ls.passes.size()),
                        ls.passes.back().radius_px_used, ls.radius_px));
    }
    return;
  }
  if (!std::isfinite(cal.length_px)) return;
  // Both given: the tracked length says which A_r the scale and diameter imply.
  const double measured = cal.length_px * *args.m_per_px / args.diameter + 1.0;
  if (std::abs(measured - ar) > kLengthCheckTolerance * (ar - 1.0)) {
    diag->Warn("length_check",
               Format("with --m-per-px %g and --diameter %g m the tracked length (%.3f px) gives "
                      "A_r = %.4f, not --ar %g (A_r - 1 %+.1f %%): one of the three is off",
                      *args.m_per_px, args.diameter, cal.length_px, measured, ar,
                      100.0 * (measured - ar) / (ar - 1.0)));
  }
}

}  // namespace dimer::tracking
