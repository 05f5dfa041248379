#!/usr/bin/env bash
# The survey baselines' experiments on a tile store (docs/baselines.md, roam.md, clipmaps.md):
#   1. ROAM's triangles and screen-space error against its error target (the flyover with
#      --quality, FRAMES frames; the reference's coverage is drawn once per run);
#   2. ROAM's and the clipmaps' CPU a frame against how far the camera moves a frame: the same
#      flyover sampled at 200, 800 and 3200 frames (no --quality), and the figures drawn.
#
#   scripts/baselines-figures.sh TELLUS STORE OUTPUT_FOLDER [SIZE] [FRAMES]
set -euo pipefail
tellus=${1:?usage: baselines-figures.sh TELLUS STORE OUTPUT_FOLDER [SIZE] [FRAMES]}
input=${2:?a tile store}
out=${3:?output folder}
size=${4:-1280x720}
frames=${5:-40}
scripts=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
targets=()
for target in 0.25 0.5 1 2 4; do
  "$tellus" bench "$input" --algo roam --roam-target "$target" --path flyover --frames "$frames" \
    --warmup 2 --size "$size" --quality --json "$out/target-$target.json" > "$out/target-$target.txt"
  targets+=("$target=$out/target-$target.json")
done
motion=()
for n in 200 800 3200; do
  "$tellus" bench "$input" --algo roam,clipmaps --path flyover --frames "$n" --warmup 2 \
    --size "$size" --json "$out/motion-$n.json" > "$out/motion-$n.txt"
  motion+=("$out/motion-$n.json")
done
/usr/bin/python3 "$scripts/plot_baselines_figures.py" "$out" --targets "${targets[@]}" --motion "${motion[@]}"
for f in "$out"/*.txt; do echo "== $(basename "$f" .txt)"; grep -E "^(roam|clipmaps) " "$f"; done
