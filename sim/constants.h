#pragma once
// Every numerical tolerance of the simulator, named once, with its unit and what it trades.
// Lengths are metres, times seconds. Tolerances that users may want to trade for speed are
// options (SimOptions); these are the fixed ones, derived from a few base values.
namespace dimer::sim {

// Default gap (m) a sphere may penetrate before an impact is declared (SimOptions::gap_tol, the
// impact-location tolerance): the impact finder steps so that no root of h(t) + gap_tol can be
// skipped, then refines to the exact root of h(t) = 0. Penetration is therefore never deeper
// than gap_tol. Warning: 1e-13 m is ~2e-11 sphere radii; far smaller values reach the
// round-off of z (~1e-18 m) and only slow the search down.
inline constexpr double kGapTol_m = 1e-13;
// Time accuracy of impact-time refinement (s): Newton stops below this step.
inline constexpr double kRootTimeTol_s = 1e-14;
// A sphere whose gap is below this at another sphere's impact takes part in it (m).
inline constexpr double kTouchTol_m = 1e-10;
// Iteration caps: root refinement, impulse segments in one impact, event-location iterations.
inline constexpr int kMaxNewtonIterations = 50;
inline constexpr int kMaxImpactSegments = 64;
inline constexpr int kMaxLocateIterations = 100;
// Relative size below which a slip velocity counts as zero (of the velocity scale g/f).
inline constexpr double kSlipZeroRel = 1e-12;
// Round-off of a position, relative to R (64 ulp): a sphere deeper than gap_tol plus this is
// a missed impact, and the run stops with an error (SimulatorTest.NoSphereThroughThePlate*).
inline constexpr double kPositionRoundoffRel = 64 * 2.220446049250313e-16;
// Relative size of a kinetic-energy change that is round-off, not physics (64 ulp).
inline constexpr double kEnergyRoundoffRel = 64 * 2.220446049250313e-16;
// Persistent-contact integration: smallest and largest step, as fractions of the plate period.
inline constexpr double kMinStepRel = 1e-12;
inline constexpr double kMaxStepRel = 1.0 / 32.0;
// Event time accuracy inside persistent contact (s).
inline constexpr double kEventTimeTol_s = 1e-13;

// Input ranges (SimOptions::Check): a run of any allowed value ends in bounded time and memory.
inline constexpr double kMaxAr = 1000;          // aspect ratio
inline constexpr double kMaxGamma = 10;         // plate acceleration / g
inline constexpr double kMaxFriction = 1000;    // any friction coefficient
inline constexpr double kMaxPhase = 1e6;        // plate and release phases, periods
inline constexpr double kMaxPeriods = 1e9;      // --cycles, --duration x --freq, sweep windows
inline constexpr double kMinFps = 1e-3;         // samples/s, when sampling at all
inline constexpr double kMaxFps = 1e7;          // samples/s
// Events a period keeps in the log for the memory estimate: a drift orbit logs ~18 (the sample
// scene), an irregular one more; the estimate is a bound to refuse absurd runs, not a budget.
inline constexpr double kEventsPerPeriodEstimate = 30;

}  // namespace dimer::sim
