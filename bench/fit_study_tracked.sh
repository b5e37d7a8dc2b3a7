#!/usr/bin/env bash
# The fit study's tracked half (docs/BENCHMARKS.md, fit_study_tracked.sh): bench_fit_study's
# drift scenes simulated, rendered (backlit and mirror-lit, sensor noise), tracked and fitted
# with `compare --fit` from the paper's coefficients and from a far start. Per fit: each
# coefficient as the report gives it (value +- half-width of its profile range, a bound, or
# nothing) marked where its range misses the truth, chi2/dof and its p-value at the analysis
# floors as set, the factor the fit scaled them by (compare/fit.h), simulations and the
# fit's wall time (`compare --fit` on one core, nice); then the coverage of the stated ranges
# per start, as text.
#   bench/fit_study_tracked.sh [BUILD_DIR] [WORK_DIR] [SCENES] [BACKLIT_METHOD]
# SCENES: indices into the list below (default all six, "0 1 2 3 4 5"; ~1 h on one core). Frames: 0.4 mm/px, 700x128, noise 2 grey levels, 100 periods at
# 2000 frames/s (8001 frames, ~340 MB of PNG per film, deleted once tracked; a track is reused
# while WORK_DIR holds it). The commands' own lines go to WORK_DIR/log.txt. BACKLIT_METHOD: the
# backlit films' `track --method` (default auto; the mirror-lit films are tracked with auto).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
work=${2:-fit_study_tracked}
scenes=${3:-"0 1 2 3 4 5"}
backlit_method=${4:-auto}
dimerlab="$build/app/dimerlab"
scale=4e-4
mkdir -p "$work"
# A_r Gamma eps mu_hat mu_hat_s mu mu_s: bench_fit_study's kScenes, in its order.
all=("2.5 0.90 0.70 0.08 0.15 0.15 0.35" "3.3 1.00 0.70 0.08 0.15 0.15 0.35"
     "4.2 0.85 0.60 0.12 0.25 0.30 0.50" "4.8 1.05 0.72 0.07 0.18 0.18 0.30"
     "5.5 1.00 0.55 0.14 0.30 0.30 0.45" "6.0 1.10 0.62 0.09 0.22 0.35 0.60")
far="--eps 0.85 --mu-hat 0.3 --mu-hat-s 0.6 --mu 0.6 --mu-s 1.2"
results="$work/results.txt"
: > "$results"
for i in $scenes; do
  read -r ar gamma eps mh mhs mu mus <<< "${all[$i]}"
  dir="$work/ar${ar}_g${gamma}"
  mkdir -p "$dir"
  "$dimerlab" sim --ar "$ar" --gamma "$gamma" --eps "$eps" --mu-hat "$mh" --mu-hat-s "$mhs" --mu "$mu" \
    --mu-s "$mus" --cycles 100 --fps 2000 -o "$dir/sim.h5" --force -q >> "$work/log.txt"
  for lighting in backlit reflect; do
    if [ ! -f "$dir/track_$lighting.h5" ]; then
      nice "$dimerlab" render "$dir/sim.h5" -o "$dir/frames" --force --m-per-px "$scale" --width 700 \
        --height 128 --lighting "$lighting" --noise 2 --threads 1 -q >> "$work/log.txt"
      method=auto
      [ "$lighting" = backlit ] && method=$backlit_method
      nice "$dimerlab" track "$dir/frames" -o "$dir/track_$lighting.h5" --m-per-px "$scale" --force -q \
        --threads 1 --method "$method" >> "$work/log.txt"
      rm -rf "$dir/frames"
    fi
    for start in paper far; do
      args=""
      [ "$start" = far ] && args=$far
      t0=$(date +%s.%N)
      # shellcheck disable=SC2086  # $args: several options
      nice "$dimerlab" compare "$dir/track_$lighting.h5" --fit $args -o "$dir/fit_${lighting}_$start" --force -q \
        >> "$work/log.txt"
      t1=$(date +%s.%N)
      echo "$ar $gamma $eps $mh $mhs $mu $mus $lighting $start $(echo "$t1 - $t0" | bc) $dir/fit_${lighting}_$start/compare.h5" >> "$results"
    done
  done
done

printf 'fit_study_tracked.sh: %s cores, load average %s\n\n' "$(nproc)" "$(cut -d' ' -f1 /proc/loadavg)"
/usr/bin/python3 - "$results" <<'EOF'
import sys

sys.path.insert(0, "bench")  # the scripts run from the repository's top
from h5dump_read import values as dataset

names = {"paper": "paper's", "far": "far"}
tally = {}
print("| scene: A_r, Γ; truth | lighting | start | ε | μ̂ | μ̂_s | μ | μ_s | χ²/dof at the floors | p | floor scale | simulations | s |")
print("|---|---|---|---|---|---|---|---|---:|---:|---:|---:|---:|")
for line in open(sys.argv[1]):
    f = line.split()
    ar, gamma, truth, lighting, start, seconds, path = f[0], f[1], [float(x) for x in f[2:7]], f[7], f[8], float(f[9]), f[10]
    status = dataset(path, "/fit/status")
    value, err = [float(x) for x in dataset(path, "/fit/value")], [float(x) for x in dataset(path, "/fit/err")]
    lo, hi = [float(x) for x in dataset(path, "/fit/range_lo")], [float(x) for x in dataset(path, "/fit/range_hi")]
    sims = float(dataset(path, "/fit/summary")[3])
    scale, chi2_dof, p = [float(x) for x in dataset(path, "/fit/floors")]
    t = tally.setdefault(start, [0, 0, 0, 0, 0, 0, 0.0])  # fits, acceptable, constrained, held, bounds, held, s
    t[0] += 1
    t[1] += status[0] != "no_acceptable_fit"
    t[6] += seconds
    cells = []
    for k in range(5):
        holds = lo[k] <= truth[k] <= hi[k]
        mark = "" if holds else " **misses**"
        if status[k] == "constrained":
            cells.append(f"{value[k]:.4f} ± {err[k]:.4f}{mark}")
            t[2] += 1; t[3] += holds
        elif status[k] == "bounded_above":
            cells.append(f"≤ {hi[k]:.3g}{mark}"); t[4] += 1; t[5] += holds
        elif status[k] == "bounded_below":
            cells.append(f"≥ {lo[k]:.3g}{mark}"); t[4] += 1; t[5] += holds
        elif status[k] == "unconstrained":
            cells.append("unconstrained")
        else:
            cells.append("none")
    scene = f"{float(ar):.1f}, {float(gamma):.2f}; " + ", ".join(f"{x:.2f}" for x in truth)
    print(f"| {scene} | {lighting} | {names[start]} | " + " | ".join(cells) +
          f" | {chi2_dof:.3g} | {p:.3g} | {scale:.3g} | {sims:.0f} | {seconds:.0f} |")
print()
# The coverage as text, not a table: docs/BENCHMARKS.md quotes it in the section's prose.
for start, t in tally.items():
    share = f"{100.0 * t[3] / t[2]:.0f} %" if t[2] else "-"
    print(f"from the {names[start]} start: {t[1]} of {t[0]} fits acceptable; {t[3]} of {t[2]} constrained "
          f"ranges ({share}) and {t[5]} of {t[4]} bounds hold the truth; {t[6] / t[0]:.0f} s a fit")
EOF
