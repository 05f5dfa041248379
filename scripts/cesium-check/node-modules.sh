#!/usr/bin/env bash
# Sourced by run.sh, validate-gltf.sh and validate-3dtiles.sh: installs this folder's pinned npm
# packages (npm ci) into $TELLUS_NPM_CACHE/node_modules (default build/cesium-check under the
# repository root) once per lock file, under a lock (two tests may start at once), and sets
# `cache` to that folder.
# Needs `here` (this folder), `root` (the repository) and a `die` function.
cache=${TELLUS_NPM_CACHE:-$root/build/cesium-check}
mkdir -p "$cache"
cache=$(cd "$cache" && pwd)
want=$(cat "$here/package.json" "$here/package-lock.json" | sha256sum | cut -c1-16)
(
  flock 9
  if [[ ! -f $cache/node_modules/.tellus-lock-hash || $(cat "$cache/node_modules/.tellus-lock-hash") != "$want" ]]; then
    echo "cesium-check: installing node modules into $cache (npm ci)"
    rm -rf "$cache/node_modules"
    cp "$here/package.json" "$here/package-lock.json" "$cache/"
    if ! (cd "$cache" && npm ci --no-audit --no-fund --loglevel=error >"$cache/npm-ci.log" 2>&1); then
      cat "$cache/npm-ci.log" >&2
      exit 3
    fi
    echo "$want" >"$cache/node_modules/.tellus-lock-hash"
  fi
) 9>"$cache/.install.lock" || die "npm ci failed"
