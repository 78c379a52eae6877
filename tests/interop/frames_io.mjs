// The tests' plain exchange file between C++ and these scripts, little-endian:
// u32 vertex_count, u32 frame_count, u32 face_id_count, u32 face ids, then f32 x, y, z per
// vertex per frame.
import { readFileSync, writeFileSync } from 'node:fs';

export function readFrames(path) {
  const b = readFileSync(path);
  const v = b.readUInt32LE(0), n = b.readUInt32LE(4), f = b.readUInt32LE(8);
  const faces = new Uint32Array(f);
  for (let i = 0; i < f; i++) faces[i] = b.readUInt32LE(12 + 4 * i);
  const frames = [];
  let at = 12 + 4 * f;
  for (let k = 0; k < n; k++) {
    const xyz = new Float32Array(3 * v);
    for (let i = 0; i < 3 * v; i++, at += 4) xyz[i] = b.readFloatLE(at);
    frames.push(xyz);
  }
  return { vertexCount: v, faces, frames };
}

export function writeFrames(path, { vertexCount, faces, frames }) {
  const b = Buffer.alloc(12 + 4 * faces.length + 12 * vertexCount * frames.length);
  b.writeUInt32LE(vertexCount, 0);
  b.writeUInt32LE(frames.length, 4);
  b.writeUInt32LE(faces.length, 8);
  let at = 12;
  for (const id of faces) { b.writeUInt32LE(id, at); at += 4; }
  for (const xyz of frames) for (const x of xyz) { b.writeFloatLE(x, at); at += 4; }
  writeFileSync(path, b);
}
