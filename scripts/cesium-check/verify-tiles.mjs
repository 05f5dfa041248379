#!/usr/bin/env node
// An independent check of a quantized-mesh-1.0 tile set (or of a 3D Tiles set of glTF tiles:
// see verifyTileset below) against the SRTM tiles it was made from, written from the format's specification (github.com/CesiumGS/quantized-mesh) and
// WGS84's formulas, sharing no code with Tellus:
//
//   node verify-tiles.mjs TILESET_DIR --hgt FILE.hgt [--hgt ...] [--geoid FILE.gtx] [--summary OUT.json]
//
// For every tile layer.json lists: decodes it (header, zig-zag delta vertices, high-water-mark
// indices, edge lists, extensions), places its vertices as Cesium does (longitude and latitude
// from u and v over the tile, height between the header's minimum and maximum, then ECEF on
// WGS84) and, for every SRTM sample strictly inside the tile, finds the triangle over it and
// measures the 3-D distance between the sample's true position (its longitude, latitude and
// height in ECEF) and the triangle's point at the sample's tile coordinates: how far the
// surface Cesium draws is from the data. That distance must not exceed Cesium's geometric
// error of the tile's level (CesiumTerrainProvider's estimate for a 65-sample heightmap:
// a * 2 pi * 0.25 / (65 * 2) / 2^level). Also: every sample is covered by a triangle, the edge
// lists name exactly the vertices on each edge, and neighbouring tiles of a level have the same
// vertices along their shared edge (heights within the two tiles' quantization).
// The horizon occlusion point: from cameras around each tile (heights from 10 m to 40,000 km),
// whenever Cesium's test (EllipsoidalOccluder.isScaledSpacePointVisible, in the ellipsoid-scaled
// frame) calls the tile's point hidden, every vertex of the tile must be hidden too (else
// Cesium culls a tile that shows). Tiles with heights under the ellipsoid are skipped: Cesium
// computes their point again from the vertices.
// The tiles' heights are the SRTM heights as they are, or (--geoid, for a set exported with
// the same geoid) those plus the geoid's undulation, read here from the .gtx grid (a 40-byte
// big-endian header: south latitude, west longitude, steps, rows, columns; then float32 rows from
// the south) and interpolated bilinearly, longitudes wrapped.
// Prints a table per level with the worst ratio; exits 1 when any check fails, 2 on bad usage.
import { existsSync, readFileSync, readdirSync, writeFileSync } from "node:fs";
import path from "node:path";

const A = 6378137.0;
const F = 1 / 298.257223563;
const E2 = F * (2 - F);
const Q = 32767;

function usage(msg) {
  console.error(`verify-tiles.mjs: ${msg}`);
  console.error("usage: node verify-tiles.mjs TILESET_DIR --hgt FILE.hgt [--hgt ...] [--geoid FILE.gtx] [--summary OUT.json]");
  process.exit(2);
}

const args = process.argv.slice(2);
let dir = null, summaryPath = null, geoidPath = null;
const hgtFiles = [];
for (let i = 0; i < args.length; i++) {
  if (args[i] === "--hgt") hgtFiles.push(args[++i]);
  else if (args[i] === "--summary") summaryPath = args[++i];
  else if (args[i] === "--geoid") geoidPath = args[++i];
  else if (!dir) dir = args[i];
  else usage(`unexpected argument '${args[i]}'`);
}
if (!dir || hgtFiles.length === 0) usage("a tile set folder and at least one --hgt file are needed");

function ecef(lonDeg, latDeg, h) {
  const lon = (lonDeg * Math.PI) / 180, lat = (latDeg * Math.PI) / 180;
  const s = Math.sin(lat), c = Math.cos(lat);
  const n = A / Math.sqrt(1 - E2 * s * s);
  return [(n + h) * c * Math.cos(lon), (n + h) * c * Math.sin(lon), (n * (1 - E2) + h) * s];
}

// --- The geoid's undulation (0 without --geoid).
const undulation = (() => {
  if (!geoidPath) return () => 0;
  const g = readFileSync(geoidPath);
  const south = g.readDoubleBE(0), west = g.readDoubleBE(8), dLat = g.readDoubleBE(16), dLon = g.readDoubleBE(24);
  const rows = g.readInt32BE(32), cols = g.readInt32BE(36);
  if (g.length !== 40 + rows * cols * 4) usage(`${geoidPath}: ${g.length} bytes is not a ${cols} x ${rows} .gtx grid`);
  const at = (r, c) => g.readFloatBE(40 + 4 * (r * cols + (((c % cols) + cols) % cols)));
  return (latDeg, lonDeg) => {
    const y = Math.min(Math.max((latDeg - south) / dLat, 0), rows - 1);
    let x = (lonDeg - west) / dLon;
    const period = Math.round(360 / dLon);
    x = ((x % period) + period) % period;
    const r0 = Math.min(Math.floor(y), rows - 2), c0 = Math.floor(x);
    const fy = y - r0, fx = x - c0;
    return (at(r0, c0) * (1 - fx) + at(r0, c0 + 1) * fx) * (1 - fy) + (at(r0 + 1, c0) * (1 - fx) + at(r0 + 1, c0 + 1) * fx) * fy;
  };
})();

// --- SRTM samples: an .hgt file is N x N big-endian int16, row 0 north, its name the south-west
// corner (N37E127), samples on whole fractions of a degree, -32768 a void.
const sources = hgtFiles.map((file) => {
  const m = /([NS])(\d\d)([EW])(\d\d\d)\.hgt$/i.exec(path.basename(file));
  if (!m) usage(`${file}: not an SRTM tile name (like N37E127.hgt)`);
  const lat0 = (m[1].toUpperCase() === "N" ? 1 : -1) * Number(m[2]);
  const lon0 = (m[3].toUpperCase() === "E" ? 1 : -1) * Number(m[4]);
  const bytes = readFileSync(file);
  const n = Math.round(Math.sqrt(bytes.length / 2));
  if (n * n * 2 !== bytes.length) usage(`${file}: ${bytes.length} bytes is no square of int16`);
  const heights = new Int16Array(n * n);
  for (let k = 0; k < n * n; k++) heights[k] = bytes.readInt16BE(2 * k);
  return { lat0, lon0, n, heights };
});

// --- Tiles ---
function zigZag(v) { return (v >> 1) ^ -(v & 1); }

function decodeTile(buf, where) {
  let o = 0;
  const need = (k, what) => { if (o + k > buf.length) throw new Error(`${where}: truncated in ${what}`); };
  const f64 = () => { need(8, "header"); const v = buf.readDoubleLE(o); o += 8; return v; };
  const f32 = () => { need(4, "header"); const v = buf.readFloatLE(o); o += 4; return v; };
  const u32 = (what) => { need(4, what); const v = buf.readUInt32LE(o); o += 4; return v; };
  const header = { centre: [f64(), f64(), f64()], minH: f32(), maxH: f32(),
    sphere: [f64(), f64(), f64(), f64()], hop: [f64(), f64(), f64()] };
  const count = u32("vertex count");
  const arrays = [new Uint16Array(count), new Uint16Array(count), new Uint16Array(count)];
  for (const arr of arrays) {
    let value = 0;
    for (let k = 0; k < count; k++) {
      need(2, "vertices");
      value += zigZag(buf.readUInt16LE(o)); o += 2;
      if (value < 0 || value > Q) throw new Error(`${where}: vertex value ${value} outside 0..32767`);
      arr[k] = value;
    }
  }
  const wide = count > 65536;
  const size = wide ? 4 : 2;
  if (o % size) o += size - (o % size);
  const readIndex = () => { need(size, "indices"); const v = wide ? buf.readUInt32LE(o) : buf.readUInt16LE(o); o += size; return v; };
  const triangles = u32("triangle count");
  const indices = new Uint32Array(triangles * 3);
  let highest = 0;
  for (let k = 0; k < indices.length; k++) {
    const code = readIndex();
    indices[k] = highest - code;
    if (code === 0) highest++;
    if (indices[k] >= count) throw new Error(`${where}: index ${indices[k]} beyond ${count} vertices`);
  }
  const edges = [];
  for (let e = 0; e < 4; e++) {
    const n = u32("edge list");
    const list = [];
    for (let k = 0; k < n; k++) list.push(readIndex());
    edges.push(list);
  }
  // Extensions: an id byte, a uint32 length, the bytes. Metadata (4): a uint32 length and JSON.
  let metadata = null;
  while (o < buf.length) {
    need(5, "extension header");
    const id = buf.readUInt8(o), length = buf.readUInt32LE(o + 1);
    o += 5;
    need(length, "extension");
    if (id === 4) {
      if (length < 4) throw new Error(`${where}: metadata extension of ${length} bytes`);
      const textLength = buf.readUInt32LE(o);
      if (textLength > length - 4) throw new Error(`${where}: metadata text of ${textLength} bytes in ${length}`);
      metadata = JSON.parse(buf.toString("utf8", o + 4, o + 4 + textLength));
    }
    o += length;
  }
  return { header, u: arrays[0], v: arrays[1], h: arrays[2], indices, edges, metadata };
}

const B = A * (1 - F);
const scaled = (p) => [p[0] / A, p[1] / A, p[2] / B];
// Cesium's EllipsoidalOccluder.isScaledSpacePointVisible.
function scaledPointVisible(o, cv) {
  const vh2 = cv[0] * cv[0] + cv[1] * cv[1] + cv[2] * cv[2] - 1;
  const vt = [o[0] - cv[0], o[1] - cv[1], o[2] - cv[2]];
  const vtDotVc = -(vt[0] * cv[0] + vt[1] * cv[1] + vt[2] * cv[2]);
  const occluded = vh2 < 0 ? vtDotVc > 0
    : vtDotVc > vh2 && (vtDotVc * vtDotVc) / (vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]) > vh2;
  return !occluded;
}
// A deterministic generator (mulberry32): the same cameras every run.
function random32(seed) {
  return () => {
    seed |= 0; seed = (seed + 0x6d2b79f5) | 0;
    let t = Math.imul(seed ^ (seed >>> 15), 1 | seed);
    t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}
const camerasPerTile = (level) => (level <= 2 ? 5000 : 300);  // more where tiles are few and large

const geometricError = (level) => (A * 2 * Math.PI * 0.25) / (65 * 2) / 2 ** level;

// Every SRTM sample strictly inside the tile (west, south, extent degrees): the triangle over it
// (found in the tile's coordinates: uvOf(k) gives vertex k's, 0..1 west to east and south to
// north), and the 3-D distance between the sample's true position and that triangle's point at
// the sample's coordinates (pos: the vertices in ECEF). Adds to stats.samples, worstM, holes.
function measureSamples(stats, name, west, south, extent, uvOf, pos, indices) {
  for (const s of sources) {
    const step = 1 / (s.n - 1);
    const colLo = Math.max(0, Math.floor((west - s.lon0) / step));
    const colHi = Math.min(s.n - 1, Math.ceil((west + extent - s.lon0) / step));
    const rowLo = Math.max(0, Math.floor((s.lat0 + 1 - Math.min(90, south + extent)) / step));
    const rowHi = Math.min(s.n - 1, Math.ceil((s.lat0 + 1 - south) / step));
    if (colLo > colHi || rowLo > rowHi) continue;
    const covered = new Uint8Array((colHi - colLo + 1) * (rowHi - rowLo + 1));
    const inside = (col, row) => {
      const lo = s.lon0 + col * step, la = s.lat0 + 1 - row * step;
      return lo > west && lo < west + extent && la > south && la < south + extent &&
             s.heights[row * s.n + col] !== -32768;
    };
    for (let t = 0; t < indices.length; t += 3) {
      const a = indices[t], b = indices[t + 1], c = indices[t + 2];
      const [ua, va] = uvOf(a), [ub, vb] = uvOf(b), [uc, vc] = uvOf(c);
      const area = (ub - ua) * (vc - va) - (uc - ua) * (vb - va);
      if (area === 0) continue;
      const minLon = west + Math.min(ua, ub, uc) * extent, maxLon = west + Math.max(ua, ub, uc) * extent;
      const minLat = south + Math.min(va, vb, vc) * extent, maxLat = south + Math.max(va, vb, vc) * extent;
      const c0 = Math.max(colLo, Math.floor((minLon - s.lon0) / step));
      const c1 = Math.min(colHi, Math.ceil((maxLon - s.lon0) / step));
      const r0 = Math.max(rowLo, Math.floor((s.lat0 + 1 - maxLat) / step));
      const r1 = Math.min(rowHi, Math.ceil((s.lat0 + 1 - minLat) / step));
      for (let row = r0; row <= r1; row++) {
        for (let col = c0; col <= c1; col++) {
          if (!inside(col, row)) continue;
          const lo = s.lon0 + col * step, la = s.lat0 + 1 - row * step;
          const pu = (lo - west) / extent, pv = (la - south) / extent;
          const wa = ((ub - pu) * (vc - pv) - (uc - pu) * (vb - pv)) / area;
          const wb = ((uc - pu) * (va - pv) - (ua - pu) * (vc - pv)) / area;
          const wc = 1 - wa - wb;
          const eps = -1e-12;
          if (wa < eps || wb < eps || wc < eps) continue;
          const cell = (row - rowLo) * (colHi - colLo + 1) + (col - colLo);
          if (covered[cell]) continue;
          covered[cell] = 1;
          const truth = ecef(lo, la, s.heights[row * s.n + col] + undulation(la, lo));
          let d2 = 0;
          for (let i = 0; i < 3; i++) {
            const drawn = wa * pos[a][i] + wb * pos[b][i] + wc * pos[c][i];
            d2 += (truth[i] - drawn) ** 2;
          }
          const d = Math.sqrt(d2);
          stats.samples++;
          if (d > stats.worstM) { stats.worstM = d; stats.worstTile = name; }
        }
      }
    }
    for (let row = rowLo; row <= rowHi; row++) {
      for (let col = colLo; col <= colHi; col++) {
        if (inside(col, row) && !covered[(row - rowLo) * (colHi - colLo + 1) + (col - colLo)]) stats.holes++;
      }
    }
  }
}

// ECEF -> longitude, latitude (degrees) and height (metres) on WGS84, by fixed-point iteration
// on the latitude (converges to well under a millimetre in a few steps).
function geodetic([x, y, z]) {
  const lon = Math.atan2(y, x), p = Math.hypot(x, y);
  let lat = Math.atan2(z, p * (1 - E2)), h = 0;
  for (let i = 0; i < 6; i++) {
    const s = Math.sin(lat), c = Math.cos(lat);
    // The height along the normal, well conditioned at the poles too.
    h = p * c + z * s - A * Math.sqrt(1 - E2 * s * s);
    const n = A / Math.sqrt(1 - E2 * s * s);
    lat = Math.atan2(z, p * (1 - E2 * n / (n + h)));
  }
  return [(lon * 180) / Math.PI, (lat * 180) / Math.PI, h];
}

// A binary glTF's first mesh primitive, from the container and accessor rules of glTF 2.0:
// positions (float VEC3, tightly packed or strided), indices (unsigned byte, short or int) and
// TEXCOORD_0 when there is one,
// placed by the first node's translation and scale (a rotation or matrix is refused); integer
// components (KHR_mesh_quantization) read as glTF defines them, normalized or not.
function decodeGlb(buf, where) {
  if (buf.length < 20 || buf.toString("latin1", 0, 4) !== "glTF" || buf.readUInt32LE(4) !== 2) throw new Error(`${where}: not a glTF 2.0 binary`);
  if (buf.readUInt32LE(8) !== buf.length) throw new Error(`${where}: length ${buf.readUInt32LE(8)} in the header, ${buf.length} in the file`);
  let o = 12, json = null, bin = null;
  while (o + 8 <= buf.length) {
    const length = buf.readUInt32LE(o), type = buf.readUInt32LE(o + 4);
    if (type === 0x4e4f534a) json = JSON.parse(buf.toString("utf8", o + 8, o + 8 + length));
    else if (type === 0x004e4942) bin = buf.subarray(o + 8, o + 8 + length);
    o += 8 + length;
  }
  if (!json || !bin) throw new Error(`${where}: no JSON or BIN chunk`);
  const node = json.nodes[json.scenes[json.scene || 0].nodes[0]];
  if (node.rotation || node.matrix) throw new Error(`${where}: a node rotation or matrix (a translation and a scale expected)`);
  const accessorValues = (index, components) => {
    const acc = json.accessors[index], view = json.bufferViews[acc.bufferView];
    const size = { 5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4 }[acc.componentType];
    // Normalized integers (KHR_mesh_quantization): to -1..1 or 0..1 as glTF defines.
    const scale = !acc.normalized ? 1 : { 5120: 127, 5121: 255, 5122: 32767, 5123: 65535 }[acc.componentType];
    const stride = view.byteStride || size * components;
    const base = (view.byteOffset || 0) + (acc.byteOffset || 0);
    const out = new Float64Array(acc.count * components);
    for (let k = 0; k < acc.count; k++) {
      for (let c = 0; c < components; c++) {
        const at = base + k * stride + c * size;
        const raw = { 5120: () => bin.readInt8(at), 5121: () => bin.readUInt8(at), 5122: () => bin.readInt16LE(at),
                      5123: () => bin.readUInt16LE(at), 5125: () => bin.readUInt32LE(at), 5126: () => bin.readFloatLE(at) }[acc.componentType]();
        out[k * components + c] = acc.normalized ? Math.max(raw / scale, -1) : raw;
      }
    }
    return out;
  };
  const primitive = json.meshes[node.mesh].primitives[0];
  const local = accessorValues(primitive.attributes.POSITION, 3);
  const indices = accessorValues(primitive.indices, 1);
  // TEXCOORD_0: the tile's own coordinates, s eastwards and t southwards over its extent.
  const st = primitive.attributes.TEXCOORD_0 !== undefined ? accessorValues(primitive.attributes.TEXCOORD_0, 2) : null;
  const t = node.translation || [0, 0, 0], sc = node.scale || [1, 1, 1];
  // 3D Tiles takes glTF as y-up and turns it z-up: (x, y, z) -> (x, -z, y).
  const pos = [];
  for (let k = 0; k < local.length / 3; k++) {
    const gx = t[0] + sc[0] * local[3 * k], gy = t[1] + sc[1] * local[3 * k + 1], gz = t[2] + sc[2] * local[3 * k + 2];
    pos.push([gx, -gz, gy]);
  }
  // The grid step of quantized positions (KHR_mesh_quantization: the node's scale), metres.
  const step = local instanceof Float64Array && json.accessors[primitive.attributes.POSITION].componentType !== 5126 ? Math.max(...sc) : 0;
  // Texture coordinates as normalized 16-bit integers are within half of 1/65535 of the tile.
  const texStep = st && json.accessors[primitive.attributes.TEXCOORD_0].componentType !== 5126 ? 1 / 65535 : 0;
  return { pos, indices, st, step, texStep };
}

// --- A 3D Tiles set (tileset.json, as `tellus export --3d-tiles` writes it): the explicit root's
// children are implicit quadtrees over regions; each content H/tiles/L/X/Y.glb is checked like a
// quantized-mesh tile against every sample inside its region, with the geometric error the
// tile set gives it (its implicit root's halved L times), and its vertices must lie inside its
// bounding region.
function verifyTileset() {
  const tileset = JSON.parse(readFileSync(path.join(dir, "tileset.json"), "utf8"));
  const roots = tileset.root.children || [];
  const byLevel = [];
  roots.forEach((root, h) => {
    const [west, south, east, north, minH, maxH] = root.boundingVolume.region.map((v, i) => (i < 4 ? (v * 180) / Math.PI : v));
    const template = root.content.uri;
    const tilesDir = path.join(dir, path.dirname(template.split("{level}")[0] + "x"));
    for (const l of readdirSync(tilesDir).filter((n) => /^\d+$/.test(n)).map(Number)) {
      for (const x of readdirSync(path.join(tilesDir, `${l}`)).map(Number)) {
        for (const f of readdirSync(path.join(tilesDir, `${l}`, `${x}`))) {
          const y = Number(f.replace(/\.glb$/, ""));
          (byLevel[l] = byLevel[l] || []).push({ h, l, x, y, file: path.join(tilesDir, `${l}`, `${x}`, f),
            west: west + x * (east - west) / 2 ** l, south: south + y * (north - south) / 2 ** l,
            extent: (east - west) / 2 ** l, bound: root.geometricError / 2 ** l, minH, maxH });
        }
      }
    }
  });
  for (let z = 0; z < byLevel.length; z++) {
    const stats = { level: z, tiles: 0, samples: 0, worstM: 0, worstRatio: 0, worstTile: "", holes: 0, outsideVolume: 0, coordinateMismatches: 0 };
    let bound = 0;
    for (const t of byLevel[z] || []) {
      const name = `${t.h}/tiles/${t.l}/${t.x}/${t.y}.glb`;
      const { pos, indices, st, step, texStep } = decodeGlb(readFileSync(t.file), name);
      if (!st) throw new Error(`${name}: no TEXCOORD_0 (the tile's coordinates)`);
      stats.tiles++;
      bound = t.bound;
      // The tile coordinates of each vertex (u east, v north, 0..1) from TEXCOORD_0; its height
      // from its position. The position must be where the coordinates and height put it (within
      // float32's precision over the tile: 1e-6 of its size, and a centimetre; and half a grid
      // step's diagonal when positions or texture coordinates are quantized).
      const sizeM = (t.extent * Math.PI / 180) * A;
      const reachM = 1e-6 * sizeM + 0.01 + step * Math.sqrt(3) / 2 + sizeM * texStep * Math.SQRT1_2;
      const uv = pos.map((p, k) => {
        const hh = geodetic(p)[2];
        const u = st[2 * k], v = 1 - st[2 * k + 1];
        const expected = ecef(t.west + u * t.extent, Math.min(90, t.south + v * t.extent), hh);
        const miss = Math.hypot(expected[0] - p[0], expected[1] - p[1], expected[2] - p[2]);
        if (miss > reachM) {
          if (!stats.coordinateMismatches++) console.error(`${name}: vertex ${k} at ${miss.toFixed(3)} m from where (u ${u}, v ${v}, height ${hh.toFixed(2)}) puts it`);
        }
        return [u, v, hh];
      });
      // Inside the bounding region (by up to the reach above: the positions' own precision).
      for (const p of pos) {
        const [lo, la, hh] = geodetic(p);
        const du = Math.min(Math.abs(lo - t.west), Math.abs(lo + 360 - t.west), Math.abs(lo - 360 - t.west));
        const inLon = Math.abs(la) > 89.9 || (((lo - t.west) % 360 + 360) % 360) <= t.extent + 1e-9 || du < 1e-9;
        const slackDeg = (reachM / A) * 180 / Math.PI / Math.max(Math.cos(la * Math.PI / 180), 1e-3);
        const lonSlack = Math.min(((t.west - lo) % 360 + 360) % 360, ((lo - t.west - t.extent) % 360 + 360) % 360);
        const outsideLon = !inLon && lonSlack > slackDeg;
        const outsideLat = la < t.south - (reachM / A) * 180 / Math.PI || la > Math.min(90, t.south + t.extent) + (reachM / A) * 180 / Math.PI;
        if (outsideLon || outsideLat || hh < t.minH - reachM || hh > t.maxH + reachM) stats.outsideVolume++;
      }
      const before = stats.worstM;
      measureSamples(stats, name, t.west, t.south, t.extent, (k) => uv[k], pos, indices);
      if (stats.worstM > before) stats.worstBound = t.bound;
    }
    stats.boundM = bound;
    stats.worstRatio = bound ? stats.worstM / bound : 0;
    if (stats.worstRatio > 1) failures.push(`level ${z}: ${stats.worstM.toFixed(2)} m in ${stats.worstTile}, over the ${bound.toFixed(2)} m geometric error (ratio ${stats.worstRatio.toFixed(3)})`);
    if (stats.holes) failures.push(`level ${z}: ${stats.holes} samples covered by no triangle`);
    if (stats.outsideVolume) failures.push(`level ${z}: ${stats.outsideVolume} vertices outside their tile's bounding region`);
    if (stats.coordinateMismatches) failures.push(`level ${z}: ${stats.coordinateMismatches} vertices whose TEXCOORD_0 is not their longitude and latitude`);
    levels.push(stats);
  }
  console.log("level  tiles  samples measured  worst 3-D m  geometric error m  worst ratio  holes  vertices outside volume");
  for (const s of levels) {
    console.log(`${String(s.level).padStart(5)}  ${String(s.tiles).padStart(5)}  ${String(s.samples).padStart(16)}  ` +
      `${s.worstM.toFixed(2).padStart(11)}  ${s.boundM.toFixed(2).padStart(17)}  ${s.worstRatio.toFixed(3).padStart(11)}  ` +
      `${String(s.holes).padStart(5)}  ${String(s.outsideVolume).padStart(23)}`);
  }
  const worst = Math.max(...levels.map((s) => s.worstRatio));
  console.log(`worst ratio of 3-D error to the tile's geometric error: ${worst.toFixed(3)}`);
  if (summaryPath) writeFileSync(summaryPath, JSON.stringify({ levels, worstRatio: worst, failures }, null, 1));
  for (const f of failures.slice(0, 20)) console.error(`verify-tiles: ${f}`);
  process.exit(failures.length ? 1 : 0);
}

const failures = [];
const levels = [];
if (existsSync(path.join(dir, "tileset.json")) && !existsSync(path.join(dir, "layer.json"))) verifyTileset();

const layer = JSON.parse(readFileSync(path.join(dir, "layer.json"), "utf8"));
const decoded = new Map();  // "z/x/y" -> tile, for the shared edges of a level

// The tiles of each level as "x/y" sets (TMS: y from the south), from a list of ranges.
const addRanges = (set, ranges) => {
  for (const r of ranges) for (let x = r.startX; x <= r.endX; x++) for (let y = r.startY; y <= r.endY; y++) set.add(`${x}/${y}`);
};
const listed = layer.available.map((ranges) => { const set = new Set(); addRanges(set, ranges); return set; });
const metadataLevels = layer.metadataAvailability;
const byMetadata = [];  // level -> Set, filled from the metadata of the tiles as they are read
if (metadataLevels !== undefined) {
  if (!Number.isInteger(metadataLevels) || metadataLevels < 1) failures.push(`layer.json: metadataAvailability ${metadataLevels}`);
  if (!(layer.extensions || []).includes("metadata")) failures.push("layer.json: metadataAvailability without the metadata extension");
  byMetadata[0] = new Set(["0/0", "1/0"]);  // as Cesium assumes
}
const maxLevel = metadataLevels !== undefined ? layer.maxzoom : layer.available.length - 1;
// Files on disk: Z/X/Y.terrain, each of which must be available.
const onDisk = [];
for (const z of readdirSync(dir).filter((n) => /^\d+$/.test(n))) {
  for (const x of readdirSync(path.join(dir, z))) {
    for (const f of readdirSync(path.join(dir, z, x))) onDisk.push(`${z}/${x}/${f.replace(/\.terrain$/, "")}`);
  }
}
const metadataStats = { tilesWithMetadata: 0 };

for (let z = 0; z <= maxLevel; z++) {
  let tilesOfLevel = listed[z] || new Set();
  if (metadataLevels !== undefined) {
    const fromMetadata = byMetadata[z] || new Set();
    const missing = [...tilesOfLevel].filter((t) => !fromMetadata.has(t));
    const extra = [...fromMetadata].filter((t) => !tilesOfLevel.has(t));
    if (missing.length || extra.length) {
      failures.push(`level ${z}: the tiles' metadata names ${fromMetadata.size} tiles, layer.json ${tilesOfLevel.size} ` +
                    `(${missing.length} only in layer.json, e.g. ${missing[0]}; ${extra.length} only in metadata, e.g. ${extra[0]})`);
    }
    tilesOfLevel = fromMetadata;
  }
  const rangesOfLevel = [...tilesOfLevel].map((t) => { const [x, y] = t.split("/").map(Number); return { startX: x, endX: x, startY: y, endY: y }; });
  const extent = 180 / 2 ** z;
  const bound = geometricError(z);
  const stats = { level: z, tiles: 0, samples: 0, worstM: 0, worstRatio: 0, worstTile: "", holes: 0,
                  edgeMismatches: 0, worstEdgeHeightM: 0, horizonCameras: 0, horizonWrong: 0 };
  decoded.clear();
  for (const range of rangesOfLevel) {
    for (let x = range.startX; x <= range.endX; x++) {
      for (let y = range.startY; y <= range.endY; y++) {
        const name = `${z}/${x}/${y}`;
        const tile = decodeTile(readFileSync(path.join(dir, `${z}`, `${x}`, `${y}.terrain`)), name);
        decoded.set(name, tile);
        if (tile.metadata) {
          metadataStats.tilesWithMetadata++;
          if (metadataLevels === undefined || z % metadataLevels !== 0) {
            failures.push(`${name}: metadata in a tile of level ${z}, which Cesium does not read it from`);
          }
          (tile.metadata.available || []).forEach((ranges, offset) => {
            const deeper = z + offset + 1;
            byMetadata[deeper] = byMetadata[deeper] || new Set();
            for (const r of ranges) {
              const span = 1 << (offset + 1);
              if (r.startX < x * span || r.endX >= (x + 1) * span || r.startY < y * span || r.endY >= (y + 1) * span) {
                failures.push(`${name}: its metadata lists tiles of level ${deeper} outside it`);
              }
            }
            addRanges(byMetadata[deeper], ranges);
          });
        } else if (metadataLevels !== undefined && z % metadataLevels === 0 && z < maxLevel) {
          failures.push(`${name}: a tile of level ${z} without the metadata extension`);
        }
        stats.tiles++;
        const west = -180 + x * extent, south = -90 + y * extent;
        const { u, v, h, indices, header } = tile;
        const lon = (k) => west + (u[k] / Q) * extent;
        const lat = (k) => Math.min(90, south + (v[k] / Q) * extent);
        const height = (k) => header.minH + (h[k] / Q) * (header.maxH - header.minH);
        const pos = [];
        for (let k = 0; k < u.length; k++) pos.push(ecef(lon(k), lat(k), height(k)));
        // The horizon occlusion point against the vertices, from cameras around the tile.
        if (header.minH >= 0) {
          const rand = random32(z * 1000003 + x * 1009 + y);
          const hop = header.hop;
          const scaledVertices = pos.map(scaled);
          for (let c = 0; c < camerasPerTile(z); c++) {
            const lonC = west + extent / 2 + (rand() - 0.5) * Math.min(360, extent + 120);
            const latC = Math.max(-90, Math.min(90, south + extent / 2 + (rand() - 0.5) * Math.min(180, extent + 60)));
            const height = 10 * Math.pow(4e6, rand());  // 10 m .. 40,000 km
            const cv = scaled(ecef(lonC, latC, height));
            stats.horizonCameras++;
            if (scaledPointVisible(hop, cv)) continue;
            if (scaledVertices.some((p) => scaledPointVisible(p, cv))) {
              stats.horizonWrong++;
              if (stats.horizonWrong === 1) {
                failures.push(`${name}: its horizon occlusion point is hidden from (${lonC.toFixed(2)}, ${latC.toFixed(2)}, ${height.toFixed(0)} m) while some of its vertices are visible`);
              }
            }
          }
        }
        // Edge lists: exactly the vertices with u == 0, v == 0, u == Q, v == Q.
        const onEdge = [(k) => u[k] === 0, (k) => v[k] === 0, (k) => u[k] === Q, (k) => v[k] === Q];
        onEdge.forEach((test, e) => {
          const want = [];
          for (let k = 0; k < u.length; k++) if (test(k)) want.push(k);
          const got = [...tile.edges[e]].sort((a, b) => a - b);
          if (want.length !== got.length || want.some((k, i) => k !== got[i])) {
            failures.push(`${name}: edge list ${["west", "south", "east", "north"][e]} does not name the vertices on that edge`);
          }
        });
        measureSamples(stats, name, west, south, extent, (k) => [u[k] / Q, v[k] / Q], pos, indices);
      }
    }
  }
  // Shared edges: the east edge of x against the west edge of x + 1, north of y against south of y + 1.
  for (const [name, tile] of decoded) {
    const [, x, y] = name.split("/").map(Number);
    for (const [other, mine, theirs, along] of [[`${z}/${x + 1}/${y}`, 2, 0, "v"], [`${z}/${x}/${y + 1}`, 3, 1, "u"]]) {
      const next = decoded.get(other);
      if (!next) continue;
      const heightOf = (t, k) => t.header.minH + (t.h[k] / Q) * (t.header.maxH - t.header.minH);
      const a = tile.edges[mine].map((k) => [tile[along][k], heightOf(tile, k)]).sort((p, q) => p[0] - q[0]);
      const b = next.edges[theirs].map((k) => [next[along][k], heightOf(next, k)]).sort((p, q) => p[0] - q[0]);
      const tolerance = (tile.header.maxH - tile.header.minH + next.header.maxH - next.header.minH) / Q + 1e-3;
      if (a.length !== b.length || a.some((p, i) => p[0] !== b[i][0])) {
        stats.edgeMismatches++;
        failures.push(`${name} and ${other}: different vertices along their shared edge (${a.length} and ${b.length})`);
        continue;
      }
      a.forEach((p, i) => {
        const diff = Math.abs(p[1] - b[i][1]);
        stats.worstEdgeHeightM = Math.max(stats.worstEdgeHeightM, diff);
        if (diff > tolerance) failures.push(`${name} and ${other}: shared edge heights differ by ${diff.toFixed(3)} m`);
      });
    }
  }
  stats.boundM = bound;
  stats.worstRatio = stats.worstM / bound;
  if (stats.worstRatio > 1) failures.push(`level ${z}: ${stats.worstM.toFixed(2)} m in ${stats.worstTile}, over the ${bound.toFixed(2)} m bound (ratio ${stats.worstRatio.toFixed(3)})`);
  if (stats.holes) failures.push(`level ${z}: ${stats.holes} samples covered by no triangle`);
  levels.push(stats);
}

console.log("level  tiles  samples measured  worst 3-D m  bound m  worst ratio  holes  edge height diff m  horizon wrong/cameras");
for (const s of levels) {
  console.log(`${String(s.level).padStart(5)}  ${String(s.tiles).padStart(5)}  ${String(s.samples).padStart(16)}  ` +
    `${s.worstM.toFixed(2).padStart(11)}  ${s.boundM.toFixed(2).padStart(7)}  ${s.worstRatio.toFixed(3).padStart(11)}  ` +
    `${String(s.holes).padStart(5)}  ${s.worstEdgeHeightM.toFixed(3).padStart(18)}  ${s.horizonWrong}/${s.horizonCameras}`);
}
const available = new Set(levels.flatMap((s, z) => [...(metadataLevels !== undefined ? byMetadata[z] || [] : listed[z] || [])].map((t) => `${z}/${t}`)));
const orphans = onDisk.filter((t) => !available.has(t));
if (orphans.length) failures.push(`${orphans.length} tile file(s) not available to a client, e.g. ${orphans[0]}.terrain`);
if (onDisk.length !== available.size) failures.push(`${available.size} tiles available, ${onDisk.length} files on disk`);
console.log(`availability: ${available.size} tiles, ${onDisk.length} files` +
            (metadataLevels !== undefined ? `, from the metadata of ${metadataStats.tilesWithMetadata} tiles (every ${metadataLevels} levels)` : ", from layer.json"));
const worst = Math.max(...levels.map((s) => s.worstRatio));
console.log(`worst ratio of 3-D error to the level's geometric error: ${worst.toFixed(3)}`);
if (summaryPath) writeFileSync(summaryPath, JSON.stringify({ levels, worstRatio: worst, availableTiles: available.size, filesOnDisk: onDisk.length,
  tilesWithMetadata: metadataStats.tilesWithMetadata, failures }, null, 1));
for (const f of failures.slice(0, 20)) console.error(`verify-tiles: ${f}`);
if (failures.length > 20) console.error(`verify-tiles: ... and ${failures.length - 20} more`);
process.exit(failures.length ? 1 : 0);
