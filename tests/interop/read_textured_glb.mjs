// node read_textured_glb.mjs IN.glb: reads a glTF file with glTF-Transform and prints as JSON
// what a game would take from it. Per primitive: its vertices' positions and normals at each
// key (base + weight x target), UVs, indices, material name and base colour texture bytes;
// and the mesh node's world matrix and name, the mesh name, the key times.
import { NodeIO } from '@gltf-transform/core';

const [input] = process.argv.slice(2);
const doc = await new NodeIO().read(input);
const root = doc.getRoot();
const node = root.listNodes().find((n) => n.getMesh());
const sampler = root.listAnimations()[0].listSamplers()[0];
const times = Array.from(sampler.getInput().getArray());
const weights = sampler.getOutput().getArray();
const blend = (prim, name) => {
  const base = prim.getAttribute(name)?.getArray();
  if (!base) return null;
  const targets = prim.listTargets().map((t) => t.getAttribute(name)?.getArray());
  return times.map((_, k) => {
    const out = Float32Array.from(base);
    targets.forEach((t, j) => {
      const w = weights[k * targets.length + j];
      if (w !== 0 && t) for (let i = 0; i < out.length; i++) out[i] += w * t[i];
    });
    return Array.from(out);
  });
};
const primitives = root.listMeshes()[0].listPrimitives().map((prim) => {
  const material = prim.getMaterial();
  const image = material?.getBaseColorTexture()?.getImage();
  return {
    positions: blend(prim, 'POSITION'),
    normals: blend(prim, 'NORMAL'),
    uv: prim.getAttribute('TEXCOORD_0') ? Array.from(prim.getAttribute('TEXCOORD_0').getArray()) : null,
    indices: prim.getIndices() ? Array.from(prim.getIndices().getArray()) : null,
    material: material ? material.getName() : null,
    baseColor: material ? material.getBaseColorFactor() : null,
    texture: image ? Buffer.from(image).toString('base64') : null,
  };
});
console.log(JSON.stringify({
  primitives,
  worldMatrix: node.getWorldMatrix(),
  nodeName: node.getName(),
  meshName: root.listMeshes()[0].getName(),
  times,
}));
