#pragma once
// Mapping between lab metres and image pixels (docs/FORMATS.md, "Conventions"). The renderer shifts columns by
// `col_offset` so that a trajectory at any x fits the frame; the tracker writes
// x = col * m_per_px (col_offset 0), so a rendered sequence maps back with
// x_true = (col - col_offset) * m_per_px.
//   col = x / m_per_px + col_offset,   row = row0 - z / m_per_px   (rows grow downward)
#include <Eigen/Core>

namespace dimer::tracking {

struct PixelMap {
  double m_per_px = 2.0e-4;  // m per pixel, > 0
  double row0 = 0.0;         // row of z = 0 (the plate's mean surface), px
  double col_offset = 0.0;   // column of x = 0, px

  Eigen::Vector2d PixelFromLab(const Eigen::Vector2d& lab_m) const {
    return {lab_m.x() / m_per_px + col_offset, row0 - lab_m.y() / m_per_px};
  }
  Eigen::Vector2d LabFromPixel(const Eigen::Vector2d& px) const {
    return {(px.x() - col_offset) * m_per_px, (row0 - px.y()) * m_per_px};
  }
  double RowFromZ(double z_m) const { return row0 - z_m / m_per_px; }
  double ZFromRow(double row) const { return (row0 - row) * m_per_px; }
};

}  // namespace dimer::tracking
