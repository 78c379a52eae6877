// node read_glb.mjs IN.glb FRAMES.bin: reads a glTF file with glTF-Transform and writes the
// mesh at each key of its weights animation (base + sum of weight x target), prints
// "keys N fps F".
import { NodeIO } from '@gltf-transform/core';
import { writeFrames } from './frames_io.mjs';

const [input, output] = process.argv.slice(2);
const doc = await new NodeIO().read(input);
const root = doc.getRoot();
const prim = root.listMeshes()[0].listPrimitives()[0];
const base = prim.getAttribute('POSITION').getArray();
const targets = prim.listTargets().map((t) => t.getAttribute('POSITION').getArray());
const sampler = root.listAnimations()[0].listSamplers()[0];
const times = sampler.getInput().getArray();
const weights = sampler.getOutput().getArray();
const frames = [];
for (let k = 0; k < times.length; k++) {
  const xyz = Float32Array.from(base);
  targets.forEach((t, j) => {
    const w = weights[k * targets.length + j];
    if (w !== 0) for (let i = 0; i < xyz.length; i++) xyz[i] += w * t[i];
  });
  frames.push(xyz);
}
const faces = prim.getIndices() ? Uint32Array.from(prim.getIndices().getArray()) : new Uint32Array(0);
writeFrames(output, { vertexCount: base.length / 3, faces, frames });
const fps = times.length > 1 ? (times.length - 1) / (times[times.length - 1] - times[0]) : 0;
console.log(`keys ${times.length} fps ${fps.toFixed(3)}`);
