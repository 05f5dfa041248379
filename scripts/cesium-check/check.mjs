#!/usr/bin/env node
// Tellus: drives headless Chromium (Debian's, through puppeteer-core) to load index.html, which shows a
// quantized-mesh tile set in CesiumJS, and checks that it rendered. Normally started by run.sh.
//
// node check.mjs --url http://127.0.0.1:PORT/index.html --summary OUT.json --screenshot OUT.png
//   [--camera lon,lat,height,heading,pitch] [--sample lon,lat]... [--timeout SECONDS] [--size WxH]
//   [--param key=value]... (more query parameters for index.html: exaggeration, normals=0, time)
//   [--stable-frames N] [--min-fraction F] [--globe-disc] [--tileset] [--node-modules DIR] [--chromium PATH]
//
// --tileset: the page draws a 3D Tiles set (tiles/tileset.json, index.html's tileset=1) instead of
// quantized-mesh terrain: its glTF contents are the tiles counted, tileset.json must load, heights
// are sampled from the drawn tiles (scene.sampleHeightMostDetailed), and every tile the set fails
// to load is a console error.
//
// --globe-disc (with --param lighting=0, so that no globe pixel is black) also compares the
// screenshot with the WGS84 ellipsoid as Cesium's own camera sees it (camera.pickEllipsoid for
// every pixel): the drawn globe's area-equivalent radius must be within 1 % of the ellipsoid's
// (the limb), no pixel more than 2 pixels inside the ellipsoid's outline may show the
// background (a hole, a crack, a tile sunk below the horizon), and none more than 2 pixels
// outside it may show the globe (a bulge: checked from 100 km up, where no mountain rises
// above the ellipsoid's outline by 2 pixels). From close up, where the globe fills the view,
// the same checks say: no background anywhere it should be ground.
//
// Exits 0 when all is well; 1 with a line per failure on stderr (and "failures" in the summary) when:
// a console error or page error, a failed request or an HTTP error status, a request that left
// 127.0.0.1, no .terrain tile answered with 200, WebGL missing, tiles still loading at the timeout,
// a sampled height that is not finite, or a screenshot that is nearly one colour (under --min-fraction,
// default 0.15, of its pixels differ from the commonest colour: tiles drawn with clockwise triangles, so that
// only their skirts show, left 5%; a whole globe seen from 20,000 km fills 23%). 2: bad arguments.
import { createRequire } from "node:module";
import { writeFileSync } from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));

function usage(msg) {
  if (msg) console.error(`check.mjs: ${msg}`);
  console.error("usage: node check.mjs --url URL --summary FILE.json --screenshot FILE.png " +
    "[--camera lon,lat,height,heading,pitch] [--sample lon,lat]... [--param key=value]... [--timeout S] [--size WxH] " +
    "[--stable-frames N] [--min-fraction F] [--node-modules DIR] [--chromium PATH]");
  process.exit(2);
}

const opts = {
  url: null, summary: null, screenshot: null, camera: null, samples: [], params: [], timeout: 120,
  width: 1024, height: 640, stableFrames: 10, minFraction: 0.15, globeDisc: false, tileset: false,
  nodeModules: process.env.CESIUM_CHECK_NODE_MODULES || path.join(here, "node_modules"),
  chromium: process.env.CHROMIUM_PATH || "/usr/bin/chromium",
};
{
  const argv = process.argv.slice(2);
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    const val = () => { if (i + 1 >= argv.length) usage(`${a} needs a value`); return argv[++i]; };
    const nums = (s, n, what) => {
      const v = s.split(",").map(Number);
      if (v.length !== n || v.some((x) => !Number.isFinite(x))) usage(`${what}: expected ${n} numbers separated by commas, got '${s}'`);
      return v;
    };
    switch (a) {
      case "--url": opts.url = val(); break;
      case "--summary": opts.summary = val(); break;
      case "--screenshot": opts.screenshot = val(); break;
      case "--camera": opts.camera = nums(val(), 5, "--camera"); break;
      case "--param": { const v = val(); const eq = v.indexOf("="); if (eq < 1) usage(`--param wants key=value, got '${v}'`); opts.params.push([v.slice(0, eq), v.slice(eq + 1)]); break; }
      case "--sample": opts.samples.push(nums(val(), 2, "--sample")); break;
      case "--timeout": opts.timeout = Number(val()); break;
      case "--size": { const [w, h] = val().split("x").map(Number); opts.width = w; opts.height = h; break; }
      case "--stable-frames": opts.stableFrames = Number(val()); break;
      case "--min-fraction": opts.minFraction = Number(val()); break;
      case "--globe-disc": opts.globeDisc = true; break;
      case "--tileset": opts.tileset = true; break;
      case "--node-modules": opts.nodeModules = val(); break;
      case "--chromium": opts.chromium = val(); break;
      case "-h": case "--help": usage(); break;
      default: usage(`unknown argument '${a}'`);
    }
  }
  if (!opts.url || !opts.summary || !opts.screenshot) usage("--url, --summary and --screenshot are required");
  if (!(opts.timeout > 0) || !(opts.width > 0) || !(opts.height > 0)) usage("bad --timeout or --size");
}

const require = createRequire(path.join(path.resolve(opts.nodeModules), "noop.js"));
const puppeteer = require("puppeteer-core");
const { PNG } = require("pngjs");

// Headless Chromium gets WebGL from SwiftShader (software Vulkan under ANGLE): there is no GPU here.
const CHROMIUM_ARGS = [
  "--headless=new",
  "--no-sandbox",                 // runs as root in a container
  "--use-angle=swiftshader",
  "--enable-unsafe-swiftshader",  // Chromium >= 137 refuses SwiftShader WebGL without it
  "--ignore-gpu-blocklist",
  "--disable-dev-shm-usage",
  "--no-first-run",
  "--no-default-browser-check",
  "--disable-background-networking",
  "--disable-component-update",
  "--disable-sync",
  "--disable-extensions",
  "--disable-breakpad",
  "--disable-features=Translate,OptimizationHints,MediaRouter",
  "--mute-audio",
];

const started = Date.now();
const elapsed = () => ((Date.now() - started) / 1000).toFixed(1);
const log = (m) => console.log(`check: [${elapsed()} s] ${m}`);

const pageUrl = new URL(opts.url);
if (opts.camera) {
  const [lon, lat, height, heading, pitch] = opts.camera;
  Object.entries({ lon, lat, height, heading, pitch }).forEach(([k, v]) => pageUrl.searchParams.set(k, String(v)));
}
for (const [k, v] of opts.params) pageUrl.searchParams.set(k, v);
if (opts.tileset) pageUrl.searchParams.set("tileset", "1");

const summary = {
  ok: false,
  url: pageUrl.href,
  chromium: null,
  webgl: null,
  tilesRequested: 0,        // .terrain (or, with --tileset, .glb) responses with status 200
  levelsRequested: [],
  tilesPerLevel: {},
  layerJson: false,         // with --tileset: tileset.json
  subtreesRequested: 0,     // with --tileset: .subtree responses with status 200
  consoleErrors: [],
  consoleWarnings: [],
  pageErrors: [],
  failedRequests: [],
  abortedRequests: [],
  offsiteRequests: [],
  frames: 0,
  tilesLoadedAfterS: null,
  sampledHeights: [],
  screenshot: { width: 0, height: 0, nonBackgroundFraction: 0, backgroundColor: null, distinctColors: 0, lumaStdDev: 0 },
  globeDisc: null,          // with --globe-disc: the drawn globe against the ellipsoid
  failures: [],
  seconds: 0,
};

function pngStats(buf) {
  const png = PNG.sync.read(buf);
  const { width, height, data } = png;
  const counts = new Map();
  let sum = 0, sum2 = 0;
  for (let i = 0; i < data.length; i += 4) {
    const key = (data[i] << 16) | (data[i + 1] << 8) | data[i + 2];
    counts.set(key, (counts.get(key) || 0) + 1);
    const y = 0.2126 * data[i] + 0.7152 * data[i + 1] + 0.0722 * data[i + 2];
    sum += y; sum2 += y * y;
  }
  let bgKey = 0, bgCount = 0;
  for (const [k, c] of counts) if (c > bgCount) { bgKey = k; bgCount = c; }
  const n = width * height;
  const mean = sum / n;
  return {
    width, height,
    nonBackgroundFraction: Number((1 - bgCount / n).toFixed(4)),
    backgroundColor: "#" + bgKey.toString(16).padStart(6, "0"),
    distinctColors: counts.size,
    lumaStdDev: Number(Math.sqrt(Math.max(0, sum2 / n - mean * mean)).toFixed(2)),
  };
}

// The drawn globe (pixels not pure black) against the ellipsoid's mask ('1': the pixel's ray
// meets the ellipsoid): area-equivalent radii, and pixels on the wrong side of the outline by
// more than `margin` pixels.
function compareDisc(buf, mask, margin = 2) {
  const { width, height, data } = PNG.sync.read(buf);
  const drawn = (x, y) => { const i = 4 * (y * width + x); return data[i] | data[i + 1] | data[i + 2]; };
  const inMask = (x, y) => x >= 0 && y >= 0 && x < width && y < height && mask.charCodeAt(y * width + x) === 49;
  // Whether every pixel within `margin` has the same mask value (the pixel is not near the outline).
  const settled = (x, y, value) => {
    for (let dy = -margin; dy <= margin; dy++) {
      for (let dx = -margin; dx <= margin; dx++) {
        const xx = x + dx, yy = y + dy;
        if (xx < 0 || yy < 0 || xx >= width || yy >= height) continue;
        if (inMask(xx, yy) !== value) return false;
      }
    }
    return true;
  };
  let expected = 0, drawnCount = 0, holes = 0, bulges = 0, firstHole = null, firstBulge = null;
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const m = inMask(x, y), d = drawn(x, y) !== 0;
      if (m) expected++;
      if (d) drawnCount++;
      if (m && !d && settled(x, y, true)) { holes++; firstHole = firstHole || [x, y]; }
      if (!m && d && settled(x, y, false)) { bulges++; firstBulge = firstBulge || [x, y]; }
    }
  }
  const radiusExpected = Math.sqrt(expected / Math.PI), radiusDrawn = Math.sqrt(drawnCount / Math.PI);
  return {
    expectedPixels: expected, drawnPixels: drawnCount,
    radiusRatio: expected ? Number((radiusDrawn / radiusExpected).toFixed(5)) : null,
    backgroundInside: holes, firstBackgroundInside: firstHole,
    globeOutside: bulges, firstGlobeOutside: firstBulge,
    fillsView: expected === width * height,
  };
}

let browser;
let exitCode = 1;
try {
  browser = await puppeteer.launch({
    executablePath: opts.chromium,
    headless: true,
    args: [...CHROMIUM_ARGS, `--window-size=${opts.width},${opts.height}`],
    defaultViewport: { width: opts.width, height: opts.height },
    timeout: 60000,
    protocolTimeout: (opts.timeout + 60) * 1000,
  });
  summary.chromium = await browser.version();
  const page = await browser.newPage();

  page.on("console", (msg) => {
    const loc = msg.location();
    const where = loc && loc.url ? ` (${loc.url}${loc.lineNumber !== undefined ? ":" + loc.lineNumber : ""})` : "";
    if (msg.type() === "error") summary.consoleErrors.push(msg.text() + where);
    else if (msg.type() === "warn" || msg.type() === "warning") summary.consoleWarnings.push(msg.text());
  });
  page.on("pageerror", (err) => summary.pageErrors.push(String(err && err.stack ? err.stack : err)));
  page.on("request", (req) => {
    const u = new URL(req.url());
    if ((u.protocol === "http:" || u.protocol === "https:" || u.protocol === "ws:" || u.protocol === "wss:") &&
        u.host !== pageUrl.host) summary.offsiteRequests.push(req.url());
  });
  page.on("requestfailed", (req) => {
    const f = req.failure();
    const why = f ? f.errorText : "failed";
    // Cesium cancels tile requests it no longer needs: aborted ones are listed, not failures.
    if (why === "net::ERR_ABORTED") summary.abortedRequests.push(req.url());
    else summary.failedRequests.push(`${req.url()}: ${why}`);
  });
  page.on("response", (res) => {
    const u = new URL(res.url());
    if (u.host !== pageUrl.host) return;
    const status = res.status();
    if (status >= 400) summary.failedRequests.push(`${res.url()}: HTTP ${status}`);
    if (status === 200 && u.pathname.endsWith(opts.tileset ? "/tiles/tileset.json" : "/layer.json")) summary.layerJson = true;
    if (status === 200 && u.pathname.endsWith(".subtree")) summary.subtreesRequested++;
    // A 3D Tiles set's contents: H/tiles/L/X/Y.glb as Tellus writes them, or any other .glb
    // (counted at level 0).
    const m = opts.tileset ? (/\/tiles\/\d\/tiles\/(\d+)\/(\d+)\/(\d+)\.glb$/.exec(u.pathname) ||
                              (/^\/tiles\/.*\.glb$/.test(u.pathname) ? [u.pathname, "0"] : null))
                           : /\/terrain\/(\d+)\/(\d+)\/(\d+)\.terrain$/.exec(u.pathname);
    if (m && status === 200) {
      summary.tilesRequested++;
      summary.tilesPerLevel[m[1]] = (summary.tilesPerLevel[m[1]] || 0) + 1;
    }
  });

  await page.goto(pageUrl.href, { waitUntil: "load", timeout: 60000 });

  // WebGL must be real (SwiftShader), else Cesium cannot draw anything.
  summary.webgl = await page.evaluate(() => {
    const c = document.createElement("canvas");
    const gl = c.getContext("webgl2") || c.getContext("webgl");
    if (!gl) return null;
    const dbg = gl.getExtension("WEBGL_debug_renderer_info");
    return {
      version: gl.getParameter(gl.VERSION),
      renderer: dbg ? gl.getParameter(dbg.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER),
      vendor: dbg ? gl.getParameter(dbg.UNMASKED_VENDOR_WEBGL) : gl.getParameter(gl.VENDOR),
    };
  });
  if (!summary.webgl) throw new Error("WebGL is not available in headless Chromium (SwiftShader flags?)");
  log(`${summary.chromium}, WebGL: ${summary.webgl.version}, ${summary.webgl.renderer}`);

  // Wait until the globe says its tiles are loaded for several frames in a row.
  const deadline = started + opts.timeout * 1000;
  let state;
  let lastReport = 0;
  for (;;) {
    state = await page.evaluate(() => ({ ...window.tellus }));
    summary.frames = state.frames;
    if (state.phase === "failed") throw new Error(`page setup failed: ${state.error}`);
    if (state.phase === "rendering" && state.stableFrames >= opts.stableFrames) break;
    if (Date.now() > deadline) {
      throw new Error(`timeout after ${opts.timeout} s: phase ${state.phase}, ${state.frames} frames, ` +
        `${summary.tilesRequested} tiles, globe.tilesLoaded not stable`);
    }
    if (Date.now() - lastReport > 10000) {
      lastReport = Date.now();
      log(`waiting: ${state.frames} frames, ${summary.tilesRequested} tiles so far`);
    }
    await new Promise((r) => setTimeout(r, 200));
  }
  summary.tilesLoadedAfterS = Number(elapsed());
  log(`tiles loaded: ${summary.tilesRequested} ${opts.tileset ? `glTF tiles, ${summary.subtreesRequested} subtrees` : ".terrain tiles"}, ${state.frames} frames`);

  if (opts.samples.length) {
    summary.sampledHeights = await page.evaluate(async (pts, tilesetMode) => {
      const carto = pts.map(([lo, la]) => Cesium.Cartographic.fromDegrees(lo, la));
      const res = tilesetMode ? await window.viewer.scene.sampleHeightMostDetailed(carto)
                              : await Cesium.sampleTerrainMostDetailed(window.viewer.terrainProvider, carto);
      return pts.map(([lo, la], i) => ({ lon: lo, lat: la, height: res[i].height === undefined ? null : res[i].height }));
    }, opts.samples, opts.tileset);
    for (const s of summary.sampledHeights) log(`height at ${s.lon},${s.lat}: ${s.height}`);
  }

  const shot = await page.screenshot({ type: "png" });
  if (opts.globeDisc) {
    const mask = await page.evaluate((w, h) => {
      const scene = window.viewer.scene, camera = scene.camera;
      const ellipsoid = Cesium.Ellipsoid.WGS84;
      const position = new Cesium.Cartesian2();
      const out = new Array(h);
      for (let y = 0; y < h; y++) {
        let row = "";
        for (let x = 0; x < w; x++) {
          position.x = x + 0.5;
          position.y = y + 0.5;
          row += camera.pickEllipsoid(position, ellipsoid) ? "1" : "0";
        }
        out[y] = row;
      }
      return out.join("");
    }, opts.width, opts.height);
    summary.globeDisc = compareDisc(shot, mask);
    summary.globeDisc.cameraHeightM = await page.evaluate(() => window.viewer.camera.positionCartographic.height);
    const g = summary.globeDisc;
    log(`globe disc: ${g.drawnPixels} pixels drawn, ${g.expectedPixels} in the ellipsoid's outline` +
      `${g.fillsView ? " (it fills the view)" : `, radius ratio ${g.radiusRatio}`}; ` +
      `${g.backgroundInside} background pixels inside, ${g.globeOutside} globe pixels outside`);
  }
  writeFileSync(opts.screenshot, shot);
  summary.screenshot = pngStats(shot);
  log(`screenshot ${summary.screenshot.width}x${summary.screenshot.height}: ` +
    `${(summary.screenshot.nonBackgroundFraction * 100).toFixed(1)}% not ${summary.screenshot.backgroundColor}, ` +
    `${summary.screenshot.distinctColors} colours, luma std dev ${summary.screenshot.lumaStdDev}`);
} catch (err) {
  summary.failures.push(String(err && err.message ? err.message : err));
} finally {
  if (browser) await browser.close().catch(() => {});
}

const levels = Object.keys(summary.tilesPerLevel).map(Number).sort((a, b) => a - b);
summary.levelsRequested = levels;
const f = summary.failures;
if (summary.consoleErrors.length) f.push(`${summary.consoleErrors.length} console error(s), first: ${summary.consoleErrors[0]}`);
if (summary.pageErrors.length) f.push(`${summary.pageErrors.length} page error(s), first: ${summary.pageErrors[0]}`);
if (summary.failedRequests.length) f.push(`${summary.failedRequests.length} failed request(s), first: ${summary.failedRequests[0]}`);
if (summary.offsiteRequests.length) f.push(`${summary.offsiteRequests.length} request(s) left the local server, first: ${summary.offsiteRequests[0]}`);
if (!summary.layerJson) f.push(`${opts.tileset ? "tileset.json" : "layer.json"} was not loaded`);
if (summary.tilesRequested === 0) f.push(`no ${opts.tileset ? ".glb" : ".terrain"} tile was requested (answered 200)`);
for (const s of summary.sampledHeights) {
  if (!Number.isFinite(s.height)) f.push(`sampled height at ${s.lon},${s.lat} is not finite (${s.height})`);
}
// (With --globe-disc the globe is drawn unlit, one colour: the comparison with the ellipsoid
// replaces the blank-screen test.)
if (!opts.globeDisc && summary.screenshot.width && summary.screenshot.nonBackgroundFraction < opts.minFraction) {
  f.push(`screenshot is blank: only ${(summary.screenshot.nonBackgroundFraction * 100).toFixed(2)}% of pixels differ from ${summary.screenshot.backgroundColor}`);
}
if (opts.globeDisc && summary.globeDisc) {
  const g = summary.globeDisc;
  if (!g.fillsView && !(Math.abs(g.radiusRatio - 1) <= 0.01)) {
    f.push(`the globe's limb is off: its area-equivalent radius is ${g.radiusRatio} of the ellipsoid's`);
  }
  if (g.backgroundInside) f.push(`${g.backgroundInside} background pixels inside the globe's outline, first at ${g.firstBackgroundInside}`);
  if (g.globeOutside && g.cameraHeightM >= 100e3) f.push(`${g.globeOutside} globe pixels outside the ellipsoid's outline, first at ${g.firstGlobeOutside}`);
} else if (opts.globeDisc) {
  f.push("--globe-disc: the globe was not compared (no screenshot)");
}
summary.ok = f.length === 0;
summary.seconds = Number(elapsed());
writeFileSync(opts.summary, JSON.stringify(summary, null, 2) + "\n");

if (summary.ok) {
  log(`OK: ${summary.tilesRequested} tiles at levels ${levels.join(",")}; summary in ${opts.summary}`);
  exitCode = 0;
} else {
  for (const m of f) console.error(`check: FAIL: ${m}`);
  exitCode = 1;
}
process.exit(exitCode);
