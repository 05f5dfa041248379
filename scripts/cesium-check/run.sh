#!/usr/bin/env bash
# Proves that CesiumJS loads and renders a quantized-mesh-1.0 tile set (as `tellus export --quantized-mesh`
# writes it) in headless Chromium: serves the tile set, Cesium and index.html from lighttpd on 127.0.0.1,
# runs check.mjs, stops the server, and leaves screenshot.png, summary.json and access.log in OUT_DIR.
#
#   scripts/cesium-check/run.sh TILESET_DIR OUT_DIR [lon lat height heading pitch] [--sample lon,lat]...
#                               [--timeout S] [--size WxH] [--min-fraction F] [--stable-frames N]
#                               [--param exaggeration=2] [--param normals=0] [--param time=ISO-8601]
#
# TILESET_DIR holds layer.json and {z}/{x}/{y}.terrain (a quantized-mesh set), or tileset.json (a 3D Tiles
# set, drawn as a Cesium3DTileset with the globe hidden: check.mjs --tileset). Camera in degrees and metres (defaults: index.html's,
# 127.5 34.9 60000 0 -30: central Korea looking north). Options after the camera go to check.mjs as they are.
# Without --sample, the height under the camera is sampled. Exits with check.mjs's status (0 = rendered,
# 1 = a check failed, 2 = bad arguments or a missing tool); OUT_DIR also gets lighttpd.log.
# Environment: TELLUS_NPM_CACHE (where node_modules lives; default build/cesium-check under the repo root),
# CHROMIUM_PATH (default Debian's /usr/lib/chromium/chromium), CESIUM_CHECK_KEEP_TMP=1 keeps the server folder.
# Needs Debian's chromium, lighttpd, nodejs and npm (scripts/install-deps.sh installs them).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)

die() { echo "cesium-check: $*" >&2; exit 2; }

(($# >= 2)) || die "usage: $0 TILESET_DIR OUT_DIR [lon lat height heading pitch] [--sample lon,lat]... [--timeout S] [--size WxH]"
tileset=$1 out=$2
shift 2
# A quantized-mesh set (layer.json) is served as terrain/, a 3D Tiles set (tileset.json) as tiles/.
if [[ -f "$tileset/layer.json" ]]; then
  mount=terrain kind=()
elif [[ -f "$tileset/tileset.json" ]]; then
  mount=tiles kind=(--tileset)
else
  die "$tileset holds neither layer.json (quantized mesh) nor tileset.json (3D Tiles)"
fi
tileset=$(cd "$tileset" && pwd)
mkdir -p "$out"
out=$(cd "$out" && pwd)

camera=()
while (($# > 0)) && [[ $1 != --* ]]; do camera+=("$1"); shift; done
((${#camera[@]} == 0 || ${#camera[@]} == 5)) || die "camera needs 5 numbers: lon lat height heading pitch"
extra=("$@")   # --sample lon,lat, --timeout S, ... go to check.mjs as they are
has_sample=0
for a in "${extra[@]}"; do [[ $a == --sample ]] && has_sample=1; done

for tool in node npm lighttpd; do
  command -v "$tool" >/dev/null || die "$tool not found (run scripts/install-deps.sh)"
done
chromium=${CHROMIUM_PATH:-}
if [[ -z $chromium ]]; then
  # The binary itself: Debian's /usr/bin/chromium wrapper only adds desktop flags and extension loading.
  for c in /usr/lib/chromium/chromium /usr/bin/chromium; do [[ -x $c ]] && { chromium=$c; break; }; done
fi
[[ -n $chromium && -x $chromium ]] || die "chromium not found (run scripts/install-deps.sh, or set CHROMIUM_PATH)"

# --- node_modules, installed once per lock file -------------------------------------------------------------
# shellcheck source=node-modules.sh
source "$here/node-modules.sh"
cesium_build=$cache/node_modules/cesium/Build/Cesium
[[ -f $cesium_build/Cesium.js ]] || die "$cesium_build/Cesium.js missing"

# --- lighttpd on 127.0.0.1 -----------------------------------------------------------------------------------
tmp=$(mktemp -d "${TMPDIR:-/tmp}/cesium-check.XXXXXX")
server_pid=
check_pid=
# shellcheck disable=SC2317  # reached through the EXIT trap
cleanup() {
  local rc=$?
  trap '' INT TERM  # a second signal (timeout(1) sends one to the script and one to its group) must not cut this short
  if [[ -n $check_pid ]] && kill -0 "$check_pid" 2>/dev/null; then
    kill "$check_pid" 2>/dev/null || true
    wait "$check_pid" 2>/dev/null || true
  fi
  if [[ -n $server_pid ]] && kill -0 "$server_pid" 2>/dev/null; then
    kill "$server_pid" 2>/dev/null || true
    wait "$server_pid" 2>/dev/null || true
  fi
  [[ -f $tmp/access.log ]] && cp "$tmp/access.log" "$out/access.log"
  [[ -s $tmp/error.log ]] && cp "$tmp/error.log" "$out/lighttpd.log"
  if [[ ${CESIUM_CHECK_KEEP_TMP:-0} == 1 ]]; then echo "cesium-check: kept $tmp" >&2; else rm -rf "$tmp"; fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

mkdir -p "$tmp/root"
ln -s "$cesium_build" "$tmp/root/Cesium"
ln -s "$tileset" "$tmp/root/$mount"
cp "$here/index.html" "$tmp/root/index.html"
rm -f "$out/screenshot.png" "$out/summary.json" "$out/access.log" "$out/lighttpd.log"

free_port() {
  node -e 'const s=require("net").createServer();s.listen(0,"127.0.0.1",()=>{console.log(s.address().port);s.close()})'
}

start_server() {
  local port=$1
  cat >"$tmp/lighttpd.conf" <<EOF
server.document-root = "$tmp/root"
server.bind = "127.0.0.1"
server.port = $port
server.errorlog = "$tmp/error.log"
server.modules = ("mod_accesslog")
accesslog.filename = "$tmp/access.log"
server.follow-symlink = "enable"
server.tag = "tellus-cesium-check"
index-file.names = ("index.html")

mimetype.assign = (
  ".terrain" => "application/vnd.quantized-mesh",
  ".html"    => "text/html; charset=utf-8",
  ".js"      => "text/javascript",
  ".mjs"     => "text/javascript",
  ".cjs"     => "text/javascript",
  ".json"    => "application/json",
  ".css"     => "text/css",
  ".wasm"    => "application/wasm",
  ".png"     => "image/png",
  ".jpg"     => "image/jpeg",
  ".jpeg"    => "image/jpeg",
  ".gif"     => "image/gif",
  ".svg"     => "image/svg+xml",
  ".ktx2"    => "image/ktx2",
  ".glb"     => "model/gltf-binary",
  ".gltf"    => "model/gltf+json",
  ".b3dm"    => "application/octet-stream",
  ".xml"     => "application/xml",
  ".txt"     => "text/plain; charset=utf-8",
  ""         => "application/octet-stream"
)
EOF
  lighttpd -tt -f "$tmp/lighttpd.conf" >/dev/null || die "lighttpd rejected its config ($tmp/lighttpd.conf)"
  lighttpd -D -f "$tmp/lighttpd.conf" </dev/null >>"$tmp/lighttpd.out" 2>&1 &
  server_pid=$!
  local i
  for ((i = 0; i < 50; i++)); do
    kill -0 "$server_pid" 2>/dev/null || { server_pid=; return 1; }
    if (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null; then return 0; fi
    sleep 0.1
  done
  return 1
}

port=
for _ in 1 2 3 4 5; do
  p=$(free_port)
  if start_server "$p"; then port=$p; break; fi
  if [[ -n $server_pid ]]; then kill "$server_pid" 2>/dev/null || true; wait "$server_pid" 2>/dev/null || true; server_pid=; fi
done
[[ -n $port ]] || { cat "$tmp/lighttpd.out" "$tmp/error.log" >&2 2>/dev/null || true; die "lighttpd did not start"; }

# --- the check --------------------------------------------------------------------------------------------------
args=(--url "http://127.0.0.1:$port/index.html" --summary "$out/summary.json" --screenshot "$out/screenshot.png"
      --node-modules "$cache/node_modules" --chromium "$chromium")
((${#camera[@]} == 5)) && args+=(--camera "$(IFS=,; echo "${camera[*]}")")
((has_sample == 1)) || args+=(--sample "${camera[0]:-127.5},${camera[1]:-34.9}")
# In the background and waited for, so that a signal to this script runs the cleanup at once (check.mjs
# closes Chromium on SIGTERM).
node "$here/check.mjs" "${args[@]}" "${kind[@]}" "${extra[@]}" &
check_pid=$!
status=0
wait "$check_pid" || status=$?
check_pid=
exit "$status"
