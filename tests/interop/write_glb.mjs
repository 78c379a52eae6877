// node write_glb.mjs FRAMES.bin OUT.glb FPS: writes the frames with glTF-Transform as one
// mesh (frame 0) with a morph target per later frame and a weights animation, one key per
// frame (the way DCC exporters write baked vertex animation).
import { Document, NodeIO } from '@gltf-transform/core';
import { readFrames } from './frames_io.mjs';

const [input, output, fpsArg] = process.argv.slice(2);
const fps = Number(fpsArg);
const { faces, frames } = readFrames(input);
const doc = new Document();
const buffer = doc.createBuffer();
const base = frames[0];
const prim = doc.createPrimitive()
  .setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(base).setBuffer(buffer))
  .setIndices(doc.createAccessor().setType('SCALAR').setArray(faces).setBuffer(buffer));
for (let k = 1; k < frames.length; k++) {
  const delta = frames[k].map((x, i) => x - base[i]);
  prim.addTarget(doc.createPrimitiveTarget()
    .setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(delta).setBuffer(buffer)));
}
const targets = frames.length - 1;
const mesh = doc.createMesh('anim').addPrimitive(prim).setWeights(new Array(targets).fill(0));
const node = doc.createNode('anim').setMesh(mesh);
doc.createScene().addChild(node);
const times = new Float32Array(frames.length).map((_, k) => k / fps);
const weights = new Float32Array(frames.length * targets);
for (let k = 1; k < frames.length; k++) weights[k * targets + k - 1] = 1;
const sampler = doc.createAnimationSampler()
  .setInput(doc.createAccessor().setType('SCALAR').setArray(times).setBuffer(buffer))
  .setOutput(doc.createAccessor().setType('SCALAR').setArray(weights).setBuffer(buffer))
  .setInterpolation('LINEAR');
doc.createAnimation('frames').addSampler(sampler)
  .addChannel(doc.createAnimationChannel().setTargetNode(node).setTargetPath('weights').setSampler(sampler));
await new NodeIO().write(output, doc);
