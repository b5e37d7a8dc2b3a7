#!/usr/bin/env bash
# Runs every example of the documentation, so that none can break unnoticed: each line that
# starts with `dimerlab ` inside a ```sh block of README.md and docs/*.md is run, in order, in a
# fresh folder per document (with samples/ linked in), against the built binary put first on
# PATH. Any non-zero exit fails the test. A line may be left out only with the marker comment
# `# examples-test: skip (REASON)`, and every skipped line is reported.
# Usage: run_examples.sh REPO_ROOT BIN_DIR
set -u
ROOT=$(cd "$1" && pwd)
BIN_DIR=$(cd "$2" && pwd)
export PATH="$BIN_DIR:$PATH"
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
ran=0 failed=0 skipped=0

for doc in "$ROOT"/README.md "$ROOT"/docs/*.md; do
  name=${doc#"$ROOT"/}
  dir="$WORK/$(echo "$name" | tr '/.' '__')"
  mkdir -p "$dir"
  ln -s "$ROOT/samples" "$dir/samples"
  in_sh=0 lineno=0
  while IFS= read -r line || [ -n "$line" ]; do
    lineno=$((lineno + 1))
    case "$line" in
      '```sh'*) in_sh=1; continue ;;
      '```'*) in_sh=0; continue ;;
    esac
    [ "$in_sh" -eq 1 ] || continue
    cmd="${line#"${line%%[![:space:]]*}"}"  # without leading blanks
    case "$cmd" in dimerlab\ *) ;; *) continue ;; esac
    if [[ "$cmd" == *"# examples-test: skip"* ]]; then
      echo "skipped: $name:$lineno: $cmd"
      skipped=$((skipped + 1))
      continue
    fi
    (cd "$dir" && timeout 300 bash -c "$cmd" </dev/null >"$dir/out.txt" 2>&1)
    rc=$?
    ran=$((ran + 1))
    if [ "$rc" -ne 0 ]; then
      echo "FAIL (exit $rc): $name:$lineno: $cmd"
      sed 's/^/    /' "$dir/out.txt" | tail -20
      failed=$((failed + 1))
    else
      echo "ok:   $name:$lineno: $cmd"
    fi
  done <"$doc"
done

echo "$ran examples run, $failed failed, $skipped skipped"
[ "$ran" -gt 0 ] || { echo "no example found: the extraction is broken"; exit 1; }
[ "$failed" -eq 0 ]
