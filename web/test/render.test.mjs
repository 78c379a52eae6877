// Render data through the wasm decoder and the loader, on a textured glTF cloth encoded at
// test time (test/textured.mjs): render vertices and their UVs as the native decoder gives
// them (its `dcurve decode -o out.glb`, read with glTF-Transform), face groups, materials and
// the embedded image, placement, seam copies that never drift apart; and a file without
// render data that reads as before.
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdtempSync, readFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { after, before, test } from "node:test";

import { Matrix4, SRGBColorSpace } from "three";

import { loadDcurve } from "../dcurve.js";
import { DcurveLoader } from "../dcurve-loader.js";
import { dcurvePath, vectors } from "./browser.mjs";
import { encodeTextured, interopScript } from "./textured.mjs";

const WORLD = [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 2.4, 0, 1]; // scale 2 of a node 1.2 up

let dir, bytes, layout, native, dcurve, dec;
before(async () => {
  dir = mkdtempSync(`${tmpdir()}/dcurve-render-`);
  let file;
  ({ file, layout } = encodeTextured(dir));
  bytes = readFileSync(file);
  execFileSync(dcurvePath(), ["decode", file, "-o", `${dir}/decoded.glb`]);
  native = JSON.parse(interopScript("read_textured_glb.mjs", `${dir}/decoded.glb`));
  dcurve = await loadDcurve();
  dec = dcurve.open(bytes);
});
after(() => {
  dec?.close();
  rmSync(dir, { recursive: true, force: true });
});

const parse = (data) => new DcurveLoader().parse(data.buffer.slice(data.byteOffset, data.byteOffset + data.byteLength));

test("render vertices: a vertex per seam copy and per primitive sharing a row", () => {
  assert.equal(dec.vertexCount, 144); // 16 around x 9 rows
  assert.equal(dec.renderVertexCount, 170); // 17 columns x (5 + 5) rows
  const source = dec.renderSource();
  assert.equal(source.length, 170);
  assert.deepEqual(new Set(source).size, 144, "every vertex shown");
});

test("UVs and index buffers equal the native decoder's", () => {
  const { uv } = dec.attributes();
  assert.equal(uv.components, 2);
  // The native decoder's glb shares the render vertices between its two primitives.
  for (const primitive of native.primitives) assert.deepEqual(Array.from(uv.values), primitive.uv);
  const faces = dec.groupFaces();
  dec.groups().forEach(({ start, count }, i) =>
    assert.deepEqual(Array.from(faces.subarray(start, start + count)), native.primitives[i].indices, `group ${i}`));
});

test("two groups, drawn with the materials cloth and trim", () => {
  const groups = dec.groups();
  const { materials } = dec.materials();
  assert.deepEqual(groups.map((g) => [g.name, materials[g.materialIndex]?.name]), [["cloth", "cloth"], ["trim", "trim"]]);
  assert.deepEqual(groups.map((g) => [g.start, g.count]), [[0, 3 * 128], [3 * 128, 3 * 128]]);
  assert.deepEqual(materials[1].pbrMetallicRoughness.baseColorFactor, [0.8, 0.1, 0.1, 1]);
});

test("the texture's image is the PNG the glTF embeds, byte for byte", () => {
  const json = dec.materials();
  const source = json.textures[json.materials[0].pbrMetallicRoughness.baseColorTexture.index].source;
  const image = dec.images()[source];
  assert.equal(image.mimeType, "image/png");
  assert.deepEqual(Buffer.from(image.bytes), Buffer.from(layout.png, "base64"));
});

test("seam copies have their vertex's position and one normal, every frame and between", () => {
  const source = dec.renderSource();
  const { uv } = dec.attributes();
  const split = (r, s) => source[r] === source[s] && uv.values[2 * r] !== uv.values[2 * s];
  assert.ok(source.some((v, r) => source.some((_, s) => split(r, s))), "copies with their own UVs (the seam)");
  const xyz = new Float32Array(dec.vertexCount * 3);
  const positions = new Float32Array(dec.renderVertexCount * 3);
  const normals = new Float32Array(positions.length);
  const frames = Array.from({ length: dec.frameCount }, (_, f) => (p, n) => dec.evaluateFrameRender(f, p, n));
  for (const [k, render] of [...frames, (p, n) => dec.evaluateRender(0.37, p, n)].entries()) {
    render(positions, normals);
    if (k < dec.frameCount) dec.evaluateFrame(k, xyz);
    else dec.evaluate(0.37, xyz);
    const first = new Map(); // vertex: its first render vertex
    for (let r = 0; r < source.length; ++r) {
      const v = source[r];
      assert.deepEqual(positions.subarray(3 * r, 3 * r + 3), xyz.subarray(3 * v, 3 * v + 3), `step ${k} render vertex ${r}`);
      if (!first.has(v)) first.set(v, r);
      const s = first.get(v);
      assert.deepEqual(normals.subarray(3 * r, 3 * r + 3), normals.subarray(3 * s, 3 * s + 3), `step ${k} normals of ${r}, ${s}`);
    }
    const length = Math.hypot(...normals.subarray(0, 3));
    assert.ok(Math.abs(length - 1) < 1e-5, `unit normals, not ${length}`);
  }
});

test("render evaluation wants renderVertexCount * 3 values, checked before decoding", () => {
  const tooFew = new Float32Array(dec.vertexCount * 3).fill(NaN); // enough for vertices only
  const enough = new Float32Array(dec.renderVertexCount * 3);
  assert.throws(() => dec.evaluateRender(0.5, tooFew), { status: "invalid argument", message: /renderVertexCount/ });
  assert.throws(() => dec.evaluateFrameRender(1, enough, tooFew), { status: "invalid argument", message: /renderVertexCount/ });
  assert.ok(tooFew.every(Number.isNaN), "nothing written");
});

test("placement: the node's world matrix, names and start time", () => {
  const matrix = dec.worldMatrix;
  assert.equal(matrix.length, 16);
  matrix.forEach((x, i) => assert.ok(Math.abs(x - WORLD[i]) < 1e-6, `${matrix} against ${WORLD}`));
  assert.equal(dec.nodeName, "cloth");
  assert.equal(dec.meshName, "tube");
  assert.equal(dec.startTime, layout.firstTime);
});

test("a file without render data: render vertices are the vertices, nothing else", async () => {
  const plain = dcurve.open(readFileSync(`${vectors}/sheet_compact_faces.dcrv`));
  assert.equal(plain.renderVertexCount, plain.vertexCount);
  assert.deepEqual([plain.renderSource(), plain.groupFaces(), plain.materials(), plain.worldMatrix], [null, null, null, null]);
  assert.deepEqual([plain.groups(), plain.images(), plain.attributes()], [[], [], {}]);
  assert.deepEqual([plain.meshName, plain.nodeName, plain.startTime], ["", "", 0]);
  assert.deepEqual(plain.renderFaces(), plain.faces());
  const n = plain.vertexCount * 3;
  const [xyz, normals, render, renderNormals] = [0, 1, 2, 3].map(() => new Float32Array(n));
  plain.evaluate(0.4, xyz, normals);
  plain.evaluateRender(0.4, render, renderNormals);
  assert.deepEqual([render, renderNormals], [xyz, normals]);
  plain.close();

  const anim = await parse(readFileSync(`${vectors}/sheet_compact_faces.dcrv`));
  assert.deepEqual([anim.materials, anim.geometry.groups, anim.object.name], [[], [], ""]);
  assert.deepEqual(Object.keys(anim.geometry.attributes).sort(), ["normal", "position"]);
  assert.ok(anim.object.isMesh && anim.object.material.isMeshStandardMaterial, "one default material");
  assert.ok(anim.object.matrix.equals(new Matrix4()), "not moved");
  anim.dispose();
});

test("the loader: render geometry in group order, a material per group, the node's placement", async () => {
  const anim = await parse(bytes);
  const { geometry, materials, object } = anim;
  assert.equal(geometry.attributes.position.count, 170);
  assert.deepEqual(geometry.index.array, dec.groupFaces());
  assert.deepEqual(geometry.groups, [{ start: 0, count: 384, materialIndex: 0 }, { start: 384, count: 384, materialIndex: 1 }]);
  assert.deepEqual(geometry.attributes.uv.array, dec.attributes().uv.values);
  assert.equal(geometry.attributes.uv.itemSize, 2);

  assert.deepEqual(materials.map((m) => m.name), ["cloth", "trim"]);
  assert.strictEqual(object.material, materials);
  const map = materials[0].map;
  assert.ok(map?.isTexture, "cloth has its texture");
  assert.deepEqual([map.flipY, map.colorSpace, map.name], [false, SRGBColorSpace, "weave"]);
  assert.equal(materials[1].map, null);
  assert.deepEqual(materials[1].color.toArray(), [0.8, 0.1, 0.1]); // linear, as glTF's factors and three's working space

  assert.equal(object.name, "cloth");
  object.updateMatrix();
  object.matrix.toArray().forEach((x, i) => assert.ok(Math.abs(x - WORLD[i]) < 1e-6, `object matrix ${object.matrix.toArray()}`));

  anim.setT(0.37);
  const normals = new Float32Array(170 * 3);
  assert.deepEqual(geometry.attributes.position.array, dec.evaluateRender(0.37, new Float32Array(170 * 3), normals));
  assert.deepEqual(geometry.attributes.normal.array, normals);
  anim.dispose();
});
