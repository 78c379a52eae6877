// The types of dcurve.js. test/types.test.mjs checks that they name exactly what the module
// exports and what its objects hold.

/** A refusal, with the decoder's message. */
export class DcurveError extends Error {
  constructor(message: string, status: string, code: number, options?: ErrorOptions);
  name: "DcurveError";
  /** The C API's name of `code` (`dcurve_status_name`: "malformed", "invalid argument", ...),
   * or "aborted" when the WebAssembly module did not load or crashed. */
  status: string;
  /** The `DCURVE_ERROR_*` code of decoder/dcurve.h; -1 with status "aborted". */
  code: number;
}

/** Where loadDcurve fetches the wasm unless told: build/dcurve_wasm.wasm beside dcurve.js. */
export const defaultWasmUrl: string;

export interface LoadDcurveOptions {
  /** The URL of dcurve_wasm.wasm (relative: to the page; in Node, a path or file: URL). */
  wasmUrl?: string | URL;
}

/** Loads the WebAssembly module (rejects with a DcurveError, status "aborted"). */
export function loadDcurve(options?: LoadDcurveOptions): Promise<DcurveModule>;

/** One loaded module; it serves any number of decoders. */
export interface DcurveModule {
  /** Opens a .dcrv from its bytes (copied); throws a DcurveError for a malformed file. */
  open(data: ArrayBuffer | ArrayBufferView): DcurveDecoder;
  /** The C API's name of a status code (dcurve_status_name); "unknown" for other codes. */
  statusName(code: number): string;
}

/** A static attribute of render vertices: renderVertexCount * components values. */
export interface DcurveAttribute {
  values: Float32Array;
  /** 2 for UVs, 3 for normals, 3 or 4 for colours. */
  components: number;
}

/** The attributes a file has, named as three.js names them (glTF's TEXCOORD_0, TEXCOORD_1,
 * COLOR_0, NORMAL); `normal` is the input's own, which the render normals follow at hard edges. */
export interface DcurveAttributes {
  uv?: DcurveAttribute;
  uv1?: DcurveAttribute;
  color?: DcurveAttribute;
  normal?: DcurveAttribute;
}

/** A face group (one per material of the input). */
export interface DcurveGroup {
  /** First index of groupFaces() (3 per triangle), as three.js's geometry groups count. */
  start: number;
  /** Indices (3 per triangle). */
  count: number;
  /** Its material in materials().materials; -1 for none. */
  materialIndex: number;
  name: string;
}

/** The groups' materials as glTF 2.0 JSON: "materials", "textures", "samplers" as glTF
 * defines them, "images" with a mimeType and no uri or bufferView (images() has the bytes). */
export interface DcurveMaterials {
  materials?: Record<string, any>[];
  textures?: Record<string, any>[];
  samplers?: Record<string, any>[];
  images?: { mimeType: string; name?: string }[];
  extensionsUsed?: string[];
  extensionsRequired?: string[];
}

/** An image of DcurveMaterials.images: its bytes as the input held them (PNG, JPEG, ...). */
export interface DcurveImage {
  bytes: Uint8Array<ArrayBuffer>;
  mimeType: string;
}

/** An open file. Arrays are Float32Arrays of at least vertexCount * 3 values (render
 * evaluation: renderVertexCount * 3); every method throws a DcurveError, status "invalid
 * argument", for any other argument or once closed. */
export interface DcurveDecoder {
  readonly vertexCount: number;
  /** Vertices as drawn: seam copies of a vertex each have their own (vertexCount for a file
   * without render data). */
  readonly renderVertexCount: number;
  readonly frameCount: number;
  readonly faceCount: number;
  /** Frames per second; 0 when the file does not say. */
  readonly frameRate: number;
  /** The guaranteed maximum error, a fraction of restDiagonal. */
  readonly tolerance: number;
  readonly restDiagonal: number;
  readonly chunkFrames: number;
  readonly memoryBytes: number;
  /** Seconds of frame 0 on the input's timeline (0 when unknown). */
  readonly startTime: number;
  /** The input node's world transform, column-major; null when the file has none. */
  readonly worldMatrix: number[] | null;
  /** The input's mesh and node names ("" when none). */
  readonly meshName: string;
  readonly nodeName: string;
  /** A copy of the 3 * faceCount vertex ids, or null when the file has no connectivity. */
  faces(): Uint32Array | null;
  /** The same triangles over render vertices (faces() without render data). */
  renderFaces(): Uint32Array | null;
  /** The vertex each render vertex shows; null when render vertices are the vertices. */
  renderSource(): Uint32Array | null;
  /** renderFaces ordered by group, or null without groups. */
  groupFaces(): Uint32Array | null;
  /** Copies of the file's static attributes. */
  attributes(): DcurveAttributes;
  /** The face groups, in the order of groupFaces ([] without groups). */
  groups(): DcurveGroup[];
  /** The groups' materials, parsed afresh; null without them. */
  materials(): DcurveMaterials | null;
  /** Copies of the images' bytes, image i of materials().images. */
  images(): DcurveImage[];
  /** Positions at t in [0, 1] (clamped) into `out`, and with `normals` their unit vertex
   * normals (the file must have connectivity). Returns `out`. */
  evaluate(t: number, out: Float32Array, normals?: Float32Array): Float32Array;
  /** Input frame `frame` exactly (clamped to [0, frameCount)), as evaluate. */
  evaluateFrame(frame: number, out: Float32Array, normals?: Float32Array): Float32Array;
  /** As evaluate, for render vertices: renderVertexCount * 3 positions (a seam's copies at
   * their vertex's) and render normals, computed in wasm memory. */
  evaluateRender(t: number, out: Float32Array, normals?: Float32Array): Float32Array;
  /** As evaluateFrame, for render vertices. */
  evaluateFrameRender(frame: number, out: Float32Array, normals?: Float32Array): Float32Array;
  /** Unit vertex normals of any positions `xyz` into `out`. Returns `out`. */
  computeNormals(xyz: Float32Array, out: Float32Array): Float32Array;
  /** Frees the decoder's wasm memory; safe to call twice. */
  close(): void;
}
