#!/usr/bin/env bash
# docs/BENCHMARKS.md shows the committed results: in each section, the tables (as TSV, through
# bench/tables.sh) equal the file its "results: `bench/results/...tsv`" names, and every section
# names one. With --write, writes those files from the page instead of checking.
# Usage: benchmark_tables_test.sh REPO_ROOT [--write]
set -u
ROOT=$(cd "$1" && pwd)
DOC="$ROOT/docs/BENCHMARKS.md"
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
# One file per section: its text, named by its number.
awk -v dir="$WORK" '/^## / { n++ } n { print > (dir "/section_" n) }' "$DOC"
failed=0 checked=0
for section in $(ls -v "$WORK"/section_*); do
  title=$(head -1 "$section")
  tsv=$(grep -o 'results: `bench/results/[^`]*\.tsv`' "$section" | head -1 | sed 's/^results: `//; s/`$//')
  if [ -z "$tsv" ]; then
    echo "FAIL: $title: no 'results: \`bench/results/...tsv\`' line"; failed=1; continue
  fi
  bash "$ROOT/bench/tables.sh" tsv <"$section" >"$WORK/tables.tsv"
  if [ "${2:-}" = --write ]; then
    mkdir -p "$(dirname "$ROOT/$tsv")"; cp "$WORK/tables.tsv" "$ROOT/$tsv"; echo "wrote $tsv"; continue
  fi
  checked=$((checked + 1))
  if [ ! -f "$ROOT/$tsv" ]; then
    echo "FAIL: $title: $tsv does not exist"; failed=1
  elif ! diff -u "$ROOT/$tsv" "$WORK/tables.tsv" >"$WORK/diff"; then
    echo "FAIL: $title: its tables differ from $tsv (- the file, + the page):"; sed 's/^/    /' "$WORK/diff"
    failed=1
  else
    echo "ok:   $title = $tsv ($(grep -c . "$ROOT/$tsv") rows)"
  fi
done
[ "${2:-}" = --write ] && exit 0
[ "$checked" -gt 0 ] || { echo "no section found: the extraction is broken"; exit 1; }
exit "$failed"
