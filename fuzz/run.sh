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
for target in model_loader gesture_loader command_decoder osc_packet midi take_reader; do
  corpus="build-fuzz/corpus/$target"
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
    "build-fuzz/bin/fuzz_$target" fuzz/regressions/"$target"/*
  fi
  echo "fuzzing $target for $seconds s"
  "build-fuzz/bin/fuzz_$target" -max_total_time="$seconds" -max_len=65536 -timeout=10 \
    -artifact_prefix="build-fuzz/crashes/$target-" "$corpus" 2>&1 | tail -3
done
