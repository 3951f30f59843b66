#!/usr/bin/env bash
# The example job: generate a small synthetic EMA corpus whose audio depends on its
# articulation, import it, train a GRU-2L on MFCC features (examples/demo-train.json), evaluate
# it beside the mean-pose and ridge baselines on held-out sentences, and predict landmarks for
# one recording. Everything goes to ./out/demo.
set -euo pipefail
cd "$(dirname "$0")/.."
G=./build/glossa
out=out/demo
rm -rf "$out"
$G corpus demo "$out/source" --speakers 2 --texts 8 --takes 3
$G corpus import "$out/source" -o "$out/corpus"
$G corpus stats "$out/corpus"
$G train -c "$out/corpus" -o "$out/gru2.glossa" --config examples/demo-train.json --cache "$out/cache"
$G eval -c "$out/corpus" -m "$out/gru2.glossa" --md "$out/results.md" --csv "$out/results.csv"
$G predict "$out/source/S01T101.wav" -m "$out/gru2.glossa" -o "$out/S01T101-landmarks"
echo "demo finished: see $out/results.md and $out/S01T101-landmarks.csv"
