#!/usr/bin/env bash
# `make fuzz`: builds the libFuzzer harnesses (tests/fuzz/) with clang into $FUZZ_BUILD, writes
# their seed corpora (make_seeds, from the samples and the shared trees), and runs each harness
# for $FUZZ_SECONDS seconds (or, with FUZZ_RUNS, for that many inputs), two at a time, keeping
# what they find in $FUZZ_BUILD/corpus/<name> (a later run continues from it). Prints one line per harness: executions, executions per
# second, coverage (edges), features, corpus size. A crash, hang (> 20 s on one input), leak,
# sanitizer report or allocation over 2 GB fails the run; its input is kept as
# $FUZZ_BUILD/findings/<name>-crash-* (make it a regression input under tests/fuzz/regressions).
#
#   FUZZ_SECONDS=60 FUZZ_SEED=1 FUZZ_HARNESSES="glb texture" scripts/fuzz.sh
#
# A timed run depends on the machine's speed; FUZZ_RUNS=N runs exactly N inputs per harness, so
# that the same seed on a fresh corpus gives the same run anywhere (CI uses it). With both set,
# a harness stops at whichever comes first (the long runs: FUZZ_RUNS=1000000 FUZZ_SECONDS=1800).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${FUZZ_BUILD:-build-fuzz}
seconds=${FUZZ_SECONDS:-60}
timed=${FUZZ_SECONDS:+yes}  # FUZZ_SECONDS given: it bounds a FUZZ_RUNS run too
runs=${FUZZ_RUNS:-}
seed=${FUZZ_SEED:-1}  # libFuzzer's -seed: the same seed repeats the same mutations
jobs=${FUZZ_JOBS:-$(nproc)}
all="glb gltf obj ply off stl texture preset set options keyframes cache"
harnesses=${FUZZ_HARNESSES:-$all}
shared=${SYLVA_SHARED_DIR:-$PWD/../shared}

case "$seed" in
  '' | *[!0-9]*) echo "fuzz: FUZZ_SEED must be a whole number, got '$seed'" >&2; exit 2 ;;
esac
case "$seconds" in
  '' | *[!0-9]*) echo "fuzz: FUZZ_SECONDS must be a whole number of seconds, got '$seconds'" >&2; exit 2 ;;
esac
case "$runs" in
  *[!0-9]*) echo "fuzz: FUZZ_RUNS must be a whole number of inputs, got '$runs'" >&2; exit 2 ;;
esac
for h in $harnesses; do
  case " $all " in *" $h "*) ;; *) echo "fuzz: unknown harness '$h' (known: $all)" >&2; exit 2 ;; esac
done

if [ ! -f "$build/build.ninja" ]; then
  # -O1 with asserts on: quicker to build than -O2, and SYLVA_CHECKs stay armed.
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
    -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -DSYLVA_FUZZ=ON -DSYLVA_SHARED_DIR="$shared" >/dev/null
fi
targets=make_seeds
for h in $harnesses; do targets="$targets fuzz_$h"; done
# shellcheck disable=SC2086
cmake --build "$build" -j "$jobs" --target $targets

export ASAN_OPTIONS=abort_on_error=1:detect_leaks=1:allocator_may_return_null=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
rm -rf "$build/seeds"
"$build/tests/fuzz/make_seeds" "$build/seeds" "$shared/assets"
mkdir -p "$build/findings" "$build/logs"

dict_of() {
  case "$1" in
    glb | gltf) echo tests/fuzz/gltf.dict ;;
    obj | ply | off | stl) echo tests/fuzz/mesh.dict ;;
    texture) echo tests/fuzz/texture.dict ;;
    *) echo tests/fuzz/text.dict ;;
  esac
}

run_one() {
  local h=$1
  mkdir -p "$build/corpus/$h" "$build/seeds/$h"
  local extra=() limit=(-max_total_time="$seconds")
  if [ -n "$runs" ]; then
    limit=(-runs="$runs")
    [ -n "$timed" ] && limit+=(-max_total_time="$seconds")
  fi
  [ -d "tests/fuzz/regressions/$h" ] && extra+=("tests/fuzz/regressions/$h")
  # -reload=0: one process per corpus, and the timed re-reading of it made runs differ.
  "$build/tests/fuzz/fuzz_$h" "${limit[@]}" -seed="$seed" -reload=0 -timeout=20 -rss_limit_mb=2048 \
    -malloc_limit_mb=2048 -print_final_stats=1 -dict="$(dict_of "$h")" \
    -artifact_prefix="$build/findings/$h-" "$build/corpus/$h" "$build/seeds/$h" "${extra[@]}" \
    >"$build/logs/$h.log" 2>&1
}

failed=""
pids=()
names=()
wait_all() {
  for i in "${!pids[@]}"; do
    wait "${pids[$i]}" || failed="$failed ${names[$i]}"
  done
  pids=()
  names=()
}
for h in $harnesses; do
  run_one "$h" &
  pids+=($!)
  names+=("$h")
  [ "${#pids[@]}" -ge "$jobs" ] && wait_all
done
wait_all

printf '%-10s %12s %9s %8s %8s %8s\n' harness executions 'exec/s' cov ft corpus
for h in $harnesses; do
  log=$build/logs/$h.log
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -1 || true)
  cov=$(sed -n 's/.*cov: \([0-9]*\).*/\1/p' <<<"$last")
  ft=$(sed -n 's/.*ft: \([0-9]*\).*/\1/p' <<<"$last")
  corp=$(find "$build/corpus/$h" -type f | wc -l)
  printf '%-10s %12s %9s %8s %8s %8s\n' "$h" "${execs:-?}" "${rate:-?}" "${cov:-?}" "${ft:-?}" "$corp"
done
if [ -n "$failed" ]; then
  for h in $failed; do
    echo "fuzz: $h found a problem ($build/logs/$h.log):" >&2
    # -m: no pipe to head, whose early exit ended the script (pipefail) before this report did;
    # libFuzzer's and the sanitizers' own lines only (OpenCV logs "[ERROR:0@...]" lines too).
    grep -m 5 -E '^==[0-9]+== ?ERROR|^SUMMARY|broken invariant|Test unit written' \
      "$build/logs/$h.log" >&2 || true
  done
  exit 1
fi
