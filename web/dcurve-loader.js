// A three.js loader for .dcrv files: a BufferGeometry over the file's render vertices whose
// positions (and normals, when the file has connectivity) the returned DcurveAnimation
// rewrites for any time, at any playback rate; with the file's UVs, colours, face groups and
// materials, and an object placed where the input's node was.
//
//   const anim = await new DcurveLoader().loadAsync("cloth.dcrv"); // setWasmUrl(url) first to move the wasm
//   scene.add(anim.object); // or new THREE.Mesh(anim.geometry, material) for a material of your own
//   renderer.setAnimationLoop(() => { anim.update(clock.getDelta()); renderer.render(scene, camera); });
import {
  BufferAttribute, BufferGeometry, ClampToEdgeWrapping, DoubleSide, DynamicDrawUsage, FileLoader, FrontSide,
  LinearFilter, LinearMipmapLinearFilter, LinearMipmapNearestFilter, LinearSRGBColorSpace, Loader, Matrix4, Mesh,
  MeshStandardMaterial, MirroredRepeatWrapping, NearestFilter, NearestMipmapLinearFilter, NearestMipmapNearestFilter,
  Points, PointsMaterial, RepeatWrapping, SRGBColorSpace, Texture,
} from "three";

import { defaultWasmUrl, loadDcurve } from "./dcurve.js";

// Each wasm URL's module (a promise), loaded once for every file; a failed load is forgotten
// so that a later file tries again.
const modules = new Map();

export class DcurveLoader extends Loader {
  wasmUrl = defaultWasmUrl;

  // Where dcurve_wasm.wasm is served; the default is build/ beside dcurve.js.
  setWasmUrl(url) {
    this.wasmUrl = url;
    return this;
  }

  load(url, onLoad, onProgress, onError) {
    // As three.js's GLTFLoader: one more manager item spans the parse, so a file that fetches
    // but does not decode reaches manager.itemError too, and manager.onLoad waits for it.
    this.manager.itemStart(url);
    const fail = (e) => {
      if (onError) onError(e);
      else console.error(e);
      this.manager.itemError(url);
      this.manager.itemEnd(url);
    };
    const files = new FileLoader(this.manager);
    files.setPath(this.path).setResponseType("arraybuffer").setRequestHeader(this.requestHeader);
    files.setWithCredentials(this.withCredentials).setPriority(this.priority).setCache(this.cache);
    const loaded = (animation) => {
      onLoad(animation);
      this.manager.itemEnd(url);
    };
    files.load(url, (buffer) => this.parse(buffer).then(loaded).catch(fail), onProgress, fail);
  }

  // An ArrayBuffer holding a .dcrv to a DcurveAnimation (rejects with a DcurveError).
  async parse(buffer) {
    const key = String(this.wasmUrl);
    if (!modules.has(key)) {
      const module = loadDcurve({ wasmUrl: this.wasmUrl });
      module.catch(() => modules.delete(key));
      modules.set(key, module);
    }
    const decoder = (await modules.get(key)).open(buffer);
    try {
      return new DcurveAnimation(decoder, await fileMaterials(decoder));
    } catch (e) {
      decoder.close();
      throw e;
    }
  }
}

// glTF sampler enums (WebGL's) to three.js's, as GLTFLoader maps them.
const FILTERS = {
  9728: NearestFilter, 9729: LinearFilter, 9984: NearestMipmapNearestFilter, 9985: LinearMipmapNearestFilter,
  9986: NearestMipmapLinearFilter, 9987: LinearMipmapLinearFilter,
};
const WRAPS = { 33071: ClampToEdgeWrapping, 33648: MirroredRepeatWrapping, 10497: RepeatWrapping };

// An image's bytes decoded as GLTFLoader's ImageBitmapLoader does; null where the runtime
// decodes no images (Node).
function decodeImage({ bytes, mimeType }) {
  if (typeof createImageBitmap !== "function") return null;
  return createImageBitmap(new Blob([bytes], { type: mimeType }), { premultiplyAlpha: "none", colorSpaceConversion: "none" });
}

// glTF texture `index` of `json` as a three.js Texture, set up as GLTFLoader sets a base
// colour map (flipY false, sRGB); its image is null where none decodes, and an image that does
// not decode (a KTX2 here) gives no texture, as in GLTFLoader.
async function loadTexture(json, images, index) {
  const def = json.textures?.[index];
  const source = images[def?.source];
  if (!source) return null;
  let image;
  try {
    image = await decodeImage(source);
  } catch (e) {
    console.warn(`DcurveLoader: texture ${index} (${source.mimeType}) does not decode: ${e?.message ?? e}`);
    return null;
  }
  const texture = new Texture(image);
  texture.name = def.name ?? json.images[def.source]?.name ?? "";
  texture.flipY = false;
  texture.colorSpace = SRGBColorSpace;
  const sampler = json.samplers?.[def.sampler] ?? {};
  texture.magFilter = FILTERS[sampler.magFilter] ?? LinearFilter;
  texture.minFilter = FILTERS[sampler.minFilter] ?? LinearMipmapLinearFilter;
  texture.wrapS = WRAPS[sampler.wrapS] ?? RepeatWrapping;
  texture.wrapT = WRAPS[sampler.wrapT] ?? RepeatWrapping;
  texture.generateMipmaps = texture.minFilter !== NearestFilter && texture.minFilter !== LinearFilter;
  if (image) texture.needsUpdate = true;
  return texture;
}

// A glTF material (core metallic-roughness: factors, base colour map, doubleSided, alphaMode)
// as GLTFLoader builds it; `{}` is glTF's default material.
function makeMaterial(def, map) {
  const pbr = def.pbrMetallicRoughness ?? {};
  const [r, g, b, a] = pbr.baseColorFactor ?? [1, 1, 1, 1];
  const blend = def.alphaMode === "BLEND";
  const material = new MeshStandardMaterial({
    name: def.name ?? "",
    map,
    opacity: a,
    metalness: pbr.metallicFactor ?? 1,
    roughness: pbr.roughnessFactor ?? 1,
    side: def.doubleSided ? DoubleSide : FrontSide,
    transparent: blend,
    depthWrite: !blend, // as GLTFLoader: three.js issue 17706
    alphaTest: def.alphaMode === "MASK" ? def.alphaCutoff ?? 0.5 : 0,
  });
  material.color.setRGB(r, g, b, LinearSRGBColorSpace);
  if (def.emissiveFactor) material.emissive.setRGB(...def.emissiveFactor, LinearSRGBColorSpace);
  return material;
}

// One three.js material per face group, from the file's glTF materials and images (groups of
// one material share it); [] for a file without groups or materials.
async function fileMaterials(decoder) {
  const json = decoder.materials();
  const groups = decoder.groups();
  if (!json || !groups.length) return [];
  const images = decoder.images();
  const textures = new Map(); // glTF texture index: a promise of its Texture, loaded once
  const texture = async (info) => {
    if (!info) return null;
    if (!textures.has(info.index)) textures.set(info.index, loadTexture(json, images, info.index));
    const loaded = await textures.get(info.index);
    if (!loaded || !(info.texCoord > 0)) return loaded;
    const other = loaded.clone(); // read through another UV set: uv1 is channel 1
    other.channel = info.texCoord;
    return other;
  };
  const made = new Map(); // glTF material index: a promise of its material
  const material = (index) => {
    if (!made.has(index)) {
      const def = json.materials?.[index] ?? {};
      made.set(index, texture(def.pbrMetallicRoughness?.baseColorTexture).then((map) => makeMaterial(def, map)));
    }
    return made.get(index);
  };
  return Promise.all(groups.map((group) => material(group.materialIndex)));
}

export class DcurveAnimation {
  #made; // the materials this object made, which dispose() frees

  // materials: one per face group of the file (DcurveLoader builds them from its glTF
  // materials); without them the object has one default material.
  constructor(decoder, materials = []) {
    this.decoder = decoder;
    this.fps = decoder.frameRate || 30; // a file may leave the rate unknown (0)
    this.duration = decoder.frameCount > 1 ? (decoder.frameCount - 1) / this.fps : 0; // seconds
    this.speed = 1; // playback rate: 2 plays twice as fast, negative plays backwards
    this.loop = true;
    this.time = 0;
    this.decodeMs = 0; // the last setTime's evaluate (and normals), in milliseconds
    this.geometry = this.#makeGeometry();
    this.materials = materials;
    this.object = this.#makeObject();
    this.#made = new Set([this.object.material].flat());
    this.setTime(0);
  }

  // Render vertices (the vertices for a file without them): dynamic positions and normals, the
  // file's static attributes, an index in group order and a geometry group per face group.
  #makeGeometry() {
    const d = this.decoder;
    const geometry = new BufferGeometry();
    const values = d.renderVertexCount * 3;
    const dynamic = () => new BufferAttribute(new Float32Array(values), 3).setUsage(DynamicDrawUsage);
    geometry.setAttribute("position", dynamic());
    const faces = d.groupFaces() ?? d.renderFaces();
    if (faces) {
      geometry.setIndex(new BufferAttribute(faces, 1));
      geometry.setAttribute("normal", dynamic());
    }
    // The input's own normals only steer the render normals, which setT writes.
    for (const [name, { values, components }] of Object.entries(d.attributes()))
      if (name !== "normal") geometry.setAttribute(name, new BufferAttribute(values, components));
    d.groups().forEach(({ start, count }, i) => geometry.addGroup(start, count, i));
    return geometry;
  }

  // A Mesh (Points without faces) named after the input's node and placed by its world
  // matrix, decomposed into position, quaternion and scale as GLTFLoader places a node.
  #makeObject() {
    const { decoder, geometry, materials } = this;
    let object;
    if (!geometry.index) object = new Points(geometry, new PointsMaterial({ size: 3, sizeAttenuation: false }));
    else object = new Mesh(geometry, materials.length ? materials : new MeshStandardMaterial());
    if (geometry.attributes.color) for (const m of materials) m.vertexColors = true; // COLOR_0 tints, as in glTF
    object.name = decoder.nodeName;
    const matrix = decoder.worldMatrix;
    if (matrix) object.applyMatrix4(new Matrix4().fromArray(matrix));
    return object;
  }

  // Advances by `seconds` of wall time times `speed`, wrapping (loop) or stopping at the ends.
  update(seconds) {
    let time = this.time + seconds * this.speed;
    if (this.loop && this.duration > 0) time = ((time % this.duration) + this.duration) % this.duration;
    return this.setTime(Math.min(Math.max(time, 0), this.duration));
  }

  // Shows the mesh at `seconds` into the clip (between stored frames too).
  setTime(seconds) {
    this.time = seconds;
    return this.setT(this.duration > 0 ? seconds / this.duration : 0);
  }

  // Shows the mesh at t in [0, 1] of the clip.
  setT(t) {
    const { position, normal } = this.geometry.attributes;
    const start = performance.now();
    this.decoder.evaluateRender(t, position.array, normal?.array); // normals from the frame in wasm memory
    this.decodeMs = performance.now() - start;
    this.time = t * this.duration;
    position.needsUpdate = true;
    if (normal) normal.needsUpdate = true;
    this.geometry.computeBoundingSphere(); // the mesh moves: keep frustum culling right
    return this;
  }

  dispose() {
    this.geometry.dispose();
    for (const material of this.#made) {
      material.map?.source.data?.close?.(); // an ImageBitmap holds its pixels until closed
      material.map?.dispose();
      material.dispose();
    }
    this.decoder.close();
  }
}
