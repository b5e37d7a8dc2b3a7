#!/usr/bin/env bash
# dimerlab's one entry point for people and CI on Debian 12 (run as root, or with sudo present).
#   ./dimerlab.sh setup      install the Debian packages dimerlab needs (idempotent)
#   ./dimerlab.sh build      configure + build (Release) into build/
#   ./dimerlab.sh demo       setup + build + the pipeline on the bundled sample scene
#   ./dimerlab.sh test       setup + build + the whole GoogleTest suite through CTest
#   ./dimerlab.sh sanitize   setup + ASan/UBSan build with warnings as errors + the suite
#   ./dimerlab.sh bench      setup + build + every benchmark program (tables, and TSVs in bench/results/)
#   ./dimerlab.sh fuzz       setup + clang build of tests/fuzz + each target for FUZZ_SECONDS (60)
#   ./dimerlab.sh install    setup + build + install `dimerlab` into PREFIX/bin (PREFIX: env, default
#                            /usr/local, already on the PATH) and its docs into PREFIX/share/doc
set -euo pipefail
cd "$(dirname "$0")"
ROOT=$(pwd)
JOBS=$(nproc)

PACKAGES=(build-essential cmake ninja-build pkg-config libopencv-dev libeigen3-dev libhdf5-dev
          hdf5-tools libcli11-dev libgtest-dev googletest libnlopt-dev gnuplot-nox
          slurm-wlm munge povray ffmpeg clang libclang-rt-14-dev)

setup() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if ((${#missing[@]})); then
    echo "dimerlab: installing ${missing[*]}" >&2
    local SUDO=""
    [ "$(id -u)" -eq 0 ] || SUDO=sudo
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
}

build_dir() {  # $1 = folder, rest = extra cmake flags
  local dir=$1; shift
  cmake -S "$ROOT" -B "$dir" -G Ninja "$@" >/dev/null
  cmake --build "$dir" -j "$JOBS"
}

build() { build_dir build -DCMAKE_BUILD_TYPE=Release; }

demo() {
  setup; build
  local out=demo_out D=./build/app/dimerlab
  mkdir -p "$out"
  echo "== 1. simulate the drift mode of samples/drift_ar3.9.scene (30 periods at 25 Hz, 2000 samples/s) =="
  $D sim --scene samples/drift_ar3.9.scene --cycles 30 -o "$out/sim.h5" --force -q
  echo "== 2. render it as 2000 frames/s footage of polished steel (our renderer, sensor noise 2 grey levels) =="
  $D render "$out/sim.h5" -o "$out/frames" --force --quiet
  echo "== 3. analyze the footage: track (the scale from the dimer's length, A_r 3.9), fit the drive, modes, drift, slip, simulate it beside the track =="
  $D analyze "$out/frames" --ar 3.9 -o "$out/report" --force -q
  echo "== the report: $out/report/summary.md (figures in $out/report/figures/, overlay.avi, compare.h5) =="
}

# The five slowest tests of a CTest log, so that a slow machine shows where its time went.
slowest_tests() {  # $1 = ctest's output
  echo "slowest tests:"
  awk '/Test +#[0-9]+: / { for (i = 1; i <= NF; ++i) if ($i == "sec") print $(i - 1), $4 }' "$1" |
    sort -rn | awk 'NR <= 5 { printf "  %8.1f s  %s\n", $1, $2 }'  # reads all: no SIGPIPE for sort
}

run_tests() {
  setup; build
  local rc=0
  ctest --test-dir build --output-on-failure -j "$JOBS" 2>&1 | tee build/ctest_last.log || rc=$?
  slowest_tests build/ctest_last.log
  return "$rc"
}

# What the sanitizers leave to the Release `test` stage: runs that repeat, with other
# assertions, a code path that a sanitized test already runs (ERE alternatives, one per line).
SANITIZE_SKIP=(
  # POV-Ray footage: each lighting's film is tracked once, sanitized, by its povray.render
  # fixture and read by its targets check; its plate, coverage, scatter and metres checks, the
  # noise seeds and levels, the film leaving the frame (the cut-sphere unit tests stay), the
  # scale on films other than front_point and front_point's mistaken A_r repeat that run with
  # other assertions.
  '^povray[.](plate|coverage|scatter|metres)[.]'
  '^povray[.](noise_seeds|lower_levels|quarter_range|leaving_the_frame)$'
  # The ruler's relearning runs sanitized in povray.detection_agreement; its 1- and 2-thread
  # rerun checks identical results, not memory.
  '^povray[.]identity[.]ruler_above_plate$'
  # The ruler's 100-frame film: its acquisition, the learning frames' one plate and the held
  # rows' referee run sanitized in their unit tests (FrameFollower.*, PlateConsensus.*,
  # HeldRows.*) and on the 20-frame film.
  '^povray[.]long_ruler$'
  '^povray[.]dimer_length[.](cluttered_backdrop|front_point_ar2_0|front_softbox|mistaken_ar|one_sided_gain_ramp|rolled_8_degrees|underexposed)$'
  '^PovrayTiltedPlate[.]'
  # Films render -> track -> compare: jump_backlit stays; the drifts add the fit (below) and
  # the tilt (in the compare unit tests).
  '^Films/Pipeline[.].*/drift_'
  # The fit's searches on simulations (hundreds to 4,390 each, 1-12 minutes sanitized): its
  # search, profiles and moves run sanitized in FitSearch.* on a chi2 of known wells, and the
  # simulations and analysis it calls in the sim and compare unit tests.
  '^Fit[.](StartedAtTheTruthStaysThere|FindsADriftWhoseSlipBinsMoveInSteps|RecoversRestitutionAndImpactFrictionFromASimulatedDrift|SaysWhenATiltedPlateIsFittedAsLevel|SaysWhenNoCoefficientsReproduceTheTrack)$'
  # Every byte of every dataset flipped (111 s sanitized): the error paths of corrupt datasets
  # and metadata run sanitized in FileIntegrity.AFlippedByteAnywhere... and
  # H5File.EveryCorruptedMetadataByte...; and the files' self-description (attributes, no path
  # of its own).
  '^FileIntegrity[.]EveryFlippedByteInADatasetIsReportedNamingIt$'
  '^FileSchema[.]EveryDatasetOfEveryFileKindDescribesItself$'
  # Bit-identical reruns (not memory), and the documentation's command lines, which each
  # command's own tests run.
  '^FileSchema[.]ChunkedCompressedFilesStayBitIdenticalOnRerun$'
  '^docs[.](examples|tracking_example|paper_current)$'
  # A long simulated run's health (the simulator's code is sanitized by its unit tests).
  '^Stability[.]LongDriftRunStaysHealthyAndInTheDriftMode$'
)

sanitize() {
  setup
  # -O1 -g1 (line tables, enough for file:line in a sanitizer's report), not -O2 -g: the
  # instrumented build was 2/3 of CI's time, and a heavy file compiles in 13 s instead of 27.
  build_dir build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDIMERLAB_SANITIZE=ON \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DDIMERLAB_WERROR=ON -DDIMERLAB_BENCH=OFF \
    -DDIMERLAB_POVRAY_CACHE_DIR="$ROOT/build/povray_footage_cache"  # the same footage, rendered once
  local skip
  skip=$(IFS='|'; echo "${SANITIZE_SKIP[*]}")
  local rc=0
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 DIMERLAB_TEST_SCALE=0.2 \
    ctest --test-dir build-asan --output-on-failure -j "$JOBS" -E "$skip" 2>&1 |
    tee build-asan/ctest_last.log || rc=$?
  slowest_tests build-asan/ctest_last.log
  return "$rc"
}

# Every benchmark program; each one's tables also go to bench/results/MACHINE/NAME.tsv
# (bench/tables.sh), from which docs/BENCHMARKS.md's tables are made (docs.benchmark_tables).
bench() {
  setup; build
  local results="bench/results/${DIMERLAB_BENCH_MACHINE:-$(hostname -s)}" b name
  mkdir -p "$results"
  for b in build/bench/bench_*; do
    name=${b##*/}
    echo "== $b =="
    case "$b" in
      */bench_compare) "$b" "$ROOT/build/app/dimerlab" ;;  # times the CLI as a user runs it
      */bench_start) "$b" "$ROOT/build/app" ;;
      */bench_plate_edge) "$b" --psf-sensitivity ;;  # the others need footage folders
      */bench_tracking_footage) "$b" 40 6 "$ROOT/build/bench_footage_cache" ;;  # POV-Ray footage, cached
      *) "$b" ;;
    esac | tee "build/$name.out"
    bench/tables.sh tsv <"build/$name.out" >"$results/$name.tsv"
  done
  echo "tables: $results/*.tsv (docs/BENCHMARKS.md shows them: bench/tables.sh md < FILE)"
}

# One libFuzzer target ($1) for $2 seconds on a copy of its seed corpus: its log in
# build-fuzz/NAME.log, "ok" or "FAILED" in build-fuzz/NAME.result.
fuzz_one() {
  local t=$1 seconds=$2 name=${1##*/fuzz_} work result
  work=$(mktemp -d)
  cp "tests/fuzz/corpus/$name/"* "$work/"
  # -timeout: an input that takes 10 s is a hang, reported as a failure with its input (the
  # default, 1200 s, let one hang hold the run for 20 minutes).
  if "$t" -max_total_time="$seconds" -timeout=10 -print_final_stats=1 -artifact_prefix=build-fuzz/crashes/ \
      "$work" >"build-fuzz/$name.log" 2>&1; then result=ok; else result=FAILED; fi
  echo "$result" >"build-fuzz/$name.result"
  rm -rf "$work"
}

# Each libFuzzer target of tests/fuzz for FUZZ_SECONDS on a copy of its seed corpus, JOBS
# targets at a time (a target is one process: the wall time is about ceil(targets / JOBS) x
# FUZZ_SECONDS); a crash, leak or sanitizer report fails the command and leaves the input in
# build-fuzz/crashes/. FUZZ_SKIP: target names left out (space-separated).
fuzz() {
  setup
  CC=clang CXX=clang++ build_dir build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDIMERLAB_FUZZ=ON \
    -DDIMERLAB_WITH_TRACKING=OFF -DDIMERLAB_TESTS=OFF -DDIMERLAB_BENCH=OFF
  local seconds=${FUZZ_SECONDS:-60} failed=0 t name result
  local targets=()
  for t in build-fuzz/tests/fuzz/fuzz_*; do
    [[ " ${FUZZ_SKIP:-} " == *" ${t##*/fuzz_} "* ]] || targets+=("$t")
  done
  mkdir -p build-fuzz/crashes
  rm -f build-fuzz/*.result
  for t in "${targets[@]}"; do
    while (($(jobs -rp | wc -l) >= JOBS)); do wait -n || true; done
    fuzz_one "$t" "$seconds" &
  done
  wait
  printf '| target | seconds | executions | exec/s | result |\n|---|---:|---:|---:|---|\n' | tee build-fuzz/table.md
  for t in "${targets[@]}"; do
    name=${t##*/fuzz_}
    result=$(cat "build-fuzz/$name.result" 2>/dev/null || echo FAILED)
    [ "$result" = ok ] || failed=1
    awk -v n="$name" -v s="$seconds" -v r="$result" '
      /stat::number_of_executed_units/ { e = $2 } /stat::average_exec_per_sec/ { x = $2 }
      END { printf "| %s | %s | %s | %s | %s |\n", n, s, e, x, r }' "build-fuzz/$name.log" | tee -a build-fuzz/table.md
  done
  mkdir -p "bench/results/${DIMERLAB_BENCH_MACHINE:-$(hostname -s)}"
  bench/tables.sh tsv <build-fuzz/table.md >"bench/results/${DIMERLAB_BENCH_MACHINE:-$(hostname -s)}/fuzz.tsv"
  [ "$failed" = 0 ] || { echo "fuzz: a target failed; its log is in build-fuzz/, the input in build-fuzz/crashes/" >&2; exit 1; }
}

install_dimerlab() {
  setup; build
  cmake --install build --prefix "${PREFIX:-/usr/local}"
  echo "dimerlab installed: $(command -v dimerlab || echo "${PREFIX:-/usr/local}/bin/dimerlab (add it to PATH)")" >&2
}

case "${1:-}" in
  setup) setup ;;
  build) setup; build ;;
  demo) demo ;;
  test) run_tests ;;
  sanitize) sanitize ;;
  bench) bench ;;
  fuzz) fuzz ;;
  install) install_dimerlab ;;
  *) echo "usage: $0 setup|build|demo|test|sanitize|bench|fuzz|install" >&2; exit 2 ;;
esac
