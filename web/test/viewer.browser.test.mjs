// The viewer page in headless Chromium: it loads a .dcrv (a waving sheet the native encoder
// writes), plays it, gives at several t the positions the native decoder gives, finds the
// error against the input OBJ frames within the file's tolerance, and draws the mesh (a
// canvas that is not blank; the screenshot's path is printed). Needs the wasm build,
// Chromium, build/cli/dcurve and build/web/dcurve_web_native.
import assert from "node:assert/strict";
import { mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { after, before, test } from "node:test";
import { fileURLToPath } from "node:url";

import { nativePositions, openViewer } from "./browser.mjs";
import { encodeWave } from "./wave.mjs";

const TIMES = [0, 0.123456789, 0.37, 0.5, 0.8, 1];

let dir, file, viewer;
before(async () => {
  dir = mkdtempSync(`${tmpdir()}/dcurve-web-`);
  file = encodeWave(dir);
  viewer = await openViewer(dir, "wave.dcrv");
});
after(async () => {
  await viewer?.close();
  rmSync(dir, { recursive: true, force: true });
});

test("playing moves the mesh through the clip", async () => {
  const { page } = viewer;
  const start = await page.evaluate(() => window.viewer.positionsAt(0));
  await page.evaluate(() => window.viewer.play());
  await page.waitForFunction(() => window.viewer.info().steps >= 5);
  await page.evaluate(() => window.viewer.pause());
  const info = await page.evaluate(() => window.viewer.info());
  assert.ok(info.duration > 0 && info.time > 0 && info.time <= info.duration, JSON.stringify(info));
  const shown = await page.evaluate(() => Array.from(window.viewer.shownPositions()));
  assert.notDeepEqual(shown, start, "the positions changed while playing");
});

test("positions in the page match the native decoder at several t", async () => {
  const expected = nativePositions(file, TIMES);
  for (const [k, t] of TIMES.entries()) {
    const got = await viewer.page.evaluate((t) => window.viewer.positionsAt(t), t);
    assert.equal(got.length, expected[k].length, `t ${t}: value count`);
    for (let i = 0; i < got.length; ++i) {
      // The same code, another compiler: float results agree to rounding.
      if (Math.abs(got[i] - expected[k][i]) > 1e-6 * (1 + Math.abs(expected[k][i])))
        assert.fail(`t ${t} value ${i}: page ${got[i]}, native ${expected[k][i]}`);
    }
  }
});

test("DcurveLoader.loadAsync fetches a file by URL", async () => {
  const counts = await viewer.page.evaluate(async () => {
    const { DcurveLoader } = await import("/dcurve-loader.js");
    const anim = await new DcurveLoader().loadAsync("/data/wave.dcrv");
    const result = [anim.geometry.attributes.position.count, anim.geometry.index.count / 3];
    anim.dispose();
    return result;
  });
  assert.deepEqual(counts, [24 * 24, 2 * 23 * 23]);
});

test("the page's error against the input frames is within the tolerance", async () => {
  const { page } = viewer;
  await page.setInputFiles("#reference", `${dir}/frames`);
  await page.waitForFunction(() => window.viewer.info().referenceError);
  const { referenceError, tolerance } = await page.evaluate(() => window.viewer.info());
  assert.equal(referenceError.frames, 30);
  assert.ok(referenceError.ofL > 0 && referenceError.ofL <= tolerance, JSON.stringify(referenceError));
});

test("the canvas shows the mesh", async () => {
  const { page, errors } = viewer;
  await page.evaluate(() => window.viewer.positionsAt(0.5));
  const { covered, total } = await page.evaluate(() => window.viewer.coveredPixels());
  const out = fileURLToPath(new URL("../out/", import.meta.url));
  mkdirSync(out, { recursive: true });
  await page.screenshot({ path: `${out}viewer.png` });
  console.log(`screenshot: ${out}viewer.png (${covered} of ${total} pixels drawn)`);
  assert.ok(covered > total * 0.02, `only ${covered} of ${total} pixels differ from the background`);
  assert.deepEqual(errors, []);
});

test("a damaged file chosen in the page shows the decoder's message", async () => {
  const { page } = viewer;
  const bytes = readFileSync(file);
  writeFileSync(`${dir}/damaged.dcrv`, bytes.subarray(0, bytes.length >> 1));
  await page.setInputFiles("#file", `${dir}/damaged.dcrv`);
  await page.waitForFunction(() => document.getElementById("message").textContent !== "");
  const message = await page.evaluate(() => document.getElementById("message").textContent);
  assert.match(message, /^damaged\.dcrv: \S/);
});
