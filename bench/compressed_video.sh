#!/usr/bin/env bash
# The POV-Ray drift film (bench/povray_film.sh) exported as a lab exports its films: FFV1
# (lossless), Motion JPEG and H.264 at two qualities (ffmpeg), each tracked as a video file and
# compared with the simulation. Prints, per export: the file size, the tracked centres and plate
# against truth.csv, the offsets' stated uncertainties, A_r as compare measures it, the drift and
# the slip. docs/BENCHMARKS.md, compressed_video.sh.
#   bench/compressed_video.sh [BUILD_DIR] [FILM_DIR]
# FILM_DIR: a folder made by bench/povray_film.sh (frames/, sim.h5); default povray_film.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
film=${2:-povray_film}
dimerlab="$build/app/dimerlab"
scale=4e-4
[ -f "$film/frames/truth.csv" ] || { echo "$film/frames: run bench/povray_film.sh first" >&2; exit 2; }
work="$film/video"
mkdir -p "$work"
exports=(
  "ffv1.mkv|-c:v ffv1 -pix_fmt gray"
  "mjpeg_q3.avi|-c:v mjpeg -q:v 3 -pix_fmt yuvj420p"
  "h264_crf18.mkv|-c:v libx264 -crf 18 -pix_fmt yuv420p"
  "h264_crf23.mkv|-c:v libx264 -crf 23 -pix_fmt yuv420p"
)
echo "| export | MB | col bias L / R (px) | row bias L / R (px) | sd col / row, worst sphere (px) | stated offset σ col L / R, row L / R (px) | plate bias / worst (px) | A_r (3.9) | drift ⟨u⟩ (mm/s) | slip after (mm/s) |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for e in "${exports[@]}"; do
  name=${e%%|*}
  args=${e#*|}
  # shellcheck disable=SC2086
  ffmpeg -loglevel error -y -framerate 2000 -i "$film/frames/frame_%06d.png" $args "$work/$name"
  base=${name%.*}
  "$dimerlab" track "$work/$name" -o "$work/$base.h5" --m-per-px "$scale" --force -q 2>/dev/null
  # compare refuses a track whose A_r is not the simulation's (the error line is kept)
  rm -rf "$work/$base.compare"
  "$dimerlab" compare "$work/$base.h5" --sim "$film/sim.h5" -o "$work/$base.compare" --force -q \
    >/dev/null 2>"$work/$base.compare_error" || true
  /usr/bin/python3 - "$work/$name" "$work/$base.h5" "$film/frames/truth.csv" \
    "$work/$base.compare/summary.md" <<'PY'
import os, re, sys
import numpy as np

sys.path.insert(0, "bench")  # the scripts run from the repository's top
from h5dump_read import dataset

video, track, truth_csv, summary = sys.argv[1:5]
rows = [l.split(",") for l in open(truth_csv) if l[:1].isdigit()]
truth = np.array([[float(x) for i, x in enumerate(r) if i != 1] for r in rows])
e = [dataset(track, "/pixels/" + n).reshape(-1, 2) - truth[:, c:c + 2]
     for n, c in (("left", 2), ("right", 4))]
p = dataset(track, "/pixels/plate_row") - truth[:, 6]
err = dataset(track, "/template/offset_err").reshape(2, 2)
text = open(summary).read() if os.path.exists(summary) else ""
def grab(pattern):
    m = re.search(pattern, text)
    return m.group(1) if m else "n/a"
ar = grab(r"\| A_r \(measured\) \| ([0-9.]+) \|")
if not text:  # compare refused it: its reason holds the measured A_r
    m = re.search(r"A_r ([0-9.]+) vs", open(summary.replace(".compare/summary.md", ".compare_error")).read())
    ar = (m.group(1) + " (compare refused it)") if m else "n/a"
drift = grab(r"\| drift ⟨u⟩ \(mm/s\) \| ([^|]+) \|")
slip = grab(r"\| slip after impact \(mm/s\) \| ([^|]+) \|")
sd = max(max(x[:, 0].std(), x[:, 1].std()) for x in e)
print(f"| {os.path.basename(video)} | {os.path.getsize(video) / 1e6:.2f} "
      f"| {e[0][:, 0].mean():+.3f} / {e[1][:, 0].mean():+.3f} "
      f"| {e[0][:, 1].mean():+.3f} / {e[1][:, 1].mean():+.3f} | {sd:.3f} "
      f"| {err[0, 0]:.3f} / {err[1, 0]:.3f}, {err[0, 1]:.3f} / {err[1, 1]:.3f} "
      f"| {p.mean():+.3f} / {abs(p).max():.3f} | {ar} | {drift.strip()} | {slip.strip()} |")
PY
done
