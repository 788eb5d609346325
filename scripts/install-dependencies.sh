#!/usr/bin/env bash
# Installs the Debian 12 packages CoShell needs, only those missing
# (idempotent). Needs root or sudo.
#   --with-peers   also the peer codes of the comparisons (CalculiX ccx),
#                  which the set-up command installs and the CI test run
#                  does not need.
set -euo pipefail

packages=(
  cmake g++ make git pkg-config
  libdeal.ii-dev        # deal.II 9.4 with Trilinos, METIS, HDF5, SuiteSparse
  libgtest-dev          # unit tests
  libbenchmark-dev      # speed benchmarks (Google Benchmark)
  gmsh                  # meshes .geo files
  python3 python3-matplotlib  # test checkers and plots (/usr/bin/python3)
  python3-h5py          # the checkpoint test reads the HDF5 files
  libopenblas0-pthread  # faster BLAS than the reference one for UMFPACK
  ccache                # compiler cache: a rebuild or a second clone compiles only what changed
)
if [ "${1:-}" = "--with-peers" ]; then
  packages+=(calculix-ccx)  # scripts/calculix_compare.py
fi

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-dependencies: all packages present"
  exit 0
fi

as_root=()
if [ "$(id -u)" -ne 0 ]; then
  as_root=(sudo)
fi
echo "install-dependencies: installing ${missing[*]}"
"${as_root[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
