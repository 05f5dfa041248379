#!/usr/bin/env bash
# Validates a 3D Tiles 1.1 tile set (tileset JSON, external tilesets, implicit tiling subtrees,
# content files) against the official 3D Tiles 1.1 JSON schemas vendored in 3d-tiles-schema/,
# with ajv (npm, pinned in package.json); see validate-3dtiles.mjs for what is checked:
#
#   scripts/cesium-check/validate-3dtiles.sh TILESET_DIR|TILESET.json [--summary OUT.json]
#       [--list-contents FILE] [--list-tiles FILE] [--gltf]
#
# --gltf also runs the Khronos glTF validator over every .glb/.gltf content (fails on any error
# or warning). Node modules are installed once per lock file into $TELLUS_NPM_CACHE/node_modules
# (default build/cesium-check), as for validate-gltf.sh. Exits 0 when valid, 1 when anything
# fails, 2 on bad usage or a missing tool.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
die() { echo "validate-3dtiles: $*" >&2; exit 2; }
(($# >= 1)) || die "usage: $0 TILESET_DIR|TILESET.json [--summary OUT.json] [--list-contents FILE] [--list-tiles FILE] [--gltf]"
command -v node >/dev/null || die "node not found (run scripts/install-deps.sh)"
command -v npm >/dev/null || die "npm not found (run scripts/install-deps.sh)"
# shellcheck source=node-modules.sh
source "$here/node-modules.sh"
exec node "$here/validate-3dtiles.mjs" --node-modules "$cache/node_modules" "$@"
