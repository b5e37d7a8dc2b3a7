#!/usr/bin/env bash
# The exit-code table of the README ("Exit codes"), checked row by row through the real binary:
#   0 success, 1 bad input or failed run, 2 usage error, 130 interrupted.
# Each case also checks the one-line message, so a case cannot pass for the wrong reason.
# Usage: exit_codes_test.sh path/to/dimerlab
set -u
BIN=$1
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
failures=0

# expect CODE REGEX ARGS...: runs `dimerlab ARGS`, checks the exit code and that stderr matches
# REGEX (extended grep; "" matches anything) and holds exactly one "error:" line (none for 0).
expect() {
  local code=$1 regex=$2; shift 2
  "$BIN" "$@" >out.txt 2>err.txt
  local rc=$?
  local errors
  errors=$(grep -c "error:" err.txt)
  local want_errors=1
  [ "$code" -eq 0 ] && want_errors=0
  if [ "$rc" -ne "$code" ] || [ "$errors" -ne "$want_errors" ] ||
     { [ -n "$regex" ] && ! grep -Eq -- "$regex" err.txt; }; then
    echo "FAIL: dimerlab $* -> exit $rc (want $code), stderr:"; sed 's/^/    /' err.txt
    echo "    (want a match for: '$regex', and $want_errors error line(s))"
    failures=$((failures + 1))
  else
    echo "ok:   exit $rc  dimerlab $*"
  fi
}

# 0: success, including --help and --version.
expect 0 '' sim --cycles 2 --fps 200 -q -o ok.h5
expect 0 '' --version
expect 0 '' sim --help

# 2: usage errors: unknown subcommand or option (named, with the nearest valid one), bad value,
# missing required option. Only the root cause is reported.
expect 2 "unknown subcommand 'simm'; did you mean 'sim'" simm -o x.h5
expect 2 "unknown subcommand 'trak'; did you mean 'track'" trak frames -o x.h5
expect 2 "a subcommand is required" 
expect 2 "unknown option '--fsp'; did you mean '--fps'" sim --fsp 100 -o x.h5
expect 2 "unknown option '--lightning'; did you mean '--lighting'" render ok.h5 -o f --lightning reflect
expect 2 "--init: bogus" sim --init bogus -o x.h5
expect 2 "--lighting 'bogus'" render ok.h5 -o f --lighting bogus
expect 2 "--method 'bogus'" track f -o x.h5 --method bogus
expect 2 "^dimerlab: error: invalid simulation parameters: --ar: 0.5: [^;]*$" sim --ar 0.5 -o x.h5
expect 2 "^dimerlab: error: invalid simulation parameters: --freq: 0: [^;]*$" sim --freq 0 -o x.h5
expect 2 "--output is required" sim --cycles 1
expect 2 "--init-state" sim --init-state "1,2,3" -o x.h5
expect 2 "--fps" sim --fps abc -o x.h5
expect 2 "unknown subcommand 'compre'; did you mean 'compare'" compre ok.h5 -o r
expect 2 "--phase-bins: 1: expected 2..1000" compare ok.h5 -o r --phase-bins 1
expect 2 "--sim and --simulate: give one of them" compare ok.h5 -o r --sim ok.h5 --simulate

# 1: bad input (files) and failed runs.
echo "not HDF5" >not-hdf5.h5
expect 1 "not-hdf5.h5: not an HDF5 file" render not-hdf5.h5 -o f
expect 1 "ok.h5: already exists; pass --force" sim --cycles 1 -o ok.h5
mkdir -p a_folder
expect 1 "a_folder: is a folder" sim --cycles 1 -o a_folder --force
expect 1 "no_dir/x.h5: folder no_dir does not exist" sim --cycles 1 -o no_dir/x.h5
expect 1 "event storm" sim --max-events-per-period 10 --cycles 5 -q -o storm.h5 --force
expect 1 "no_frames: no such file or folder" track no_frames -o t.h5
expect 1 "not-hdf5.h5: not an HDF5 file" compare not-hdf5.h5 -o r
expect 0 '' sim --cycles 1.5 --fps 200 -q -o short.h5
expect 1 "short.h5: 1.5 plate periods long; at least 2 are needed" compare short.h5 -o r
expect 1 "no_frames: no such file or folder" analyze no_frames -o r2

# 130: interrupted (SIGINT, as Ctrl-C), with a valid partial file.
"$BIN" sim --cycles 10000000 -q -o long.h5 >/dev/null 2>err.txt &
pid=$!
for _ in $(seq 50); do sleep 0.1; done
kill -INT "$pid"
wait "$pid"
rc=$?
if [ "$rc" -ne 130 ] || [ ! -f long.h5 ]; then
  echo "FAIL: interrupted sim -> exit $rc (want 130) or no partial long.h5"; failures=$((failures + 1))
else
  echo "ok:   exit 130  dimerlab sim (interrupted), partial file kept"
fi

# 1: `dimerlab` copied without dimerlab-full: it still runs sim, and an image command says what is
# missing instead of failing obscurely.
mkdir lonely && cp "$BIN" lonely/dimerlab
SAVED_BIN=$BIN
BIN=$WORK/lonely/dimerlab
expect 0 '' sim --cycles 1 -q -o lonely.h5
expect 1 "dimerlab-full .* is not installed beside" track some_frames -o t.h5
BIN=$SAVED_BIN

[ "$failures" -eq 0 ] || { echo "$failures case(s) failed"; exit 1; }
