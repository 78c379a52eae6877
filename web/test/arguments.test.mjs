// Arguments the JS wrapper checks before calling into wasm memory: every exported function
// refuses a missing, mistyped or too-short argument with a DcurveError ("invalid argument"),
// never reads stale heap memory and never lets a RangeError or TypeError out.
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { test } from "node:test";

import { DcurveError, loadDcurve } from "../dcurve.js";

const vector = (name) => readFileSync(new URL(`../../format_spec/test_vectors/${name}.dcrv`, import.meta.url));

function assertInvalid(call, what) {
  assert.throws(call, (e) => {
    assert.ok(e instanceof DcurveError, `${what}: ${e?.name}: ${e?.message}`);
    assert.equal(e.status, "invalid argument", what);
    return true;
  });
}

test("computeNormals refuses short, missing or mistyped arrays", async () => {
  const dcurve = await loadDcurve();
  const dec = dcurve.open(vector("sheet_compact_faces"));
  const n = dec.vertexCount * 3;
  assert.ok(dec.faceCount > 0, "a vector with faces");
  const xyz = new Float32Array(n);
  dec.evaluate(0.5, xyz);
  const normals = dec.computeNormals(xyz, new Float32Array(n));
  // Positions one vertex short would leave the last vertex's stale positions in wasm memory.
  assertInvalid(() => dec.computeNormals(xyz.subarray(0, n - 3), new Float32Array(n)), "short positions");
  assertInvalid(() => dec.computeNormals(new Float32Array(0), new Float32Array(n)), "empty positions");
  assertInvalid(() => dec.computeNormals(xyz, new Float32Array(n - 1)), "short output");
  assertInvalid(() => dec.computeNormals(Array.from(xyz), new Float32Array(n)), "a plain array");
  assertInvalid(() => dec.computeNormals(xyz), "no output");
  assertInvalid(() => dec.computeNormals(undefined, new Float32Array(n)), "no positions");
  // A refused call leaves the decoder usable and its results the same.
  assert.deepEqual(dec.computeNormals(xyz, new Float32Array(n)), normals);
  dec.close();
});

test("evaluate's normals output is checked before anything is decoded", async () => {
  const dcurve = await loadDcurve();
  const dec = dcurve.open(vector("sheet_compact_faces"));
  const n = dec.vertexCount * 3;
  const out = new Float32Array(n).fill(NaN);
  for (const [normals, what] of [[new Float32Array(n - 1), "short"], [Array(n).fill(0), "a plain array"], [null, "null"]]) {
    assertInvalid(() => dec.evaluate(0.5, out, normals), `evaluate's normals ${what}`);
    assertInvalid(() => dec.evaluateFrame(1, out, normals), `evaluateFrame's normals ${what}`);
  }
  assert.ok(out.every(Number.isNaN), "nothing written by a refused call");
  dec.close();
  const flat = dcurve.open(vector("zero_segments_no_faces"));
  assert.equal(flat.faceCount, 0);
  const xyz = new Float32Array(flat.vertexCount * 3).fill(NaN);
  assert.throws(() => flat.evaluate(0.5, xyz, new Float32Array(xyz.length)), { status: "invalid argument", message: /connectivity/ });
  assert.ok(xyz.every(Number.isNaN), "no positions without the normals asked for");
  flat.evaluate(0.5, xyz); // without normals, it decodes
  flat.close();
});

test("evaluate, evaluateFrame and their render forms refuse bad outputs, times and frame numbers", async () => {
  const dcurve = await loadDcurve();
  const dec = dcurve.open(vector("chunked"));
  const n = dec.vertexCount * 3;
  for (const [out, what] of [[new Float32Array(n - 1), "short"], [new Float64Array(n), "Float64Array"], [null, "null"]]) {
    assertInvalid(() => dec.evaluate(0.5, out), `evaluate into ${what}`);
    assertInvalid(() => dec.evaluateFrame(0, out), `evaluateFrame into ${what}`);
    assertInvalid(() => dec.evaluateRender(0.5, out), `evaluateRender into ${what}`);
    assertInvalid(() => dec.evaluateFrameRender(0, out), `evaluateFrameRender into ${what}`);
  }
  const xyz = new Float32Array(n);
  for (const t of [NaN, "0.5", undefined, Symbol("t")]) assertInvalid(() => dec.evaluate(t, xyz), `t = ${String(t)}`);
  for (const f of [1.5, NaN, "1", undefined]) assertInvalid(() => dec.evaluateFrame(f, xyz), `frame ${String(f)}`);
  assertInvalid(() => dec.evaluateRender(NaN, xyz), "evaluateRender at t = NaN");
  assertInvalid(() => dec.evaluateFrameRender(0.5, xyz), "evaluateFrameRender of frame 0.5");
  dec.evaluateFrame(1, xyz); // still usable
  dec.close();
  assertInvalid(() => dec.evaluate(0, xyz), "a closed decoder");
});

test("open refuses what is not a file's bytes, and takes any view of them", async () => {
  const dcurve = await loadDcurve();
  for (const data of [undefined, null, 42, "dcurve", {}, [1, 2, 3]]) assertInvalid(() => dcurve.open(data), `open(${String(data)})`);
  const bytes = vector("fit");
  const padded = new Uint8Array(bytes.length + 8);
  padded.set(bytes, 4);
  const view = new DataView(padded.buffer, 4, bytes.length);
  const [dec, whole] = [dcurve.open(view), dcurve.open(bytes)];
  assert.equal(dec.vertexCount, whole.vertexCount);
  dec.close();
  whole.close();
});
