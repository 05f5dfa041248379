#!/usr/bin/env bash
# The timing check of every renderer (issue 44), one script for any machine with a built
# tellus: it builds the stores it needs from ../shared/data (kept in OUT for the next run), runs
# the timing benches and writes their JSON reports and one markdown table (OUT/summary.md):
# per renderer and path, the frame, render-thread CPU, background CPU and GPU milliseconds
# (medians), triangles and GPU waits (median/max). Nothing is measured under --quality.
#
#   scripts/gpu-check.sh [--quick] [--frames N] [--tellus PATH] [--out DIR]
#
#   Korea flyover   korea.tstore (the 16 SRTM tiles, with BDAM's patches), every flat renderer,
#                   1280x720, and again at 3840x2160
#   globe           earth.tstore (ETOPO5 and the Korea tiles), RINGO and the spiral, descent
#                   and low flight, 1280x720
#   stacks          the seed-like preset (tellus stacks preset), stacks-full and stacks,
#                   1920x1080
#
# --quick: a few frames of each at small sizes, and a small generated stack terrain instead of
# the preset: a check that everything runs (a minute or two on llvmpipe), not figures to quote.
# --frames N: N frames a path instead of 200 (llvmpipe: 30 give medians in about 15 minutes).
# On an H200-class machine the full run takes about five minutes, most of it building stores.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
repo="$(dirname "$here")"
tellus="$repo/build/release/apps/tellus/tellus"
out="$repo/build/gpu-check"
quick=0
frames_given=
while [[ $# -gt 0 ]]; do
  case "$1" in
    --quick) quick=1; shift ;;
    --frames) frames_given="$2"; shift 2 ;;
    --tellus) tellus="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) echo "gpu-check: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
data="${TELLUS_DATA_DIR:-$repo/../shared/data}"
[[ -x "$tellus" ]] || { echo "gpu-check: no tellus binary at $tellus (make build, or --tellus PATH)" >&2; exit 1; }
[[ -d "$data/srtm3-hgt-east-asia" && -f "$data/etopo5-global/etopo5_int16.tif" ]] ||
  { echo "gpu-check: the shared data is not at $data (set TELLUS_DATA_DIR)" >&2; exit 1; }
mkdir -p "$out"

if [[ $quick == 1 ]]; then
  frames=8; warmup=2; flat=640x360; big=1280x720; stack_size=640x360
else
  frames=200; warmup=3; flat=1280x720; big=3840x2160; stack_size=1920x1080
fi
if [[ -n "$frames_given" ]]; then frames="$frames_given"; fi
step() { echo "gpu-check: $*"; }
timed() { local start=$SECONDS; "$@"; step "  ($((SECONDS - start)) s)"; }

korea_tiles=()
for lat in 34 35 36 37; do
  for lon in 126 127 128 129; do korea_tiles+=("$data/srtm3-hgt-east-asia/N${lat}E${lon}.hgt"); done
done

# The stores, built once (an existing one is reused: delete it to rebuild).
if [[ ! -f "$out/korea.tstore" || ! -f "$out/korea.bdam" ]]; then
  step "building korea.tstore with BDAM's patches (16 SRTM tiles)"
  timed "$tellus" build "${korea_tiles[@]}" -o "$out/korea.tstore" --bdam
fi
if [[ ! -f "$out/earth.tstore" ]]; then
  step "building earth.tstore (ETOPO5 and the Korea tiles)"
  timed "$tellus" build --global "$data/etopo5-global/etopo5_int16.tif" "${korea_tiles[@]}" \
    -o "$out/earth.tstore"
fi
if [[ $quick == 1 ]]; then
  stacks="$out/hills.tstack"
  if [[ ! -f "$stacks" ]]; then
    step "building hills.tstack (a generated 513 x 513 terrain)"
    "$tellus" generate --size 513 --spacing 10 --relief 800 -o "$out/hills.tif"
    timed "$tellus" stacks build "$out/hills.tif" -o "$stacks"
  fi
else
  stacks="$out/preset.tstack"
  if [[ ! -f "$stacks" ]]; then
    step "building preset.tstack (the seed-like preset)"
    timed "$tellus" stacks preset -o "$stacks"
  fi
fi

bench() {  # NAME INPUT ARGS...: one bench run into NAME.json, its table into NAME.txt
  local name="$1" input="$2"
  shift 2
  step "bench $name"
  timed "$tellus" bench "$input" --frames "$frames" --warmup "$warmup" --json "$out/$name.json" "$@" \
    | tee "$out/$name.txt"
}
flat_renderers=reference,rings,rag,roam,clipmaps,gamer,bdam,giw
bench korea-flyover "$out/korea.tstore" --algo "$flat_renderers" --path flyover --size "$flat"
bench korea-flyover-big "$out/korea.tstore" --algo "${flat_renderers#reference,}" --path flyover --size "$big"
bench globe-descent "$out/earth.tstore" --algo ringo,spiral --path descent --size "$flat"
bench globe-lowflight "$out/earth.tstore" --algo ringo,spiral --path lowflight --size "$flat"
bench stacks-flyover "$stacks" --algo stacks-full,stacks --path flyover --size "$stack_size"

python3 "$here/gpu_check_table.py" "$out" > "$out/summary.md"
step "wrote $out/summary.md"
cat "$out/summary.md"
