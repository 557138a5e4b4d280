#!/usr/bin/env bash
# Installs the Debian 12 packages ecorail builds against. Idempotent: packages already present
# are skipped, so a machine that has everything does not touch the network. clang and
# libclang-rt-14-dev (libFuzzer, sanitizer runtimes) are for scripts/sanitize-and-fuzz-smoke.sh;
# pybind11-dev, python3-dev, -numpy and -pytest for the Python module (docs/python.md);
# python3-matplotlib, which only one example uses when present, is left to the user.
set -euo pipefail
packages=(cmake g++ make pkg-config libeigen3-dev libceres-dev libgtest-dev libgmock-dev
  libbenchmark-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libxlsxwriter-dev
  gnuplot-nox clang libclang-rt-14-dev libopenmpi-dev openmpi-bin
  pybind11-dev python3-dev python3-numpy python3-pytest)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
