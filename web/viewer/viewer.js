// The viewer page: open or drop a .dcrv, play, scrub, set the speed, see the file's figures
// and the decode time per frame, and optionally the error against a folder of OBJ frames. A
// file with materials shows them (textures too), placed where its input put the mesh.
// `?file=URL` opens a file at start. Nothing here is for tests: they drive the page from
// outside (web/test/browser.mjs), through its controls and three.js's devtools hook.
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";
import { RoomEnvironment } from "three/addons/environments/RoomEnvironment.js";

import { DcurveLoader } from "../dcurve-loader.js";

const $ = (id) => document.getElementById(id);
const BACKGROUND = 0x20232a;
const DECODE_WINDOW = 60; // frames the shown decode time averages

const renderer = new THREE.WebGLRenderer({ canvas: $("view"), antialias: true });
const scene = new THREE.Scene();
scene.background = new THREE.Color(BACKGROUND);
scene.add(new THREE.HemisphereLight(0xffffff, 0x404050, 1.5));
const sun = new THREE.DirectionalLight(0xffffff, 2);
sun.position.set(1, 2, 3);
scene.add(sun);
let room = null; // the environment of files with materials, made when first needed
const camera = new THREE.PerspectiveCamera(45, 1, 0.01, 1000);
const controls = new OrbitControls(camera, renderer.domElement);
const clock = new THREE.Clock();

const state = { anim: null, mesh: null, ownMaterial: null, playing: false, fileBytes: 0, name: "", decodeMs: [], referenceError: null };

function resize() {
  renderer.setSize(innerWidth, innerHeight, false);
  renderer.setPixelRatio(devicePixelRatio);
  camera.aspect = innerWidth / innerHeight;
  camera.updateProjectionMatrix();
}

// The loader's object (a mesh, or points without faces) with the file's materials, or this
// page's own colour when the file has none.
function makeObject(anim) {
  const object = anim.object;
  const fromFile = anim.materials.length > 0;
  // glTF materials are metallic unless they say otherwise, and a metal with nothing to
  // reflect draws black: a room to reflect, as glTF viewers give.
  if (fromFile) room ??= new THREE.PMREMGenerator(renderer).fromScene(new RoomEnvironment(), 0.04).texture;
  scene.environment = fromFile ? room : null;
  if (!fromFile) {
    object.material = state.ownMaterial = object.isMesh
      ? new THREE.MeshStandardMaterial({ color: 0x8fb3e0, roughness: 0.6, side: THREE.DoubleSide })
      : new THREE.PointsMaterial({ color: 0x8fb3e0, size: 3, sizeAttenuation: false });
  }
  return object;
}

// Looks at the whole mesh across its thinnest extent (a sheet face-on), slightly tilted.
function frameCamera(object) {
  const { geometry } = object;
  geometry.computeBoundingBox();
  object.updateMatrixWorld();
  // Where the file's placement puts the mesh.
  const box = geometry.boundingBox.clone().applyMatrix4(object.matrixWorld);
  const size = box.getSize(new THREE.Vector3()).toArray();
  const thin = size.indexOf(Math.min(...size));
  const direction = new THREE.Vector3(0.3, 0.3, 0.3).setComponent(thin, 1).normalize();
  const sphere = geometry.boundingSphere.clone().applyMatrix4(object.matrixWorld);
  const distance = sphere.radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2)) || 1;
  camera.position.copy(sphere.center).addScaledVector(direction, distance);
  camera.near = distance / 100;
  camera.far = distance * 100;
  camera.updateProjectionMatrix();
  controls.target.copy(sphere.center);
  controls.update();
}

function unload() {
  if (!state.anim) return;
  scene.remove(state.mesh);
  state.ownMaterial?.dispose();
  state.anim.dispose(); // and the file's materials
  state.anim = state.mesh = state.ownMaterial = null;
}

// Opens a .dcrv from its bytes (or a promise of them); a failure to fetch or decode is shown
// in the panel, prefixed with the file's name.
async function open(bytes, name) {
  $("message").textContent = "";
  unload();
  let buffer;
  try {
    buffer = await bytes;
    state.anim = await new DcurveLoader().parse(buffer);
  } catch (e) {
    $("message").textContent = `${name}: ${e.message}`;
    return;
  }
  state.fileBytes = buffer.byteLength;
  state.name = name;
  state.decodeMs = [];
  state.referenceError = null;
  state.mesh = makeObject(state.anim);
  scene.add(state.mesh);
  frameCamera(state.mesh);
  for (const id of ["play", "scrub", "reference"]) $(id).disabled = false;
  showInfo();
}

async function fetchBytes(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`HTTP ${response.status}`);
  return response.arrayBuffer();
}

function decodeMsAverage() {
  const ms = state.decodeMs;
  return ms.length ? ms.reduce((a, b) => a + b, 0) / ms.length : 0;
}

function showInfo() {
  const anim = state.anim;
  const d = anim.decoder;
  const rows = {
    file: `${state.name}, ${state.fileBytes.toLocaleString()} bytes`,
    vertices: d.vertexCount.toLocaleString(),
    faces: d.faceCount.toLocaleString(),
    frames: `${d.frameCount} at ${d.frameRate || "? (30 assumed)"} fps`,
    tolerance: `${d.tolerance} of L = ${d.restDiagonal.toPrecision(4)}`,
    "decode / frame": `${decodeMsAverage().toFixed(3)} ms (evaluate + normals)`,
    "decoder memory": `${d.memoryBytes.toLocaleString()} bytes`,
  };
  if (d.renderVertexCount !== d.vertexCount) rows["render vertices"] = d.renderVertexCount.toLocaleString();
  if (anim.materials.length) rows.materials = [...new Set(anim.materials)].map(describeMaterial).join(", ");
  const ref = state.referenceError;
  if (ref) rows["max error"] = `${ref.ofL.toExponential(3)} of L (${(ref.ofL / d.tolerance).toFixed(2)} x tolerance), ${ref.frames} frames`;
  $("info").replaceChildren(...Object.entries(rows).map(([k, v]) => {
    const tr = document.createElement("tr");
    tr.append(Object.assign(document.createElement("td"), { textContent: k }), Object.assign(document.createElement("td"), { textContent: v }));
    return tr;
  }));
}

// "cloth (texture 1x1)": a material's name and what its map shows.
function describeMaterial(material) {
  const image = material.map?.image;
  return image ? `${material.name} (texture ${image.width}x${image.height})` : material.name;
}

// One decoded time step: record its decode time and move the slider.
function showStep() {
  const anim = state.anim;
  state.decodeMs.push(anim.decodeMs);
  if (state.decodeMs.length > DECODE_WINDOW) state.decodeMs.shift();
  const t = anim.duration > 0 ? anim.time / anim.duration : 0;
  $("scrub").value = t;
  $("t").textContent = t.toFixed(3);
}

function setPlaying(playing) {
  state.playing = playing;
  $("play").textContent = playing ? "Pause" : "Play";
  clock.getDelta(); // a resumed clip starts where it stopped
  if (state.anim) showInfo();
}

function tick() {
  const dt = clock.getDelta();
  if (state.anim && state.playing) {
    state.anim.update(dt);
    showStep();
    if (state.decodeMs.length % 15 === 0) showInfo();
  }
  renderer.render(scene, camera);
}

// ---- reference frames: the largest distance to a folder of OBJ frames, in units of L

function objVertices(text) {
  const xyz = [];
  for (const line of text.split("\n"))
    if (line.startsWith("v ")) xyz.push(...line.trim().split(/\s+/).slice(1, 4).map(Number));
  return xyz;
}

async function compareWithReference(files) {
  const anim = state.anim;
  const d = anim.decoder;
  const objs = [...files].filter((f) => /\.obj$/i.test(f.name));
  objs.sort((a, b) => a.name.localeCompare(b.name, undefined, { numeric: true }));
  if (objs.length !== d.frameCount) throw new Error(`${objs.length} OBJ files for ${d.frameCount} frames`);
  const xyz = new Float32Array(d.vertexCount * 3);
  let worst = 0;
  for (const [f, file] of objs.entries()) {
    const ref = objVertices(await file.text());
    if (ref.length !== xyz.length) throw new Error(`${file.name}: ${ref.length / 3} vertices, the file has ${d.vertexCount}`);
    d.evaluateFrame(f, xyz);
    for (let v = 0; v < xyz.length; v += 3)
      worst = Math.max(worst, Math.hypot(xyz[v] - ref[v], xyz[v + 1] - ref[v + 1], xyz[v + 2] - ref[v + 2]));
  }
  anim.setTime(anim.time);
  state.referenceError = { ofL: worst / d.restDiagonal, frames: objs.length };
}

// ---- wiring

const openFile = (file) => open(file.arrayBuffer(), file.name);

$("file").addEventListener("change", async (e) => {
  const file = e.target.files[0];
  if (file) await openFile(file);
});
addEventListener("dragover", (e) => { e.preventDefault(); document.body.classList.add("dragging"); });
addEventListener("dragleave", () => document.body.classList.remove("dragging"));
addEventListener("drop", async (e) => {
  e.preventDefault();
  document.body.classList.remove("dragging");
  const file = e.dataTransfer.files[0];
  if (file) await openFile(file);
});
$("play").addEventListener("click", () => setPlaying(!state.playing));
$("speed").addEventListener("input", (e) => { if (state.anim) state.anim.speed = Number(e.target.value) || 0; });
$("scrub").addEventListener("input", (e) => {
  setPlaying(false);
  state.anim.setT(Number(e.target.value));
  showStep();
  showInfo();
});
$("reference").addEventListener("change", async (e) => {
  try {
    await compareWithReference(e.target.files);
    showInfo();
  } catch (err) {
    $("message").textContent = `reference: ${err.message}`;
  }
});
addEventListener("resize", resize);
resize();
renderer.setAnimationLoop(tick);

const file = new URLSearchParams(location.search).get("file");
if (file) open(fetchBytes(file), file.split("/").pop());
