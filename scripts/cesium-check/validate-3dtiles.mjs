#!/usr/bin/env node
// Independent validator for 3D Tiles 1.1 tile sets (see validate-3dtiles.sh, which installs ajv):
//
//   node validate-3dtiles.mjs TILESET [--summary OUT.json] [--list-contents FILE] [--list-tiles FILE]
//                             [--gltf] [--node-modules DIR]
//
// TILESET is a folder holding tileset.json, or a tileset JSON file. The tool
//   * validates the tileset JSON, and every external tileset it references (content.uri of an
//     explicit tile that is a tileset JSON), against the official 3D Tiles 1.1 JSON schemas
//     vendored in 3d-tiles-schema/ (draft 2020-12, checked with Ajv2020), plus the rules the
//     schemas cannot express (spec section "Tileset JSON", "Bounding volumes", "Refinement");
//   * for every tile with `implicitTiling` (spec "Implicit Tiling"), reads every subtree reachable
//     from the root subtree through child subtree availability, in binary (.subtree) or JSON form,
//     validates its JSON against Subtree/subtree.schema.json, checks the binary layout and the
//     availability rules, decodes the availability bitstreams (Morton order) and lists every
//     available tile and content;
//   * checks that every content file (explicit, or from an expanded content template for each
//     available implicit content) exists;
//   * with --gltf, runs the Khronos glTF validator (npm gltf-validator) over every .glb/.gltf
//     content and fails on any error or warning (as validate-gltf.sh does).
// Options:
//   --summary FILE        writes {ok, tilesPerLevel, explicitTiles, contents, gltfContents, subtrees,
//                         tilesets, implicitRoots, errors, warnings, gltf} as JSON
//   --list-contents FILE  writes the path of every glTF (.glb/.gltf) content, one a line
//   --list-tiles FILE     writes every available implicit tile, one a line:
//                         "level x y [z] content-path|-" (one path per content layer)
//   --node-modules DIR    where ajv (and gltf-validator) are installed (default: Node's own lookup)
// Exit 0: valid (warnings allowed); 1: some error; 2: bad usage or missing tool.
//
// Sections cited below are those of the 3D Tiles 1.1 specification
// (https://github.com/CesiumGS/3d-tiles, specification/README.adoc, ImplicitTiling/README.adoc,
// ImplicitTiling/AVAILABILITY.adoc, Metadata/README.adoc).
import { createRequire } from "node:module";
import { readFileSync, writeFileSync, existsSync, statSync, readdirSync, openSync, readSync, closeSync } from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const schemaDir = path.join(here, "3d-tiles-schema");

// ---------------------------------------------------------------------------------------------
// Command line
function usage(msg) {
  if (msg) console.error(`validate-3dtiles: ${msg}`);
  console.error("usage: node validate-3dtiles.mjs TILESET_DIR|TILESET.json [--summary OUT.json] " +
    "[--list-contents FILE] [--list-tiles FILE] [--gltf] [--node-modules DIR]");
  process.exit(2);
}
let input = null, summaryFile = null, listContentsFile = null, listTilesFile = null;
let nodeModules = null, runGltf = false;
{
  const argv = process.argv.slice(2);
  const value = (i) => (i < argv.length ? argv[i] : usage(`${argv[i - 1]} needs a value`));
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    if (a === "--summary") summaryFile = value(++i);
    else if (a === "--list-contents") listContentsFile = value(++i);
    else if (a === "--list-tiles") listTilesFile = value(++i);
    else if (a === "--node-modules") nodeModules = value(++i);
    else if (a === "--gltf") runGltf = true;
    else if (a === "-h" || a === "--help") usage();
    else if (a.startsWith("--")) usage(`unknown option ${a}`);
    else if (input === null) input = a;
    else usage(`unexpected argument ${a}`);
  }
}
if (input === null) usage("no tile set given");
if (!existsSync(input)) usage(`${input} does not exist`);
const rootFile = path.resolve(statSync(input).isDirectory() ? path.join(input, "tileset.json") : input);
const rootDir = path.dirname(rootFile);

const requireFrom = createRequire(nodeModules ? path.join(path.resolve(nodeModules), "noop.js") : import.meta.url);
function load(name) {
  try {
    return requireFrom(name);
  } catch (e) {
    console.error(`validate-3dtiles: cannot load npm package ${name} (${e.code || e.message}); ` +
      "run validate-3dtiles.sh, which installs it, or pass --node-modules DIR");
    process.exit(2);
  }
}

// ---------------------------------------------------------------------------------------------
// Problems. Each names the file (relative to the tile set folder), a JSON pointer into that
// file's JSON (or "" for the file as a whole / its binary layout) and a message.
const errors = [], warnings = [];
const MAX_KEPT = 2000; // errors/warnings kept in the summary; all are counted
let errorCount = 0, warningCount = 0;
const rel = (f) => path.relative(rootDir, f) || path.basename(f);
const esc = (k) => String(k).replace(/~/g, "~0").replace(/\//g, "~1");
const ptr = (...keys) => keys.map((k) => "/" + esc(k)).join("");
function error(file, pointer, message) {
  errorCount++;
  if (errors.length < MAX_KEPT) errors.push({ file: rel(file), pointer, message });
}
function warn(file, pointer, message) {
  warningCount++;
  if (warnings.length < MAX_KEPT) warnings.push({ file: rel(file), pointer, message });
}

// ---------------------------------------------------------------------------------------------
// JSON schemas. The vendored schemas' "$id"s are bare file names ("tile.schema.json", and
// "subtree.schema.json" for Subtree/subtree.schema.json) while their "$ref"s are paths relative
// to the referring file ("../PropertyTable/propertyTable.schema.json"). Each schema is therefore
// registered under an absolute id made from its path in 3d-tiles-schema/, so the relative refs
// resolve as the schema README says ("resolved against the respective subdirectories").
//
// Ajv strict mode is kept on, except:
//   strictTypes: false    - the schemas put `required`/`properties` next to a `$ref` to
//                           common/rootProperty.schema.json, which carries `"type": "object"`;
//                           strictTypes wants the type in the same schema object.
//   strictRequired: false - `"not": {"required": ["content", "contents"]}` (tile) and
//                           `["schema", "schemaUri"]` (tileset) name properties defined outside
//                           the `not`, which strictRequired rejects.
// and the one string format the schemas use, "iri-reference" (tileset.schemaUri, Subtree buffer
// uri), is given a lenient check (no whitespace or control characters, well-formed %-escapes)
// instead of adding the ajv-formats package.
const Ajv2020 = load("ajv/dist/2020").default;
const ajvVersion = (() => { try { return requireFrom("ajv/package.json").version; } catch { return "?"; } })();
const ajv = new Ajv2020({ strict: true, strictTypes: false, strictRequired: false, allErrors: true });
ajv.addFormat("iri-reference", (s) => !/[\u0000-\u0020\u007f]/.test(s) && !/%(?![0-9A-Fa-f]{2})/.test(s));
const SCHEMA_BASE = "https://tellus.invalid/3d-tiles-schema/";
function schemaFiles(dir) {
  return readdirSync(dir, { withFileTypes: true }).flatMap((e) =>
    e.isDirectory() ? schemaFiles(path.join(dir, e.name))
      : e.name.endsWith(".schema.json") ? [path.join(dir, e.name)] : []);
}
for (const f of schemaFiles(schemaDir)) {
  const schema = JSON.parse(readFileSync(f, "utf8"));
  schema.$id = SCHEMA_BASE + path.relative(schemaDir, f).split(path.sep).join("/");
  ajv.addSchema(schema);
}
const validateTilesetSchema = ajv.getSchema(SCHEMA_BASE + "tileset.schema.json");
const validateSubtreeSchema = ajv.getSchema(SCHEMA_BASE + "Subtree/subtree.schema.json");

function schemaCheck(validate, json, file) {
  if (validate(json)) return true;
  // With anyOf/oneOf (refine, availability, ...), Ajv reports each failed branch; keep them
  // all but drop exact duplicates.
  const seen = new Set();
  for (const e of validate.errors) {
    let msg = `${e.message}`;
    if (e.params && e.keyword === "additionalProperties") msg += ` (${e.params.additionalProperty})`;
    if (e.params && e.keyword === "const") msg += ` (${JSON.stringify(e.params.allowedValue)})`;
    msg += ` [schema ${e.schemaPath.replace(SCHEMA_BASE, "")}]`;
    const key = e.instancePath + msg;
    if (!seen.has(key)) { seen.add(key); error(file, e.instancePath, `schema: ${msg}`); }
  }
  return false;
}

function readJson(file, pointerForMissing, referrer) {
  let text;
  try {
    text = readFileSync(file, "utf8");
  } catch (e) {
    error(referrer ?? file, pointerForMissing ?? "", `cannot read ${rel(file)}: ${e.code || e.message}`);
    return undefined;
  }
  try {
    return JSON.parse(text);
  } catch (e) {
    error(file, "", `not valid JSON: ${e.message}`);
    return undefined;
  }
}

// ---------------------------------------------------------------------------------------------
// URIs (spec "URIs": relative paths are relative to the referring file). Returns the local path,
// or null for a URI this offline check cannot follow (http:, https:, data:; a warning).
function resolveUri(uri, referrer, pointer) {
  if (/^[A-Za-z][A-Za-z0-9+.-]*:/.test(uri)) {
    warn(referrer, pointer, `URI ${uri} is not a relative path; not checked`);
    return null;
  }
  const p = uri.replace(/[?#].*$/, "");
  let decoded;
  try { decoded = decodeURIComponent(p); } catch { error(referrer, pointer, `bad %-escape in URI ${uri}`); return null; }
  if (decoded.startsWith("/")) {
    warn(referrer, pointer, `URI ${uri} is an absolute path; not checked`);
    return null;
  }
  return path.resolve(path.dirname(referrer), decoded);
}

// What a content file is: by extension, else by its first bytes (spec "Tile content": the format
// is identified by the magic in its header, or else it is an external tileset if it is JSON).
function contentKind(file) {
  const ext = path.extname(file).toLowerCase();
  if (ext === ".json") return "tileset";
  if (ext === ".glb" || ext === ".gltf") return "gltf";
  const head = Buffer.alloc(4);
  const fd = openSync(file, "r");
  try { readSync(fd, head, 0, 4, 0); } finally { closeSync(fd); }
  const magic = head.toString("latin1");
  if (magic === "glTF") return "gltf";
  if (["b3dm", "i3dm", "pnts", "cmpt"].includes(magic)) return magic;
  if (magic.trimStart().startsWith("{")) {
    try {
      const j = JSON.parse(readFileSync(file, "utf8"));
      if (j.root) return "tileset";
      if (j.asset && String(j.asset.version).startsWith("2.")) return "gltf";
    } catch { /* fall through */ }
  }
  return "unknown";
}

// ---------------------------------------------------------------------------------------------
// Results
const tilesPerLevel = {};            // implicit level -> available tiles (all implicit roots)
const contentFiles = new Set();      // every content file found (absolute paths)
const gltfFiles = new Set();
const tilesetFiles = [];
const implicitRoots = [];
const tileLines = [];
let explicitTiles = 0, subtreesRead = 0, missingContents = 0;

// ---------------------------------------------------------------------------------------------
// Tileset JSON (spec "Tileset JSON", "Tiles", "External tilesets")
const visiting = new Set();
function checkTileset(file, referrer, referrerPointer) {
  if (visiting.has(file)) {
    error(referrer, referrerPointer, `external tileset ${rel(file)} references itself (cycle)`);
    return;
  }
  const json = readJson(file, referrerPointer, referrer);
  if (json === undefined) return;
  visiting.add(file);
  tilesetFiles.push(rel(file));
  schemaCheck(validateTilesetSchema, json, file);
  if (typeof json !== "object" || json === null) { visiting.delete(file); return; }

  // asset.version: CesiumJS refuses anything but "0.0", "1.0" and "1.1"; implicit tiling, multiple
  // contents, metadata and glTF content are 1.1 core features.
  const version = json.asset?.version;
  if (typeof version === "string" && !["1.0", "1.1"].includes(version))
    error(file, "/asset/version", `asset.version is "${version}"; 3D Tiles 1.1 tilesets use "1.1"`);
  const uses11 = json.schema || json.schemaUri || json.groups || json.statistics || json.metadata;
  if (version === "1.0" && uses11)
    warn(file, "", 'uses 3D Tiles 1.1 features (metadata, schema, groups, statistics) but asset.version is "1.0"');

  // extensionsRequired shall be a subset of extensionsUsed (tileset.schema.json description).
  for (const [i, ext] of (json.extensionsRequired ?? []).entries())
    if (!(json.extensionsUsed ?? []).includes(ext))
      error(file, ptr("extensionsRequired", i), `${ext} is required but not in extensionsUsed`);

  if (json.root && typeof json.root === "object") {
    // spec "Refinement": a refinement type is required for the root tile of a tileset.
    if (json.root.refine === undefined) error(file, "/root", "the root tile needs `refine` (ADD or REPLACE)");
    if (typeof json.geometricError === "number" && typeof json.root.geometricError === "number" &&
        json.root.geometricError > json.geometricError)
      warn(file, "/root/geometricError", `root geometricError ${json.root.geometricError} > tileset geometricError ${json.geometricError}`);
    checkTile(json.root, file, "/root", version, null);
  }
  visiting.delete(file);
}

// spec "Bounding volumes": region = [west, south, east, north, minHeight, maxHeight] in radians
// (EPSG:4979 with radians); west > east is allowed (crosses the antimeridian).
function checkBoundingVolume(bv, file, pointer) {
  if (!bv || typeof bv !== "object") return;
  const r = bv.region;
  if (Array.isArray(r) && r.length === 6 && r.every((v) => typeof v === "number")) {
    const [w, s, e, n, lo, hi] = r;
    if (Math.abs(w) > Math.PI + 1e-12 || Math.abs(e) > Math.PI + 1e-12)
      error(file, pointer + "/region", `west/east ${w}/${e} outside [-pi, pi] (radians expected)`);
    if (Math.abs(s) > Math.PI / 2 + 1e-12 || Math.abs(n) > Math.PI / 2 + 1e-12)
      error(file, pointer + "/region", `south/north ${s}/${n} outside [-pi/2, pi/2] (radians expected)`);
    if (s > n) error(file, pointer + "/region", `south ${s} > north ${n}`);
    if (lo > hi) error(file, pointer + "/region", `minimum height ${lo} > maximum height ${hi}`);
  }
  const sp = bv.sphere;
  if (Array.isArray(sp) && sp.length === 4 && sp[3] < 0) error(file, pointer + "/sphere", "negative radius");
}

function tileContents(tile) {
  if (tile.content) return [["content", tile.content]];
  if (Array.isArray(tile.contents)) return tile.contents.map((c, i) => [`contents/${i}`, c]);
  return [];
}

function checkTile(tile, file, pointer, version, parent) {
  if (!tile || typeof tile !== "object") return;
  explicitTiles++;
  checkBoundingVolume(tile.boundingVolume, file, pointer + "/boundingVolume");
  checkBoundingVolume(tile.viewerRequestVolume, file, pointer + "/viewerRequestVolume");
  if (typeof tile.refine === "string" && !["ADD", "REPLACE"].includes(tile.refine))
    error(file, pointer + "/refine", `refine is "${tile.refine}"; must be ADD or REPLACE`);
  // spec "Geometric error": a child should not have a larger geometric error than its parent.
  if (parent && typeof tile.geometricError === "number" && typeof parent.geometricError === "number" &&
      tile.geometricError > parent.geometricError)
    warn(file, pointer + "/geometricError", `geometricError ${tile.geometricError} > parent's ${parent.geometricError}`);
  if ((tile.contents || tile.metadata) && version === "1.0")
    warn(file, pointer, 'uses 3D Tiles 1.1 tile features (contents/metadata) but asset.version is "1.0"');

  if (tile.implicitTiling) {
    if (version !== "1.1") warn(file, pointer + "/implicitTiling", 'implicit tiling is 3D Tiles 1.1; asset.version should be "1.1"');
    checkImplicitRoot(tile, file, pointer);
    return;
  }
  for (const [key, content] of tileContents(tile)) {
    if (!content || typeof content.uri !== "string") continue;
    const cptr = `${pointer}/${key}/uri`;
    if (/\{(level|x|y|z)\}/.test(content.uri))
      warn(file, cptr, "template variables in the content URI of a tile without implicitTiling");
    const f = resolveUri(content.uri, file, cptr);
    if (!f) continue;
    if (!existsSync(f)) { missingContents++; error(file, cptr, `content ${content.uri} not found (${rel(f)})`); continue; }
    const kind = contentKind(f);
    if (kind === "tileset") checkTileset(f, file, cptr); // spec "External tilesets"
    else addContent(f, kind);
  }
  if (Array.isArray(tile.children))
    tile.children.forEach((child, i) => checkTile(child, file, `${pointer}/children/${i}`, version, tile));
}

function addContent(f, kind) {
  contentFiles.add(f);
  if (kind === "gltf") gltfFiles.add(f);
}

// ---------------------------------------------------------------------------------------------
// Implicit tiling (ImplicitTiling/README.adoc "Implicit Root Tile", "Subdivision Scheme",
// "Template URIs", "Subtrees", "Subtree JSON Format", "Subtree Binary Format" and
// AVAILABILITY.adoc "Availability Indexing").

// spec "Template URIs": {level}, {x}, {y} are required; {z} for octrees (and only for them).
function checkTemplate(uri, dims, file, pointer) {
  for (const v of ["level", "x", "y"]) if (!uri.includes(`{${v}}`)) error(file, pointer, `template URI ${uri} lacks {${v}}`);
  if (dims === 3 && !uri.includes("{z}")) error(file, pointer, `OCTREE template URI ${uri} lacks {z}`);
  if (dims === 2 && uri.includes("{z}")) error(file, pointer, `QUADTREE template URI ${uri} has {z}`);
}
const expand = (uri, c) => uri.replace(/\{level\}/g, c.level).replace(/\{x\}/g, c.x).replace(/\{y\}/g, c.y).replace(/\{z\}/g, c.z);

// Morton index -> local coordinates (AVAILABILITY.adoc "Converting from Tile Coordinates to Morton
// Index": mortonIndex = interleaveBits(x, y[, z]), x in bit 0, y in bit 1[, z in bit 2], ...).
function mortonDecode(m, dims, level) {
  const c = [0, 0, 0];
  for (let b = 0; b < level; b++)
    for (let d = 0; d < dims; d++)
      if (Math.floor(m / 2 ** (b * dims + d)) % 2) c[d] += 2 ** b;
  return c;
}

function checkImplicitRoot(tile, file, pointer) {
  const it = tile.implicitTiling;
  const ip = pointer + "/implicitTiling";
  const scheme = it.subdivisionScheme;
  const dims = scheme === "QUADTREE" ? 2 : scheme === "OCTREE" ? 3 : 0;
  if (!dims) { error(file, ip + "/subdivisionScheme", `subdivisionScheme "${scheme}" is neither QUADTREE nor OCTREE`); return; }
  const N = 2 ** dims;
  const { subtreeLevels, availableLevels } = it;
  if (!Number.isInteger(subtreeLevels) || subtreeLevels < 1 || !Number.isInteger(availableLevels) || availableLevels < 1) return; // schema error already
  if (N ** subtreeLevels > 2 ** 31) { error(file, ip + "/subtreeLevels", `subtreeLevels ${subtreeLevels} too large for this validator`); return; }
  // "Implicit Root Tile": the tile shall omit children and metadata; its content shall not be an
  // external tileset and shall omit boundingVolume. "Subdivision Scheme": no sphere volumes.
  if (tile.children) error(file, pointer + "/children", "an implicit root tile shall omit `children`");
  if (tile.metadata) error(file, pointer + "/metadata", "an implicit root tile shall omit `metadata`");
  if (tile.boundingVolume?.sphere) error(file, pointer + "/boundingVolume", "sphere bounding volumes cannot be subdivided implicitly");
  const templates = [];
  for (const [key, content] of tileContents(tile)) {
    if (!content || typeof content.uri !== "string") continue;
    if (content.boundingVolume) error(file, `${pointer}/${key}/boundingVolume`, "the content of an implicit root tile shall omit `boundingVolume`");
    if (/\.json$/i.test(content.uri.replace(/[?#].*$/, "")))
      error(file, `${pointer}/${key}/uri`, "the content of an implicit root tile shall not be an external tileset");
    checkTemplate(content.uri, dims, file, `${pointer}/${key}/uri`);
    templates.push({ uri: content.uri, pointer: `${pointer}/${key}/uri` });
  }
  const subtreeUri = it.subtrees?.uri;
  if (typeof subtreeUri !== "string") return;
  checkTemplate(subtreeUri, dims, file, ip + "/subtrees/uri");

  const info = { tileset: rel(file), pointer, scheme, subtreeLevels, availableLevels, tilesPerLevel: {}, contents: 0, subtrees: 0 };
  implicitRoots.push(info);
  // Bitstream lengths (AVAILABILITY.adoc "Availability Bitstream Lengths").
  const nodes = (N ** subtreeLevels - 1) / (N - 1);
  const childNodes = N ** subtreeLevels;
  const levelOffset = (L) => (N ** L - 1) / (N - 1);

  // Breadth-first over subtrees, starting at the implicit root (global coordinates).
  const queue = [{ level: 0, x: 0, y: 0, z: 0, parentFile: null }];
  while (queue.length) {
    const root = queue.shift();
    const uri = expand(subtreeUri, root);
    const where = root.parentFile ? { file: root.parentFile, pointer: "/childSubtreeAvailability" } : { file, pointer: ip + "/subtrees/uri" };
    const sfile = resolveUri(uri, file, ip + "/subtrees/uri");
    if (!sfile) continue;
    if (!existsSync(sfile)) {
      error(where.file, where.pointer, `subtree ${uri} (level ${root.level}, x ${root.x}, y ${root.y}${dims === 3 ? `, z ${root.z}` : ""}) is available but ${rel(sfile)} does not exist`);
      continue;
    }
    const st = readSubtree(sfile, { nodes, childNodes, contentCount: templates.length });
    subtreesRead++;
    info.subtrees++;
    if (!st) continue;
    const tileAv = st.tile, contentAv = st.content, childAv = st.child;

    // Walk every node of the subtree, level by level, in Morton order.
    let available = 0, beyondLevels = 0, orphan = 0, contentWithoutTile = 0;
    for (let L = 0; L < subtreeLevels; L++) {
      const G = root.level + L;
      const scale = 2 ** L;
      for (let m = 0; m < N ** L; m++) {
        const idx = levelOffset(L) + m;
        const tileOn = tileAv.get(idx);
        const [lx, ly, lz] = mortonDecode(m, dims, L);
        // AVAILABILITY.adoc "Global and Local Tile Coordinates": global = concatBits(root, local).
        const c = { level: G, x: root.x * scale + lx, y: root.y * scale + ly, z: root.z * scale + lz };
        if (tileOn) {
          available++;
          if (G >= availableLevels) beyondLevels++;
          // "Tile Availability": a non-root tile's parent shall be available.
          if (L > 0 && !tileAv.get(levelOffset(L - 1) + Math.floor(m / N))) orphan++;
          tilesPerLevel[G] = (tilesPerLevel[G] ?? 0) + 1;
          info.tilesPerLevel[G] = (info.tilesPerLevel[G] ?? 0) + 1;
        }
        const line = tileOn ? [G, c.x, c.y, ...(dims === 3 ? [c.z] : [])] : null;
        templates.forEach((t, k) => {
          if (!contentAv[k]?.get(idx)) { if (line) line.push("-"); return; }
          // "Content Availability": available content needs an available tile.
          if (!tileOn) { contentWithoutTile++; return; }
          info.contents++;
          const curi = expand(t.uri, c);
          const cf = resolveUri(curi, file, t.pointer);
          if (line) line.push(cf ? rel(cf) : curi);
          if (!cf) return;
          if (!existsSync(cf)) {
            missingContents++;
            error(sfile, `/contentAvailability/${k}`, `content of tile (level ${G}, x ${c.x}, y ${c.y}${dims === 3 ? `, z ${c.z}` : ""}) is available but ${curi} does not exist`);
            return;
          }
          const kind = contentKind(cf);
          if (kind === "tileset") error(sfile, `/contentAvailability/${k}`, `implicit content ${curi} is a tileset JSON (not allowed)`);
          else addContent(cf, kind);
        });
        if (line && listTilesFile) tileLines.push(line.join(" "));
      }
    }
    if (available === 0) error(sfile, "/tileAvailability", "a subtree shall have at least one available tile");
    else if (!tileAv.get(0)) error(sfile, "/tileAvailability", "the subtree root tile is not available, but other tiles are");
    if (beyondLevels) error(sfile, "/tileAvailability", `${beyondLevels} available tiles at levels >= availableLevels (${availableLevels})`);
    if (orphan) error(sfile, "/tileAvailability", `${orphan} available tiles whose parent tile is not available`);
    if (contentWithoutTile) error(sfile, "/contentAvailability", `${contentWithoutTile} available contents whose tile is not available`);

    // "Child Subtree Availability": one bit per node one level below the subtree, Morton order.
    const childLevel = root.level + subtreeLevels;
    const childScale = 2 ** subtreeLevels;
    let childBeyond = 0, childOrphan = 0;
    for (let m = 0; m < childNodes; m++) {
      if (!childAv.get(m)) continue;
      if (childLevel >= availableLevels) { childBeyond++; continue; }
      // The child subtree's root is a child of a deepest-level tile of this subtree, which must
      // be available for it to be (tile availability parent rule across subtrees).
      if (!tileAv.get(levelOffset(subtreeLevels - 1) + Math.floor(m / N))) childOrphan++;
      const [lx, ly, lz] = mortonDecode(m, dims, subtreeLevels);
      queue.push({ level: childLevel, x: root.x * childScale + lx, y: root.y * childScale + ly, z: root.z * childScale + lz, parentFile: sfile });
    }
    if (childBeyond) error(sfile, "/childSubtreeAvailability", `${childBeyond} child subtrees at level ${childLevel} >= availableLevels (${availableLevels})`);
    if (childOrphan) error(sfile, "/childSubtreeAvailability", `${childOrphan} child subtrees below a tile that is not available`);
  }
}

// Reads one subtree file, binary or JSON. Returns {tile, content: [...], child} availability
// accessors (get(i) -> 0/1), or null when it cannot be used.
function readSubtree(file, { nodes, childNodes, contentCount }) {
  const bytes = readFileSync(file);
  let json, chunk = null;
  // "Subtree Binary Format": 24-byte header: magic "subt" (0x74627573 little-endian), uint32
  // version 1, uint64 JSON byte length, uint64 binary byte length; then the JSON chunk padded
  // with spaces to 8 bytes, then the binary chunk padded with zeros to 8 bytes.
  if (bytes.length >= 4 && bytes.toString("latin1", 0, 4) === "subt") {
    if (bytes.length < 24) { error(file, "", `binary subtree: ${bytes.length} bytes, shorter than its 24-byte header`); return null; }
    const version = bytes.readUInt32LE(4);
    const jsonLen = Number(bytes.readBigUInt64LE(8));
    const binLen = Number(bytes.readBigUInt64LE(16));
    if (version !== 1) error(file, "", `binary subtree version ${version}; must be 1`);
    if (24 + jsonLen + binLen !== bytes.length) {
      error(file, "", `binary subtree: header says 24 + ${jsonLen} (JSON) + ${binLen} (binary) = ${24 + jsonLen + binLen} bytes, file has ${bytes.length}`);
      if (24 + jsonLen + binLen > bytes.length) return null;
    }
    if (jsonLen % 8) error(file, "", `binary subtree: JSON chunk length ${jsonLen} is not a multiple of 8 (pad with spaces)`);
    if (binLen % 8) error(file, "", `binary subtree: binary chunk length ${binLen} is not a multiple of 8 (pad with zeros)`);
    const text = bytes.toString("utf8", 24, 24 + jsonLen);
    if (/[\u0000]/.test(text)) error(file, "", "binary subtree: JSON chunk padded with NUL bytes; must be padded with spaces (0x20)");
    try { json = JSON.parse(text.replace(/\u0000+$/, "")); } catch (e) { error(file, "", `binary subtree: JSON chunk is not valid JSON: ${e.message}`); return null; }
    if (binLen) chunk = bytes.subarray(24 + jsonLen, 24 + jsonLen + binLen);
  } else {
    try { json = JSON.parse(bytes.toString("utf8")); } catch (e) {
      error(file, "", `neither a binary subtree (magic "subt") nor JSON: ${e.message}`);
      return null;
    }
  }
  if (!schemaCheck(validateSubtreeSchema, json, file) && (typeof json !== "object" || json === null)) return null;

  // "Buffers and Buffer Views": a buffer without uri is the binary chunk (only the first buffer
  // of a binary subtree may be); others are files relative to the subtree file; no data URIs.
  const buffers = (json.buffers ?? []).map((b, i) => {
    const bp = ptr("buffers", i);
    if (!b || typeof b !== "object") return null;
    if (b.uri === undefined) {
      if (i !== 0 || !chunk) { error(file, bp, "buffer without uri: only buffer 0 of a binary subtree (its binary chunk) may omit uri"); return null; }
      if (b.byteLength > chunk.length) { error(file, bp + "/byteLength", `byteLength ${b.byteLength} > binary chunk length ${chunk.length}`); return null; }
      if (Math.ceil(b.byteLength / 8) * 8 !== chunk.length)
        warn(file, bp + "/byteLength", `binary chunk is ${chunk.length} bytes; byteLength ${b.byteLength} padded to 8 would be ${Math.ceil(b.byteLength / 8) * 8}`);
      if (chunk.subarray(b.byteLength).some((v) => v !== 0)) error(file, "", "binary subtree: binary chunk padding is not zeros");
      return chunk.subarray(0, b.byteLength);
    }
    if (typeof b.uri !== "string") return null;
    if (b.uri.startsWith("data:")) { error(file, bp + "/uri", "data URIs are not allowed for subtree buffers"); return null; }
    const bf = resolveUri(b.uri, file, bp + "/uri");
    if (!bf) return null;
    if (!existsSync(bf)) { error(file, bp + "/uri", `buffer ${b.uri} not found`); return null; }
    const data = readFileSync(bf);
    if (data.length < b.byteLength) { error(file, bp + "/byteLength", `byteLength ${b.byteLength} > file ${b.uri} length ${data.length}`); return null; }
    return data.subarray(0, b.byteLength);
  });
  if (chunk && !(json.buffers?.[0] && json.buffers[0].uri === undefined))
    warn(file, "", "binary subtree has a binary chunk that no buffer refers to");

  // Buffer views: inside their buffer; byteOffset aligned to a multiple of 8 bytes.
  const views = (json.bufferViews ?? []).map((v, i) => {
    const vp = ptr("bufferViews", i);
    if (!v || typeof v !== "object" || !Number.isInteger(v.buffer)) return null;
    if (v.buffer >= (json.buffers ?? []).length) { error(file, vp + "/buffer", `buffer ${v.buffer} does not exist`); return null; }
    if (v.byteOffset % 8) error(file, vp + "/byteOffset", `byteOffset ${v.byteOffset} is not a multiple of 8`);
    const bl = json.buffers[v.buffer].byteLength;
    if (v.byteOffset + v.byteLength > bl) { error(file, vp, `bytes [${v.byteOffset}, ${v.byteOffset + v.byteLength}) outside buffer ${v.buffer} (byteLength ${bl})`); return null; }
    const data = buffers[v.buffer];
    return data ? data.subarray(v.byteOffset, v.byteOffset + v.byteLength) : null;
  });

  // Availability: a bitstream (a buffer view of ceil(bits/8) bytes, bit i = byte i>>3, bit i&7,
  // trailing bits 0; Metadata "Booleans") or a constant 0/1; availableCount, if given, must match.
  function availability(a, bits, ap) {
    const none = { get: () => 0 };
    if (!a || typeof a !== "object") { error(file, ap, "availability missing"); return none; }
    let get;
    if (a.bitstream !== undefined) {
      const v = views[a.bitstream];
      if (!Number.isInteger(a.bitstream) || a.bitstream >= views.length) { error(file, ap + "/bitstream", `buffer view ${a.bitstream} does not exist`); return none; }
      const want = Math.ceil(bits / 8);
      const vlen = json.bufferViews[a.bitstream].byteLength;
      if (vlen !== want) error(file, ap + "/bitstream", `bitstream buffer view ${a.bitstream} is ${vlen} bytes; ${bits} bits need ceil(${bits}/8) = ${want}`);
      if (!v) return none;
      get = (i) => (i >> 3 < v.length ? (v[i >> 3] >> (i & 7)) & 1 : 0);
      let stray = 0;
      for (let i = bits; i < v.length * 8; i++) stray += get(i);
      if (stray) error(file, ap + "/bitstream", `${stray} bits set past the ${bits} used bits (trailing bits shall be 0)`);
    } else if (a.constant === 0 || a.constant === 1) {
      get = () => a.constant;
    } else {
      return none; // schema error already reported
    }
    if (a.availableCount !== undefined) {
      let n = 0;
      for (let i = 0; i < bits; i++) n += get(i);
      if (n !== a.availableCount) error(file, ap + "/availableCount", `availableCount ${a.availableCount}, but ${n} bits are set`);
    }
    return { get };
  }
  // "Availability": tile and child subtree availability always; one content availability per
  // content template of the implicit root tile, and none when it has no content.
  const tile = availability(json.tileAvailability, nodes, "/tileAvailability");
  const child = availability(json.childSubtreeAvailability, childNodes, "/childSubtreeAvailability");
  const ca = json.contentAvailability ?? [];
  if (ca.length !== contentCount)
    error(file, "/contentAvailability", `${ca.length} content availabilities; the implicit root tile has ${contentCount} content template(s)`);
  const content = ca.slice(0, contentCount).map((a, k) => availability(a, nodes, `/contentAvailability/${k}`));

  // Metadata indices (spec "Metadata"): tileMetadata/contentMetadata name property tables;
  // property tables name buffer views.
  const tables = json.propertyTables ?? [];
  if (json.tileMetadata !== undefined && !(json.tileMetadata < tables.length))
    error(file, "/tileMetadata", `property table ${json.tileMetadata} does not exist`);
  (json.contentMetadata ?? []).forEach((t, k) => {
    if (!(t < tables.length)) error(file, `/contentMetadata/${k}`, `property table ${t} does not exist`);
  });
  if (json.contentMetadata && json.contentMetadata.length !== contentCount)
    error(file, "/contentMetadata", `${json.contentMetadata.length} entries; the implicit root tile has ${contentCount} content template(s)`);
  tables.forEach((t, ti) => {
    for (const [name, p] of Object.entries(t?.properties ?? {}))
      for (const key of ["values", "arrayOffsets", "stringOffsets"])
        if (p?.[key] !== undefined && !(p[key] < views.length))
          error(file, ptr("propertyTables", ti, "properties", name, key), `buffer view ${p[key]} does not exist`);
  });
  return { tile, content, child };
}

// ---------------------------------------------------------------------------------------------
// Run
if (!existsSync(rootFile)) {
  error(rootFile, "", `${rel(rootFile)} not found`);
} else {
  checkTileset(rootFile, rootFile, "");
}

const gltfResult = { files: gltfFiles.size, checked: 0, errors: 0, warnings: 0, failed: [] };
if (runGltf && gltfFiles.size) {
  const validator = load("gltf-validator");
  for (const f of gltfFiles) {
    const report = await validator.validateBytes(new Uint8Array(readFileSync(f)), {
      uri: path.basename(f),
      maxIssues: 100,
      externalResourceFunction: (uri) => new Promise((resolve, reject) => {
        try { resolve(new Uint8Array(readFileSync(path.join(path.dirname(f), decodeURIComponent(uri))))); }
        catch (e) { reject(e.message); }
      }),
    });
    const is = report.issues;
    gltfResult.checked++;
    gltfResult.errors += is.numErrors;
    gltfResult.warnings += is.numWarnings;
    if (is.numErrors || is.numWarnings) {
      gltfResult.failed.push(rel(f));
      const first = is.messages.filter((m) => m.severity <= 1).slice(0, 3)
        .map((m) => `${m.code} ${m.pointer || ""}: ${m.message}`).join("; ");
      error(f, "", `glTF validator: ${is.numErrors} errors, ${is.numWarnings} warnings (${first})`);
    }
  }
}

if (listContentsFile) writeFileSync(listContentsFile, [...gltfFiles].map((f) => f + "\n").join(""));
if (listTilesFile) writeFileSync(listTilesFile, tileLines.map((l) => l + "\n").join(""));

const ok = errorCount === 0;
const kinds = {};
for (const f of contentFiles) { const k = gltfFiles.has(f) ? "glTF" : path.extname(f).slice(1) || "other"; kinds[k] = (kinds[k] ?? 0) + 1; }
console.log(`3D Tiles check of ${rel(rootFile)} in ${rootDir} (ajv ${ajvVersion}, 3D Tiles 1.1 schemas)`);
console.log(`  tilesets: ${tilesetFiles.length} (${tilesetFiles.join(", ")})`);
console.log(`  explicit tiles: ${explicitTiles}`);
for (const r of implicitRoots)
  console.log(`  implicit root ${r.tileset}#${r.pointer}: ${r.scheme}, subtreeLevels ${r.subtreeLevels}, availableLevels ${r.availableLevels}, ${r.subtrees} subtrees, ${r.contents} contents`);
console.log(`  subtrees read: ${subtreesRead}`);
console.log(`  available implicit tiles per level: ${Object.keys(tilesPerLevel).length ? Object.entries(tilesPerLevel).map(([l, n]) => `${l}: ${n}`).join(", ") : "none"}`);
console.log(`  content files: ${contentFiles.size}${Object.keys(kinds).length ? ` (${Object.entries(kinds).map(([k, n]) => `${n} ${k}`).join(", ")})` : ""}, missing: ${missingContents}`);
if (runGltf) console.log(`  glTF validator: ${gltfResult.checked} files, ${gltfResult.errors} errors, ${gltfResult.warnings} warnings`);
const show = (kind, list, count) => {
  for (const p of list.slice(0, 50)) console.log(`  ${kind}: ${p.file}#${p.pointer}: ${p.message}`);
  if (count > 50) console.log(`  ... ${count - 50} more ${kind}s${summaryFile ? " (see the summary)" : ""}`);
};
show("warning", warnings, warningCount);
show("error", errors, errorCount);
console.log(`${ok ? "OK" : "FAILED"}: ${errorCount} errors, ${warningCount} warnings`);

if (summaryFile) {
  writeFileSync(summaryFile, JSON.stringify({
    ok, tileset: rootFile, ajv: ajvVersion, tilesPerLevel, explicitTiles,
    contents: contentFiles.size, gltfContents: gltfFiles.size, missingContents, subtrees: subtreesRead,
    tilesets: tilesetFiles, implicitRoots, errorCount, warningCount, errors, warnings,
    ...(runGltf ? { gltf: gltfResult } : {}),
  }, null, 1) + "\n");
}
process.exit(ok ? 0 : 1);
