#!/usr/bin/env bash
# One command from a fresh Debian 12 machine: installs the dependencies, builds glossa and runs
# the example job (examples/demo.sh: generate a small corpus, import, train, evaluate, predict).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
bash examples/demo.sh
