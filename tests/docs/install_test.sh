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
