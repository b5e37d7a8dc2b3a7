#!/usr/bin/env bash
# `--method auto` against every method on our renderer's films of the paper's scenes: the jump
# release (`dimerlab sim --ar A --init jump --cycles 4`, 321 frames) at A_r 2.0, 3.9 and 6.1,
# rendered mirror-lit (reflect) and backlit (`render --noise 2`), tracked with the scale given
# by each method and by auto, as a user runs it (files on disk, the process included).
# Per film and method: the scatter of each sphere's column and row about its mean error against
# truth.csv (the worst of the two spheres), frames with a sphere more than 0.5 px from its mean
# error, and the wall time; then auto's choice and its scatter over the best method's per axis
# (the target: within 10 %). docs/BENCHMARKS.md, auto_choice.sh.
# FOOTAGE: folders of POV-Ray footage from bench_tracking_footage's cache (frames and truth.csv,
# A_r 3.9), tracked as they are with the scale in their truth.csv, rows of their own.
#   bench/auto_choice.sh [BUILD_DIR] [WORK_DIR] [FOOTAGE...]
# Defaults: build, auto_choice (the films are rendered again on each run: ~1 s each), none.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
work=${2:-auto_choice}
footage=("${@:3}")
dimerlab="$build/app/dimerlab"
scale=2e-4
methods="centroid discfit template auto"
mkdir -p "$work"
results="$work/results.txt"
: >"$results"

# Each method on FRAMES at SCALE, a line of results.txt keyed by A_r and LIGHTING.
track_all() {
  local ar=$1 lighting=$2 frames=$3 film_scale=$4 method track start end
  for method in $methods; do
    track="$work/track_${ar}_${lighting}_$method.h5"
    start=$(date +%s.%N)
    # A method that cannot track the film (exit 1, one line) is a row of its own.
    if "$dimerlab" track "$frames" -o "$track" --method "$method" --m-per-px "$film_scale" \
         --force -q >/dev/null 2>"$work/stderr.txt"; then
      end=$(date +%s.%N)
      echo "$ar $lighting $method $(echo "$end - $start" | bc) $track $frames/truth.csv" >>"$results"
    else
      echo "$ar $lighting $method fail $(head -1 "$work/stderr.txt" | sed 's/^.*error: [^:]*: //; s/ (.*//')" \
        >>"$results"
    fi
  done
}
for ar in 2.0 3.9 6.1; do
  "$dimerlab" sim --ar "$ar" --init jump --cycles 4 -o "$work/sim_$ar.h5" --force -q &>/dev/null
  for lighting in reflect backlit; do
    frames="$work/frames_${ar}_$lighting"
    "$dimerlab" render "$work/sim_$ar.h5" -o "$frames" --lighting "$lighting" --noise 2 --force \
      -q >/dev/null
    track_all "$ar" "$lighting" "$frames" "$scale"
  done
done
for frames in "${footage[@]}"; do
  track_all 3.9 "POV-Ray_$(basename "$frames")" "$frames" \
    "$(grep -o 'm_per_px=[0-9.e-]*' "$frames/truth.csv" | cut -d= -f2)"
done

printf 'Our renderer, 512x256, 0.2 mm/px, noise 2 grey levels; 321 frames; POV-Ray footage: %s; %s cores, load average %s\n\n' \
  "${footage[*]:-none}" "$(nproc)" "$(cut -d' ' -f1 /proc/loadavg)"
/usr/bin/python3 - "$results" <<'EOF'
import sys
import numpy as np

sys.path.insert(0, "bench")  # the scripts run from the repository's top
from h5dump_read import dataset, attribute

films = {}  # (A_r, lighting) -> method -> (run, scatter per axis, frames off, frames/s) or note
for line in open(sys.argv[1]):
    f = line.split()
    key, method = (f[0], f[1]), f[2]
    if f[3] == "fail":
        films.setdefault(key, {})[method] = " ".join(f[4:])
        continue
    seconds, track, truth_csv = float(f[3]), f[4], f[5]
    lines = [l.split(",") for l in open(truth_csv) if l[:1].isdigit()]
    truth = np.array([[float(x) for i, x in enumerate(r) if i != 1] for r in lines])
    scatter = np.zeros(2)  # the worse sphere, per axis
    off = 0
    for name, col in (("left", 2), ("right", 4)):
        e = dataset(track, "/pixels/" + name).reshape(-1, 2) - truth[:, col:col + 2]
        e = e[np.isfinite(e).all(axis=1)]
        scatter = np.maximum(scatter, e.std(axis=0))
        off = max(off, int((np.abs(e - e.mean(axis=0)) > 0.5).any(axis=1).sum()))
    films.setdefault(key, {})[method] = (attribute(track, "/method"), scatter, off,
                                         len(truth) / seconds)

def cell(r):
    if isinstance(r, str):
        return "fails (" + r + ")"
    run, s, off, _ = r
    return f"{s[0]:.4f} / {s[1]:.4f}" + (f", {off} frames > 0.5 px off" if off else "")

print("| A_r, lighting | centroid: column / row scatter (px) | discfit | template | auto runs "
      "| auto | auto / best, column / row | within 10 % | frames/s: centroid / discfit / "
      "template / auto |")
print("|---|---|---|---|---|---|---|---|---|")
for key, by in films.items():
    auto = by["auto"]
    best = np.min([r[1] for m, r in by.items() if m != "auto" and not isinstance(r, str)],
                  axis=0)
    ratio = auto[1] / best
    rates = " / ".join("-" if isinstance(by[m], str) else f"{by[m][3]:.0f}"
                       for m in ("centroid", "discfit", "template", "auto"))
    print(f"| {key[0]}, {key[1].replace('_', ' ')} | {cell(by['centroid'])} | {cell(by['discfit'])} "
          f"| {cell(by['template'])} | {auto[0]} | {cell(auto)} | {ratio[0]:.2f} / {ratio[1]:.2f} "
          f"| {'yes' if (ratio <= 1.1).all() else 'no'} | {rates} |")
EOF
