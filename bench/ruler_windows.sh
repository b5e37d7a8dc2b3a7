#!/usr/bin/env bash
# The ruler's POV-Ray film (ruler_above_plate rendered to 100 frames: a white band behind the
# spheres' lower halves, the right sphere hopping up to 16.5 px in front of it) tracked over
# windows of it, as a user cuts a recording with `--frames`: windows of 20, 40 and 60 frames in
# 10-frame steps, each with the scale (its truth.csv's m_per_px) and without. Per window: the
# method run, each sphere's worst distance from its truth over the window's frames, the
# warnings `track` gave, whether the dimer's length warned (`length_departs`), and whether the
# learning's length referee learnt a sphere again (tracking/length_relearn.h); then the counts
# (docs/BENCHMARKS.md, ruler_windows.sh; docs/TRACKING.md, Limits).
# FILM: the 100-frame film, e.g. build/povray_footage_cache/ruler_above_plate_100_frames (the
# test povray.long_ruler renders it), or bench_tracking_footage's 100-frame cache.
#   bench/ruler_windows.sh [BUILD_DIR] [FILM] [WORK_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
film=${2:-$build/povray_footage_cache/ruler_above_plate_100_frames}
work=${3:-ruler_windows}
dimerlab="$build/app/dimerlab"
[ -f "$film/truth.csv" ] || { echo "ruler_windows.sh: $film/truth.csv: no such film" >&2; exit 1; }
scale=$(grep -o 'm_per_px=[0-9.e-]*' "$film/truth.csv" | cut -d= -f2)
frames=$(grep -c '^[0-9]' "$film/truth.csv")
mkdir -p "$work"
results="$work/results.txt"
: >"$results"
for first in 0 10 20 30 40 50 60; do
  for span in 20 40 60; do
    end=$((first + span))
    [ "$end" -le "$frames" ] || continue
    for given in scale none; do
      args=()
      [ "$given" = scale ] && args=(--m-per-px "$scale")
      track="$work/track_${first}_${end}_$given.h5"
      # A window `track` refuses (exit 1, one line) is a row of its own.
      if "$dimerlab" track "$film" "${args[@]}" --frames "$first:$end" -o "$track" --force \
           >/dev/null 2>"$work/stderr.txt"; then
        warnings=$(grep -c 'warning:' "$work/stderr.txt" || true)
        length=$(grep -c "departs from its median" "$work/stderr.txt" || true)
        relearnt=$(grep -c "the dimer's length departed from its median by more than" \
                     "$work/stderr.txt" || true)
        echo "$first $end $given $warnings $length $relearnt $track" >>"$results"
      else
        echo "$first $end $given fail $(head -1 "$work/stderr.txt" | sed 's/^.*error: [^:]*: //')" \
          >>"$results"
      fi
    done
  done
done

printf 'ruler_windows.sh: %s, %s frames; %s cores, load average %s\n\n' "$film" "$frames" \
  "$(nproc)" "$(cut -d' ' -f1 /proc/loadavg)"
/usr/bin/python3 - "$results" "$film/truth.csv" <<'EOF'
import sys
import numpy as np

sys.path.insert(0, "bench")  # the scripts run from the repository's top
from h5dump_read import dataset, attribute

lines = [l.split(",") for l in open(sys.argv[2]) if l[:1].isdigit()]
truth = np.array([[float(x) for i, x in enumerate(r) if i != 1] for r in lines])
print("| frames | scale | method run | worst left / right (px) | warnings | the length warns "
      "| learnt again by the length | a sphere > 1 px off, no warning |")
print("|---|---|---|---|---:|---|---|---|")
count = {}  # per scale: windows, refused, off, silent, length warned, learnt again
for line in open(sys.argv[1]):
    f = line.split()
    first, end, given = int(f[0]), int(f[1]), f[2]
    c = count.setdefault(given, [0] * 6)
    c[0] += 1
    if f[3] == "fail":
        c[1] += 1
        print(f"| {first}:{end} | {given} | fails ({' '.join(f[4:])}) | | | | | |")
        continue
    warnings, length, relearnt, track = int(f[3]), int(f[4]), int(f[5]), f[6]
    worst = []
    for name, col in (("left", 2), ("right", 4)):
        e = dataset(track, "/pixels/" + name).reshape(-1, 2) - truth[first:end, col:col + 2]
        worst.append(np.nanmax(np.hypot(e[:, 0], e[:, 1])))
    off = max(worst) > 1.0
    silent = off and warnings == 0
    for i, flag in enumerate((off, silent, length > 0, relearnt > 0)):
        c[2 + i] += flag
    print(f"| {first}:{end} | {given} | {attribute(track, '/method')} "
          f"| {worst[0]:.2f} / {worst[1]:.2f} | {warnings} | {'yes' if length else 'no'} "
          f"| {'yes' if relearnt else 'no'} | {'**yes**' if silent else 'no'} |")
print()
print("| scale | windows | refused | a sphere > 1 px off | of those, no warning | the length warns "
      "| learnt again by the length |")
print("|---|---:|---:|---:|---:|---:|---:|")
for given, c in count.items():
    print(f"| {'given' if given == 'scale' else 'none'} | " + " | ".join(str(x) for x in c) + " |")
EOF
