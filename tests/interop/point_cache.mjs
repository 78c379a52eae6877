// node point_cache.mjs write|read pc2|mdd CACHE FRAMES.bin: writes a PC2 or MDD file from
// the frames (by the formats' published layouts, not dcurve's code), or reads one back into
// frames. PC2: "POINTCACHE2\0", i32 version 1, i32 points, f32 start frame, f32 sample rate,
// i32 samples, then f32 x y z, little-endian. MDD: i32 frames, i32 points, f32 time per
// frame, then f32 x y z, big-endian. Reading prints "frames N points V start S".
import { readFileSync, writeFileSync } from 'node:fs';
import { readFrames, writeFrames } from './frames_io.mjs';

const [mode, kind, cache, framesPath] = process.argv.slice(2);
const fps = 24;
if (mode === 'write') {
  const { vertexCount, frames } = readFrames(framesPath);
  const header = kind === 'pc2' ? 32 : 8 + 4 * frames.length;
  const b = Buffer.alloc(header + 12 * vertexCount * frames.length);
  if (kind === 'pc2') {
    b.write('POINTCACHE2\0', 0, 'latin1');
    b.writeInt32LE(1, 12); b.writeInt32LE(vertexCount, 16); b.writeFloatLE(1, 20);
    b.writeFloatLE(1, 24); b.writeInt32LE(frames.length, 28);
  } else {
    b.writeInt32BE(frames.length, 0); b.writeInt32BE(vertexCount, 4);
    frames.forEach((_, k) => b.writeFloatBE((k + 1) / fps, 8 + 4 * k));
  }
  let at = header;
  for (const xyz of frames) for (const x of xyz) { kind === 'pc2' ? b.writeFloatLE(x, at) : b.writeFloatBE(x, at); at += 4; }
  writeFileSync(cache, b);
} else {
  const b = readFileSync(cache);
  const pc2 = kind === 'pc2';
  const points = pc2 ? b.readInt32LE(16) : b.readInt32BE(4);
  const count = pc2 ? b.readInt32LE(28) : b.readInt32BE(0);
  const start = pc2 ? b.readFloatLE(20) : b.readFloatBE(8);
  let at = pc2 ? 32 : 8 + 4 * count;
  const frames = [];
  for (let k = 0; k < count; k++) {
    const xyz = new Float32Array(3 * points);
    for (let i = 0; i < xyz.length; i++, at += 4) xyz[i] = pc2 ? b.readFloatLE(at) : b.readFloatBE(at);
    frames.push(xyz);
  }
  if (at !== b.length) throw new Error(`${cache}: ${b.length - at} bytes left over`);
  writeFrames(framesPath, { vertexCount: points, faces: new Uint32Array(0), frames });
  console.log(`frames ${count} points ${points} start ${start}`);
}
