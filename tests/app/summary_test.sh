#!/usr/bin/env bash
# Every subcommand ends with a one-line summary on stdout naming its output; -q/--quiet leaves
# stderr empty on success; progress into a file (not a terminal) is plain lines, no carriage
# returns. Usage: summary_test.sh path/to/dimerlab
set -u
BIN=$1
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
failures=0

# check NAME OUTPUT ARGS...: quiet run; one stdout line starting with OUTPUT, nothing on stderr.
check() {
  local output=$1; shift
  "$BIN" "$@" >out.txt 2>err.txt || { echo "FAIL: dimerlab $* exited $?"; cat err.txt; failures=$((failures + 1)); return; }
  if [ "$(wc -l <out.txt)" -ne 1 ] || ! grep -q "^$output: " out.txt || [ -s err.txt ]; then
    echo "FAIL: dimerlab $*: want one summary line '$output: ...' and a silent stderr"
    echo "  stdout:"; sed 's/^/    /' out.txt; echo "  stderr:"; sed 's/^/    /' err.txt
    failures=$((failures + 1))
  else
    echo "ok:   dimerlab $* -> $(cat out.txt)"
  fi
}

check sim.h5 sim --cycles 2 -q -o sim.h5
check frames render sim.h5 -o frames --frames 8 -q
check track.h5 track frames -o track.h5 --quiet

# Progress into a log file: plain lines, no carriage return.
"$BIN" sim --cycles 2 -o logged.h5 >/dev/null 2>log.txt
if grep -q $'\r' log.txt || ! grep -q "^sim: 2/2 periods" log.txt; then
  echo "FAIL: progress in a log file:"; cat -A log.txt; failures=$((failures + 1))
else
  echo "ok:   progress in a log file: $(cat log.txt)"
fi

[ "$failures" -eq 0 ]
