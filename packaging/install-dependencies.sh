#!/usr/bin/env bash
# Installs the Debian (bookworm) packages Archet builds and tests with, only those missing.
# Runs apt-get as root, or through sudo when there is one. With --peers, also the peers that
# the bench-peers target times Archet against (Faust, for mi.lib's string, and STK).
set -euo pipefail

peers=0
for arg in "$@"; do
  case "$arg" in
    --peers) peers=1 ;;
    -h | --help)
      echo "usage: packaging/install-dependencies.sh [--peers]"
      echo "  installs the Debian packages Archet builds and tests with, only those missing;"
      echo "  --peers also installs faust and libstk-dev for the bench-peers target"
      exit 0
      ;;
    *)
      echo "archet: install-dependencies.sh: unknown option '$arg' (the one option is --peers)" >&2
      exit 2
      ;;
  esac
done

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev nlohmann-json3-dev libsimdjson-dev libcli11-dev libsndfile1-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  qt6-base-dev libqcustomplot-dev
  libjack-jackd2-dev librtaudio-dev jackd2 libevdev-dev libsdl2-dev
  liblo-dev liblo-tools librtmidi-dev lv2-dev liblilv-dev lilv-utils
  clang libclang-rt-14-dev dpkg-dev
)
if [ "$peers" -eq 1 ]; then
  packages+=(faust libstk-dev)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "archet: all build dependencies are installed$([ "$peers" -eq 1 ] && echo ', and the peers')"
  exit 0
fi

as_root=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then
    as_root=(sudo)
  else
    echo "archet: missing packages: ${missing[*]}" >&2
    echo "archet: run this script as root (or install sudo) to install them" >&2
    exit 1
  fi
fi
echo "archet: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
