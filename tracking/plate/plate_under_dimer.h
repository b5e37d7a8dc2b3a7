#pragma once
// The plate is the line the dimer stands on. The image alone cannot tell the plate's edge from a
// ruler, a backdrop's band, a reflection or the plate's lower face, any of which can be the
// strongest step in the frame (FindPlateRowCoarse's evidence of the dimer above an edge fails
// where such an edge runs behind the spheres: it then has the most of the dimer above it). The
// dimer settles it: a sphere resting on the plate has its lowest point on the plate's top, so
// of the frame's candidate edges (PlateCandidates) the plate is the one the lowest sphere's
// lowest point meets, within kPlateMeetPx. A frame whose spheres are all in flight meets none,
// and the image's choice stands.
#include <vector>

#include "tracking/plate/plate_edge.h"

namespace dimer::tracking {

// The coarse lowest point (a blob's top, +-1 px, and a diameter: of the radius the tracker knows,
// or the distance transform's, +-1 px) against a candidate's whole-pixel row: they meet within
// this, px. Candidates are at least kPlateCandidateSeparationRows apart, so at most one meets
// (PlateUnderTheDimer.TheCandidateTheLowestPointMeets).
inline constexpr double kPlateMeetPx = 3.0;

// Index into `candidates` of the one the dimer stands on: nearest to `lowest_point_row` (the
// lowest sphere's lowest point, moved along the plate's slope to the frame's centre column)
// and within kPlateMeetPx; -1 if none meets (or the row is NaN).
int CandidateTheDimerStandsOn(const std::vector<PlateCandidate>& candidates,
                              double lowest_point_row);

}  // namespace dimer::tracking
