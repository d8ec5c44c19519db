#!/usr/bin/env bash
# The README's two commands. `quickstart.sh` installs what is missing, builds (Release) and
# starts Archet; `quickstart.sh test` does the same set-up and runs the whole test suite.
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
    ;;
  run)
    studio="$root/build/bin/archet-studio"
    if [ -x "$studio" ] && [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
      exec "$studio" "$root/resources/models/bowed-string-220.json"
    fi
    # No studio or no display: render the paper's sound examples instead.
    out="$root/out/sound-examples"
    mkdir -p "$out"
    archet="$root/build/bin/archet"
    models="$root/resources/models"
    gestures="$root/resources/gestures"
    "$archet" render "$models/bowed-string-110.json" --gesture "$gestures/steady-bow.json" -o "$out/sound-1-110Hz-steady-bow.wav"
    "$archet" render "$models/bowed-string-220.json" --gesture "$gestures/detache.json" -o "$out/sound-2-220Hz-detache.wav"
    "$archet" render "$models/bowed-string-440.json" --gesture "$gestures/crescendo.json" -o "$out/sound-5-440Hz-crescendo.wav"
    "$archet" render "$models/bowed-string-880.json" --gesture "$gestures/pressure-sweep.json" -o "$out/sound-6-880Hz-pressure-sweep.wav"
    echo
    echo "No display (or no studio yet): the paper's sound examples are in $out"
    ;;
  *)
    echo "usage: $0 [run|test]" >&2
    exit 2
    ;;
esac
