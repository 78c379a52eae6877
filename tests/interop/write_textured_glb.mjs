// node write_textured_glb.mjs OUT.glb: writes with glTF-Transform what a DCC exporter writes
// for a textured cloth: an open tube in two primitives (rows 0-4 with a textured material,
// rows 4-8 with a plain one; row 4 is in both), whose UV seam splits each vertex of one column
// into two copies (same position, u = 0 and u = 1); UVs, normals, morph-target animation keyed
// from 1/24 s, the mesh node translated inside a scaled parent, and a second animation that
// moves the parent (which dcurve does not store, and must say so). Prints the layout as JSON.
import { Document, NodeIO } from '@gltf-transform/core';

const [output] = process.argv.slice(2);
const around = 16, rows = 8, split = 4, frameCount = 10, fps = 24;
const columns = around + 1;  // the seam column twice
// A 1x1 PNG: the texture's bytes must come back unchanged.
const png = Buffer.from('iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNk+M9QDwADhgGAWjR9awAAAABJRU5ErkJggg==', 'base64');
const position = (i, j, f) => {
  const a = (2 * Math.PI * (i % around)) / around, y = j / rows;
  const r = 0.5 + (f > 0 ? 0.1 * Math.sin(3 * y + f * 0.4) : 0);
  return [r * Math.cos(a), y, r * Math.sin(a)];
};

const doc = new Document();
const buffer = doc.createBuffer();
const acc = (type, array) => doc.createAccessor().setType(type).setArray(array).setBuffer(buffer);
const texture = doc.createTexture('weave').setImage(new Uint8Array(png)).setMimeType('image/png');
const materials = [
  doc.createMaterial('cloth').setBaseColorTexture(texture),
  doc.createMaterial('trim').setBaseColorFactor([0.8, 0.1, 0.1, 1]),
];
const mesh = doc.createMesh('tube');
const parts = [[0, split], [split, rows]];
parts.forEach(([j0, j1], p) => {
  const frames = [], uv = [], normal = [], faces = [];
  for (let f = 0; f < frameCount; f++) {
    const xyz = [];
    for (let j = j0; j <= j1; j++) for (let i = 0; i < columns; i++) xyz.push(...position(i, j, f));
    frames.push(new Float32Array(xyz));
  }
  for (let j = j0; j <= j1; j++)
    for (let i = 0; i < columns; i++) {
      const a = (2 * Math.PI * (i % around)) / around;
      uv.push(i / around, j / rows);
      normal.push(Math.cos(a), 0, Math.sin(a));
    }
  for (let j = 0; j < j1 - j0; j++)
    for (let i = 0; i < around; i++) {
      const v = j * columns + i;
      faces.push(v, v + columns, v + 1, v + 1, v + columns, v + columns + 1);
    }
  const prim = doc.createPrimitive().setMaterial(materials[p])
    .setAttribute('POSITION', acc('VEC3', frames[0]))
    .setAttribute('NORMAL', acc('VEC3', new Float32Array(normal)))
    .setAttribute('TEXCOORD_0', acc('VEC2', new Float32Array(uv)))
    .setIndices(acc('SCALAR', new Uint32Array(faces)));
  for (let k = 1; k < frameCount; k++)
    prim.addTarget(doc.createPrimitiveTarget().setAttribute('POSITION', acc('VEC3', frames[k].map((x, i) => x - frames[0][i]))));
  mesh.addPrimitive(prim);
});
const targets = frameCount - 1;
mesh.setWeights(new Array(targets).fill(0));
const node = doc.createNode('cloth').setMesh(mesh).setTranslation([0, 1.2, 0]);
const parent = doc.createNode('rig').setScale([2, 2, 2]).addChild(node);
doc.createScene().addChild(parent);
const times = new Float32Array(frameCount).map((_, k) => (k + 1) / fps);
const weights = new Float32Array(frameCount * targets);
for (let k = 1; k < frameCount; k++) weights[k * targets + k - 1] = 1;
const sampler = doc.createAnimationSampler().setInput(acc('SCALAR', times)).setOutput(acc('SCALAR', weights))
  .setInterpolation('LINEAR');
doc.createAnimation('shape').addSampler(sampler)
  .addChannel(doc.createAnimationChannel().setTargetNode(node).setTargetPath('weights').setSampler(sampler));
const moveSampler = doc.createAnimationSampler().setInput(acc('SCALAR', new Float32Array([0, 1])))
  .setOutput(acc('VEC3', new Float32Array([0, 0, 0, 1, 0, 0]))).setInterpolation('LINEAR');
doc.createAnimation('walk').addSampler(moveSampler)
  .addChannel(doc.createAnimationChannel().setTargetNode(parent).setTargetPath('translation').setSampler(moveSampler));
await new NodeIO().write(output, doc);
console.log(JSON.stringify({ columns, around, rows, split, frames: frameCount, fps, firstTime: times[0], png: png.toString('base64') }));
