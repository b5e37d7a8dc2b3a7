#!/usr/bin/env bash
# The build's cost at given commits: each commit checked out into a scratch worktree and built
# from nothing as `./dimerlab.sh build` builds (Release, Ninja, -j JOBS), everything (libraries,
# app, tests, benches). Prints one TSV row per commit: commit, CPU seconds (user + system, all
# compiler processes), wall seconds, jobs. CPU time is what another build's load hardly moves.
# Usage: bench/build_time.sh COMMIT... (from the repository; JOBS defaults to 2; needs GNU time,
# Debian's package `time`)
set -eu
ROOT=$(git rev-parse --show-toplevel)
JOBS=${JOBS:-2}
SCRATCH=$(mktemp -d)
trap 'git -C "$ROOT" worktree remove --force "$SCRATCH/src" >/dev/null 2>&1 || true; rm -rf "$SCRATCH"' EXIT
printf 'commit\tcpu_s\twall_s\tjobs\n'
for commit in "$@"; do
  git -C "$ROOT" worktree add --detach -q "$SCRATCH/src" "$commit"
  cmake -S "$SCRATCH/src" -B "$SCRATCH/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  /usr/bin/time -f '%U %S %e' -o "$SCRATCH/time" cmake --build "$SCRATCH/build" -j "$JOBS" >/dev/null
  read -r user sys wall < "$SCRATCH/time"
  awk -v c="$(git -C "$ROOT" rev-parse --short "$commit")" -v u="$user" -v s="$sys" -v w="$wall" \
    -v j="$JOBS" 'BEGIN { printf "%s\t%.0f\t%.0f\t%s\n", c, u + s, w, j }'
  git -C "$ROOT" worktree remove --force "$SCRATCH/src"
  rm -rf "$SCRATCH/build"
done
