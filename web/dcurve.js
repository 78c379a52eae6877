// The dcurve decoder as an ES module: the C API of decoder/dcurve.h over the WebAssembly
// build (web/build.sh), with errors as DcurveError exceptions carrying the decoder's message.
//
//   const dcurve = await loadDcurve();
//   const dec = dcurve.open(arrayBuffer);          // throws DcurveError on a malformed file
//   const xyz = new Float32Array(dec.vertexCount * 3);
//   dec.evaluate(0.5, xyz);                        // any t in [0, 1]
//   dec.evaluateFrame(3, xyz);                     // input frame 3 exactly
//   dec.close();
import { decompress } from "fzstd";
import createDcurveModule from "./build/dcurve_wasm.mjs";

const ERROR_BYTES = 256;
const STATUS_NAMES = ["ok", "malformed", "invalid argument", "i/o error", "corrupt chunk", "out of memory", "internal error"];

export class DcurveError extends Error {
  constructor(message, status) {
    super(message);
    this.name = "DcurveError";
    // DCURVE_ERROR_* as its name; "aborted" when the wasm module itself failed (a crash).
    this.status = status < 0 ? "aborted" : STATUS_NAMES[status] ?? "internal error";
  }
}

// Node cannot fetch a file: URL, so the wasm bytes are read and handed over there.
async function wasmBinaryForNode() {
  if (typeof process !== "object" || !process.versions?.node) return undefined;
  const { readFile } = await import("node:fs/promises");
  return readFile(new URL("./build/dcurve_wasm.wasm", import.meta.url));
}

// Loads and instantiates the WebAssembly module; one module serves any number of decoders.
export async function loadDcurve() {
  const module = await createDcurveModule({ zstdDecompress: decompress, wasmBinary: await wasmBinaryForNode() });
  return { open: (data) => new Decoder(module, data) };
}

const INVALID = 2; // DCURVE_ERROR_INVALID_ARGUMENT

// The bytes of a file given as an ArrayBuffer or a typed array / DataView over one.
function asBytes(data) {
  if (data instanceof Uint8Array) return data;
  if (data instanceof ArrayBuffer) return new Uint8Array(data);
  if (ArrayBuffer.isView(data)) return new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  throw new DcurveError("open needs the file's bytes: an ArrayBuffer or a typed array", INVALID);
}

// A Float32Array of at least n values: anything shorter would read stale wasm memory or
// throw a RangeError half-way.
function floats(array, n, what) {
  if (!(array instanceof Float32Array) || array.length < n)
    throw new DcurveError(`${what} must be a Float32Array of at least ${n} values (vertexCount * 3)`, INVALID);
}

// Runs a call into the module; an abort (out of memory: exceptions are not caught in the
// wasm build) leaves the module unusable and becomes a DcurveError.
function guarded(call) {
  try {
    return call();
  } catch (e) {
    if (e instanceof DcurveError) throw e;
    throw new DcurveError(`the decoder aborted (${e?.message ?? e}); load a new module`, -1);
  }
}

class Decoder {
  #m;
  #decoder = 0;
  #cursor = 0;
  #xyz = 0; // vertexCount * 3 floats in wasm memory: evaluation output, normals input
  #normals = 0;
  #error = 0;
  #values = 0; // 3 * vertexCount

  constructor(module, data) {
    this.#m = module;
    const bytes = asBytes(data);
    try {
      guarded(() => this.#open(bytes));
    } catch (e) {
      this.close();
      throw e;
    }
  }

  // malloc, or a DcurveError when the wasm memory cannot grow (malloc returns 0 then).
  #alloc(bytes) {
    const p = this.#m._malloc(Math.max(bytes, 4));
    if (!p) throw new DcurveError(`out of memory allocating ${bytes} bytes`, 5);
    return p;
  }

  #open(bytes) {
    const m = this.#m;
    this.#error = this.#alloc(ERROR_BYTES + 8);
    const out = this.#error + ERROR_BYTES; // dcurve_decoder** / dcurve_cursor**
    const src = this.#alloc(bytes.length);
    m.HEAPU8.set(bytes, src);
    const status = m._dcurve_open_memory(src, bytes.length, out, this.#error, ERROR_BYTES);
    m._free(src); // the decoder keeps its own copy of what it needs
    this.#check(status);
    this.#decoder = m.HEAPU32[out >> 2];
    this.#check(m._dcurve_cursor_create(this.#decoder, out));
    this.#cursor = m.HEAPU32[out >> 2];
    this.#values = 3 * m._dcurve_vertex_count(this.#decoder);
    this.#xyz = this.#alloc(this.#values * 4);
    this.#normals = this.#alloc(this.#values * 4);
  }

  #check(status) {
    if (status === 0) return;
    const m = this.#m;
    const end = m.HEAPU8.indexOf(0, this.#error);
    const message = new TextDecoder().decode(m.HEAPU8.subarray(this.#error, end));
    throw new DcurveError(message || STATUS_NAMES[status] || "error", status);
  }

  #live() {
    if (!this.#decoder) throw new DcurveError("the decoder is closed", INVALID);
    return this.#m;
  }

  get vertexCount() { return this.#live() && this.#values / 3; }
  get frameCount() { return this.#live()._dcurve_frame_count(this.#decoder); }
  get faceCount() { return this.#live()._dcurve_face_count(this.#decoder); }
  get frameRate() { return this.#live()._dcurve_frame_rate(this.#decoder); } // 0: unknown
  get tolerance() { return this.#live()._dcurve_tolerance(this.#decoder); } // fraction of restDiagonal
  get restDiagonal() { return this.#live()._dcurve_rest_diagonal(this.#decoder); }
  get chunkFrames() { return this.#live()._dcurve_chunk_frames(this.#decoder); }
  get memoryBytes() {
    const m = this.#live();
    return m._dcurve_memory_bytes(this.#decoder) + m._dcurve_cursor_memory_bytes(this.#cursor);
  }

  // A copy of the 3 * faceCount vertex ids, or null when the file has no connectivity.
  faces() {
    const m = this.#live();
    const p = m._dcurve_faces(this.#decoder);
    return p ? m.HEAPU32.slice(p >> 2, (p >> 2) + 3 * this.faceCount) : null;
  }

  // Writes vertexCount * 3 positions at t in [0, 1] (clamped) into `out` (a Float32Array).
  evaluate(t, out) {
    if (typeof t !== "number" || Number.isNaN(t)) throw new DcurveError(`evaluate needs a time t in [0, 1], not ${String(t)}`, INVALID);
    return this.#evaluate(out, () => this.#m._dcurve_cursor_evaluate(this.#cursor, t, this.#xyz, this.#error, ERROR_BYTES));
  }

  // Writes input frame f exactly (clamped to [0, frameCount)).
  evaluateFrame(f, out) {
    if (!Number.isInteger(f)) throw new DcurveError(`evaluateFrame needs a frame number, not ${String(f)}`, INVALID);
    return this.#evaluate(out, () => this.#m._dcurve_cursor_evaluate_frame(this.#cursor, f, this.#xyz, this.#error, ERROR_BYTES));
  }

  #evaluate(out, call) {
    const m = this.#live();
    const n = this.#values;
    floats(out, n, "the output");
    this.#check(guarded(call));
    out.set(m.HEAPF32.subarray(this.#xyz >> 2, (this.#xyz >> 2) + n));
    return out;
  }

  // Unit vertex normals of the positions `xyz` into `out`; throws without connectivity.
  computeNormals(xyz, out) {
    const m = this.#live();
    const n = this.#values;
    floats(xyz, n, "the positions");
    floats(out, n, "the output");
    m.HEAPF32.set(xyz.subarray(0, n), this.#xyz >> 2);
    if (guarded(() => m._dcurve_compute_normals(this.#decoder, this.#xyz, this.#normals)) !== 0)
      throw new DcurveError("the file has no connectivity: no normals", 2);
    out.set(m.HEAPF32.subarray(this.#normals >> 2, (this.#normals >> 2) + n));
    return out;
  }

  // Frees the decoder's wasm memory; further calls throw. Safe to call twice.
  close() {
    const m = this.#m;
    if (this.#cursor) m._dcurve_cursor_destroy(this.#cursor);
    if (this.#decoder) m._dcurve_close(this.#decoder);
    for (const p of [this.#xyz, this.#normals, this.#error]) if (p) m._free(p);
    this.#cursor = this.#decoder = this.#xyz = this.#normals = this.#error = 0;
  }
}
