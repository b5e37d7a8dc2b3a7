#!/usr/bin/env bash
# The whole pipeline on a film the project did not draw: the sample drift scene simulated,
# rendered by POV-Ray (tests/footage: polished steel lit by point lights, a perspective camera,
# the plate's front edge nearer the camera than the dimer), tracked and compared with the
# simulation. Prints the tracker's accuracy against the scene's truth, then the compare table
# (track against simulation), then Gamma again with the plate edge's own scale given.
# docs/BENCHMARKS.md, povray_film.sh.
#   bench/povray_film.sh [BUILD_DIR] [WORK_DIR] [CYCLES] [ROLL_DEG] [TILT_DEG] [INIT] [LIGHTING]
# Defaults: build, povray_film, 30 plate periods (2401 frames at 2000 frames/s), a level camera
# (ROLL_DEG: the camera turned about its axis, the plate's edge sloping) and a level plate
# (TILT_DEG: the plate tilted, > 0 rising toward +x, simulated so and seen by a level camera;
# compare takes the tilt from the sim file and compares in the plate's frame) and the scene's
# release, drift (INIT jump: both ends fly, and the flights give the plate's tilt back), and
# front_point lighting (LIGHTING: any of make_povray_footage --lighting's). The frames are
# 320x160 at 0.4 mm/px, one exposure slice, noise 2 grey levels; the footage is kept in
# WORK_DIR/frames and reused while its scenes are unchanged (POV-Ray: ~6 min on 2 cores).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
work=${2:-povray_film}
cycles=${3:-30}
roll=${4:-0}
tilt=${5:-0}
init=${6:-drift}
lighting=${7:-front_point}
dimerlab="$build/app/dimerlab"
footage="$build/tests/footage/make_povray_footage"
scale=4e-4
mkdir -p "$work"

"$dimerlab" sim --scene samples/drift_ar3.9.scene --cycles "$cycles" --tilt-deg "$tilt" --init "$init" \
  -o "$work/sim.h5" --force -q
frames=$((cycles * 80 + 1))  # 25 Hz at 2000 samples/s, both ends
"$footage" --sim "$work/sim.h5" --frames "$frames" --lighting "$lighting" --subframes 1 \
  --width 320 --height 160 --m-per-px "$scale" --horizon-row 124.5 --roll-deg "$roll" \
  -o "$work/frames" --reuse -q
start=$(date +%s.%N)
"$dimerlab" track "$work/frames" -o "$work/track.h5" --m-per-px "$scale" --force -q
end=$(date +%s.%N)
"$dimerlab" compare "$work/track.h5" --sim "$work/sim.h5" -o "$work/compare" --force -q

printf 'POV-Ray film: %s frames, 320x160, %s m/px, %s, camera roll %s deg, plate tilt %s deg, %s; %s cores, ' \
  "$frames" "$scale" "$lighting" "$roll" "$tilt" "$init" "$(nproc)"
printf 'load average %s;\n' "$(cut -d' ' -f1 /proc/loadavg)"
printf 'dimerlab track: %.1f s (the scene: Gamma 0.9, f 25 Hz)\n' "$(echo "$end - $start" | bc)"
echo
# The tracked centres and plate against truth.csv (px): mean and sd of the error per axis.
/usr/bin/python3 - "$work/track.h5" "$work/frames/truth.csv" <<'EOF'
import sys
import numpy as np

sys.path.insert(0, "bench")  # the scripts run from the repository's top
from h5dump_read import dataset

track, truth_csv = sys.argv[1], sys.argv[2]
rows = [l.split(",") for l in open(truth_csv) if l[:1].isdigit()]
truth = np.array([[float(x) for i, x in enumerate(r) if i != 1] for r in rows])
print("| tracked against truth (px) | column bias | column sd | row bias | row sd |")
print("|---|---|---|---|---|")
for name, col in (("left", 2), ("right", 4)):
    e = dataset(track, "/pixels/" + name).reshape(-1, 2) - truth[:, col:col + 2]
    print(f"| {name} sphere | {e[:, 0].mean():+.3f} | {e[:, 0].std():.3f} | "
          f"{e[:, 1].mean():+.3f} | {e[:, 1].std():.3f} |")
p = dataset(track, "/pixels/plate_row") - truth[:, 6]
print(f"| plate row | | | {p.mean():+.3f} | {p.std():.3f} (worst {abs(p).max():.3f}) |")
EOF
echo
grep -E '^\| (Γ|plate amplitude) ' "$work/compare/summary.md"
sed -n '/^| quantity | track | simulation |/,/^$/p' "$work/compare/summary.md"

# The plate's front edge is half the plate's depth nearer the camera than the dimer, so it moves
# more px per metre: tracked again with that edge's own scale (--plate-m-per-px), as a user who
# calibrates at the edge would, Gamma read off the plate again.
plate_scale=$(/usr/bin/python3 -c "import json, sys; f = json.load(open(sys.argv[1]))
d = f['camera_distance']; print('%.10g' % ($scale * (d - f['plate_depth'] / 2) / d))" \
  "$work/frames/footage.json")
"$dimerlab" track "$work/frames" -o "$work/track_plate_scale.h5" --m-per-px "$scale" \
  --plate-m-per-px "$plate_scale" --force -q
"$dimerlab" compare "$work/track_plate_scale.h5" --sim "$work/sim.h5" \
  -o "$work/compare_plate_scale" --force -q
echo "With --plate-m-per-px $plate_scale (the front edge's scale):"
grep -E '^\| (Γ|plate amplitude) ' "$work/compare_plate_scale/summary.md"
