// Sizes of the web decoder and its per-frame decode time in headless Chromium against the
// native decoder on the same file, both measured in this run:
//   node web/bench.mjs FILE.dcrv [PASSES=7]
// A pass opens the file (not timed) and plays every frame in order through a fresh cursor
// (evaluateFrame); the figure is the median pass's milliseconds per frame. Node runs the same
// wasm as a third column. Needs web/build.sh's output, Chromium and build/web/dcurve_web_native.
import { readFileSync } from "node:fs";
import { basename, dirname, resolve } from "node:path";
import { gzipSync } from "node:zlib";

import { loadDcurve } from "./dcurve.js";
import { native, openViewer } from "./test/browser.mjs";
import { playbackMs } from "./test/playback.mjs";

const [file, passesArg] = process.argv.slice(2);
if (!file) {
  console.error("usage: node web/bench.mjs FILE.dcrv [PASSES=7]");
  process.exit(2);
}
const passes = Number(passesArg ?? 7);

function sizes() {
  const parts = {
    "dcurve_wasm.wasm": "build/dcurve_wasm.wasm",
    "dcurve_wasm.mjs (glue)": "build/dcurve_wasm.mjs",
    "dcurve.js (wrapper)": "dcurve.js",
    "fzstd (zstd for the shared sections)": "node_modules/fzstd/esm/index.mjs",
  };
  const rows = Object.entries(parts).map(([name, path]) => {
    const bytes = readFileSync(new URL(path, import.meta.url));
    return { name, raw: bytes.length, gzip: gzipSync(bytes, { level: 9 }).length };
  });
  rows.push({ name: "total", raw: rows.reduce((a, r) => a + r.raw, 0), gzip: rows.reduce((a, r) => a + r.gzip, 0) });
  return rows;
}

async function browserMs(path) {
  const viewer = await openViewer(dirname(resolve(path)), basename(path));
  try {
    await viewer.stopRendering(); // a quiet page: the viewer only hosts the modules here
    return await viewer.page.evaluate(async ({ url, passes }) => {
      const [{ loadDcurve }, { playbackMs }] = await Promise.all([import("/dcurve.js"), import("/test/playback.mjs")]);
      const bytes = new Uint8Array(await (await fetch(url)).arrayBuffer());
      return playbackMs(loadDcurve, bytes, passes);
    }, { url: `/data/${encodeURIComponent(basename(path))}`, passes });
  } finally {
    await viewer.close();
  }
}

console.log("size of the web decoder (bytes):");
for (const r of sizes()) console.log(`  ${r.name.padEnd(40)} raw ${String(r.raw).padStart(7)}  gzip -9 ${String(r.gzip).padStart(6)}`);

const nat = JSON.parse(native("bench", file, passes));
const nodeMs = await playbackMs(loadDcurve, readFileSync(file), passes);
const chromeMs = await browserMs(file);
console.log(`\n${basename(file)}: ${nat.vertices} vertices, ${nat.frames} frames, median of ${passes} passes, ms per frame:`);
console.log(`  native ${nat.ms_per_frame.toFixed(4)}   node (wasm) ${nodeMs.toFixed(4)}   chromium (wasm) ${chromeMs.toFixed(4)}`);
console.log(`  chromium / native ${(chromeMs / nat.ms_per_frame).toFixed(2)} (goal <= 3), node / native ${(nodeMs / nat.ms_per_frame).toFixed(2)}`);
