#!/usr/bin/env bash
# The README's two commands. `quickstart.sh` installs what is missing, builds (Release) and
# starts Archet; `quickstart.sh test` does the same set-up and runs the whole test suite, then
# again under the sanitizers, then the fuzzers for a bounded time.
set -euo pipefail

mode=${1:-run}
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

"$root/packaging/install-dependencies.sh"
cmake --preset release >/dev/null
cmake --build --preset release

case "$mode" in
  test)
    ctest --preset release
    # Then under the sanitizers: AddressSanitizer + UndefinedBehaviorSanitizer over the whole
    # suite, ThreadSanitizer over the rings, the engine and takes; then a bounded fuzzing run.
    cmake --preset asan >/dev/null
    cmake --build --preset asan
    ctest --preset asan
    cmake --preset tsan >/dev/null
    cmake --build --preset tsan
    ctest --preset tsan
    ARCHET_FUZZ_SECONDS="${ARCHET_FUZZ_SECONDS:-30}" "$root/fuzz/run.sh"
    ;;
  run)
    studio="$root/build/bin/archet-studio"
    if [ -x "$studio" ] && [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
      exec "$studio" "$root/resources/models/bowed-string-220.json"
    fi
    # No studio or no display: render the paper's sound examples instead.
    out="$root/out/sound-examples"
    mkdir -p "$out"
    "$root/build/bin/archet" examples -o "$out"
    echo
    echo "No display: the paper's sound examples are in $out (the studio needs a display)"
    ;;
  *)
    echo "usage: $0 [run|test]" >&2
    exit 2
    ;;
esac
