// A three.js loader for .dcrv files: a BufferGeometry whose positions (and normals, when the
// file has connectivity) the returned DcurveAnimation rewrites for any time, at any playback
// rate.
//
//   const anim = await new DcurveLoader().loadAsync("cloth.dcrv"); // setWasmUrl(url) first to move the wasm
//   scene.add(new THREE.Mesh(anim.geometry, material));
//   renderer.setAnimationLoop(() => { anim.update(clock.getDelta()); renderer.render(scene, camera); });
import { BufferAttribute, BufferGeometry, DynamicDrawUsage, FileLoader, Loader } from "three";

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
    return new DcurveAnimation((await modules.get(key)).open(buffer));
  }
}

export class DcurveAnimation {
  constructor(decoder) {
    this.decoder = decoder;
    this.fps = decoder.frameRate || 30; // a file may leave the rate unknown (0)
    this.duration = decoder.frameCount > 1 ? (decoder.frameCount - 1) / this.fps : 0; // seconds
    this.speed = 1; // playback rate: 2 plays twice as fast, negative plays backwards
    this.loop = true;
    this.time = 0;
    this.decodeMs = 0; // the last setTime's evaluate (and normals), in milliseconds
    this.geometry = this.#makeGeometry();
    this.setTime(0);
  }

  #makeGeometry() {
    const geometry = new BufferGeometry();
    const values = this.decoder.vertexCount * 3;
    const position = new BufferAttribute(new Float32Array(values), 3).setUsage(DynamicDrawUsage);
    geometry.setAttribute("position", position);
    const faces = this.decoder.faces();
    if (faces) {
      geometry.setIndex(new BufferAttribute(faces, 1));
      geometry.setAttribute("normal", new BufferAttribute(new Float32Array(values), 3).setUsage(DynamicDrawUsage));
    }
    return geometry;
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
    this.decoder.evaluate(t, position.array, normal?.array); // normals from the frame in wasm memory
    this.decodeMs = performance.now() - start;
    this.time = t * this.duration;
    position.needsUpdate = true;
    if (normal) normal.needsUpdate = true;
    this.geometry.computeBoundingSphere(); // the mesh moves: keep frustum culling right
    return this;
  }

  dispose() {
    this.geometry.dispose();
    this.decoder.close();
  }
}
