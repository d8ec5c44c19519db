#!/usr/bin/env bash
# Builds the fuzzers (clang) and runs each for a bounded time on its corpus, after replaying
# every crashing input ever found (fuzz/regressions/<target>/). A new crash fails the run and
# leaves its input in build-fuzz/crashes/ to be added to the regressions.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=${ARCHET_FUZZ_SECONDS:-30}
cd "$root"
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz
mkdir -p build-fuzz/crashes

# One target: seed its corpus, replay its regressions, then fuzz it for $seconds.
fuzz_target() {
  local target=$1 corpus="build-fuzz/corpus/$1"
  mkdir -p "$corpus" "fuzz/regressions/$target"
  # Seeds: the shipped files for the loaders.
  case "$target" in
    model_loader) cp -n resources/models/*.json tests/data/bad-models/*.json "$corpus/" 2>/dev/null || true ;;
    gesture_loader) cp -n resources/gestures/*.json tests/data/bad-gestures/*.json "$corpus/" 2>/dev/null || true ;;
    take_reader) cp -n fuzz/seeds/take_reader/* "$corpus/" ;;
    osc_packet) cp -n fuzz/seeds/osc_packet/* "$corpus/" ;;
    midi) cp -n fuzz/seeds/midi/* "$corpus/" ;;
  esac
  if compgen -G "fuzz/regressions/$target/*" >/dev/null; then
    "build-fuzz/bin/fuzz_$target" fuzz/regressions/"$target"/* >"build-fuzz/$target-replay.log" 2>&1 ||
      { cat "build-fuzz/$target-replay.log"; echo "$target: a regression input fails again"; return 1; }
    echo "$target: every regression input passes"
  fi
  echo "fuzzing $target for $seconds s"
  "build-fuzz/bin/fuzz_$target" -max_total_time="$seconds" -max_len=65536 -timeout=10 \
    -artifact_prefix="build-fuzz/crashes/$target-" "$corpus" > "build-fuzz/$target.log" 2>&1 ||
    { tail -40 "build-fuzz/$target.log"; echo "$target: FAILED (input in build-fuzz/crashes/)"; return 1; }
  tail -3 "build-fuzz/$target.log" | sed "s/^/$target: /"
}

# libFuzzer runs on one core: as many targets at once as there are cores, each still fuzzed for
# its whole time. Any failure fails the run, after the others have finished.
at_once=$(nproc)
running=0
failed=0
for target in model_loader gesture_loader command_decoder osc_packet midi take_reader; do
  fuzz_target "$target" &
  running=$((running + 1))
  if [ "$running" -ge "$at_once" ]; then
    wait -n || failed=1
    running=$((running - 1))
  fi
done
while [ "$running" -gt 0 ]; do
  wait -n || failed=1
  running=$((running - 1))
done
exit "$failed"
