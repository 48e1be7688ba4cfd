#!/usr/bin/env bash
# Installs from Debian's packages exactly what MeshNBV's build, tests, tools
# and benchmarks need. Works as root or through sudo; does nothing (and needs
# no network) when everything is already installed.
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake ninja-build pkg-config
  # core
  libeigen3-dev libembree-dev libopencv-dev libopenmesh-dev libcgal-dev libtbb-dev
  nlohmann-json3-dev libpugixml-dev libcli11-dev libtinyobjloader-dev
  # drone missions (libs/mission, docs/missions.md): coordinate systems (with
  # the EGM96 grid of proj-data), EXIF, KMZ (Debian's libzip CMake config
  # names the zipcmp/zipmerge/ziptool programs)
  libproj-dev proj-data libexiv2-dev libzip-dev zipcmp zipmerge ziptool
  # tests/cli/mission.sh writes EXIF GPS tags with Pillow (an independent writer)
  python3-pil
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev python3
  # evaluation loop (libs/eval/src, bench/eval): Boost.Graph max-flow for the
  # visibility mesher, COLMAP 3.8 for sparse reconstruction, plots
  libboost-dev colmap python3-matplotlib
  # meshnbv-mpi (libs/mpi, docs/scale.md): Open MPI
  libopenmpi-dev openmpi-bin
  # robustness (fuzz/, docs/robustness.md): clang 14 with libFuzzer and the
  # sanitizer runtimes
  clang libclang-rt-14-dev
  # VTK pipeline algorithms (filters/), Python-wrapped, rendered under Xvfb
  libvtk9-dev python3-vtk9 vtk9 python3-numpy xvfb xauth
  # MeshLab 2020.09 plugin (plugins/meshlab/): MeshLab itself, Qt and GL to
  # build against, dpkg-dev for `apt-get source` of MeshLab's headers
  meshlab qtbase5-dev libqt5opengl5-dev libqt5xmlpatterns5-dev qtscript5-dev
  libglew-dev libgl-dev libglu1-mesa-dev dpkg-dev
  # ParaView 5.11 plugin (plugins/paraview/): ParaView and its CMake package;
  # its Python (pvpython) is unpacked apart below
  paraview paraview-dev
  # the report's 3-D view (libs/report/web): its browser test and bench run
  # headless chromium (tests/report/viewer_3d.sh, bench/report/run.sh)
  chromium chromium-driver
)
# The report's 3-D view is bundled with npm at build time: Debian's nodejs
# and npm, unless an npm is already on PATH (e.g. NodeSource's).
if ! command -v npm >/dev/null 2>&1; then PACKAGES+=(nodejs npm); fi

# pvpython: Debian 12's python3-paraview conflicts with python3-vtk9 (both
# install the Python package vtkmodules) and so would remove the VTK 9.1
# that filters/ builds against. Its files are unpacked instead into a folder
# of their own (no dpkg database entry); the ParaView tests put that folder
# first on pvpython's path (plugins/paraview/tools/pvpython).
PVPYTHON_ROOT=/opt/meshnbv/python3-paraview
unpack_pvpython() {
  local version
  version=$(dpkg-query -W -f='${Version}' paraview 2>/dev/null) || return 0
  [ -n "$version" ] || return 0
  if [ -x "$PVPYTHON_ROOT/usr/bin/pvpython3.11" ] && [ "$(cat "$PVPYTHON_ROOT/version" 2>/dev/null)" = "$version" ]; then
    return 0
  fi
  echo "install-deps: unpacking python3-paraview $version into $PVPYTHON_ROOT"
  local tmp
  tmp=$(mktemp -d)
  chmod 755 "$tmp"  # apt's download user writes there
  (cd "$tmp" && $SUDO apt-get -o DPkg::Lock::Timeout=600 download -qq "python3-paraview=$version")
  $SUDO rm -rf "$PVPYTHON_ROOT"
  $SUDO mkdir -p "$PVPYTHON_ROOT"
  $SUDO dpkg -x "$tmp"/python3-paraview_*.deb "$PVPYTHON_ROOT"
  echo "$version" | $SUDO tee "$PVPYTHON_ROOT/version" >/dev/null
  rm -rf "$tmp"
}

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

SUDO=""
if [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1; then SUDO="sudo"; fi

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  unpack_pvpython
  exit 0
fi

if [ "$(id -u)" -ne 0 ] && [ -z "$SUDO" ]; then
  echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get -o DPkg::Lock::Timeout=600 update -qq
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600 install -y -qq --no-install-recommends "${missing[@]}"
unpack_pvpython
