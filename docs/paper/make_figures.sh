#!/usr/bin/env bash
# Makes every figure of docs/PAPER.md from scratch: each sweep of samples/sweeps/ (one dimerlab
# command each), its rows as TSV in docs/paper/data/, the PNGs by gnuplot, the numbers in
# docs/paper/data/summary.txt, and docs/PAPER.md itself from docs/paper/PAPER.md.in with those
# numbers filled in (docs/paper/render_paper.sh).
#   docs/paper/make_figures.sh [path/to/dimerlab]      (from anywhere; default build/app/dimerlab)
# Set SWEEPS="fig4a gamma_curve" to redo only some. The sweep files themselves (.h5) go to a
# temporary folder: the TSV holds every row. The test docs.paper_current reruns the cheap sweeps
# and a subsample of the others and fails when the committed data or PAPER.md differ.
set -euo pipefail
cd "$(dirname "$0")/../.."
D=$(realpath "${1:-build/app/dimerlab}")
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
mkdir -p docs/paper/data
export SOURCE_DATE_EPOCH=${SOURCE_DATE_EPOCH:-0}
SEEDS=8  # random drops per point of the basin sweeps

# One line per sweep in wall_times.tsv, replaced when that sweep is redone.
record_time() {  # $1 = name, $2 = start (ns)
  local ms=$(( ($(date +%s%N) - $2) / 1000000 ))
  { grep -v "^$1	" docs/paper/data/wall_times.tsv 2>/dev/null || true
    printf '%s\t%d.%03d s on %d cores\n' "$1" $((ms / 1000)) $((ms % 1000)) "$(nproc)"; } > "$TMP/times"
  mv "$TMP/times" docs/paper/data/wall_times.tsv
}

# A sweep of one spec, its rows to docs/paper/data/NAME.tsv.
one_sweep() {  # $1 = name
  "$D" sweep --spec "samples/sweeps/$1.sweep" -o "$TMP/$1.h5" --tsv "$TMP/$1.tsv" -q
  mv "$TMP/$1.tsv" "docs/paper/data/$1.tsv"
}

# Basins: the same grid dropped from SEEDS random states per point (--seed 1..SEEDS); the rows of
# every seed, each block headed by its seed, in docs/paper/data/NAME.tsv.
basin_sweep() {  # $1 = name, $2 = spec
  local seed
  : > "$TMP/$1.all"
  for seed in $(seq 1 $SEEDS); do
    "$D" sweep --spec "samples/sweeps/$2.sweep" --seed "$seed" -o "$TMP/$1.$seed.h5" \
      --tsv "$TMP/$1.$seed.tsv" -q
    { echo "# seed $seed"; cat "$TMP/$1.$seed.tsv"; } >> "$TMP/$1.all"
  done
  mv "$TMP/$1.all" "docs/paper/data/$1.tsv"
}

# Releases: the drift release at a few A_r where the orbit depends on it, at each lift (fraction
# of d; "default": 0.3 d x (25 Hz / f)^2); rows prefixed by the lift.
release_sweep() {
  local lift
  : > "$TMP/releases.all"
  for lift in default 0.05 0.1 0.2 0.3 0.5; do
    "$D" sweep --ar 3.2,3.3,5.7,5.8,5.9 --freq 25,75 --init drift --lift "$lift" \
      --transient 100 --periods 200 -o "$TMP/rel.$lift.h5" --tsv "$TMP/rel.$lift.tsv" -q
    grep -v '^#' "$TMP/rel.$lift.tsv" | sed "s/^/$lift\t/" >> "$TMP/releases.all"
  done
  mv "$TMP/releases.all" docs/paper/data/releases.tsv
}

for s in ${SWEEPS:-fig4a fig4a_similar fig4b gamma_curve mode_map_fine fig4a_drops mode_map_basins releases}; do
  echo "== $s" >&2
  start=$(date +%s%N)
  case "$s" in
    fig4a_drops) basin_sweep fig4a_drops fig4a_drops ;;
    mode_map_basins)
      basin_sweep mode_map_basins mode_map
      awk -f docs/paper/basin_fractions.awk docs/paper/data/mode_map_basins.tsv \
        > docs/paper/data/mode_map_basins_fractions.tsv ;;
    releases) release_sweep ;;
    *) one_sweep "$s" ;;
  esac
  record_time "$s" "$start"
done
for g in fig4a fig4b gamma_curve mode_map fig4a_drops mode_map_basins; do gnuplot "docs/paper/$g.gp"; done
docs/paper/summarize.sh > docs/paper/data/summary.txt
docs/paper/render_paper.sh docs/paper/data/summary.txt docs/paper/data/wall_times.tsv > docs/PAPER.md
cat docs/paper/data/summary.txt
