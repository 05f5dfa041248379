#!/usr/bin/env bash
# Seed 004's experiments on a terrain (docs/rag.md): the rotation test (360 one-degree steps
# around a fixed position near the centre) for the settings of Figures 23-25, plotted as
# Figures 26-28 (frame time and triangles per step), and the Figure 14 comparison of the two
# variants at 3 passes.
#
#   scripts/rag-figures.sh TELLUS INPUT OUTPUT_FOLDER [SIZE]
set -euo pipefail
tellus=${1:?usage: rag-figures.sh TELLUS INPUT OUTPUT_FOLDER [SIZE]}
input=${2:?input DEM or store}
out=${3:?output folder}
size=${4:-640x360}
scripts=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
run() {  # name algo options...
  local name=$1 algo=$2
  shift 2
  "$tellus" bench "$input" --algo "$algo" --path rotate --frames 360 --warmup 2 --size "$size" \
    --json "$out/$name.json" --rag-unaligned "$@" > "$out/$name.txt"  # the seed's coarse mesh
}
for passes in 0 1 2; do run "fig26-passes-$passes" rag --rag-coarse 20 --rag-pixels 10 --rag-passes "$passes"; done
for pixels in 20 10 5; do run "fig27-pixels-$pixels" rag --rag-coarse 20 --rag-pixels "$pixels" --rag-passes 2; done
for coarse in 20 40 80; do run "fig28-coarse-$coarse" rag --rag-coarse "$coarse" --rag-pixels 10 --rag-passes 2; done
run fig14-rag rag --rag-passes 3
run fig14-rag-right rag-right --rag-passes 3
/usr/bin/python3 "$scripts/plot_rag_figures.py" "$out/fig26.png" "Figure 26: 20x20, 10 px, 0 / 1 / 2 passes" \
  "0 passes=$out/fig26-passes-0.json" "1 pass=$out/fig26-passes-1.json" "2 passes=$out/fig26-passes-2.json"
/usr/bin/python3 "$scripts/plot_rag_figures.py" "$out/fig27.png" "Figure 27: 20x20, 2 passes, 20 / 10 / 5 px" \
  "20 px=$out/fig27-pixels-20.json" "10 px=$out/fig27-pixels-10.json" "5 px=$out/fig27-pixels-5.json"
/usr/bin/python3 "$scripts/plot_rag_figures.py" "$out/fig28.png" "Figure 28: 2 passes, 10 px, 20 / 40 / 80 coarse" \
  "20x20=$out/fig28-coarse-20.json" "40x40=$out/fig28-coarse-40.json" "80x80=$out/fig28-coarse-80.json"
/usr/bin/python3 "$scripts/plot_rag_figures.py" "$out/fig14.png" "Figure 14: the two variants at 3 passes (defaults otherwise)" \
  "rag=$out/fig14-rag.json" "rag-right=$out/fig14-rag-right.json"
for f in "$out"/*.txt; do echo "== $(basename "$f" .txt)"; grep -E "^rag" "$f"; done
