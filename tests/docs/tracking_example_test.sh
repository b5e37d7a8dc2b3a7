#!/usr/bin/env bash
# Runs docs/TRACKING.md's worked example as a reader would: every line of its ```bash blocks, in
# order, in a fresh folder, with the built dimerlab and make_povray_footage first on the PATH;
# then checks what the page says the example shows: auto chose the template, and --ar gave the
# scale within 0.5 % of the footage's 2e-4 m/px. Exit 77 (skipped) without POV-Ray.
# Usage: tracking_example_test.sh REPO_ROOT DIMERLAB_DIR MAKE_POVRAY_FOOTAGE_DIR
set -u
ROOT=$(cd "$1" && pwd)
export PATH="$(cd "$2" && pwd):$(cd "$3" && pwd):$PATH"
command -v povray >/dev/null || { echo "povray is not installed: skipped"; exit 77; }
command -v h5dump >/dev/null || { echo "h5dump is not installed: skipped"; exit 77; }
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
awk '/^```bash/ { on = 1; next } /^```/ { on = 0 } on' "$ROOT/docs/TRACKING.md" >"$WORK/example.sh"
[ -s "$WORK/example.sh" ] || { echo "no \`\`\`bash block in docs/TRACKING.md"; exit 1; }
echo "== the example =="; cat "$WORK/example.sh"
echo "== its output =="
(cd "$WORK" && bash -e -o pipefail example.sh) 2>&1 | tee "$WORK/out.txt"
[ "${PIPESTATUS[0]}" -eq 0 ] || { echo "FAIL: the example failed"; exit 1; }
fail=0
grep -q 'method auto -> template' "$WORK/out.txt" ||
  { echo "FAIL: track did not say that auto chose the template"; fail=1; }
scale=$(h5dump -a /m_per_px "$WORK/front_point_ar.h5" | awk '/\(0\):/ { print $2 }')
awk -v s="$scale" 'BEGIN { e = s / 2e-4 - 1; exit !(e < 0.005 && e > -0.005) }' ||
  { echo "FAIL: --ar gave $scale m/px, not 2e-4 within 0.5 %"; fail=1; }
[ "$fail" -eq 0 ] && echo "ok: the worked example runs and shows what the page says (scale $scale m/px)"
exit "$fail"
