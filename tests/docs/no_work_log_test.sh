#!/usr/bin/env bash
# Sources, CMake files and docs say what the code does and why, not when it was measured: this
# fails on a calendar date (YYYY-MM-DD; an ISO timestamp's date followed by T, and the Unix
# epoch 1970-01-01, are formats, not dates) and on work-log words: an ordinal sitting ("ninth
# session"), "this/that/the same/previous/next/earlier session", "this round", "previous round",
# "the round before", "earlier rounds". CHANGELOG.md is not checked (its versions carry dates).
# Usage: no_work_log_test.sh REPO_ROOT
set -u
ROOT=$(cd "$1" && pwd)
ordinal='first|second|third|fourth|fifth|sixth|seventh|eighth|ninth|tenth|eleventh|twelfth'
ordinal="$ordinal|thirteenth|fourteenth|fifteenth|sixteenth|seventeenth|eighteenth|nineteenth"
ordinal="$ordinal|twentieth|[0-9]+(st|nd|rd|th)"
pattern="(?<![0-9])(?!1970-01-01)(19|20)[0-9]{2}-(0[1-9]|1[0-2])-(0[1-9]|[12][0-9]|3[01])(?![0-9T])"
pattern="$pattern|\\b($ordinal) (session|sitting)s?\\b"
pattern="$pattern|\\b(this|that|the same|same|previous|next|earlier|one) (session|sitting)\\b"
pattern="$pattern|\\b(this|previous|last|earlier|next) rounds?\\b|\\bthe round before\\b"
cd "$ROOT" || exit 1
files=$(find . \( -path ./.git -o -path './build*' -o -name 'build-*' \) -prune -o -type f \
          \( -name '*.cc' -o -name '*.h' -o -name CMakeLists.txt \) -print;
        ls docs/*.md README.md CONTRIBUTING.md 2>/dev/null)
hits=$(printf '%s\n' $files | sort | xargs grep -n -i -P "$pattern")
if [ -n "$hits" ]; then
  echo "dates or work-log words (say why in a sentence and name the test that holds the number;"
  echo "the history belongs in the commit messages):"
  echo "$hits"
  exit 1
fi
echo "no dates or work-log words in $(printf '%s\n' $files | wc -l) files"
