// The TypeScript declarations (dcurve.d.ts, dcurve-loader.d.ts) against the modules: each
// declares exactly the values its module exports, and each declared class or interface
// exactly the members its objects have at run time. Skipped without the typescript package
// (a devDependency); web/test.sh also type-checks them with `tsc --noEmit`.
import assert from "node:assert/strict";
import { mkdtempSync, readFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { test } from "node:test";

import { Loader } from "three";

import * as dcurveJs from "../dcurve.js";
import * as loaderJs from "../dcurve-loader.js";
import { encodeTextured } from "./textured.mjs";

const ts = await import("typescript").then((m) => m.default, () => null);
const vector = readFileSync(new URL("../../format_spec/test_vectors/sheet_compact_faces.dcrv", import.meta.url));

// { values: exported value names, members: { type name: member names } } of a .d.ts.
function declarations(file) {
  const text = readFileSync(new URL(`../${file}`, import.meta.url), "utf8");
  const source = ts.createSourceFile(file, text, ts.ScriptTarget.Latest);
  const values = [], members = {};
  const exported = (node) => node.modifiers?.some((m) => m.kind === ts.SyntaxKind.ExportKeyword);
  for (const node of source.statements) {
    if (!exported(node)) continue;
    if (ts.isVariableStatement(node)) values.push(...node.declarationList.declarations.map((d) => d.name.text));
    if (ts.isFunctionDeclaration(node) || ts.isClassDeclaration(node)) values.push(node.name.text);
    if (ts.isClassDeclaration(node) || ts.isInterfaceDeclaration(node))
      members[node.name.text] = node.members.filter((m) => m.name).map((m) => m.name.text).sort();
  }
  return { values: values.sort(), members };
}

// The names an object's own class chain defines: its own properties but those an object of
// the parent class (`base`) has too, and its prototypes' up to the parent's.
function runtimeMembers(object, base = {}) {
  const names = new Set(Object.getOwnPropertyNames(object).filter((name) => !Object.hasOwn(base, name)));
  for (let o = Object.getPrototypeOf(object); o !== Object.getPrototypeOf(base); o = Object.getPrototypeOf(o))
    for (const name of Object.getOwnPropertyNames(o)) if (name !== "constructor") names.add(name);
  return [...names].sort();
}

test("dcurve.d.ts declares what dcurve.js exports", { skip: !ts && "no typescript package" }, async () => {
  const { values, members } = declarations("dcurve.d.ts");
  assert.deepEqual(values, Object.keys(dcurveJs).sort());
  const dcurve = await dcurveJs.loadDcurve();
  assert.deepEqual(members.DcurveModule, runtimeMembers(dcurve));
  const dec = dcurve.open(vector);
  assert.deepEqual(members.DcurveDecoder, runtimeMembers(dec));
  assert.deepEqual(members.LoadDcurveOptions, ["wasmUrl"]);
  const error = (() => { try { dec.close(); return dec.faces(); } catch (e) { return e; } })();
  assert.ok(error instanceof dcurveJs.DcurveError);
  assert.deepEqual(members.DcurveError, runtimeMembers(error, new Error("", { cause: 0 })));
});

test("dcurve-loader.d.ts declares what dcurve-loader.js exports", { skip: !ts && "no typescript package" }, async () => {
  const { values, members } = declarations("dcurve-loader.d.ts");
  assert.deepEqual(values, Object.keys(loaderJs).sort());
  const loader = new loaderJs.DcurveLoader();
  assert.deepEqual(members.DcurveLoader, runtimeMembers(loader, new Loader()));
  const anim = await loader.parse(vector);
  assert.deepEqual(members.DcurveAnimation, runtimeMembers(anim));
  anim.dispose();
});

test("dcurve.d.ts declares the render data as the decoder gives it", { skip: !ts && "no typescript package" }, async () => {
  const { members } = declarations("dcurve.d.ts");
  const dir = mkdtempSync(`${tmpdir()}/dcurve-types-`);
  try {
    const dec = (await dcurveJs.loadDcurve()).open(readFileSync(encodeTextured(dir).file));
    const keys = (object) => Object.keys(object).sort();
    assert.deepEqual(members.DcurveGroup, keys(dec.groups()[0]));
    assert.deepEqual(members.DcurveImage, keys(dec.images()[0]));
    assert.deepEqual(members.DcurveAttribute, keys(dec.attributes().uv));
    // Every attribute a file may hold: the file's own are some of them.
    assert.deepEqual(members.DcurveAttributes, ["color", "normal", "uv", "uv1"]);
    assert.ok(keys(dec.attributes()).every((name) => members.DcurveAttributes.includes(name)));
    assert.ok(keys(dec.materials()).every((name) => members.DcurveMaterials.includes(name)), keys(dec.materials()).join());
    dec.close();
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});
