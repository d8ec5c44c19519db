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
    "$root/build/bin/archet" examples -o "$out"
    echo
    echo "No display: the paper's sound examples are in $out (the studio needs a display)"
    ;;
  *)
    echo "usage: $0 [run|test]" >&2
    exit 2
    ;;
esac
