#include "tests/footage/scaled_track.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "common/h5_file.h"
#include "tests/footage/track_accuracy.h"
#include "tracking/run_track.h"

namespace dimer::footage {

ScaledTrack TrackScaled(const std::string& folder, const std::string& output, double m_per_px,
                        double ar) {
  tracking::TrackArgs t;
  t.input = folder;
  t.output = output;
  t.force = true;
  if (!std::isnan(m_per_px)) t.m_per_px = m_per_px;
  if (!std::isnan(ar)) t.ar = ar;
  t.quiet = true;
  const auto start = std::chrono::steady_clock::now();
  tracking::RunTrack(t);
  ScaledTrack out;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  H5Reader h(output);
  out.m_per_px = *h.AttrDouble("/", "m_per_px");
  out.m_per_px_given = *h.AttrDouble("/", "m_per_px_given");
  out.ar_passes = *h.AttrDouble("/", "ar_passes");
  const std::vector<TruthRow> truth = ReadTruthCsv(folder + "/truth.csv");
  const std::vector<std::string> files = h.ReadStrings("/frame_files");
  for (int k = 0; k < 2; ++k) {
    const std::vector<double> px = h.ReadDoubles(k == 0 ? "/pixels/left" : "/pixels/right");
    for (size_t i = 0; i < files.size(); ++i) {
      const auto row = std::find_if(truth.begin(), truth.end(),
                                    [&](const TruthRow& r) { return r.file == files[i]; });
      if (row == truth.end() || std::isnan(px[2 * i])) continue;
      out.bias[k] += Eigen::Vector2d(px[2 * i], px[2 * i + 1]) - row->centre[k];
      ++out.found[k];
    }
    if (out.found[k] > 0) out.bias[k] /= double(out.found[k]);
  }
  return out;
}

}  // namespace dimer::footage
