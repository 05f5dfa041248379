#!/usr/bin/env node
// Runs the Khronos glTF validator on each file given (see validate-gltf.sh, which installs it).
//   node validate-gltf.mjs --node-modules DIR FILE... [--report DIR]
// Exit 0: no error and no warning in any file; 1: some; 2: bad usage or an unreadable file.
import { createRequire } from "node:module";
import { readFileSync, writeFileSync, mkdirSync } from "node:fs";
import path from "node:path";

const files = [];
let nodeModules = null, reportDir = null;
const argv = process.argv.slice(2);
for (let i = 0; i < argv.length; i++) {
  if (argv[i] === "--node-modules") nodeModules = argv[++i];
  else if (argv[i] === "--report") reportDir = argv[++i];
  else files.push(argv[i]);
}
if (!nodeModules || files.length === 0) {
  console.error("usage: node validate-gltf.mjs --node-modules DIR FILE... [--report DIR]");
  process.exit(2);
}
const require = createRequire(path.join(path.resolve(nodeModules), "noop.js"));
const validator = require("gltf-validator");

let bad = 0;
for (const file of files) {
  let bytes;
  try {
    bytes = new Uint8Array(readFileSync(file));
  } catch (e) {
    console.error(`validate-gltf: ${file}: ${e.message}`);
    process.exit(2);
  }
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 100,
    // External resources (a .gltf's .bin or images) beside the file.
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        try { resolve(new Uint8Array(readFileSync(path.join(path.dirname(file), decodeURIComponent(uri))))); }
        catch (e) { reject(e.message); }
      }),
  });
  const issues = report.issues;
  if (reportDir) {
    mkdirSync(reportDir, { recursive: true });
    writeFileSync(path.join(reportDir, `${path.basename(file)}.json`), JSON.stringify(report, null, 1));
  }
  const first = issues.messages.filter((m) => m.severity <= 1).slice(0, 3)
    .map((m) => `${m.code} ${m.pointer || ""}: ${m.message}`).join("; ");
  console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ${issues.numInfos} infos, ` +
    `${issues.numHints} hints${first ? ` (${first})` : ""}`);
  if (issues.numErrors || issues.numWarnings) bad++;
}
process.exit(bad ? 1 : 0);
