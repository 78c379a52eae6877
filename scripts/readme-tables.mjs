// Formats `dcurve bench --json` results as the top-level README's markdown tables
// (scripts/readme-tables.sh runs the benches and calls this).
//   node scripts/readme-tables.mjs comparison FIRST_COLUMN BENCH.json
//   node scripts/readme-tables.mjs tolerances BENCH.json
import { readFileSync } from 'node:fs';

const [mode, ...args] = process.argv.slice(2);
const load = (path) => JSON.parse(readFileSync(path, 'utf8')).results;
const method = (input, name) => input.methods.find((m) => m.method === name && m.meets_tolerance);
const fixed = (x, digits) => (x === undefined ? 'n/a' : x.toFixed(digits));

// One row per input at one tolerance: bits per vertex per frame and dcurve's ratios to Draco
// per frame and to the better of quantized delta and PCA (by bytes).
function comparison(firstColumn, results) {
  const rows = [`| ${firstColumn} | dcurve | Draco per frame | quantized delta | PCA | dcurve / Draco | dcurve / best of delta, PCA |`,
    '|---|---|---|---|---|---|---|'];
  results.forEach((input, i) => {
    const [d, draco, delta, pca] = ['dcurve', 'draco_per_frame', 'quantized_delta', 'pca'].map((n) => method(input, n));
    const toDraco = d && draco ? d.bytes / draco.bytes : undefined;
    const best = [delta, pca].filter(Boolean).sort((a, b) => a.bytes - b.bytes)[0];
    const toBest = d && best ? `${fixed(d.bytes / best.bytes, 3)}${best === pca ? ' (PCA)' : ''}` : 'n/a';
    const times = toDraco ? ` (${(1 / toDraco).toFixed(1)}x${i === 0 ? ' smaller' : ''})` : '';
    rows.push(`| ${input.input} | ${fixed(d?.bpvf, 2)} | ${fixed(draco?.bpvf, 2)} | ${fixed(delta?.bpvf, 2)} | ` +
      `${fixed(pca?.bpvf, 2)} | ${fixed(toDraco, 3)}${times} | ${toBest} |`);
  });
  return rows.join('\n');
}

// dcurve's bytes and their ratio to quantized delta's at every tolerance of the run.
function tolerances(results) {
  const tols = [...new Set(results.map((r) => r.tolerance))];
  const head = tols.map((t) => `dcurve bytes at ${t} | / quantized delta`).join(' | ');
  const rows = [`| sequence | ${head} |`, `|---|${tols.map(() => '---|---|').join('')}`];
  for (const name of [...new Set(results.map((r) => r.input))]) {
    const cells = tols.map((t) => {
      const input = results.find((r) => r.input === name && r.tolerance === t);
      const d = method(input, 'dcurve'), delta = method(input, 'quantized_delta');
      return `${d ? d.bytes.toLocaleString('en-US') : 'n/a'} | ${d && delta ? fixed(d.bytes / delta.bytes, 3) : 'n/a'}`;
    });
    rows.push(`| ${name} | ${cells.join(' | ')} |`);
  }
  return rows.join('\n');
}

if (mode === 'comparison') console.log(comparison(args[0], load(args[1])));
else if (mode === 'tolerances') console.log(tolerances(load(args[0])));
else { console.error(`readme-tables.mjs: unknown mode ${mode}`); process.exit(2); }
