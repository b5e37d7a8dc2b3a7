#!/usr/bin/env bash
# docs/PAPER.md from docs/paper/PAPER.md.in: each {{name}} becomes the value of `name = value` in
# the summary's numbers (docs/paper/summarize.sh), each {{wall:SWEEP}} the sweep's line of
# wall_times.tsv. A name with no value is an error: PAPER.md never quotes a number by hand.
#   docs/paper/render_paper.sh SUMMARY WALL_TIMES > docs/PAPER.md
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
awk -v summary="$1" -v walls="$2" '
  BEGIN {
    while ((getline line < summary) > 0) {
      if (line ~ /^== numbers/) { on = 1; continue }
      if (!on) continue
      i = index(line, " = "); V[substr(line, 1, i - 1)] = substr(line, i + 3)
    }
    FS = "\t"
    while ((getline line < walls) > 0) { split(line, w, "\t"); sub(/ on .*/, "", w[2]); V["wall:" w[1]] = w[2] }
  }
  {
    out = ""; rest = $0
    while ((i = index(rest, "{{")) > 0) {
      j = index(substr(rest, i), "}}")
      if (j == 0) break
      name = substr(rest, i + 2, j - 3)
      if (!(name in V)) { printf "render_paper.sh: no value for {{%s}} (line %d of PAPER.md.in)\n", name, NR > "/dev/stderr"; bad = 1 }
      out = out substr(rest, 1, i - 1) V[name]; rest = substr(rest, i + j + 1)
    }
    print out rest
  }
  END { exit bad }
' "$here/PAPER.md.in"
