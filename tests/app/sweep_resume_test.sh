#!/usr/bin/env bash
# A sweep killed with kill -9 resumes without redoing a finished point and without losing one:
#  1. an uninterrupted run writes the reference file;
#  2. the same sweep, one thread, is killed with SIGKILL once some points are finished
#     (--verbose prints "sweep: point I done" after each point's journal record is fsync'd);
#  3. the rerun of the same command computes exactly the points the first run did not log,
#     never one it logged, and writes a file byte-identical to the reference (SOURCE_DATE_EPOCH).
# Usage: sweep_resume_test.sh path/to/dimerlab
set -u
BIN=$(realpath "$1")
WORK=$(mktemp -d)
pid=
trap '[ -n "$pid" ] && kill -9 "$pid" 2>/dev/null; rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
export SOURCE_DATE_EPOCH=1700000000
SPEC=(--ar 3:6:0.5 --gamma 0.8,0.9 --periods 400 --transient 10)   # 14 points, ~30 ms each
fail() { echo "FAIL: $*"; exit 1; }

"$BIN" sweep "${SPEC[@]}" --threads 2 -q -o ref.h5 >/dev/null || fail "reference run"

"$BIN" sweep "${SPEC[@]}" --threads 1 --verbose -q -o run.h5 >/dev/null 2>run1.log &
pid=$!
for _ in $(seq 1 3000); do   # up to 60 s for 4 points
  [ "$(grep -c 'point .* done' run1.log)" -ge 4 ] && break
  sleep 0.02
done
kill -9 "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
pid=
logged=$(grep -o 'point [0-9]* done' run1.log | awk '{print $2}' | sort)
n_logged=$(echo "$logged" | grep -c .)
[ "$n_logged" -ge 4 ] || fail "the first run finished only $n_logged points"
[ "$n_logged" -lt 14 ] || fail "the first run finished every point before the kill"
[ -e run.h5 ] && fail "a killed run left its output file"
[ -s run.h5.journal ] || fail "no journal after the kill"
echo "killed after $n_logged logged points: $(echo $logged)"

"$BIN" sweep "${SPEC[@]}" --threads 2 --verbose -o run.h5 >out2.txt 2>run2.log ||
  { cat run2.log; fail "the rerun failed"; }
computed=$(grep -o 'point [0-9]* done' run2.log | awk '{print $2}' | sort)
redone=$(comm -12 <(echo "$logged") <(echo "$computed"))
[ -z "$redone" ] || fail "the rerun recomputed finished points: $redone"
all=$(printf '%s\n%s\n' "$logged" "$computed" | grep . | sort -u)
n_computed=$(echo "$computed" | grep -c .)
# Points fsync'd but not yet logged at the kill are taken from the journal too: nothing is
# computed twice and nothing is lost.
[ "$(echo "$all" | grep -c .)" -le 14 ] || fail "more points than the grid"
grep -q "resuming from run.h5.journal: [0-9]* of 14 points already done" run2.log ||
  { cat run2.log; fail "no resume message"; }
recovered=$(grep -o 'resuming from run.h5.journal: [0-9]*' run2.log | awk '{print $NF}')
[ "$recovered" -ge "$n_logged" ] || fail "the journal held $recovered points, $n_logged were logged"
[ $((recovered + n_computed)) -eq 14 ] || fail "recovered $recovered + computed $n_computed != 14"
grep -q "$recovered from the journal, $n_computed computed" out2.txt || { cat out2.txt; fail "summary"; }
cmp ref.h5 run.h5 || fail "the resumed file differs from the uninterrupted run"
[ -e run.h5.journal ] && fail "the journal was not removed after the final write"
echo "ok: resumed $recovered points from the journal, computed $n_computed, file identical"
