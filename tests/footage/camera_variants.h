#pragma once
// Cameras the tracker was not tuned on: the front-lit steel scene (Lighting::kFrontPoint) filmed
// at another scale, out of focus, at 16 bits, through a camera not quite level, under lamps
// that flicker with the mains, or through a lens that is not a pinhole. Every other POV-Ray
// case is 0.2 mm/px (sphere radius 23.75 px), PSF 0.5 px, 8 bit; a lab's lens and camera give
// other figures, and the tracker's reaches, bands and thresholds were set there. Used by the tests
// (tests/tracking/povray_footage_test.cc) and the bench (bench_tracking_footage --camera).
#include <string>
#include <vector>

#include "tests/footage/povray_footage.h"

namespace dimer::footage {

struct CameraVariant {
  const char* name;
  double m_per_px;      // scale at the dimer plane
  double psf_sigma_px;  // Gaussian PSF (defocus)
  int bit_depth;
  double roll_deg = 0;  // turned about its axis (the plate edge slopes)
  double flicker = 0;   // lamps on the mains: the light's relative swing at 100 Hz
  double lens_k1 = 0;   // a lens's pincushion distortion (OpenCV's k1); tracked with its lens.yml
  double off_axis = 0;  // the dimer this far right of the optical axis, m
};

inline std::vector<CameraVariant> CameraVariants() {
  return {
      {"fine_scale", 1.0e-4, 0.5, 8},    // R = 47.5 px: a macro lens, or a larger sensor
      {"coarse_scale", 4.0e-4, 0.5, 8},  // R = 11.9 px: a wide field for a long drift
      {"defocus_1px", 2.0e-4, 1.0, 8},   // the dimer plane slightly out of focus
      {"defocus_2px", 2.0e-4, 2.0, 8},   // a shallow depth of field at full aperture
      {"bit16", 2.0e-4, 0.5, 16},        // a 12-bit sensor saved in 16-bit files
      // Levelled by eye: the plate's edge falls 5.6 px across the frame.
      {"rolled_half_degree", 2.0e-4, 0.5, 8, 0.5},
      // Turned 8 degrees: to the tracker, as a plate tilted by the largest tilt of the paper's
      // Fig. 4b seen by a level camera (the edge falls 90 px across the frame).
      {"rolled_8_degrees", 2.0e-4, 0.5, 8, 8.0},
      // Lamps on 50 Hz mains, +-30 % at 100 Hz: 20 frames a cycle, the light different in
      // every frame (the camera is the default one).
      {"mains_flicker", 2.0e-4, 0.5, 8, 0.0, 0.3},
      // A lens with 0.67 % of pincushion distortion at the frame's far corner (k1 = 0.5; zoom
      // lenses at their long end show as much), the dimer 35 mm right of the optical axis, where
      // the lens moves the right sphere by 0.6 px and the left by 0.06: tracked with the lens's
      // calibration (`track --lens`, the folder's lens.yml).
      {"pincushion_lens", 2.0e-4, 0.5, 8, 0.0, 0.0, 0.5, 0.035},
  };
}

// Front-lit steel (front_point) with the variant's camera.
inline FootageOptions FootageFor(const CameraVariant& v) {
  FootageOptions o = FootageOptions::For(Lighting::kFrontPoint);
  o.camera.m_per_px = v.m_per_px;
  o.psf_sigma_px = v.psf_sigma_px;
  o.bit_depth = v.bit_depth;
  o.camera.roll_deg = v.roll_deg;
  o.flicker = v.flicker;
  o.lens_k1 = v.lens_k1;
  o.dimer_off_axis = v.off_axis;
  return o;
}

// The index of the variant called `name` in CameraVariants(), -1 if none.
inline int CameraIndex(const std::string& name) {
  const std::vector<CameraVariant> v = CameraVariants();
  for (size_t i = 0; i < v.size(); ++i) {
    if (name == v[i].name) return int(i);
  }
  return -1;
}

// The lens calibration the footage of camera `camera` in `dir` is tracked with (`track --lens`,
// the folder's lens.yml), or "" for a pinhole (or no camera variant, -1).
inline std::string LensFileOf(int camera, const std::string& dir) {
  return camera >= 0 && CameraVariants()[size_t(camera)].lens_k1 != 0 ? dir + "/lens.yml" : "";
}

// A case's footage options: its lighting's own camera, or (camera >= 0) front_point through
// CameraVariants()[camera].
inline FootageOptions CaseFootageOptions(Lighting lighting, int camera) {
  return camera >= 0 ? FootageFor(CameraVariants()[size_t(camera)])
                     : FootageOptions::For(lighting);
}

}  // namespace dimer::footage
