// The three.js loader: the geometry holds the decoder's faces and positions, and update()
// moves through the clip at the playback rate, wrapping at the end; load() reports a file
// or a wasm that fails to the manager as three.js's loaders do; the wasm comes from
// setWasmUrl's URL.
import assert from "node:assert/strict";
import { copyFileSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { after, before, test } from "node:test";
import { fileURLToPath } from "node:url";

import { LoadingManager } from "three";

import { DcurveError, defaultWasmUrl, loadDcurve } from "../dcurve.js";
import { DcurveLoader } from "../dcurve-loader.js";
import { serve } from "../serve.mjs";

const file = readFileSync(new URL("../../format_spec/test_vectors/sheet_compact_faces.dcrv", import.meta.url));
const buffer = file.buffer.slice(file.byteOffset, file.byteOffset + file.byteLength);

// three's FileLoader reports download progress with ProgressEvent, which Node lacks.
globalThis.ProgressEvent ??= class extends Event {
  constructor(type, init) {
    super(type);
    Object.assign(this, init);
  }
};

let dir, server;
before(async () => {
  dir = mkdtempSync(`${tmpdir()}/dcurve-loader-`);
  writeFileSync(`${dir}/good.dcrv`, file);
  writeFileSync(`${dir}/bad.dcrv`, file.subarray(0, 40));
  server = await serve({ mounts: { "/data/": dir } });
});
after(() => {
  server?.close();
  rmSync(dir, { recursive: true, force: true });
});

// Loads `url` with a loader `configure` sets up, through a LoadingManager of its own; resolves
// once the manager is done, with the animation or error and the calls made, in order.
function managedLoad(url, configure = (loader) => loader) {
  return new Promise((resolve) => {
    const calls = [];
    let animation, error;
    const done = () => {
      calls.push("manager.onLoad");
      resolve({ animation, error, calls });
    };
    const manager = new LoadingManager(done, undefined, (item) => calls.push(`manager.itemError ${item}`));
    const onLoad = (a) => {
      calls.push("onLoad");
      animation = a;
    };
    const onError = (e) => {
      calls.push("onError");
      error = e;
    };
    configure(new DcurveLoader(manager)).load(url, onLoad, undefined, onError);
  });
}

test("the geometry follows the decoder at any playback rate", async () => {
  const anim = await new DcurveLoader().parse(buffer);
  const reference = (await loadDcurve()).open(file);
  const { position, normal } = anim.geometry.attributes;
  assert.equal(position.count, reference.vertexCount);
  assert.deepEqual(anim.geometry.index.array, reference.faces());
  assert.ok(normal, "normals for a file with faces");

  const expected = new Float32Array(reference.vertexCount * 3);
  const frameTime = 1 / anim.fps;
  anim.speed = 2;
  anim.update(frameTime * 0.75); // 1.5 frames in
  assert.ok(Math.abs(anim.time - 1.5 * frameTime) < 1e-9);
  reference.evaluate(anim.time / anim.duration, expected);
  assert.deepEqual(position.array, expected);

  const normals = reference.computeNormals(expected, new Float32Array(expected.length));
  assert.deepEqual(normal.array, normals);

  const frames = anim.decoder.frameCount - 1;
  anim.update(0.4 * frames * frameTime); // 0.8 * frames frames further at speed 2: past the end, wraps
  assert.equal(frames, 3);
  assert.ok(Math.abs(anim.time - 0.9 * frameTime) < 1e-9, `time ${anim.time}`);
  anim.dispose();
  reference.close();
});

test("a malformed file rejects with the decoder's message", async () => {
  await assert.rejects(new DcurveLoader().parse(buffer.slice(0, 40)), { name: "DcurveError" });
});

test("setT takes the normals from the frame in wasm memory, not through computeNormals", async () => {
  const anim = await new DcurveLoader().parse(buffer);
  const reference = (await loadDcurve()).open(file);
  anim.decoder.computeNormals = () => assert.fail("positions copied back into wasm memory");
  anim.setT(0.3);
  const { position, normal } = anim.geometry.attributes;
  const xyz = reference.evaluate(0.3, new Float32Array(position.array.length));
  assert.deepEqual(position.array, xyz);
  assert.deepEqual(normal.array, reference.computeNormals(xyz, new Float32Array(xyz.length)));
  anim.dispose();
  reference.close();
});

test("load() gives the animation to onLoad before the manager finishes", async () => {
  const { animation, calls } = await managedLoad(`${server.url}/data/good.dcrv`);
  assert.deepEqual(calls, ["onLoad", "manager.onLoad"]);
  assert.equal(animation.geometry.attributes.position.count, animation.decoder.vertexCount);
  animation.dispose();
});

test("load() of a file that does not decode reaches onError and manager.itemError", async () => {
  const url = `${server.url}/data/bad.dcrv`;
  const { error, calls } = await managedLoad(url);
  assert.deepEqual(calls, ["onError", `manager.itemError ${url}`, "manager.onLoad"]);
  assert.ok(error instanceof DcurveError && error.status === "malformed", String(error));
});

test("load() with a wasm that does not load reaches onError and manager.itemError", async () => {
  const url = `${server.url}/data/good.dcrv`;
  const wasmUrl = `${dir}/missing.wasm`;
  const { error, calls } = await managedLoad(url, (loader) => loader.setWasmUrl(wasmUrl));
  assert.deepEqual(calls, ["onError", `manager.itemError ${url}`, "manager.onLoad"]);
  assert.ok(error instanceof DcurveError && error.status === "aborted", String(error));
  assert.ok(error.message.includes(wasmUrl), error.message);
});

test("setWasmUrl: the module comes from the URL given, and a failed load is tried again", async () => {
  const path = `${dir}/moved.wasm`;
  const loader = new DcurveLoader().setWasmUrl(path);
  await assert.rejects(loader.parse(buffer), { name: "DcurveError", status: "aborted" });
  copyFileSync(fileURLToPath(defaultWasmUrl), path);
  (await loader.parse(buffer)).dispose();
  // Over HTTP, as a page fetches it.
  (await new DcurveLoader().setWasmUrl(`${server.url}/data/moved.wasm`).parse(buffer)).dispose();
});
