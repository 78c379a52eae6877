// The three.js loader: the geometry holds the decoder's faces and positions, and update()
// moves through the clip at the playback rate, wrapping at the end.
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { test } from "node:test";

import { loadDcurve } from "../dcurve.js";
import { DcurveLoader } from "../dcurve-loader.js";

const file = readFileSync(new URL("../../format_spec/test_vectors/sheet_compact_faces.dcrv", import.meta.url));
const buffer = file.buffer.slice(file.byteOffset, file.byteOffset + file.byteLength);

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
