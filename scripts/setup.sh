#!/usr/bin/env bash
# Installs the Debian 12 packages unsatmpm needs, only those missing. Idempotent.
# Works as root (no sudo needed) or as a user with sudo.
set -euo pipefail

PACKAGES=(
  g++ cmake make pkg-config
  libsundials-dev libsuitesparse-dev libhypre-dev mpi-default-dev libeigen3-dev libvtk9-dev
  libgtest-dev libbenchmark-dev libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev
  python3-matplotlib python3-numpy python3-vtk9 python3-yaml
  # SciPy's stiff integrator for V15's reference, Richards' equation (verification/wetting).
  python3-scipy
  # The BLAS under UMFPACK, the flow's sparse LU (numerics/umfpack_keeper.hpp): OpenBLAS's serial
  # build, 2.4 times faster there than the reference BLAS, and threadless so that it leaves the
  # cores to OpenMP.
  libopenblas0-serial
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
  SUDO=()
elif command -v sudo >/dev/null 2>&1; then
  SUDO=(sudo)
else
  echo "setup: missing packages (${missing[*]}) and neither root nor sudo to install them" >&2
  exit 1
fi

echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" apt-get update -qq
"${SUDO[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
