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

// Runs the native reference: `positions FILE T...` or `bench FILE PASSES`.
export function native(...args) {
  return execFileSync(nativePath(), args.map(String), { encoding: "utf8", maxBuffer: 1 << 28 });
}

// Positions the native decoder gives at each t: [[x, y, z, ...] per t].
export function nativePositions(file, times) {
  return native("positions", file, ...times).trim().split("\n").map((line) => line.split(" ").slice(1).map(Number));
}

// Serves web/ with `dir` at /data/, opens the viewer on /data/<file> in headless Chromium
// (WebGL through SwiftShader) and waits for the file to load. Page errors fail the load.
export async function openViewer(dir, file) {
  const server = await serve({ mounts: { "/data/": dir } });
  const browser = await chromium.launch({
    executablePath: chromiumPath(),
    args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
  });
  const page = await browser.newPage({ viewport: { width: 640, height: 480 } });
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
    await page.waitForFunction(() => window.viewer?.ready);
    await page.evaluate(() => window.viewer.ready);
    if (errors.length) throw new Error(`the page reported: ${errors.join("; ")}`);
  } catch (e) {
    await close();
    throw e;
  }
  return { page, errors, close };
}
