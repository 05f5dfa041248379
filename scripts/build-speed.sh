#!/usr/bin/env bash
# `tellus build` against GDAL's COG writer (docs/globe.md, "Build speed"): for each input,
# PAIRS alternating runs of
#   tellus build INPUT -o OUT.tstore                      (default codec: zstd)
#   gdal_translate -of COG -co COMPRESS=ZSTD -co PREDICTOR=2 -co NUM_THREADS=ALL_CPUS INPUT OUT.tif
# with wall time and peak memory from /usr/bin/time; prints the median of each, their ratio and
# both file sizes as a markdown table.
#
# Inputs: the Korea SRTM mosaic (16 .hgt tiles; GDAL reads them through a VRT made by
# gdalbuildvrt) and a 16385 x 16385 generated float terrain (`tellus generate`, made once in
# WORK and kept). Nothing else should run meanwhile.
#
#   scripts/build-speed.sh TELLUS SHARED_DATA WORK [PAIRS=5]
#   make build-speed    (build/release/apps/tellus/tellus, ../shared/data, build/build-speed)
set -euo pipefail
tellus=${1:?usage: build-speed.sh TELLUS SHARED_DATA WORK [PAIRS]}
data=${2:?the shared data folder}
work=${3:?a work folder}
pairs=${4:-5}
mkdir -p "$work"
tellus=$(cd "$(dirname "$tellus")" && pwd)/$(basename "$tellus")

korea=("$data"/srtm3-hgt-east-asia/N3[4-7]E12[6-9].hgt)
if [ "${#korea[@]}" -ne 16 ]; then
  echo "build-speed: expected the 16 Korea tiles in $data/srtm3-hgt-east-asia" >&2
  exit 1
fi
gdalbuildvrt -q -overwrite "$work/korea.vrt" "${korea[@]}"
if [ ! -s "$work/generated-16385.tif" ]; then
  echo "build-speed: generating the 16385 x 16385 terrain (once)" >&2
  "$tellus" generate --size 16385 -o "$work/generated-16385.tif.part" >/dev/null
  mv "$work/generated-16385.tif.part" "$work/generated-16385.tif"
fi

# measure NAME OUTPUT COMMAND...: appends "seconds kilobytes bytes" to $work/NAME.runs
measure() {
  local name=$1 output=$2
  shift 2
  rm -f "$output"
  /usr/bin/time -o "$work/time.txt" -f "%e %M" "$@" >/dev/null 2>"$work/stderr.txt" || {
    cat "$work/stderr.txt" >&2
    exit 1
  }
  echo "$(cat "$work/time.txt") $(stat -c %s "$output")" >>"$work/$name.runs"
}

median() {  # median of column $2 of file $1
  sort -n -k"$2" "$1" | awk -v c="$2" '{v[NR]=$c} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2}'
}

describe() {  # runs file -> "s (all runs), peak MB, file MB"
  local runs s
  runs=$(awk '{printf "%s%s", sep, $1; sep=" / "}' "$1")
  s=$(median "$1" 1)
  awk -v s="$s" -v runs="$runs" -v kb="$(median "$1" 2)" -v b="$(median "$1" 3)" \
    'BEGIN {printf "%.2f s (%s), %.0f MB, %.1f MB", s, runs, kb / 1024, b / 1e6}'
}

cog=(gdal_translate -q -of COG -co COMPRESS=ZSTD -co PREDICTOR=2 -co NUM_THREADS=ALL_CPUS)
# The global store's deepest SRTM3 depth (10) samples every 180 / 2^10 / 256 degrees; GDAL does
# the same job with one warp to that grid (bilinear, float) written as a COG.
step=$(awk 'BEGIN {printf "%.12f", 180 / 1024 / 256}')
warp=(gdalwarp -q -overwrite -t_srs EPSG:4326 -tr "$step" "$step" -r bilinear -ot Float32 -multi
  -wo NUM_THREADS=ALL_CPUS -of COG -co COMPRESS=ZSTD -co PREDICTOR=3 -co NUM_THREADS=ALL_CPUS)

# compare NAME LABEL: PAIRS alternating runs of the commands in arrays `ours` and `theirs`.
compare() {
  local name=$1 label=$2
  rm -f "$work/$name-tellus.runs" "$work/$name-gdal.runs"
  for ((i = 1; i <= pairs; i++)); do
    echo "build-speed: $name pair $i of $pairs" >&2
    measure "$name-tellus" "$work/out.tstore" "${ours[@]}"
    measure "$name-gdal" "$work/out.tif" "${theirs[@]}"
  done
  rm -f "$work/out.tstore" "$work/out.tif"
  local t g
  t=$(median "$work/$name-tellus.runs" 1) g=$(median "$work/$name-gdal.runs" 1)
  echo "| $label | $(describe "$work/$name-tellus.runs") | $(describe "$work/$name-gdal.runs") | $(awk -v t="$t" -v g="$g" 'BEGIN {printf "%.2fx", t / g}') |"
}

echo "| input | tellus: median s (runs), peak MB, file MB | GDAL: median s (runs), peak MB, file MB | time ratio |"
echo "|---|---|---|---:|"
ours=("$tellus" build "${korea[@]}" -o "$work/out.tstore")
theirs=("${cog[@]}" "$work/korea.vrt" "$work/out.tif")
compare korea "Korea mosaic, 4801²: \`build\` / \`gdal_translate -of COG\`"
ours=("$tellus" build "$work/generated-16385.tif" -o "$work/out.tstore")
theirs=("${cog[@]}" "$work/generated-16385.tif" "$work/out.tif")
compare generated "generated 16385² (float): \`build\` / \`gdal_translate -of COG\`"
ours=("$tellus" build --global "${korea[@]}" -o "$work/out.tstore")
theirs=("${warp[@]}" "$work/korea.vrt" "$work/out.tif")
compare korea-global "Korea mosaic to latitude/longitude: \`build --global\` / \`gdalwarp -of COG\`"
