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
# NaN means "not given" inside the tracker: the text nan is refused, as are rates no camera has.
expect 2 "--fps: 'nan' is not a finite number" track f -o x.h5 --fps nan
expect 2 "--m-per-px: 'inf' is not a finite number" track f -o x.h5 --m-per-px inf
expect 2 "--fps must be 1 .. 1e7 frames/s" track f -o x.h5 --fps 1e308
expect 2 "--fps must be 1 .. 1e7 frames/s" track f -o x.h5 --fps 1e-300
expect 2 "--fps: 'nan' is not a finite number" analyze f -o x --fps nan
expect 2 "^dimerlab: error: invalid simulation parameters: --ar: 0.5: [^;]*$" sim --ar 0.5 -o x.h5
expect 2 "^dimerlab: error: invalid simulation parameters: --freq: 0: [^;]*$" sim --freq 0 -o x.h5
expect 2 "--output is required" sim --cycles 1
expect 2 "--init-state" sim --init-state "1,2,3" -o x.h5
expect 2 "--fps" sim --fps abc -o x.h5
expect 2 "unknown subcommand 'compre'; did you mean 'compare'" compre ok.h5 -o r
expect 2 "--phase-bins: 1: expected 2..1000" compare ok.h5 -o r --phase-bins 1
expect 2 "--sim and --simulate: give one of them" compare ok.h5 -o r --sim ok.h5 --simulate
# Sweep specs: an empty range, a zero step, an unknown parameter (flag or spec-file line), a bad
# shard, a point the simulator rejects.
expect 2 '--ar: "4:3:0.1": empty range' sweep --ar 4:3:0.1 -o x.h5
expect 2 '--gamma: "0.5:1:0": step 0' sweep --gamma 0.5:1:0 -o x.h5
expect 2 "unknown option '--colour'" sweep --colour 3 -o x.h5
printf 'ar = 3:4:0.5\ncolour = 2\n' >bad.sweep
expect 2 'bad.sweep:2: unknown sweep parameter "colour"' sweep --spec bad.sweep -o x.h5
expect 2 '--shard: "3/2": expected K/N with 1 <= K <= N' sweep --shard 3/2 -o x.h5
expect 2 'invalid sweep point 1 \(ar=0.5\): --ar: 0.5' sweep --ar 3,0.5 -o x.h5

# Values out of their documented range (docs/FORMATS.md, "Simulation options"), NaN and inf,
# and runs whose results would not fit in memory: refused before anything is written.
expect 2 "--gamma: 1e\+22: expected 0 <= Gamma <= 10" sim --gamma 1e22 -o x.h5
expect 2 "--fps: 1e\+308: expected 0 \(events only\) or a sampling rate" sim --fps 1e308 -o x.h5
expect 2 "--fps: 1e-300: expected" sim --fps 1e-300 -o x.h5
expect 2 "--fps: nan: expected" sim --fps nan -o x.h5
expect 2 "--cycles: 1.84467e\+19: expected" sim --cycles 18446744073709551616 -o x.h5
expect 2 "--duration: 4.29497e\+09: expected at most 1e9 plate periods" sim --duration 4294967296 -o x.h5
expect 2 "the run needs about [0-9.e+]+ GB, more than the [0-9.e+]+ GB allowed" sim --cycles 1e8 -o x.h5
expect 2 '--transient: 4294967296: expected 0 to 1e9' sweep --transient 4294967296 -o x.h5
printf '[sweep]\ngamma = 1e22\n' >huge.sweep
expect 2 'invalid sweep settings: --gamma: 1e\+22: expected' sweep --spec huge.sweep -o x.h5
if [ -e x.h5 ]; then echo "FAIL: a refused run wrote x.h5"; failures=$((failures + 1)); fi
# A scene file that names a setting twice: an error naming both lines, whichever would win.
printf 'gamma = 0.9\nar = 3\ngamma = banana\n' >twice.scene
expect 1 "twice.scene:3: gamma is set again \(first at line 1\)" sim --scene twice.scene -o x.h5

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
expect 0 '' sweep --ar 3.9,6.1 --periods 4 --transient 2 -q -o sweep.h5
expect 1 "sweep.h5: point 0 is also in sweep.h5" merge sweep.h5 sweep.h5 -o merged.h5
expect 0 '' sweep --ar 3.9,6.1 --periods 4 --transient 2 -q --shard 1/2 -o part1.h5
expect 1 "merge: 1 of 2 points missing \(first: 1\)" merge part1.h5 -o merged.h5

# 130: interrupted (SIGINT, as Ctrl-C), with a valid partial file.
"$BIN" sim --cycles 1000000 --fps 0 -q -o long.h5 >/dev/null 2>err.txt &
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

# A sweep interrupted by SIGINT exits 130 and keeps its finished points in the journal.
"$BIN" sweep --ar 2:6:0.01 --periods 100000 --threads 1 -q -o isweep.h5 >/dev/null 2>err.txt &
pid=$!
for _ in $(seq 20); do sleep 0.1; done
kill -INT "$pid"
wait "$pid"
rc=$?
if [ "$rc" -ne 130 ] || [ -e isweep.h5 ] || [ ! -s isweep.h5.journal ]; then
  echo "FAIL: interrupted sweep -> exit $rc (want 130), want a journal and no output"
  cat err.txt; failures=$((failures + 1))
else
  echo "ok:   exit 130  dimerlab sweep (interrupted), journal kept"
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
