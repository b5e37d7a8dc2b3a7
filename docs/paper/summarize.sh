#!/usr/bin/env bash
# The numbers docs/PAPER.md quotes, from the sweep TSVs: human-readable sections, then one
# `name = value` line per number (docs/paper/render_paper.sh fills them into PAPER.md.in).
#   docs/paper/summarize.sh [DATA_DIR]      (default docs/paper/data)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
cd "${1:-$here/data}"
awk -f "$here/summarize.awk" fig4a.tsv fig4a_similar.tsv fig4b.tsv gamma_curve.tsv \
  mode_map_fine.tsv fig4a_drops.tsv mode_map_basins.tsv releases.tsv
