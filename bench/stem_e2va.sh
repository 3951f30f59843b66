#!/usr/bin/env bash
# Regenerates the STEM-E2VA tables of bench/RESULTS.md: imports ../shared/data/stem-e2va,
# trains the paper's decoders with MFCC on (i) the text split (texts 13-16 held out) and
# (ii) the cross-speaker split, and evaluates them beside the mean-pose and ridge baselines.
# Usage: bench/stem_e2va.sh [work-dir]   (needs a built ./build/glossa)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
G=${GLOSSA:-$here/build/glossa}
data=${STEM_DATA:-$here/../shared/data/stem-e2va}
work=${1:-$here/out/stem}
if [ ! -d "$data" ]; then echo "skip: $data is absent"; exit 0; fi
mkdir -p "$work"
[ -f "$work/corpus/manifest.json" ] || "$G" corpus import "$data" -o "$work/corpus"
"$G" corpus stats "$work/corpus" > "$work/stats.txt"
COMMON=(--encoder mfcc --hidden "${HIDDEN:-256}" --epochs "${EPOCHS:-40}" --patience 8 --seed 1 --quiet)
# Rows: file tag | label | flags. The papers train on 15-frame (300 ms) windows; the
# bidirectional rows are also trained on 1 s windows (the thesis' supplement), which this small
# corpus needs (bench/RESULTS.md). Bidirectional models run on overlapping windows of their
# training length at inference.
ROWS=(
  "gru1|GRU-1L|--decoder gru --layers 1"
  "gru2|GRU-2L|--decoder gru --layers 2"
  "bigru2|Bi-GRU-2L|--decoder gru --layers 2 --bidirectional"
  "bigru2-w50|Bi-GRU-2L 1 s|--decoder gru --layers 2 --bidirectional --window 50"
  "bilstm2|Bi-LSTM-2L|--decoder lstm --layers 2 --bidirectional"
  "bilstm2-w50|Bi-LSTM-2L 1 s|--decoder lstm --layers 2 --bidirectional --window 50"
  "mlp|MLP 15:5|--decoder mlp --layers 2"
)
for split in "text:13,14,15,16" "speaker:DPM"; do
  tag=$(echo "$split" | cut -d: -f1)
  models=()
  names=()
  for row in "${ROWS[@]}"; do
    IFS='|' read -r file name flags <<< "$row"
    m="$work/$tag-$file.glossa"
    if [ ! -f "$m" ]; then
      echo "== $split $name"
      # shellcheck disable=SC2086  # $flags is a list of words
      "$G" train -c "$work/corpus" -o "$m" --split "$split" $flags "${COMMON[@]}" --resume
    fi
    models+=(-m "$m")
    names+=(--name "$name MFCC")
  done
  "$G" eval -c "$work/corpus" --split "$split" "${models[@]}" "${names[@]}" \
    --ridge-features mfcc --ridge-features logmel --threads 1 \
    --md "$work/$tag.md" --csv "$work/$tag.csv"
done
