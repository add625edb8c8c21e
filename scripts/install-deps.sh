#!/usr/bin/env bash
# Installs the Debian packages the project needs; skips what is present.
# Usage: scripts/install-deps.sh [demo|all]   (default: all)
#   demo: what `make demo` needs: the compilers, the libraries of build/biped and node/npm for its
#         report viewer (no tests, benchmarks, browser, video or plotting packages)
#   all:  everything the project builds and tests with (`make test`, `make bench`, `make experiments`)
# Idempotent: safe to run before every build (make does); prints nothing when nothing is missing.
set -euo pipefail

set_name=${1:-all}
demo_packages=(
  cmake g++ make ninja-build
  libmujoco-dev libqhull-dev      # physics (MuJoCo's CMake config needs qhull)
  libeigen3-dev                   # linear algebra
  libyaml-cpp-dev                 # scenario and parameter files
  libcli11-dev                    # command line
  nlohmann-json3-dev              # summary.json, bench JSON
  libegl-dev libgl-dev            # headers and link libraries of `biped run --video` (EGL, GL), linked into build/biped
  libsqlite3-dev                  # campaign results (campaign.sqlite)
  libopenmpi-dev                  # distributed campaigns (MPI; build/biped runs without a launcher too)
  libtinyxml2-dev                 # `biped robot import`: reads the URDF, edits the MJCF MuJoCo writes
  libpagmo-dev                    # CMA-ES of `biped tune` (linked into build/biped)
)
test_packages=(
  libgtest-dev                    # tests
  libbenchmark-dev                # benchmarks
  chromium                        # report.html's browser test (headless)
  libegl-mesa0 libgl1-mesa-dri    # Mesa's EGL and its software renderer: `--video` without GPU or display
  ffmpeg                          # encodes the video; its ffprobe checks it in the tests
  python3-matplotlib python3-yaml # `make experiments` figures (experiments/plot.py) and their test
  sqlite3 openmpi-bin             # the SQLite CLI for queries of campaign.sqlite; mpirun (the MPI test)
)
case "$set_name" in
  demo) packages=("${demo_packages[@]}") ;;
  all) packages=("${demo_packages[@]}" "${test_packages[@]}") ;;
  *) echo "usage: scripts/install-deps.sh [demo|all]" >&2; exit 2 ;;
esac
# node and npm build the report viewer (web/report); a node already there (with its npm) will do.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps ($set_name): installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
start=$(date +%s)
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps ($set_name): done in $(( $(date +%s) - start )) s"
