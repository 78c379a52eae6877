// A small animated test mesh for the browser tests: a square sheet of n x n vertices with a
// travelling wave, written as OBJ frames and encoded by the native `dcurve encode`.
import { execFileSync } from "node:child_process";
import { mkdirSync, writeFileSync } from "node:fs";

import { dcurvePath } from "./browser.mjs";

function frameObj(n, f, frames) {
  const lines = [];
  for (let i = 0; i < n; ++i)
    for (let j = 0; j < n; ++j) {
      const x = i / (n - 1), y = j / (n - 1);
      const z = 0.15 * Math.sin(2 * Math.PI * (x + f / frames)) * y;
      lines.push(`v ${x.toFixed(6)} ${y.toFixed(6)} ${z.toFixed(6)}`);
    }
  for (let i = 0; i + 1 < n; ++i)
    for (let j = 0; j + 1 < n; ++j) {
      const a = i * n + j + 1; // OBJ counts from 1
      lines.push(`f ${a} ${a + n} ${a + 1}`, `f ${a + 1} ${a + n} ${a + n + 1}`);
    }
  return lines.join("\n") + "\n";
}

// Writes dir/frames/frame_NNNN.obj and encodes them to dir/wave.dcrv; returns its path.
export function encodeWave(dir, { n = 24, frames = 30 } = {}) {
  const folder = `${dir}/frames`;
  mkdirSync(folder, { recursive: true });
  for (let f = 0; f < frames; ++f) writeFileSync(`${folder}/frame_${String(f).padStart(4, "0")}.obj`, frameObj(n, f, frames));
  // The quick settings (one trial grid, no low-rank search: seconds less), 4 chunks of 8 frames.
  const quick = ["--effort", "1", "--low-rank", "off", "--chunk-frames", "8"];
  execFileSync(dcurvePath(), ["encode", folder, "-o", `${dir}/wave.dcrv`, "--fps", "30", "-q", ...quick]);
  return `${dir}/wave.dcrv`;
}
