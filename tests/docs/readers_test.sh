#!/usr/bin/env bash
# Other readers open dimerlab's files with no plugin (docs/FORMATS.md, "Storage and
# integrity"): h5dump reads every dataset through the filters and checksums, and h5py (when
# installed; the test is skipped otherwise) reads the data and the self-description.
# Usage: readers_test.sh path/to/dimerlab
set -eu
BIN=$1
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
"$BIN" sim --cycles 2 -q -o sim.h5 >/dev/null
h5dump sim.h5 >dump.txt
grep -q 'DATASET "left"' dump.txt
grep -q 'CHECKSUM FLETCHER32' <(h5dump -p -d /state sim.h5)
PY=/usr/bin/python3
if ! "$PY" -c "import h5py" 2>/dev/null; then
  echo "h5py not installed: h5py part skipped (apt-get install python3-h5py)"
  exit 77
fi
"$PY" - <<'PYEOF'
import h5py
with h5py.File("sim.h5") as f:
    n = len(f["/t"])
    assert n == 161, n
    assert f["/tips/left"].shape == (n, 2)
    assert f["/tips/left"].attrs["columns"].decode() == "x,z"
    assert f["/state"].attrs["units"].decode() == "m,m,rad,m/s,m/s,rad/s"
    assert f.attrs["kind"].decode() == "sim"
    assert f.attrs["drift_speed_units"].decode() == "m/s"
    kinds = set(f["/events/kind"].asstr()[:])
    assert kinds <= {"impact", "double_impact", "collapse", "liftoff", "stick", "slip", "painleve"}, kinds
print("h5py", h5py.__version__, "reads the sim file")
PYEOF
