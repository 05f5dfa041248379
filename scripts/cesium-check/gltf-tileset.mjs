#!/usr/bin/env node
// Wraps one glTF that `tellus export --gltf` wrote into a one-tile 3D Tiles set, so that the
// Cesium check (run.sh) draws it where it lies on the globe:
//
//   node gltf-tileset.mjs FILE.glb OUT_DIR
//
// The glb's node extras give `ecefFromLocal`, the column-major matrix from its glTF frame
// (x east, y up, z south) to ECEF. 3D Tiles turns glTF's y up into z up first ((x, y, z) ->
// (x, -z, y): east, north, up), so the tile's transform is that matrix with its columns as
// east, north, up, origin. The bounding sphere: the origin and the POSITION accessor's extent;
// the tile set's geometric error its radius, the tile's 0 (it is the mesh itself).
// Writes OUT_DIR/tileset.json and OUT_DIR/model.glb (a copy). Exits 2 on bad usage or input.
import { copyFileSync, mkdirSync, readFileSync, writeFileSync } from "node:fs";
import path from "node:path";

const [file, out] = process.argv.slice(2);
if (!file || !out) {
  console.error("usage: node gltf-tileset.mjs FILE.glb OUT_DIR");
  process.exit(2);
}
const buf = readFileSync(file);
if (buf.toString("latin1", 0, 4) !== "glTF") {
  console.error(`gltf-tileset: ${file} is not a binary glTF`);
  process.exit(2);
}
const json = JSON.parse(buf.toString("utf8", 20, 20 + buf.readUInt32LE(12)));
const node = json.nodes[json.scenes[json.scene || 0].nodes[0]];
const m = node.extras && node.extras.ecefFromLocal;
if (!Array.isArray(m) || m.length !== 16) {
  console.error(`gltf-tileset: ${file} has no extras.ecefFromLocal (not a Tellus export?)`);
  process.exit(2);
}
// Columns of m: east (0..2), up (4..6), -north (8..10), origin (12..14).
const east = m.slice(0, 3), up = m.slice(4, 7), north = m.slice(8, 11).map((v) => -v), origin = m.slice(12, 15);
const transform = [...east, 0, ...north, 0, ...up, 0, ...origin, 1];
const acc = json.accessors[json.meshes[node.mesh].primitives[0].attributes.POSITION];
const s = node.scale || [1, 1, 1], t = node.translation || [0, 0, 0];
const corner = (i) => [0, 1, 2].map((c) => t[c] + s[c] * (i ? acc.max[c] : acc.min[c]));
const radius = Math.max(...[0, 1].map((i) => Math.hypot(...corner(i))));
mkdirSync(out, { recursive: true });
copyFileSync(file, path.join(out, "model.glb"));
writeFileSync(path.join(out, "tileset.json"), JSON.stringify({
  asset: { version: "1.1" },
  // Not drawing the model misses all of it: CesiumJS draws nothing of a tile set whose own
  // geometric error is under its screen-space threshold (0 would hide it from everywhere).
  geometricError: radius,
  root: {
    transform,
    boundingVolume: { sphere: [0, 0, 0, radius] },
    geometricError: 0,
    refine: "REPLACE",
    content: { uri: "model.glb" },
  },
}, null, 1));
console.log(`gltf-tileset: ${out}/tileset.json (one tile, bounding sphere ${radius.toFixed(0)} m)`);
