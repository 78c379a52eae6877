// A static file server for the viewer and its tests, on 127.0.0.1 only, no network needed:
// web/ at /, so the page finds build/ and node_modules/ beside it; `--mount /data=DIR` adds
// a folder (e.g. the test vectors or your .dcrv files).
//   node web/serve.mjs [--port 8080] [--mount /data=DIR]...   then open /viewer/
import { createReadStream, statSync } from "node:fs";
import { createServer } from "node:http";
import { extname, join, normalize, resolve, sep } from "node:path";
import { fileURLToPath } from "node:url";

const TYPES = {
  ".html": "text/html", ".js": "text/javascript", ".mjs": "text/javascript", ".css": "text/css",
  ".wasm": "application/wasm", ".json": "application/json", ".png": "image/png",
};

// The file a URL path names under its mount, or null when it leaves the mount or is absent.
function fileFor(mounts, urlPath) {
  const path = decodeURIComponent(urlPath.split("?")[0]);
  for (const [prefix, dir] of mounts) {
    if (!path.startsWith(prefix)) continue;
    let file = normalize(join(dir, path.slice(prefix.length)));
    if (file !== dir && !file.startsWith(dir.endsWith(sep) ? dir : dir + sep)) return null;
    try {
      if (statSync(file).isDirectory()) file = join(file, "index.html");
      return statSync(file).isFile() ? file : null;
    } catch {
      return null;
    }
  }
  return null;
}

// Serves until close(); mounts maps URL prefixes ("/data/") to folders; "/" is web/.
export function serve({ port = 0, mounts = {} } = {}) {
  const table = Object.entries({ ...mounts, "/": fileURLToPath(new URL(".", import.meta.url)) })
    .map(([prefix, dir]) => [prefix.endsWith("/") ? prefix : prefix + "/", resolve(dir)])
    .sort((a, b) => b[0].length - a[0].length); // longest prefix first
  const server = createServer((req, res) => {
    const file = fileFor(table, req.url);
    if (!file) return res.writeHead(404).end("not found");
    res.writeHead(200, {
      "Content-Type": TYPES[extname(file)] ?? "application/octet-stream",
      // Cross-origin isolation: performance.now() then resolves microseconds, not 0.1 ms.
      "Cross-Origin-Opener-Policy": "same-origin",
      "Cross-Origin-Embedder-Policy": "require-corp",
    });
    createReadStream(file).pipe(res);
  });
  return new Promise((ready) =>
    server.listen(port, "127.0.0.1", () =>
      ready({ url: `http://127.0.0.1:${server.address().port}`, close: () => server.close() })));
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const args = process.argv.slice(2);
  const mounts = {};
  let port = 8080;
  for (let i = 0; i < args.length; i += 2) {
    if (args[i] === "--port") port = Number(args[i + 1]);
    else if (args[i] === "--mount" && args[i + 1]?.includes("=")) {
      const [prefix, dir] = args[i + 1].split("=");
      mounts[prefix] = dir;
    } else {
      console.error("usage: node web/serve.mjs [--port N] [--mount /prefix=DIR]...");
      process.exit(2);
    }
  }
  const { url } = await serve({ port, mounts });
  console.log(`serving ${url}/viewer/ (Ctrl-C stops)`);
}
