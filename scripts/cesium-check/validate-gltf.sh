#!/usr/bin/env bash
# Validates glTF files (.glb or .gltf) with the Khronos glTF validator (npm gltf-validator,
# pinned in package.json) and fails on any error or warning:
#
#   scripts/cesium-check/validate-gltf.sh FILE... [--report DIR]
#
# Prints a line per file (errors, warnings, infos, hints, and the first messages); with
# --report, writes the validator's full JSON report of each file as DIR/<name>.json. Exits 0
# when every file has no error and no warning, 1 otherwise, 2 on bad usage or a missing tool.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
die() { echo "validate-gltf: $*" >&2; exit 2; }
(($# >= 1)) || die "usage: $0 FILE... [--report DIR]"
command -v node >/dev/null || die "node not found (run scripts/install-deps.sh)"
command -v npm >/dev/null || die "npm not found (run scripts/install-deps.sh)"
# shellcheck source=node-modules.sh
source "$here/node-modules.sh"
exec node "$here/validate-gltf.mjs" --node-modules "$cache/node_modules" "$@"
