#!/usr/bin/env bash
# Installs the Debian (bookworm) packages Archet builds and tests with, only those missing.
# Runs apt-get as root, or through sudo when there is one.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev nlohmann-json3-dev libsimdjson-dev libcli11-dev libsndfile1-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  qt6-base-dev libqcustomplot-dev
  libjack-jackd2-dev librtaudio-dev jackd2 libevdev-dev libsdl2-dev
  liblo-dev liblo-tools librtmidi-dev lv2-dev liblilv-dev lilv-utils
  clang libclang-rt-14-dev dpkg-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "archet: all build dependencies are installed"
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
