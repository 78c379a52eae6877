// The WebAssembly decoder against format_spec/test_vectors: each file (and its format 3.0
// and 3.1 copies) decodes to the positions of its .expected.txt, with the tolerance the native test
// uses (tests/decoder_vectors_test.cpp).
import assert from "node:assert/strict";
import { readFileSync, readdirSync } from "node:fs";
import { test } from "node:test";

import { loadDcurve } from "../dcurve.js";

const vectors = new URL("../../format_spec/test_vectors/", import.meta.url);
const names = readdirSync(vectors).filter((f) => f.endsWith(".dcrv")).map((f) => f.slice(0, -5));

// One line per sample time: t, then vertexCount * 3 coordinates.
function readExpected(name) {
  const text = readFileSync(new URL(`${name}.expected.txt`, vectors), "utf8");
  return text.trim().split("\n").map((line) => {
    const [t, ...xyz] = line.trim().split(/\s+/).map(Number);
    return { t, xyz };
  });
}

function assertDecodesAsExpected(dcurve, path, name) {
  const dec = dcurve.open(readFileSync(path));
  const lines = readExpected(name);
  assert.ok(lines.length > 1, `${name}: expected positions`);
  const xyz = new Float32Array(dec.vertexCount * 3);
  for (const { t, xyz: expected } of lines) {
    assert.equal(expected.length, xyz.length, `${name}: values per line`);
    dec.evaluate(t, xyz);
    for (let i = 0; i < xyz.length; ++i) {
      const tol = 1e-5 * (1 + Math.abs(expected[i]));
      if (Math.abs(xyz[i] - expected[i]) > tol)
        assert.fail(`${path} t ${t} value ${i}: ${xyz[i]} against ${expected[i]}`);
    }
  }
  dec.close();
}

test("every test vector decodes to its expected positions", async () => {
  assert.ok(names.length >= 10, "test vectors found");
  const dcurve = await loadDcurve();
  for (const name of names) assertDecodesAsExpected(dcurve, new URL(`${name}.dcrv`, vectors), name);
});

// test_vectors/3.0 and 3.1 keep the files of the vectors that existed then, as those formats
// wrote them; each decodes to the positions of the current vector of its name.
for (const version of ["3.0", "3.1"]) {
  test(`format ${version} test vectors decode to the same positions`, async () => {
    const older = readdirSync(new URL(`${version}/`, vectors)).filter((f) => f.endsWith(".dcrv"));
    assert.ok(older.length >= 10, `format ${version} vectors found`);
    const dcurve = await loadDcurve();
    for (const file of older) assertDecodesAsExpected(dcurve, new URL(`${version}/${file}`, vectors), file.slice(0, -5));
  });
}

test("evaluateFrame gives the stored frames and counts match the file", async () => {
  const dcurve = await loadDcurve();
  const dec = dcurve.open(readFileSync(new URL("chunked.dcrv", vectors)));
  assert.ok(dec.frameCount > 2 && dec.vertexCount > 0);
  const byFrame = new Float32Array(dec.vertexCount * 3);
  const byTime = new Float32Array(dec.vertexCount * 3);
  for (let f = 0; f < dec.frameCount; ++f) {
    dec.evaluateFrame(f, byFrame);
    dec.evaluate(f / (dec.frameCount - 1), byTime);
    assert.deepEqual(byFrame, byTime, `frame ${f}`);
  }
  dec.close();
  assert.throws(() => dec.evaluate(0, byFrame), { name: "DcurveError", message: /closed/ });
});

test("evaluate's and evaluateFrame's normals are computeNormals of their positions", async () => {
  const dcurve = await loadDcurve();
  for (const name of ["sheet_compact_faces", "fit"]) {
    const dec = dcurve.open(readFileSync(new URL(`${name}.dcrv`, vectors)));
    const n = dec.vertexCount * 3;
    const [xyz, normals, expected] = [new Float32Array(n), new Float32Array(n), new Float32Array(n)];
    for (let f = 0; f < dec.frameCount; ++f) {
      dec.evaluateFrame(f, xyz, normals);
      assert.deepEqual(normals, dec.computeNormals(xyz, expected), `${name} frame ${f}`);
      dec.evaluate((f + 0.5) / dec.frameCount, xyz, normals);
      assert.deepEqual(normals, dec.computeNormals(xyz, expected), `${name} t ${(f + 0.5) / dec.frameCount}`);
    }
    dec.close();
  }
});
