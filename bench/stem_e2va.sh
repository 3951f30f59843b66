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
for split in "text:13,14,15,16" "speaker:DPM"; do
  tag=$(echo "$split" | cut -d: -f1)
  models=()
  names=()
  for spec in "gru 1" "gru 2" "bigru 2" "bilstm 2" "mlp 1"; do
    set -- $spec
    kind=$1 layers=$2 extra=()
    case $kind in
      gru) dec=gru; name="GRU-${layers}L";;
      bigru) dec=gru; extra=(--bidirectional); name="Bi-GRU-${layers}L";;
      bilstm) dec=lstm; extra=(--bidirectional); name="Bi-LSTM-${layers}L";;
      mlp) dec=mlp; layers=2; name="MLP 15:5";;
    esac
    m="$work/$tag-$kind$layers.glossa"
    if [ ! -f "$m" ]; then
      echo "== $split $name"
      "$G" train -c "$work/corpus" -o "$m" --split "$split" --decoder $dec --layers $layers \
        "${extra[@]}" "${COMMON[@]}" --resume
    fi
    models+=(-m "$m")
    names+=(--name "$name MFCC")
  done
  "$G" eval -c "$work/corpus" --split "$split" "${models[@]}" "${names[@]}" \
    --ridge-features mfcc --ridge-features logmel --threads 1 \
    --md "$work/$tag.md" --csv "$work/$tag.csv"
done
