#!/usr/bin/env bash
# Installs the Debian packages filum needs (only those missing), configures and builds it.
# Used by the two quick-start commands (scripts/demo.sh and scripts/test.sh); run as root or
# with sudo on Debian 12.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

packages=(
  build-essential cmake          # compiler and build system
  libeigen3-dev                  # vectors, sparse matrices, dense solvers
  libsuitesparse-dev             # CHOLMOD for sparse implicit steps (CMake option FILUM_WITH_SUITESPARSE)
  nlohmann-json3-dev             # scene files
  libcgal-dev                    # triangle-mesh obstacles: AABB tree, inside test, mesh readers (FILUM_WITH_CGAL)
  zlib1g-dev                     # compressed VTK meshes (.vtp as VTK and ParaView save them by default)
  libcli11-dev                   # the filum command line
  libopencv-viz-dev libopencv-imgcodecs-dev libopencv-videoio-dev libopencv-imgproc-dev
                                 # off-screen 3D pictures, PNG, video, text overlay (FILUM_WITH_OPENCV)
  libx11-dev xvfb xauth          # the interactive window; a virtual X display for headless rendering
  libgtest-dev libgmock-dev      # tests
  libbenchmark-dev               # apps/bench
  python3 python3-matplotlib     # pictures of runs (apps/tools/plot_run.py)
  pybind11-dev python3-dev python3-numpy  # the Python module `filum` (python/): bindings, NumPy arrays
  python3-pytest                 # its tests (python/tests, ctest label python)
  python3-dask python3-distributed  # parameter sweeps on a LocalCluster or a cluster (python/filum_sweeps)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "installing: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DFILUM_WARNINGS_AS_ERRORS=ON
cmake --build "$root/build" -j"$(nproc)"
