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

/** An open file. Arrays are Float32Arrays of at least vertexCount * 3 values; every method
 * throws a DcurveError, status "invalid argument", for any other argument or once closed. */
export interface DcurveDecoder {
  readonly vertexCount: number;
  readonly frameCount: number;
  readonly faceCount: number;
  /** Frames per second; 0 when the file does not say. */
  readonly frameRate: number;
  /** The guaranteed maximum error, a fraction of restDiagonal. */
  readonly tolerance: number;
  readonly restDiagonal: number;
  readonly chunkFrames: number;
  readonly memoryBytes: number;
  /** A copy of the 3 * faceCount vertex ids, or null when the file has no connectivity. */
  faces(): Uint32Array | null;
  /** Positions at t in [0, 1] (clamped) into `out`, and with `normals` their unit vertex
   * normals (the file must have connectivity). Returns `out`. */
  evaluate(t: number, out: Float32Array, normals?: Float32Array): Float32Array;
  /** Input frame `frame` exactly (clamped to [0, frameCount)), as evaluate. */
  evaluateFrame(frame: number, out: Float32Array, normals?: Float32Array): Float32Array;
  /** Unit vertex normals of any positions `xyz` into `out`. Returns `out`. */
  computeNormals(xyz: Float32Array, out: Float32Array): Float32Array;
  /** Frees the decoder's wasm memory; safe to call twice. */
  close(): void;
}
