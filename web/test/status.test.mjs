// Status names come from the C API, not from a table in JavaScript: the module's statusName
// is the native library's dcurve_status_name for every code (dcurve_web_native status-names),
// and a DcurveError's status is that name of its code.
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { test } from "node:test";

import { DcurveError, loadDcurve } from "../dcurve.js";
import { native } from "./browser.mjs";

const vector = readFileSync(new URL("../../format_spec/test_vectors/chunked.dcrv", import.meta.url));
const nativeNames = new Map(native("status-names").trim().split("\n").map((line) => {
  const [, code, name] = line.match(/^(-?\d+) (.*)$/);
  return [Number(code), name];
}));

// The DcurveError `call` throws.
function refusal(call) {
  try {
    call();
  } catch (e) {
    assert.ok(e instanceof DcurveError, String(e));
    return e;
  }
  assert.fail("no DcurveError");
}

test("statusName is the C API's dcurve_status_name for every code", async () => {
  const dcurve = await loadDcurve();
  assert.equal(nativeNames.size, 9, "codes -1 to 7");
  for (const [code, name] of nativeNames) assert.equal(dcurve.statusName(code), name, `code ${code}`);
});

test("a DcurveError's status is the C API's name of its code", async () => {
  const dcurve = await loadDcurve();
  const errors = [refusal(() => dcurve.open(vector.subarray(0, vector.length >> 1)))];
  const closed = dcurve.open(vector);
  closed.close();
  errors.push(refusal(() => closed.faces()));
  // A flipped byte in the last chunk opens, then fails that chunk's checksum.
  const damaged = Uint8Array.from(vector);
  damaged[damaged.length - 8] ^= 1;
  const dec = dcurve.open(damaged);
  errors.push(refusal(() => dec.evaluate(1, new Float32Array(dec.vertexCount * 3))));
  dec.close();
  assert.deepEqual(errors.map((e) => e.code), [1, 2, 4]);
  for (const e of errors) assert.equal(e.status, nativeNames.get(e.code), e.message);
});
