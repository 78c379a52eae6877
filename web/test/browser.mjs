// What the browser tests and the benchmark share: the local server, headless Chromium
// (Debian's, driven by playwright-core) with the viewer page open, and the native reference
// program. Nothing goes to the network.
import { execFileSync } from "node:child_process";
import { existsSync } from "node:fs";
import { fileURLToPath } from "node:url";

import { chromium } from "playwright-core";

import { serve } from "../serve.mjs";

export const repo = fileURLToPath(new URL("../../", import.meta.url));
export const vectors = `${repo}format_spec/test_vectors`;

// The first of the paths that exists, or a thrown error naming what to set.
function findExisting(what, variable, candidates) {
  const found = [process.env[variable], ...candidates].find((p) => p && existsSync(p));
  if (!found) throw new Error(`${what} not found: set ${variable} (tried ${candidates.join(", ")})`);
  return found;
}

export const chromiumPath = () => findExisting("Chromium", "CHROMIUM", ["/usr/bin/chromium", "/usr/bin/chromium-browser"]);
export const nativePath = () => findExisting("the native reference (cmake --build build --target dcurve_web_native)",
  "DCURVE_WEB_NATIVE", [`${repo}build/web/dcurve_web_native`]);

// The native encoder and decoder program.
export const dcurvePath = () => process.env.DCURVE ?? `${repo}build/cli/dcurve`;

// Runs the native reference: `positions FILE T...` or `bench FILE PASSES`.
export function native(...args) {
  return execFileSync(nativePath(), args.map(String), { encoding: "utf8", maxBuffer: 1 << 28 });
}

// Positions the native decoder gives at each t: [[x, y, z, ...] per t].
export function nativePositions(file, times) {
  return native("positions", file, ...times).trim().split("\n").map((line) => line.split(" ").slice(1).map(Number));
}

// Installed in the page before its scripts run: three.js announces every Scene and
// WebGLRenderer it creates to this devtools hook, which is how the tests reach the page's
// scene without the page exposing anything for them.
function threeDevtoolsHook() {
  const hook = new EventTarget();
  hook.observed = [];
  hook.addEventListener("observe", (e) => hook.observed.push(e.detail));
  hook.find = (kind) => hook.observed.find((o) => o[kind]); // "isScene", "isWebGLRenderer"
  window.__THREE_DEVTOOLS__ = hook;
}

// Serves web/ with `dir` at /data/, opens the viewer on /data/<file> in headless Chromium
// (WebGL through SwiftShader) and waits for the file to load, or for the page's message (an
// error, as are page errors). Drives the page as a user would: its controls and panel, plus
// the shown mesh's positions through the devtools hook.
export async function openViewer(dir, file) {
  const server = await serve({ mounts: { "/data/": dir } });
  const browser = await chromium.launch({
    executablePath: chromiumPath(),
    args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
  });
  const page = await browser.newPage({ viewport: { width: 640, height: 480 } });
  await page.addInitScript(threeDevtoolsHook);
  const errors = [];
  page.on("pageerror", (e) => errors.push(e.message));
  page.on("console", (m) => m.type() === "error" && errors.push(m.text()));
  page.on("response", (r) => r.status() >= 400 && errors.push(`${r.url()}: HTTP ${r.status()}`));
  const close = async () => {
    await browser.close();
    server.close();
  };
  try {
    await page.goto(`${server.url}/viewer/?file=/data/${encodeURIComponent(file)}`);
    await page.waitForFunction(() => document.querySelector("#info tr") || document.getElementById("message").textContent);
    const message = await page.textContent("#message");
    if (message) errors.push(message);
    if (errors.length) throw new Error(`the page reported: ${errors.join("; ")}`);
  } catch (e) {
    await close();
    throw e;
  }
  return {
    page, errors, close,
    // The positions of the mesh shown.
    positions: () => page.evaluate(() => {
      const shown = window.__THREE_DEVTOOLS__.find("isScene").children.find((c) => c.geometry);
      return Array.from(shown.geometry.attributes.position.array);
    }),
    // The panel's table: { vertices: "576", tolerance: "0.001 of L = ...", ... }.
    info: () => page.$$eval("#info tr", (rows) => Object.fromEntries(rows.map((r) => [...r.cells].map((c) => c.textContent)))),
    // The scene's background as #rrggbb.
    background: () => page.evaluate(() => `#${window.__THREE_DEVTOOLS__.find("isScene").background.getHexString()}`),
    stopRendering: () => page.evaluate(() => window.__THREE_DEVTOOLS__.find("isWebGLRenderer").setAnimationLoop(null)),
  };
}
