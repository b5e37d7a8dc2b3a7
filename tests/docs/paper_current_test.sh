#!/usr/bin/env bash
# docs/paper cannot go stale: reruns the cheap sweeps of docs/paper/make_figures.sh in full (Fig.
# 4a, the Gamma curve) and every other one on a subsample (a shard; one seed of the basin sweeps;
# one lift of the releases), and fails when a row differs from the committed TSV. Then checks
# that summary.txt is what summarize.sh makes of the committed data, and docs/PAPER.md what
# render_paper.sh makes of that (so no number in it is typed by hand).
#   paper_current_test.sh SOURCE_DIR DIMERLAB
set -uo pipefail
src=$1 D=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
data=$src/docs/paper/data
export SOURCE_DATE_EPOCH=0
fail=0
stale() {  # $1 = what, $2 = diff file
  echo "STALE: $1 differs from a rerun (docs/paper/make_figures.sh makes it again):"
  head -n 6 "$2"
  fail=1
}
sweep() {  # $1 = output name, rest = sweep arguments
  local name=$1; shift
  "$D" sweep "$@" -o "$tmp/$name.h5" --tsv "$tmp/$name.tsv" -q > /dev/null ||
    { echo "FAIL: dimerlab sweep $*"; fail=1; }
}
# The rows of $2 (a rerun) against the committed rows of $1 with the same grid index (column
# $3), taken from the block that follows the line "$4" ("" = the whole file), each row prefixed
# as in the committed file by $5.
same_rows() {
  awk -F'\t' -v col="$3" -v block="$4" -v prefix="$5" '
    FNR == NR { if ($0 == block) on = 1; else if (/^# seed/ && block != "") on = 0
                if ((block == "" || on) && !/^#/) C[$col] = $0; next }
    /^#/ { next }
    { row = prefix $0; split(row, f, "\t"); if (C[f[col]] != row) { print "rerun:     " row; print "committed: " C[f[col]]; bad++ } ; n++ }
    END { if (n == 0) print "no rows rerun"; exit (bad > 0 || n == 0) }' "$1" "$2"
}

for s in fig4a gamma_curve; do
  sweep "$s" --spec "$src/samples/sweeps/$s.sweep"
  diff "$data/$s.tsv" "$tmp/$s.tsv" > "$tmp/$s.diff" || stale "docs/paper/data/$s.tsv" "$tmp/$s.diff"
done
sweep fig4b --spec "$src/samples/sweeps/fig4b.sweep" --shard 3/16
same_rows "$data/fig4b.tsv" "$tmp/fig4b.tsv" 11 "" "" > "$tmp/fig4b.diff" ||
  stale "docs/paper/data/fig4b.tsv (shard 3/16)" "$tmp/fig4b.diff"
sweep mode_map_fine --spec "$src/samples/sweeps/mode_map_fine.sweep" --shard 7/101
same_rows "$data/mode_map_fine.tsv" "$tmp/mode_map_fine.tsv" 11 "" "" > "$tmp/mm.diff" ||
  stale "docs/paper/data/mode_map_fine.tsv (shard 7/101)" "$tmp/mm.diff"
sweep drops --spec "$src/samples/sweeps/fig4a_drops.sweep" --seed 3 --shard 2/9
same_rows "$data/fig4a_drops.tsv" "$tmp/drops.tsv" 11 "# seed 3" "" > "$tmp/drops.diff" ||
  stale "docs/paper/data/fig4a_drops.tsv (seed 3, shard 2/9)" "$tmp/drops.diff"
sweep basins --spec "$src/samples/sweeps/mode_map.sweep" --seed 5 --shard 4/11
same_rows "$data/mode_map_basins.tsv" "$tmp/basins.tsv" 11 "# seed 5" "" > "$tmp/basins.diff" ||
  stale "docs/paper/data/mode_map_basins.tsv (seed 5, shard 4/11)" "$tmp/basins.diff"
sweep releases --ar 3.2,3.3,5.7,5.8,5.9 --freq 25,75 --init drift --lift 0.3 --transient 100 \
  --periods 200
same_rows <(grep '^0.3	' "$data/releases.tsv") "$tmp/releases.tsv" 12 "" "0.3	" > "$tmp/rel.diff" ||
  stale "docs/paper/data/releases.tsv (lift 0.3)" "$tmp/rel.diff"

bash "$src/docs/paper/summarize.sh" "$data" > "$tmp/summary.txt" || fail=1
diff "$data/summary.txt" "$tmp/summary.txt" > "$tmp/summary.diff" ||
  stale "docs/paper/data/summary.txt" "$tmp/summary.diff"
bash "$src/docs/paper/render_paper.sh" "$data/summary.txt" "$data/wall_times.tsv" > "$tmp/PAPER.md" ||
  fail=1
diff "$src/docs/PAPER.md" "$tmp/PAPER.md" > "$tmp/paper.diff" || stale "docs/PAPER.md" "$tmp/paper.diff"
[ "$fail" = 0 ] && echo "docs/paper is current"
exit "$fail"
