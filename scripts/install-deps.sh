#!/usr/bin/env bash
# Installs the Debian packages the project builds and tests with; skips what is present.
# Idempotent: safe to run before every build (make does).
set -euo pipefail

packages=(
  cmake g++ make
  libmujoco-dev libqhull-dev      # physics (MuJoCo's CMake config needs qhull)
  libeigen3-dev                   # linear algebra
  libyaml-cpp-dev                 # scenario and parameter files
  libcli11-dev                    # command line
  nlohmann-json3-dev              # summary.json, bench JSON
  libgtest-dev                    # tests
  libbenchmark-dev                # benchmarks
  chromium                        # report.html's browser test (headless)
  libegl-dev libgl-dev            # headless rendering for `biped run --video` (EGL, GL headers)
  libegl-mesa0 libgl1-mesa-dri    # Mesa's EGL and its software renderer (no GPU, no display needed)
  ffmpeg                          # encodes the video; its ffprobe checks it in the tests
  python3-matplotlib python3-yaml # `make experiments` figures (experiments/plot.py) and their test
  libsqlite3-dev sqlite3          # campaign results (campaign.sqlite); the CLI for queries and tests
  libopenmpi-dev openmpi-bin      # distributed campaigns (mpirun; the MPI test)
)
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

echo "install-deps: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
