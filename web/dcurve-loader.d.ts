// The types of dcurve-loader.js. test/types.test.mjs checks that they name exactly what the
// module exports and what its objects hold.
import { BufferGeometry, Loader, LoadingManager, Material, Mesh, Points } from "three";

import { DcurveDecoder } from "./dcurve.js";

/** A three.js loader of .dcrv files. A file that does not fetch or decode reaches onError
 * and manager.itemError, as with three.js's own loaders. */
export class DcurveLoader extends Loader<DcurveAnimation> {
  constructor(manager?: LoadingManager);
  /** Where dcurve_wasm.wasm is fetched (default: defaultWasmUrl of dcurve.js). */
  wasmUrl: string | URL;
  setWasmUrl(url: string | URL): this;
  load(
    url: string,
    onLoad: (animation: DcurveAnimation) => void,
    onProgress?: (event: ProgressEvent) => void,
    onError?: (error: unknown) => void,
  ): void;
  /** A .dcrv's bytes to an animation; rejects with a DcurveError. */
  parse(buffer: ArrayBuffer | ArrayBufferView): Promise<DcurveAnimation>;
}

/** A .dcrv playing on a BufferGeometry over its render vertices: dynamic positions and (with
 * faces) normals, rewritten by update, setTime and setT; the file's uv, uv1 and color
 * attributes; an index in face group order with a geometry group per face group. */
export class DcurveAnimation {
  /** `materials`: one per face group (DcurveLoader builds them from the file's glTF
   * materials); without them `object` has one default material. */
  constructor(decoder: DcurveDecoder, materials?: Material[]);
  decoder: DcurveDecoder;
  geometry: BufferGeometry;
  /** The file's materials as MeshStandardMaterials, one per geometry group (groups of one
   * material share it); [] for a file without materials. */
  materials: Material[];
  /** What to add to a scene: a Mesh (Points for a file without faces) with `materials`,
   * named after the input's node and placed by its world matrix. */
  object: Mesh | Points;
  /** The file's frame rate, or 30 when it does not say. */
  fps: number;
  /** Seconds from the first frame to the last. */
  duration: number;
  /** Playback rate: 2 plays twice as fast, negative backwards. */
  speed: number;
  loop: boolean;
  /** Seconds into the clip. */
  time: number;
  /** Milliseconds of the last decode (positions and normals). */
  decodeMs: number;
  /** Advances by `seconds` of wall time times speed, wrapping (loop) or stopping at the ends. */
  update(seconds: number): this;
  setTime(seconds: number): this;
  /** Shows the mesh at t in [0, 1] of the clip. */
  setT(t: number): this;
  /** Disposes of the geometry and the materials and textures the animation made, and closes
   * the decoder. */
  dispose(): void;
}
