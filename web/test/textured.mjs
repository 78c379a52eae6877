// The textured asset of the render tests, made at test time: tests/interop/write_textured_glb.mjs
// writes a glTF cloth (an open tube in two primitives, cloth with a 1x1 PNG texture and trim,
// a UV seam, a node placed inside a scaled parent) and the native `dcurve encode` encodes it.
import { execFileSync } from "node:child_process";
import { existsSync } from "node:fs";

import { dcurvePath, repo } from "./browser.mjs";

const interop = `${repo}tests/interop`;

// Runs a script of tests/interop (glTF-Transform), installing its packages first if missing.
export function interopScript(script, ...args) {
  if (!existsSync(`${interop}/node_modules/@gltf-transform/core`))
    execFileSync("npm", ["ci", "--no-audit", "--no-fund"], { cwd: interop, stdio: ["ignore", "ignore", "inherit"] });
  return execFileSync(process.execPath, [`${interop}/${script}`, ...args], { encoding: "utf8" });
}

// Writes dir/textured.glb and dir/textured.dcrv; returns the .dcrv's path and the layout the
// script prints ({ columns, around, rows, frames, png: base64, ... }).
export function encodeTextured(dir) {
  const layout = JSON.parse(interopScript("write_textured_glb.mjs", `${dir}/textured.glb`));
  // -q: the encoder's note that the parent's animation is not stored is expected here.
  execFileSync(dcurvePath(), ["encode", `${dir}/textured.glb`, "-o", `${dir}/textured.dcrv`, "-q"]);
  return { file: `${dir}/textured.dcrv`, layout };
}
