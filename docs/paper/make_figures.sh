#!/usr/bin/env bash
# Makes every figure of docs/PAPER.md from scratch: each sweep of samples/sweeps/ (one dimerlab
# command each), its rows as TSV in docs/paper/data/, the PNGs by gnuplot, and the numbers quoted
# in PAPER.md (docs/paper/data/summary.txt).
#   docs/paper/make_figures.sh [path/to/dimerlab]      (from anywhere; default build/app/dimerlab)
# Set SWEEPS="fig4a gamma_curve" to redo only some. The sweep files themselves (.h5) go to a
# temporary folder: the TSV holds every row.
set -euo pipefail
cd "$(dirname "$0")/../.."
D=$(realpath "${1:-build/app/dimerlab}")
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
mkdir -p docs/paper/data
export SOURCE_DATE_EPOCH=${SOURCE_DATE_EPOCH:-0}
for s in ${SWEEPS:-fig4a fig4a_similar fig4b gamma_curve mode_map_fine}; do
  echo "== $s: dimerlab sweep --spec samples/sweeps/$s.sweep -o $s.h5 --tsv docs/paper/data/$s.tsv" >&2
  start=$(date +%s%N)
  "$D" sweep --spec "samples/sweeps/$s.sweep" -o "$TMP/$s.h5" --tsv "$TMP/$s.tsv" -q
  mv "$TMP/$s.tsv" "docs/paper/data/$s.tsv"
  ms=$(( ($(date +%s%N) - start) / 1000000 ))
  # One line per sweep in wall_times.tsv, replaced when that sweep is redone.
  { grep -v "^$s	" docs/paper/data/wall_times.tsv 2>/dev/null || true
    printf '%s\t%d.%03d s on %d cores\n' "$s" $((ms / 1000)) $((ms % 1000)) "$(nproc)"; } > "$TMP/times"
  mv "$TMP/times" docs/paper/data/wall_times.tsv
done
for g in fig4a fig4b gamma_curve mode_map; do gnuplot "docs/paper/$g.gp"; done
awk -f docs/paper/summarize.awk docs/paper/data/fig4a.tsv docs/paper/data/fig4a_similar.tsv \
  docs/paper/data/fig4b.tsv docs/paper/data/gamma_curve.tsv docs/paper/data/mode_map_fine.tsv \
  > docs/paper/data/summary.txt
{ echo; echo "== wall time per sweep (docs/paper/data/wall_times.tsv)"; cat docs/paper/data/wall_times.tsv; } >> docs/paper/data/summary.txt
cat docs/paper/data/summary.txt
