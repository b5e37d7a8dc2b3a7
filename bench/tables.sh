#!/usr/bin/env bash
# Markdown tables <-> TSV, the two forms of a benchmark's results.
#   tables.sh tsv < TEXT   every Markdown table in TEXT (a bench program's output, or a section of
#                          docs/BENCHMARKS.md) as TSV: a header row and data rows per table, one
#                          blank line between tables; the |---| alignment rows dropped.
#   tables.sh md < TSV     the same tables as Markdown (first column left-aligned, others right).
# bench/results/MACHINE/BENCH.tsv is the first form of BENCH's output (./dimerlab.sh bench writes
# it); docs/BENCHMARKS.md shows the second, and docs.benchmark_tables checks that they agree.
set -euo pipefail
case "${1:-}" in
  tsv)
    awk '
      /^[[:space:]]*\|/ {
        line = $0
        sub(/^[[:space:]]*\|/, "", line); sub(/\|[[:space:]]*$/, "", line)
        if (line ~ /^[-:| ]+$/) next                       # the alignment row
        gsub(/\\\|/, "\001", line)                          # an escaped | inside a cell
        n = split(line, cell, "|"); out = ""
        for (i = 1; i <= n; ++i) {
          c = cell[i]; gsub(/^[[:space:]]+|[[:space:]]+$/, "", c); gsub("\001", "|", c)
          out = out (i > 1 ? "\t" : "") c
        }
        if (!in_table && tables++) print ""
        print out; in_table = 1; next
      }
      { in_table = 0 }'
    ;;
  md)
    awk -F'\t' '
      NF == 0 || $0 == "" { if (rows) print ""; rows = 0; next }
      {
        line = "|"
        for (i = 1; i <= NF; ++i) { c = $i; gsub(/\|/, "\\|", c); line = line " " c " |" }
        print line
        if (!rows++) {
          sep = "|---|"; for (i = 2; i <= NF; ++i) sep = sep "---:|"
          print sep
        }
      }'
    ;;
  *) echo "usage: $0 tsv|md < INPUT" >&2; exit 2 ;;
esac
