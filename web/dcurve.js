// The dcurve decoder as an ES module: the C API of decoder/dcurve.h over the WebAssembly
// build (web/build.sh), with errors as DcurveError exceptions carrying the decoder's message.
//
//   const dcurve = await loadDcurve();             // or loadDcurve({ wasmUrl: "/lib/dcurve_wasm.wasm" })
//   const dec = dcurve.open(arrayBuffer);          // throws DcurveError on a malformed file
//   const xyz = new Float32Array(dec.vertexCount * 3);
//   dec.evaluate(0.5, xyz);                        // any t in [0, 1]
//   dec.evaluateFrame(3, xyz, normals);            // input frame 3 exactly, and its normals
//   const render = new Float32Array(dec.renderVertexCount * 3);
//   dec.evaluateRender(0.5, render, renderNormals); // what a renderer draws: seam copies too
//   dec.close();
import { decompress } from "fzstd";
import createDcurveModule from "./build/dcurve_wasm.mjs";

const ERROR_BYTES = 256;
const SCRATCH_BYTES = 128; // the C calls' out-parameters: up to a double[16]
// The dcurve.h codes the wrapper raises itself; every name comes from dcurve_status_name.
const INVALID_ARGUMENT = 2; // DCURVE_ERROR_INVALID_ARGUMENT
const OUT_OF_MEMORY = 5; // DCURVE_ERROR_OUT_OF_MEMORY
const ABORTED = -1; // no C status: the module failed to load or aborted
const NO_NORMALS = "the file has no connectivity: no normals";
// DCURVE_ATTRIBUTE_* by the names three.js (and GLTFLoader) give them; "normal" is the input's
// own normals, which the render normals follow at hard edges.
const ATTRIBUTES = { uv: 0, uv1: 1, color: 2, normal: 3 };

export const defaultWasmUrl = new URL("./build/dcurve_wasm.wasm", import.meta.url).href;

export class DcurveError extends Error {
  // status: the C API's name of `code` (dcurve_status_name), or "aborted" (code -1) when the
  // wasm module did not load or crashed.
  constructor(message, status, code, options) {
    super(message, options);
    this.name = "DcurveError";
    this.status = status;
    this.code = code;
  }
}

// The NUL-terminated string at `p` in wasm memory.
function cString(m, p) {
  return new TextDecoder().decode(m.HEAPU8.subarray(p, m.HEAPU8.indexOf(0, p)));
}

// A DcurveError for a C status code, named by the C API (never called once the module aborted).
function statusError(m, code, message) {
  const status = cString(m, m._dcurve_status_name(code));
  return new DcurveError(message || status, status, code);
}

// Where the glue gets the wasm. Node's fetch takes no file: URL (nor a path), so a local wasm
// is read here and handed over; anywhere else the glue fetches it (compiling as it streams).
async function wasmSource(wasmUrl) {
  if (typeof process === "object" && process.versions?.node) {
    const { pathToFileURL } = await import("node:url");
    const url = new URL(wasmUrl, pathToFileURL(`${process.cwd()}/`));
    if (url.protocol === "file:") return { wasmBinary: await (await import("node:fs/promises")).readFile(url) };
    return { locateFile: () => url.href };
  }
  return { locateFile: () => String(wasmUrl) }; // relative: to the page, as fetch resolves it
}

// Loads and instantiates the WebAssembly module; one module serves any number of decoders.
// wasmUrl: where dcurve_wasm.wasm is served (default: build/ beside this script).
export async function loadDcurve({ wasmUrl = defaultWasmUrl } = {}) {
  let module;
  try {
    module = await createDcurveModule({ zstdDecompress: decompress, ...(await wasmSource(wasmUrl)) });
  } catch (e) {
    throw new DcurveError(`the WebAssembly module did not load from ${wasmUrl}: ${e?.message ?? e}`, "aborted", ABORTED, { cause: e });
  }
  return {
    open: (data) => new Decoder(module, data),
    statusName: (code) => cString(module, module._dcurve_status_name(code)),
  };
}

// The bytes of a file given as an ArrayBuffer or a typed array / DataView over one; null else.
function asBytes(data) {
  if (data instanceof Uint8Array) return data;
  if (data instanceof ArrayBuffer) return new Uint8Array(data);
  if (ArrayBuffer.isView(data)) return new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  return null;
}

// Runs a call into the module; an abort (out of memory: exceptions are not caught in the
// wasm build) leaves the module unusable and becomes a DcurveError.
function guarded(call) {
  try {
    return call();
  } catch (e) {
    if (e instanceof DcurveError) throw e;
    throw new DcurveError(`the decoder aborted (${e?.message ?? e}); load a new module`, "aborted", ABORTED, { cause: e });
  }
}

class Decoder {
  #m;
  #decoder = 0;
  #cursor = 0;
  #xyz = 0; // vertexCount * 3 floats in wasm memory: the last evaluation, the normals' input
  #normals = 0;
  #error = 0;
  #scratch = 0; // SCRATCH_BYTES after the error message, 8-aligned
  #values = 0; // 3 * vertexCount
  #renderValues = 0; // 3 * renderVertexCount
  #renderXyz = 0; // renderValues floats each, allocated by the first evaluateRender
  #renderNormals = 0;

  constructor(module, data) {
    this.#m = module;
    const bytes = asBytes(data);
    if (!bytes) throw this.#invalid("open needs the file's bytes: an ArrayBuffer or a typed array");
    try {
      guarded(() => this.#open(bytes));
    } catch (e) {
      this.close();
      throw e;
    }
  }

  #invalid(message) {
    return statusError(this.#m, INVALID_ARGUMENT, message);
  }

  // malloc, or a DcurveError when the wasm memory cannot grow (malloc returns 0 then).
  #alloc(bytes) {
    const p = this.#m._malloc(Math.max(bytes, 4));
    if (!p) throw statusError(this.#m, OUT_OF_MEMORY, `out of memory allocating ${bytes} bytes`);
    return p;
  }

  #open(bytes) {
    const m = this.#m;
    this.#error = this.#alloc(ERROR_BYTES + SCRATCH_BYTES);
    m.HEAPU8[this.#error] = 0; // no stale message from a call that fails without writing one
    const out = (this.#scratch = this.#error + ERROR_BYTES); // dcurve_decoder** / dcurve_cursor**
    const src = this.#alloc(bytes.length);
    m.HEAPU8.set(bytes, src);
    const status = m._dcurve_open_memory(src, bytes.length, out, this.#error, ERROR_BYTES);
    m._free(src); // the decoder keeps its own copy of what it needs
    this.#check(status);
    this.#decoder = m.HEAPU32[out >> 2];
    this.#check(m._dcurve_cursor_create(this.#decoder, out));
    this.#cursor = m.HEAPU32[out >> 2];
    this.#values = 3 * m._dcurve_vertex_count(this.#decoder);
    this.#renderValues = 3 * m._dcurve_render_vertex_count(this.#decoder);
    this.#xyz = this.#alloc(this.#values * 4);
    this.#normals = this.#alloc(this.#values * 4);
  }

  #check(status) {
    if (status !== 0) throw statusError(this.#m, status, cString(this.#m, this.#error));
  }

  #live() {
    if (!this.#decoder) throw this.#invalid("the decoder is closed");
    return this.#m;
  }

  // A Float32Array of at least `values` values: anything shorter would read stale wasm memory
  // or throw a RangeError half-way.
  #floats(array, what, values = this.#values, count = "vertexCount") {
    if (!(array instanceof Float32Array) || array.length < values)
      throw this.#invalid(`${what} must be a Float32Array of at least ${values} values (${count} * 3)`);
  }

  // Checked before anything is decoded, so a refused call changes nothing.
  #checkNormalsOut(out, ...size) {
    this.#floats(out, "the normals output", ...size);
    if (!this.#m._dcurve_faces(this.#decoder)) throw this.#invalid(NO_NORMALS);
  }

  // Copies `values` floats at wasm address `p` into `out`.
  #copy(p, out, values) {
    out.set(this.#m.HEAPF32.subarray(p >> 2, (p >> 2) + values));
    return out;
  }

  // The normals of the positions at #xyz (wasm memory) into `out`: vertex normals, or with
  // `render` the render vertices'.
  #normalsOf(out, render = false) {
    const m = this.#m;
    const [compute, p, values] = render
      ? [m._dcurve_compute_render_normals, this.#renderNormals, this.#renderValues]
      : [m._dcurve_compute_normals, this.#normals, this.#values];
    const status = guarded(() => compute(this.#decoder, this.#xyz, p));
    if (status !== 0) throw statusError(m, status, NO_NORMALS); // it writes no message
    return this.#copy(p, out, values);
  }

  // The NUL-terminated string a C call returns (never NULL in dcurve.h).
  #string(call) {
    return cString(this.#live(), call(this.#decoder));
  }

  // `count` uint32 at the address a C call returns, copied; null for NULL.
  #ids(p, count) {
    return p ? this.#m.HEAPU32.slice(p >> 2, (p >> 2) + count) : null;
  }

  get vertexCount() { return this.#live() && this.#values / 3; }
  get frameCount() { return this.#live()._dcurve_frame_count(this.#decoder); }
  get faceCount() { return this.#live()._dcurve_face_count(this.#decoder); }
  get frameRate() { return this.#live()._dcurve_frame_rate(this.#decoder); } // 0: unknown
  get tolerance() { return this.#live()._dcurve_tolerance(this.#decoder); } // fraction of restDiagonal
  get restDiagonal() { return this.#live()._dcurve_rest_diagonal(this.#decoder); }
  get chunkFrames() { return this.#live()._dcurve_chunk_frames(this.#decoder); }
  get renderVertexCount() { return this.#live() && this.#renderValues / 3; }
  get startTime() { return this.#live()._dcurve_start_time(this.#decoder); } // seconds of frame 0
  get meshName() { return this.#string(this.#m._dcurve_mesh_name); }
  get nodeName() { return this.#string(this.#m._dcurve_node_name); }
  // The input node's world transform, 16 numbers column-major; null when the file has none.
  get worldMatrix() {
    const m = this.#live();
    if (!m._dcurve_world_matrix(this.#decoder, this.#scratch)) return null;
    return Array.from(m.HEAPF64.subarray(this.#scratch >> 3, (this.#scratch >> 3) + 16));
  }
  get memoryBytes() {
    const m = this.#live();
    return m._dcurve_memory_bytes(this.#decoder) + m._dcurve_cursor_memory_bytes(this.#cursor);
  }

  // A copy of the 3 * faceCount vertex ids, or null when the file has no connectivity.
  faces() {
    return this.#ids(this.#live()._dcurve_faces(this.#decoder), 3 * this.faceCount);
  }

  // The same triangles over render vertices (faces() when they are the vertices); null
  // without connectivity.
  renderFaces() {
    const m = this.#live();
    return this.#ids(m._dcurve_render_faces(this.#decoder) || m._dcurve_faces(this.#decoder), 3 * this.faceCount);
  }

  // The vertex each render vertex shows, or null when render vertices are the vertices.
  renderSource() {
    return this.#ids(this.#live()._dcurve_render_source(this.#decoder), this.#renderValues / 3);
  }

  // renderFaces ordered by group (groups() index into it), or null without groups.
  groupFaces() {
    return this.#ids(this.#live()._dcurve_group_faces(this.#decoder), 3 * this.faceCount);
  }

  // The file's static attributes of render vertices, copied: { uv, uv1, color, normal }, each
  // { values, components } and present only when the file has it.
  attributes() {
    const m = this.#live();
    const found = {};
    for (const [name, id] of Object.entries(ATTRIBUTES)) {
      const components = m._dcurve_attribute_components(this.#decoder, id);
      const p = m._dcurve_attribute(this.#decoder, id);
      if (components && p) found[name] = { values: m.HEAPF32.slice(p >> 2, (p >> 2) + components * this.#renderValues / 3), components };
    }
    return found;
  }

  // Face groups, one per material of the input: { start, count } in indices of groupFaces
  // (3 per triangle, as three.js's geometry groups), the index of its material in materials()
  // (-1: none) and its name.
  groups() {
    const m = this.#live();
    const [first, count, material, name] = [0, 4, 8, 12].map((offset) => this.#scratch + offset);
    return Array.from({ length: m._dcurve_group_count(this.#decoder) }, (_, i) => {
      this.#check(m._dcurve_group(this.#decoder, i, first, count, material, name));
      const u32 = (p) => m.HEAPU32[p >> 2];
      return { start: 3 * u32(first), count: 3 * u32(count), materialIndex: u32(material) | 0, name: cString(m, u32(name)) };
    });
  }

  // The groups' materials as glTF JSON ("materials", "textures", "samplers", "images"), parsed
  // afresh on each call; null when the file has none.
  materials() {
    const json = this.#string(this.#m._dcurve_materials_json);
    return json ? JSON.parse(json) : null;
  }

  // The bytes of the images materials() lists (image i of its "images"), copied, with their
  // media types: [{ bytes, mimeType }].
  images() {
    const m = this.#live();
    const [size, mime] = [this.#scratch, this.#scratch + 4]; // size_t and char* are 4 bytes in wasm32
    return Array.from({ length: m._dcurve_image_count(this.#decoder) }, (_, i) => {
      const p = m._dcurve_image(this.#decoder, i, size, mime);
      return { bytes: m.HEAPU8.slice(p, p + m.HEAPU32[size >> 2]), mimeType: cString(m, m.HEAPU32[mime >> 2]) };
    });
  }

  // Writes vertexCount * 3 positions at t in [0, 1] (clamped) into `out` (a Float32Array),
  // and with `normals` their unit vertex normals, from the frame still in wasm memory.
  evaluate(t, out, normals) {
    return this.#evaluate(this.#at(t, "evaluate"), out, normals, false);
  }

  // Writes input frame f exactly (clamped to [0, frameCount)), and its normals as evaluate.
  evaluateFrame(f, out, normals) {
    return this.#evaluate(this.#atFrame(f, "evaluateFrame"), out, normals, false);
  }

  // As evaluate and evaluateFrame, for render vertices: renderVertexCount * 3 positions (a
  // seam's copies at their vertex's), and render normals, computed in wasm memory.
  evaluateRender(t, out, normals) {
    return this.#evaluate(this.#at(t, "evaluateRender"), out, normals, true);
  }

  evaluateFrameRender(f, out, normals) {
    return this.#evaluate(this.#atFrame(f, "evaluateFrameRender"), out, normals, true);
  }

  // The decode call of a time t, checked before anything runs.
  #at(t, method) {
    if (typeof t !== "number" || Number.isNaN(t)) throw this.#invalid(`${method} needs a time t in [0, 1], not ${String(t)}`);
    return () => this.#m._dcurve_cursor_evaluate(this.#cursor, t, this.#xyz, this.#error, ERROR_BYTES);
  }

  #atFrame(f, method) {
    if (!Number.isInteger(f)) throw this.#invalid(`${method} needs a frame number, not ${String(f)}`);
    return () => this.#m._dcurve_cursor_evaluate_frame(this.#cursor, f, this.#xyz, this.#error, ERROR_BYTES);
  }

  // Decodes into #xyz, then writes vertex positions or (render) render vertex positions.
  #evaluate(call, out, normals, render) {
    const m = this.#live();
    const size = render ? [this.#renderValues, "renderVertexCount"] : [];
    this.#floats(out, "the output", ...size);
    if (normals !== undefined) this.#checkNormalsOut(normals, ...size);
    if (render && !this.#renderXyz) {
      this.#renderXyz = this.#alloc(this.#renderValues * 4);
      this.#renderNormals = this.#alloc(this.#renderValues * 4);
    }
    this.#check(guarded(call));
    if (render) {
      this.#check(m._dcurve_render_positions(this.#decoder, this.#xyz, this.#renderXyz));
      this.#copy(this.#renderXyz, out, this.#renderValues);
    } else this.#copy(this.#xyz, out, this.#values);
    if (normals !== undefined) this.#normalsOf(normals, render);
    return out;
  }

  // Unit vertex normals of any positions `xyz` into `out`; throws without connectivity. For
  // the frame just evaluated, evaluate's `normals` saves copying the positions back in.
  computeNormals(xyz, out) {
    const m = this.#live();
    this.#floats(xyz, "the positions");
    this.#checkNormalsOut(out);
    m.HEAPF32.set(xyz.subarray(0, this.#values), this.#xyz >> 2);
    return this.#normalsOf(out);
  }

  // Frees the decoder's wasm memory; further calls throw. Safe to call twice.
  close() {
    const m = this.#m;
    if (this.#cursor) m._dcurve_cursor_destroy(this.#cursor);
    if (this.#decoder) m._dcurve_close(this.#decoder);
    for (const p of [this.#xyz, this.#normals, this.#renderXyz, this.#renderNormals, this.#error]) if (p) m._free(p);
    this.#cursor = this.#decoder = this.#xyz = this.#normals = this.#renderXyz = this.#renderNormals = this.#error = 0;
  }
}
