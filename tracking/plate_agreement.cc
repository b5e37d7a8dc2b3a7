#include "tracking/plate_agreement.h"

#include <cmath>

#include "tracking/plate_contact.h"

namespace dimer::tracking {

PlateAgreement AgreementWithPlate(const std::vector<double>& edge,
                                  const std::vector<double>& row, std::vector<uint8_t>* resting) {
  PlateAgreement a;
  const RestingLine l = FitRestingLine(edge, row, resting);
  a.frames = l.n;
  a.edge_sd = l.edge_sd;
  if (l.n < kMinPlateAgreementFrames || !std::isfinite(l.b_err)) return a;
  a.slope = l.b;
  a.slope_err = l.b_err;
  const double low = 1.0 / kPlateSlopeBand, high = kPlateSlopeBand;
  const double outside = a.slope < low ? low - a.slope : a.slope > high ? a.slope - high : 0.0;
  a.agrees = !(outside > kPlateSlopeSigmas * a.slope_err);
  return a;
}

bool MovesMoreWithThePlate(const PlateAgreement& after, const PlateAgreement& before) {
  if (!std::isfinite(after.slope) || !std::isfinite(after.slope_err)) return false;
  if (!std::isfinite(before.slope)) return true;
  return std::abs(1.0 - after.slope) + 2.0 * std::hypot(after.slope_err, before.slope_err) <
         std::abs(1.0 - before.slope);
}

double WidenForPlate(const PlateAgreement& a, bool held, double err) {
  if (!held || !std::isfinite(a.slope)) return err;
  return std::hypot(err, std::abs(1.0 - a.slope) * a.edge_sd);
}

}  // namespace dimer::tracking
