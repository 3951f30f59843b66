#!/usr/bin/env bash
# Installs everything glossa needs to build, test and benchmark on a fresh Debian 12 machine.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends \
  build-essential cmake ninja-build ccache pkg-config git clang-format \
  libtorch-dev libopenblas0-pthread \
  libsndfile1-dev libsoxr-dev libeigen3-dev \
  nlohmann-json3-dev libcli11-dev libfmt-dev libspdlog-dev libxxhash-dev zlib1g-dev \
  libgtest-dev libgmock-dev libbenchmark-dev \
  libpocketsphinx-dev libsphinxbase-dev pocketsphinx-en-us \
  espeak-ng libespeak-ng-dev flite flite1-dev \
  python3 python3-numpy sox >/dev/null
echo "glossa: dependencies installed"
