#pragma once
// Sensor noise that is the same on every machine and for any thread count: an explicit
// Box-Muller transform over mt19937_64 (std::normal_distribution is implementation-defined),
// seeded per (sequence seed, frame) so that frames can be drawn in any order. Used by our
// renderer and by the POV-Ray test footage (tests/footage).
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace dimer::tracking {

// Standard normal deviates.
class Gaussian {
 public:
  explicit Gaussian(uint64_t seed) : rng_(seed) {}
  double Next() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    constexpr double kTwoPow53 = 9007199254740992.0;
    const double u1 = (double(rng_() >> 11) + 1.0) / (kTwoPow53 + 1.0);  // (0, 1]
    const double u2 = double(rng_() >> 11) / kTwoPow53;
    const double mag = std::sqrt(-2.0 * std::log(u1));
    spare_ = mag * std::sin(2.0 * std::numbers::pi * u2);
    has_spare_ = true;
    return mag * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  std::mt19937_64 rng_;
  double spare_ = 0;
  bool has_spare_ = false;
};

// The seed of one frame's noise: SplitMix64's finaliser of the pair (seed, frame).
inline uint64_t FrameSeed(uint64_t seed, uint64_t frame) {
  uint64_t z = seed * 0x9E3779B97F4A7C15ull + frame + 0x632BE59BD9B4E019ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace dimer::tracking
