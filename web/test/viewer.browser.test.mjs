// The viewer page in headless Chromium, driven from outside as a user would (its controls
// and panel; the shown mesh through three.js's devtools hook): it loads a .dcrv (a waving
// sheet the native encoder writes), plays it, shows at several t the positions the native
// decoder gives, finds the error against the input OBJ frames within the file's tolerance,
// and draws the mesh (a canvas that is not blank; the screenshot's path is printed); a textured
// file's texture decodes in the loader and shows in the page. Needs the wasm build, Chromium,
// build/cli/dcurve and build/web/dcurve_web_native.
import assert from "node:assert/strict";
import { copyFileSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { after, before, test } from "node:test";
import { fileURLToPath } from "node:url";

import { defaultWasmUrl } from "../dcurve.js";
import { nativePositions, openViewer } from "./browser.mjs";
import { encodeTextured } from "./textured.mjs";
import { encodeWave } from "./wave.mjs";

// On the slider's 0.001 steps; 0.123 and 0.37 fall between frames.
const TIMES = [0, 0.123, 0.37, 0.5, 0.8, 1];

let dir, file, textured, viewer;
before(async () => {
  dir = mkdtempSync(`${tmpdir()}/dcurve-web-`);
  file = encodeWave(dir);
  textured = encodeTextured(dir).file;
  copyFileSync(fileURLToPath(defaultWasmUrl), `${dir}/moved.wasm`);
  viewer = await openViewer(dir, "wave.dcrv");
});
after(async () => {
  await viewer?.close();
  rmSync(dir, { recursive: true, force: true });
});

const shownT = async () => Number(await viewer.page.textContent("#t"));

test("playing moves the mesh through the clip", async () => {
  const { page } = viewer;
  const start = await viewer.positions();
  await page.click("#play");
  await page.waitForFunction(() => Number(document.getElementById("t").textContent) > 0);
  await page.click("#play");
  assert.equal(await page.textContent("#play"), "Play", "paused");
  const t = await shownT();
  assert.ok(t > 0 && t <= 1, `t ${t}`);
  assert.notDeepEqual(await viewer.positions(), start, "the positions changed while playing");
});

test("positions in the page match the native decoder at several t", async () => {
  const expected = nativePositions(file, TIMES);
  for (const [k, t] of TIMES.entries()) {
    await viewer.page.fill("#scrub", String(t));
    assert.equal(await shownT(), t);
    const got = await viewer.positions();
    assert.equal(got.length, expected[k].length, `t ${t}: value count`);
    for (let i = 0; i < got.length; ++i) {
      // The same code, another compiler: float results agree to rounding.
      if (Math.abs(got[i] - expected[k][i]) > 1e-6 * (1 + Math.abs(expected[k][i])))
        assert.fail(`t ${t} value ${i}: page ${got[i]}, native ${expected[k][i]}`);
    }
  }
});

test("DcurveLoader.loadAsync fetches a file by URL, and the wasm from setWasmUrl's", async () => {
  const { page } = viewer;
  const requested = [];
  const record = (request) => requested.push(new URL(request.url()).pathname);
  page.on("request", record);
  const counts = await page.evaluate(async () => {
    const { DcurveLoader } = await import("/dcurve-loader.js");
    const anim = await new DcurveLoader().setWasmUrl("/data/moved.wasm").loadAsync("/data/wave.dcrv");
    const result = [anim.geometry.attributes.position.count, anim.geometry.index.count / 3];
    anim.dispose();
    return result;
  });
  page.off("request", record);
  assert.deepEqual(counts, [24 * 24, 2 * 23 * 23]);
  assert.ok(requested.includes("/data/moved.wasm"), requested.join(", "));
});

test("the page's error against the input frames is within the tolerance", async () => {
  const { page } = viewer;
  await page.setInputFiles("#reference", `${dir}/frames`);
  await page.waitForFunction(() => document.getElementById("info").textContent.includes("max error"));
  const info = await viewer.info();
  // "1.234e-4 of L (0.12 x tolerance), 30 frames" and "0.001 of L = 1.414"
  const [, ofL, frames] = info["max error"].match(/^(\S+) of L \(.*\), (\d+) frames$/);
  const tolerance = Number(info.tolerance.split(" ")[0]);
  assert.equal(Number(frames), 30);
  // The page shows 4 significant digits of the error.
  assert.ok(Number(ofL) > 0 && Number(ofL) <= tolerance * (1 + 5e-4), info["max error"]);
});

// Saves a screenshot as out/NAME.png (its path printed), then counts the pixels of another,
// with the panel painted over in the background's colour: { covered } differ from the
// background, { green } are clearly green (the textured file's texture is a green pixel).
async function screenshotPixels(name) {
  const { page } = viewer;
  const background = await viewer.background();
  const out = fileURLToPath(new URL("../out/", import.meta.url));
  mkdirSync(out, { recursive: true });
  await page.screenshot({ path: `${out}${name}.png` });
  const png = await page.screenshot({ mask: [page.locator("#panel")], maskColor: background });
  const counts = await page.evaluate(async ({ png, background }) => {
    const image = await createImageBitmap(await (await fetch(`data:image/png;base64,${png}`)).blob());
    const canvas = new OffscreenCanvas(image.width, image.height);
    const context = canvas.getContext("2d");
    context.drawImage(image, 0, 0);
    const pixels = context.getImageData(0, 0, image.width, image.height).data;
    const [r, g, b] = [1, 3, 5].map((i) => parseInt(background.slice(i, i + 2), 16));
    let covered = 0, green = 0;
    for (let i = 0; i < pixels.length; i += 4) {
      if (Math.abs(pixels[i] - r) + Math.abs(pixels[i + 1] - g) + Math.abs(pixels[i + 2] - b) > 12) ++covered;
      if (pixels[i + 1] > 2 * Math.max(pixels[i], pixels[i + 2]) + 20) ++green;
    }
    return { covered, green, total: image.width * image.height };
  }, { png: png.toString("base64"), background });
  console.log(`screenshot: ${out}${name}.png (${counts.covered} of ${counts.total} pixels drawn, ${counts.green} green)`);
  return counts;
}

test("the canvas shows the mesh", async () => {
  await viewer.page.fill("#scrub", "0.5");
  const { covered, total } = await screenshotPixels("viewer");
  assert.ok(covered > total * 0.02, `only ${covered} of ${total} pixels differ from the background`);
  assert.deepEqual(viewer.errors, []);
});

test("the page adds no globals (tests drive it from outside)", async () => {
  const added = await viewer.page.evaluate(() => {
    const frame = document.body.appendChild(document.createElement("iframe"));
    const blank = new Set(Object.getOwnPropertyNames(frame.contentWindow));
    frame.remove();
    return Object.getOwnPropertyNames(window).filter((name) => !blank.has(name)).sort();
  });
  assert.deepEqual(added, ["__THREE__"], "three.js's revision only"); // the frame has the tests' hook too
});

test("a textured file: the loader decodes its texture, and the page shows it", async () => {
  const { page } = viewer;
  const loaded = await page.evaluate(async () => {
    const { DcurveLoader } = await import("/dcurve-loader.js");
    const anim = await new DcurveLoader().loadAsync("/data/textured.dcrv");
    const result = { groups: anim.geometry.groups.length, width: anim.materials[0].map?.image?.width };
    anim.dispose(); // closes the image: read it before
    return result;
  });
  assert.deepEqual(loaded, { groups: 2, width: 1 });

  await page.setInputFiles("#file", textured);
  await page.waitForFunction(() => document.getElementById("info").textContent.includes("materials"));
  assert.equal((await viewer.info()).materials, "cloth (texture 1x1), trim");
  const shown = await page.evaluate(() => {
    const mesh = window.__THREE_DEVTOOLS__.find("isScene").children.find((c) => c.geometry);
    return { name: mesh.name, maps: mesh.material.map((m) => m.map?.image?.width ?? null) };
  });
  assert.deepEqual(shown, { name: "cloth", maps: [1, null] });
  const { green, total } = await screenshotPixels("textured");
  assert.ok(green > total * 0.005, `only ${green} of ${total} pixels show the green texture`);
  assert.deepEqual(viewer.errors, []);
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
