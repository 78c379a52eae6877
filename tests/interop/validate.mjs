// node validate.mjs FILE.glb|FILE.gltf: the Khronos glTF validator's report summary; exits 1
// when it finds any error.
import { readFileSync } from 'node:fs';
import path from 'node:path';
import validator from 'gltf-validator';

const file = process.argv[2];
const report = await validator.validateBytes(new Uint8Array(readFileSync(file)), {
  uri: path.basename(file),
  externalResourceFunction: (uri) => Promise.reject(new Error(`external resource ${uri}`)),
});
const { numErrors, numWarnings } = report.issues;
console.log(`errors ${numErrors} warnings ${numWarnings}`);
for (const m of report.issues.messages.filter((m) => m.severity <= 1)) console.log(`${m.code} ${m.pointer ?? ''} ${m.message}`);
process.exit(numErrors > 0 ? 1 : 0);
