#!/usr/bin/env bash
# make fuzz-long: every libFuzzer target for SECONDS (default 600) on two cores: two workers
# (-jobs=2 -workers=2) share one corpus and pick up each other's finds every second. Each run
# has two phases, the first minute and the rest, so the report shows whether coverage still
# grows after the first minute: "cov 60 s" is the coverage (edges) the second phase starts from
# (all that the first minute found), "cov end" the coverage at the end; "ft" the same for
# libFuzzer's features (edges with hit-count buckets, which keep growing after every edge of a
# small target is covered). Crashes stop nothing: they are counted (per worker and phase), and
# their inputs kept in the target's folder.
#
#   scripts/fuzz-long.sh BUILD_DIR [SECONDS] [TARGET...]
#
# Writes BUILD_DIR/fuzz-long/<target>/ (corpus, worker logs, crash inputs) and
# BUILD_DIR/fuzz-long/report.md (the table, also printed). Then merge what was found into the
# repository's regression corpus with scripts/fuzz-long.sh's companion command printed at the
# end.
set -euo pipefail

build=$(cd "${1:?usage: fuzz-long.sh BUILD_DIR [SECONDS] [TARGET...]}" && pwd)
seconds=${2:-600}
shift $(( $# >= 2 ? 2 : $# ))
source_dir=$(cd "$(dirname "$0")/.." && pwd)
bin="$build/fuzz"
out="$build/fuzz-long"
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(fuzz_decode_raw fuzz_decode_zstd fuzz_decode_bounded fuzz_decode_lerc
           fuzz_decode_fractal fuzz_store_reader fuzz_keyframes fuzz_dem_load
           fuzz_stack_reader fuzz_bdam_reader fuzz_store_metadata fuzz_http_response
           fuzz_quantized_mesh fuzz_terrain_mesh)
fi
first=60
(( seconds > first )) || first=$(( seconds / 2 ))

# The seed corpus folder each target starts from (see fuzz/CMakeLists.txt).
seed_folder() {
  case "$1" in
    fuzz_decode_*) echo "${1#fuzz_decode_}" ;;
    fuzz_store_reader) echo store ;;
    fuzz_keyframes) echo keyframes ;;
    fuzz_dem_load) echo dem ;;
    fuzz_stack_reader) echo stack ;;
    fuzz_bdam_reader) echo bdam ;;
    fuzz_store_metadata) echo metadata ;;
    fuzz_http_response) echo http ;;
    fuzz_quantized_mesh) echo qmesh ;;
    fuzz_terrain_mesh) echo terrainmesh ;;
  esac
}
max_len() {
  case "$1" in
    fuzz_store_reader | fuzz_dem_load | fuzz_stack_reader | fuzz_bdam_reader) echo 65536 ;;
    fuzz_store_metadata | fuzz_quantized_mesh | fuzz_http_response) echo 16384 ;;
    *) echo 4096 ;;
  esac
}

# The largest "<key>: N" over the lines of a worker's log that match the pattern.
best_after() {  # log pattern key
  grep -E "$2" "$1" | grep -oE "$3: [0-9]+" | awk '{print $2}' | sort -n | tail -1
}

# Runs one phase of a target: sums the workers' executions, takes their best coverage (edges)
# and features (edges with hit-count buckets) at the start (INITED) and at the end.
run_phase() {  # target folder seconds -> "executions cov_start cov_end ft_start ft_end crashes"
  local target=$1 folder=$2 time=$3
  rm -f "$folder"/fuzz-*.log
  (cd "$folder" && "$bin/$target" -jobs=2 -workers=2 -max_total_time="$time" \
      -max_len="$(max_len "$target")" -rss_limit_mb=2048 -timeout=20 -print_final_stats=1 \
      corpus "$bin/corpus/$(seed_folder "$target")" "$source_dir/fuzz/corpus/$target" \
      >/dev/null 2>&1) || true
  local execs=0 cs=0 ce=0 fs=0 fe=0 crashes=0 v
  for log in "$folder"/fuzz-*.log; do
    [ -f "$log" ] || continue
    v=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | awk '{print $2}' | tail -1)
    execs=$(( execs + ${v:-0} ))
    v=$(best_after "$log" 'INITED' cov); (( ${v:-0} > cs )) && cs=${v:-0}
    v=$(best_after "$log" 'INITED|NEW|REDUCE|pulse|DONE' cov); (( ${v:-0} > ce )) && ce=${v:-0}
    v=$(best_after "$log" 'INITED' ft); (( ${v:-0} > fs )) && fs=${v:-0}
    v=$(best_after "$log" 'INITED|NEW|REDUCE|pulse|DONE' ft); (( ${v:-0} > fe )) && fe=${v:-0}
    if grep -q 'ERROR: libFuzzer\|ERROR: AddressSanitizer\|runtime error' "$log"; then
      crashes=$(( crashes + 1 ))
    fi
  done
  echo "$execs $cs $ce $fs $fe $crashes"
}

mkdir -p "$out"
report="$out/report.md"
{
  echo "| target | executions | exec/s | cov 60 s | cov end | ft 60 s | ft end | crashes |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|"
} > "$report"
for target in "${targets[@]}"; do
  folder="$out/$target"
  rm -rf "$folder"
  mkdir -p "$folder/corpus"
  [ -t 1 ] && echo "fuzz-long: $target (${seconds} s on 2 workers)..."
  read -r e1 _ c1 _ f1 k1 < <(run_phase "$target" "$folder" "$first")
  read -r e2 cs2 c2 fs2 f2 k2 < <(run_phase "$target" "$folder" "$(( seconds - first ))")
  executions=$(( e1 + e2 ))
  # After the first minute: where phase 2 starts (it loads all that phase 1 found).
  cov60=$(( cs2 > c1 ? cs2 : c1 ))
  ft60=$(( fs2 > f1 ? fs2 : f1 ))
  printf '| %s | %s | %s | %s | %s | %s | %s | %s |\n' "$target" "$executions" \
    "$(( executions / seconds ))" "$cov60" "$(( c2 > cov60 ? c2 : cov60 ))" "$ft60" \
    "$(( f2 > ft60 ? f2 : ft60 ))" "$(( k1 + k2 ))" >> "$report"
done
cat "$report"
echo
echo "corpora in $out/<target>/corpus; to keep what they found as regression inputs:"
echo "  for t in ${targets[*]}; do \\"
echo "    $bin/\$t -set_cover_merge=1 -max_len=65536 $source_dir/fuzz/corpus/\$t $out/\$t/corpus; done"
