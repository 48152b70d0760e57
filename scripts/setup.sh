#!/usr/bin/env bash
# Installs the Debian 12 packages the host build needs (only those missing). Open MPI is
# optional to the build (gyro_campaign runs on threads and shards without it); installed here
# so that the test suite also runs the campaign under mpiexec. The Python module and its tests
# (docs/python.md) need pybind11, the interpreter's headers, NumPy, pytest and matplotlib; the
# Fortran drop-in, the MEX gateway in Octave and the pkg-config consumer (docs/embedding.md)
# gfortran, Octave with its headers and a font for its figures, and pkg-config.
# Usage: scripts/setup.sh [extra-package ...]
set -euo pipefail
packages=(cmake make g++ libeigen3-dev libgtest-dev nlohmann-json3-dev libcli11-dev gnuplot-nox
  openmpi-bin libopenmpi-dev python3-dev python3-numpy pybind11-dev python3-pytest python3-matplotlib
  gfortran octave liboctave-dev fonts-freefont-otf pkg-config "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "installing: ${missing[*]}"
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
