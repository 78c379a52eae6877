// The README's uses of the API, type-checked against the declarations by `npx tsc --noEmit`
// (web/tsconfig.json); never run.
import { DoubleSide, LoadingManager, Mesh, MeshStandardMaterial, Object3D } from "three";

import { DcurveError, loadDcurve } from "../dcurve.js";
import { DcurveAnimation, DcurveLoader } from "../dcurve-loader.js";

export async function decode(bytes: ArrayBuffer): Promise<Float32Array> {
  const dcurve = await loadDcurve({ wasmUrl: new URL("https://example.org/dcurve_wasm.wasm") });
  const dec = dcurve.open(bytes);
  const xyz = new Float32Array(dec.vertexCount * 3);
  const normals = dec.faces() ? new Float32Array(xyz.length) : undefined;
  try {
    return dec.evaluateFrame(dec.frameCount - 1, dec.evaluate(0.5, xyz, normals));
  } catch (e) {
    if (e instanceof DcurveError && e.status === dcurve.statusName(e.code)) throw new Error(e.message);
    throw e;
  } finally {
    dec.close();
  }
}

export async function textured(bytes: ArrayBuffer): Promise<string[]> {
  const dec = (await loadDcurve()).open(bytes);
  const xyz = new Float32Array(dec.renderVertexCount * 3);
  dec.evaluateFrameRender(0, dec.evaluateRender(0.5, xyz, new Float32Array(xyz.length)));
  const uv: Float32Array | undefined = dec.attributes().uv?.values;
  const json = dec.materials();
  const names = dec.groups().map((g) => `${g.name} ${json?.materials?.[g.materialIndex]?.name} ${g.start / 3} ${uv?.length}`);
  const blobs = dec.images().map(({ bytes, mimeType }) => new Blob([bytes], { type: mimeType }));
  const matrix = dec.worldMatrix ?? [];
  dec.close();
  return [...names, `${blobs.length} ${matrix.length} ${dec.nodeName} ${dec.meshName} ${dec.startTime}`];
}

export async function placed(loader: DcurveLoader): Promise<Object3D> {
  const anim = await loader.loadAsync("cloth.dcrv");
  for (const material of anim.materials) material.side = DoubleSide;
  return anim.object;
}

export async function play(manager: LoadingManager): Promise<Mesh> {
  const loader = new DcurveLoader(manager).setWasmUrl("/lib/dcurve_wasm.wasm").setPath("/data/");
  const anim: DcurveAnimation = await loader.loadAsync("cloth.dcrv");
  loader.load("other.dcrv", (other) => other.setT(0.5).dispose(), undefined, (error) => console.error(error));
  anim.speed = 0.5;
  anim.update(1 / 60).setTime(anim.duration);
  return new Mesh(anim.geometry, new MeshStandardMaterial());
}
