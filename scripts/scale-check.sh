#!/usr/bin/env bash
# The planet-scale checks of docs/scale.md (issue 47), on generated SRTM tiles: `make scale-check`.
#
#   scripts/scale-check.sh --tellus BIN [--out DIR] [--box W,S,E,N] [--seed N] [--ranks "1 2 4"]
#                          [--frames N] [--skip-http] [--skip-builds] [--skip-update]
#
# 1. Generates the procedural planet's land in the box as SRTM3 tiles (tellus generate
#    --srtm-tiles; default: 369 land tiles of the 400 in 60..40 W, 20..0 S of seed 5, 1 GB) and
#    the planet itself as the global source (4096 x 2048), once: they are kept in DIR.
# 2. Builds one global store of them without mpirun, then with `mpirun -np N` for each N of
#    --ranks, and checks that every build wrote the same bytes. Each build's wall time, tiles a
#    second, its steps and its ranks' peak memory go into DIR/summary.md.
#    Then updates the store with four more tiles (--update) and checks it against a build of all
#    the sources: the time of each and the tiles rewritten.
# 3. Serves the store from a stock lighttpd on 127.0.0.1 and flies RINGO down a descent onto the
#    box's highest sample over HTTP with --quality (cracks, SSE: the ground truth reads the finest
#    tiles in view, over HTTP too), then RINGO and the spiral again through
#    scripts/latency-proxy.py (50 ms on every answer) without --quality: frame times, the render
#    thread's LOD step, GPU waits and tiles missed into DIR/summary.md. --skip-builds reuses DIR/planet-1proc.tstore.
#
# Needs mpirun (openmpi-bin), lighttpd and python3; make test installs them. Exit status 0 when
# every build gave the same bytes and the descents drew without cracks.
set -euo pipefail

die() { echo "scale-check: $*" >&2; exit 2; }

tellus= out=build/scale box=-60,-20,-40,0 seed=5 ranks="1 2 4" frames=60 http=1 builds=1 update=1
while (($#)); do
  case $1 in
    --tellus) tellus=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --box) box=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --ranks) ranks=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --skip-http) http=0; shift ;;
    --skip-builds) builds=0; shift ;;
    --skip-update) update=0; shift ;;
    *) die "unknown argument '$1'" ;;
  esac
done
[[ -x $tellus ]] || die "give the tellus binary with --tellus (got '$tellus')"
tellus=$(realpath "$tellus")
scripts=$(dirname "$(realpath "$0")")
for tool in mpirun python3; do command -v $tool >/dev/null || die "$tool is missing (scripts/install-deps.sh)"; done
((http == 0)) || command -v lighttpd >/dev/null || die "lighttpd is missing (scripts/install-deps.sh)"
mkdir -p "$out"
out=$(realpath "$out")
summary=$out/summary.md
log() { echo "scale-check: $*" >&2; }

# --- 1. inputs ------------------------------------------------------------------------------------
tiles=$out/srtm-$seed-${box//,/_}
planet=$out/planet-$seed.tif
if [[ ! -f $tiles/.complete ]]; then
  rm -rf "$tiles"
  log "generating the SRTM tiles of $box (seed $seed) into $tiles"
  "$tellus" generate --seed "$seed" --srtm-tiles "$box" -o "$tiles"
  touch "$tiles/.complete"
fi
if [[ ! -f $planet ]]; then
  log "generating the planet (seed $seed) into $planet"
  "$tellus" generate --planet --seed "$seed" --size 4096 -o "$planet"
fi
mapfile -t sources < <(find "$tiles" -name '*.hgt' | sort)
((${#sources[@]} > 0)) || die "no .hgt tile in $tiles"
input_bytes=$(du -cb "${sources[@]}" | tail -1 | cut -f1)

# --- 2. builds ------------------------------------------------------------------------------------
peak_of() { sed -n 's/.*peak memory of a rank \(.*\)$/\1/p' "$1"; }
steps_of() { sed -n 's/.*steps (slowest rank): \(.*\); peak.*/\1/p' "$1"; }
{
  echo "# Scale check: $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores"
  echo
  echo "Inputs: ${#sources[@]} SRTM3 tiles ($((input_bytes / 1048576)) MiB) of $box, seed $seed, and the planet $(basename "$planet")."
  echo
  echo "| build | wall s | tiles | tiles/s | store | steps (slowest rank) | peak memory of a rank | same bytes |"
  echo "|---|---|---|---|---|---|---|---|"
} >"$summary"
reference=$out/planet-1proc.tstore
status=0
run_build() {  # NAME LAUNCHER...
  local name=$1; shift
  local store=$out/planet-$name.tstore report=$out/build-$name.log
  log "build: $name"
  local start end
  start=$(date +%s.%N)
  "$@" "$tellus" build --global "$planet" "${sources[@]}" -o "$store" 2>&1 | tee "$report" >&2
  end=$(date +%s.%N)
  local wall tiles same
  wall=$(python3 -c "print(f'{$end - $start:.1f}')")
  tiles=$(sed -n 's/.* depths 0\.\.[0-9]*, \([0-9]*\) tiles.*/\1/p' "$report")
  if [[ $store == "$reference" ]]; then same="(reference)"
  elif cmp -s "$store" "$reference"; then same=yes; rm -f "$store"
  else same=NO; status=1; fi
  echo "| $name | $wall | $tiles | $(python3 -c "print(f'{$tiles / $wall:.1f}')") | $(du -h "$reference" | cut -f1) | $(steps_of "$report") | $(peak_of "$report") | $same |" >>"$summary"
}
if ((builds)); then
  run_build 1proc
  for n in $ranks; do
    run_build "mpirun-$n" mpirun --allow-run-as-root --oversubscribe -np "$n"
  done
else
  [[ -f $reference ]] || die "--skip-builds: $reference is missing"
  echo "| (builds skipped: $(basename "$reference") reused) | | | | | | | |" >>"$summary"
fi

# --- 2b. an update: four more tiles west of the box ------------------------------------------------
if ((update)); then
  extra=$out/srtm-$seed-update
  if [[ ! -f $extra/.complete ]]; then
    rm -rf "$extra"
    log "generating the update's tiles (-62,-12,-60,-10) into $extra"
    "$tellus" generate --seed "$seed" --srtm-tiles -62,-12,-60,-10 -o "$extra"
    touch "$extra/.complete"
  fi
  mapfile -t additions < <(find "$extra" -name '*.hgt' | sort)
  timed() {  # LOG COMMAND...: runs it, its output into LOG, prints the wall seconds
    local log=$1; shift
    local start end
    start=$(date +%s.%N)
    "$@" >"$log" 2>&1 || { cat "$log" >&2; die "failed: $*"; }
    end=$(date +%s.%N)
    python3 -c "print(f'{$end - $start:.1f}')"
  }
  log "update: ${#additions[@]} tiles into $(basename "$reference")"
  update_s=$(timed "$out/update.log" "$tellus" build --global --update "$reference" "${additions[@]}" -o "$out/planet-updated.tstore")
  # The full build of the same sources: the store's own in its order (finest first: the SRTM tiles
  # as given, then the planet), then the new ones.
  full_s=$(timed "$out/update-full.log" "$tellus" build --global "${sources[@]}" "$planet" "${additions[@]}" -o "$out/planet-full.tstore")
  if cmp -s "$out/planet-updated.tstore" "$out/planet-full.tstore"; then same=yes; else same=NO; status=1; fi
  {
    echo
    echo "Update with ${#additions[@]} SRTM tiles of -62,-12,-60,-10: \`tellus build --global --update $(basename "$reference") NEW.hgt... -o planet-updated.tstore\` against a build of all the sources."
    echo
    echo "| build | wall s | tiles | same bytes |"
    echo "|---|---|---|---|"
    echo "| update | $update_s | $(sed -n 's/.*updated from [^:]*: \(.*\)$/\1/p' "$out/update.log") | $same |"
    echo "| full build | $full_s | $(sed -n 's/.* depths 0\.\.[0-9]*, \([0-9]*\) tiles.*/\1/p' "$out/update-full.log") | (reference) |"
  } >>"$summary"
  rm -f "$out/planet-full.tstore"
fi

# --- 3. served over HTTP --------------------------------------------------------------------------
if ((http)); then
  tmp=$(mktemp -d)
  server_pid= proxy_pid=
  cleanup() {
    [[ -n $server_pid ]] && kill "$server_pid" 2>/dev/null || true
    [[ -n $proxy_pid ]] && kill "$proxy_pid" 2>/dev/null || true
    rm -rf "$tmp"
  }
  trap cleanup EXIT
  free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }
  port=$(free_port)
  mkdir -p "$tmp/root"
  ln -s "$reference" "$tmp/root/planet.tstore"
  cat >"$tmp/lighttpd.conf" <<EOF
server.document-root = "$tmp/root"
server.bind = "127.0.0.1"
server.port = $port
server.errorlog = "$tmp/error.log"
server.follow-symlink = "enable"
mimetype.assign = ("" => "application/octet-stream")
EOF
  lighttpd -D -f "$tmp/lighttpd.conf" </dev/null >"$tmp/lighttpd.out" 2>&1 &
  server_pid=$!
  proxy_port=$(free_port)
  python3 "$scripts/latency-proxy.py" "$proxy_port" "$port" 50 >"$tmp/proxy.out" 2>&1 &
  proxy_pid=$!
  for _ in $(seq 100); do
    (exec 3<>"/dev/tcp/127.0.0.1/$proxy_port") 2>/dev/null && break
    sleep 0.1
  done
  direct=http://127.0.0.1:$port/planet.tstore
  delayed=http://127.0.0.1:$proxy_port/planet.tstore
  "$tellus" info "$delayed" >"$out/info-http.txt" 2>&1 || { cat "$out/info-http.txt" >&2; die "the store is not readable over HTTP"; }
  {
    echo
    echo "Served by lighttpd $(lighttpd -v 2>&1 | head -1 | cut -d' ' -f1 | cut -d/ -f2) on 127.0.0.1, directly and through scripts/latency-proxy.py (50 ms on every answer): \`tellus bench URL --algo ALGO --path descent --frames $frames --size 640x360 [--quality]\`."
    echo
    echo "| renderer | served | frames | cracks (px in all, worst frame) | SSE p95 / p99 px | frame ms median | slowest frame ms | render thread's LOD step, max ms | GPU waits | tiles missed |"
    echo "|---|---|---|---|---|---|---|---|---|---|"
  } >>"$summary"
  descend() {  # ALGO LABEL URL [--quality]
    local algo=$1 label=$2 url=$3; shift 3
    log "descent over HTTP: $algo, $label"
    local report=$out/descent-$algo-$label.json
    "$tellus" bench "$url" --algo "$algo" --path descent --frames "$frames" --size 640x360 "$@" \
      --json "$report" >"$out/descent-$algo-$label.log" 2>&1 || { tail -5 "$out/descent-$algo-$label.log" >&2; status=1; return; }
    python3 "$scripts/scale_descent_row.py" "$report" "$algo" "$label" >>"$summary" || status=1
  }
  descend ringo direct "$direct" --quality
  descend ringo 50ms "$delayed"
  descend spiral 50ms "$delayed"
fi
cat "$summary"
exit $status
