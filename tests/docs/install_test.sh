#!/usr/bin/env bash
# `cmake --install` (what `./dimerlab.sh install` runs) puts a working `dimerlab` in PREFIX/bin:
# installed into a temporary prefix, then run from there by name, as the README's examples are.
# Usage: install_test.sh BUILD_DIR
set -eu
BUILD=$1
PREFIX=$(mktemp -d)
trap 'rm -rf "$PREFIX"' EXIT
cmake --install "$BUILD" --prefix "$PREFIX" >/dev/null
test -x "$PREFIX/bin/dimerlab"
cd "$PREFIX"
PATH="$PREFIX/bin:$PATH" dimerlab --version
PATH="$PREFIX/bin:$PATH" dimerlab sim --cycles 2 -q -o installed.h5
test -s installed.h5
# The image commands are handed to dimerlab-full, installed in PREFIX/libexec/dimerlab.
test -x "$PREFIX/libexec/dimerlab/dimerlab-full"
PATH="$PREFIX/bin:$PATH" dimerlab render --help >/dev/null
# OpenCV's image and video codecs are not linked into dimerlab-full (its start would load ~190
# more libraries); they come from PREFIX/lib/dimerlab/libdimer_codecs.so on first use
# (tracking/io/image_codecs.h), which this exercises: PNG frames written, then read back.
test -f "$PREFIX/lib/dimerlab/libdimer_codecs.so"
if ldd "$PREFIX/libexec/dimerlab/dimerlab-full" | grep -E 'libopencv_(imgcodecs|videoio)'; then
  echo "dimerlab-full links OpenCV's codecs directly" >&2
  exit 1
fi
PATH="$PREFIX/bin:$PATH" dimerlab render installed.h5 -o frames --frames 3 --width 160 \
  --height 96 --m-per-px 5e-4 -q
test -s frames/frame_000002.png
PATH="$PREFIX/bin:$PATH" dimerlab track frames -o track.h5 -q --method centroid
test -s track.h5
# ... and from there, not from the build tree: without it the PNG folder is one line naming it.
mv "$PREFIX/lib/dimerlab/libdimer_codecs.so" "$PREFIX/moved.so"
if PATH="$PREFIX/bin:$PATH" dimerlab track frames -o track2.h5 -q 2>err.txt; then
  echo "track read PNG frames without PREFIX/lib/dimerlab/libdimer_codecs.so" >&2
  exit 1
fi
grep -qx "dimerlab: error: cannot load $PREFIX/lib/dimerlab/libdimer_codecs.so, .*" err.txt
test "$(wc -l <err.txt)" -eq 1
