// Malformed input to the WebAssembly decoder: every truncation and a flip of every byte (one
// bit, rotating; the native tests flip all eight) of the test vectors is refused with a DcurveError carrying the decoder's message, at open or
// by the evaluation of the damaged frame (as tests/decoder_robustness_test.cpp natively),
// and never aborts the module.
import assert from "node:assert/strict";
import { readFileSync, readdirSync } from "node:fs";
import { test } from "node:test";

import { DcurveError, loadDcurve } from "../dcurve.js";

const vectors = new URL("../../format_spec/test_vectors/", import.meta.url);
const files = readdirSync(vectors).filter((f) => f.endsWith(".dcrv")).map((f) => readFileSync(new URL(f, vectors)));

// Opens and decodes every frame; returns the DcurveError raised, or null when all decoded.
function refusal(dcurve, bytes) {
  let dec;
  try {
    dec = dcurve.open(bytes);
    const xyz = new Float32Array(dec.vertexCount * 3);
    for (let f = 0; f < dec.frameCount; ++f) dec.evaluateFrame(f, xyz);
    return null;
  } catch (e) {
    if (!(e instanceof DcurveError)) throw e;
    assert.notEqual(e.status, "aborted", e.message);
    assert.ok(e.message.length > 0, "a message");
    return e;
  } finally {
    dec?.close();
  }
}

test("the unmodified test vectors decode", async () => {
  const dcurve = await loadDcurve();
  for (const bytes of files) assert.equal(refusal(dcurve, bytes), null);
});

test("every truncation is refused", async () => {
  const dcurve = await loadDcurve();
  for (const [k, bytes] of files.entries())
    for (let n = 0; n < bytes.length; ++n) assert.ok(refusal(dcurve, bytes.subarray(0, n)), `file ${k} cut at ${n}`);
});

test("a flipped bit in any byte is refused", async () => {
  const dcurve = await loadDcurve();
  for (const [k, bytes] of files.entries())
    for (let i = 0; i < bytes.length; ++i) {
      const bad = Uint8Array.from(bytes);
      bad[i] ^= 1 << (i + k) % 8;
      assert.ok(refusal(dcurve, bad), `file ${k} byte ${i} bit ${(i + k) % 8}`);
    }
});

test("random bytes behind a valid header are refused", async () => {
  const dcurve = await loadDcurve();
  let seed = 3;
  const next = () => (seed = (Math.imul(seed, 1103515245) + 12345) >>> 0) >>> 16;
  for (let i = 0; i < 2000; ++i) {
    const bad = new Uint8Array(next() % 400);
    for (let j = 0; j < bad.length; ++j) bad[j] = next();
    if (i % 2 && bad.length >= 20) bad.set(files[0].subarray(0, 20));
    assert.ok(refusal(dcurve, bad), `random file ${i}`);
  }
});
