// The studio page: a three.js view of the surface and the result, the controls for every
// parameter of `meander curve` and `meander wire`, and the JSON API of docs/studio.md.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

const $ = (id) => document.getElementById(id);

// ---- the view -------------------------------------------------------------------------
const container = $('view');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setClearColor(0xffffff);
container.appendChild(renderer.domElement);
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(35, 1, 0.01, 1000);
camera.position.set(3, 2, 4);
const controls = new OrbitControls(camera, renderer.domElement); // left: orbit, wheel: zoom, right: pan
// Drawn on demand, not every frame: a software-rendered browser would otherwise take the
// CPU the server needs for the next update.
let frameQueued = false, dirty = false;
function draw() {
  if (!dirty) return;
  dirty = false;
  renderer.render(scene, camera);
}
function redraw() {
  dirty = true;
  if (frameQueued) return;
  frameQueued = true;
  requestAnimationFrame(() => {
    frameQueued = false;
    draw();
  });
}
controls.addEventListener('change', redraw);
scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8070, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.6);
camera.add(sun);
sun.position.set(2, 3, 1);
scene.add(camera);

// Pushed back so that a curve lying on the surface is drawn over it, not through it.
const surfaceMaterial = new THREE.MeshStandardMaterial({
  color: 0xcfcfcf, roughness: 0.9, side: THREE.DoubleSide,
  polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
});
const resultMaterial = new THREE.MeshStandardMaterial({ color: 0xb8733a, roughness: 0.45, metalness: 0.3, side: THREE.DoubleSide });
const curveMaterial = new THREE.LineBasicMaterial({ color: 0xbf1f14 });
const duotoneMaterial = new THREE.MeshStandardMaterial({ roughness: 0.8, side: THREE.DoubleSide });
let loadedTexture = null; // stats.texture of the atlas on duotoneMaterial
let surfaceObject = null;
let resultObject = null;

function resize() {
  const { clientWidth: w, clientHeight: h } = container;
  renderer.setSize(w, h, false);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
  redraw();
}
new ResizeObserver(resize).observe(container);
resize();

// The binary view format of studio.h (studio_view_bytes): "MNDR", vertex, quad,
// triangle and segment counts, flags (1: texture coordinates, 2: normals) and the
// bounding box, then float32 positions, [int8 normals, padded to 4 bytes], [float32
// texture coordinates], uint32 quads, uint32 triangles, uint32 segments. Every array but
// the quads is used where it lies in the buffer: no loop over the vertices here
// (computing normals in the page took longer than making a preview on the server).
function parseView(buffer) {
  const header = new DataView(buffer, 0, 48);
  if (new TextDecoder().decode(new Uint8Array(buffer, 0, 4)) !== 'MNDR') throw new Error('not a Meander view');
  const [v, q, t, s, flags] = [4, 8, 12, 16, 20].map((at) => header.getUint32(at, true));
  const textured = (flags & 1) !== 0, shaded = (flags & 2) !== 0;
  const box = new Float32Array(buffer, 24, 6);
  let offset = 48;
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(buffer, offset, v * 3), 3));
  offset += v * 12;
  if (shaded) {
    geometry.setAttribute('normal', new THREE.BufferAttribute(new Int8Array(buffer, offset, v * 3), 3, true));
    offset += Math.ceil(v * 3 / 4) * 4;
  }
  if (textured) {
    geometry.setAttribute('uv', new THREE.BufferAttribute(new Float32Array(buffer, offset, v * 2), 2));
    offset += v * 8;
  }
  const quads = new Uint32Array(buffer, offset, q * 4);
  const triangles = new Uint32Array(buffer, offset + q * 16, t * 3);
  const lines = q + t === 0;
  let index = triangles;
  if (q > 0) {
    // Each quad as its two triangles, the way the server fans a polygon.
    index = new Uint32Array(q * 6 + t * 3);
    for (let i = 0, j = 0; i < q * 4; i += 4, j += 6) {
      const a = quads[i], b = quads[i + 1], c = quads[i + 2], d = quads[i + 3];
      index[j] = a; index[j + 1] = b; index[j + 2] = c;
      index[j + 3] = a; index[j + 4] = c; index[j + 5] = d;
    }
    index.set(triangles, q * 6);
  }
  geometry.setIndex(new THREE.BufferAttribute(lines ? new Uint32Array(buffer, offset + q * 16 + t * 12, s * 2) : index, 1));
  // The bounds three.js would otherwise compute with a loop over the positions (the
  // sphere when it first culls): the box's circumscribed sphere encloses them too.
  geometry.boundingBox = new THREE.Box3(new THREE.Vector3(box[0], box[1], box[2]), new THREE.Vector3(box[3], box[4], box[5]));
  geometry.boundingSphere = geometry.boundingBox.isEmpty() ? new THREE.Sphere()
    : geometry.boundingBox.getBoundingSphere(new THREE.Sphere());
  return { geometry, lines, textured };
}

function replace(old, object) {
  if (old) {
    scene.remove(old);
    old.geometry.dispose();
  }
  if (object) scene.add(object);
  redraw();
  return object;
}

function fit() {
  const target = resultObject ?? surfaceObject;
  if (!target) return;
  const sphere = new THREE.Box3().setFromObject(target).getBoundingSphere(new THREE.Sphere());
  const distance = sphere.radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2)) * 1.05;
  const direction = camera.position.clone().sub(controls.target).normalize();
  controls.target.copy(sphere.center);
  camera.position.copy(sphere.center).addScaledVector(direction, distance);
  camera.near = distance / 100;
  camera.far = distance * 10;
  camera.updateProjectionMatrix();
  controls.update();
  redraw();
}

function applySurfaceStyle() {
  if (!surfaceObject) return;
  const style = $('surface').value;
  surfaceObject.visible = style !== 'off';
  surfaceMaterial.transparent = style === 'faint';
  surfaceMaterial.opacity = style === 'faint' ? 0.3 : 1;
  surfaceMaterial.depthWrite = style !== 'faint';
  surfaceMaterial.needsUpdate = true;
  redraw();
}

// ---- state and the API ------------------------------------------------------------------
const state = { session: null, revision: 0, busy: false, pending: false, lastUpdateMs: null, phases: null, error: null, stats: null,
  surfaceBox: null };
window.studio = {
  state,
  // The latency script (latency.mjs) times a preview and a full update through this.
  make: (preview) => make(preview),
  // Nothing in flight, queued or about to be asked (a change within the debounce): what
  // the browser test waits for, so that no pause of a busy machine can fool it.
  idle: () => !state.busy && !state.pending && debounce === null,
  // What the browser test reads: the result in the scene.
  resultInfo() {
    if (!resultObject) return null;
    const box = resultObject.geometry.boundingBox;
    return {
      vertices: resultObject.geometry.attributes.position.count,
      indices: resultObject.geometry.index.count,
      lines: resultObject.isLineSegments === true,
      textured: resultObject.geometry.attributes.uv !== undefined,
      texture: loadedTexture,
      min: box.min.toArray(), max: box.max.toArray(),
    };
  },
};

function showError(message) {
  state.error = message;
  $('error').textContent = message ?? '';
  $('error').hidden = !message;
}

async function api(path, options) {
  const response = await fetch(path, options);
  if (!response.ok) {
    let message = `HTTP ${response.status}`;
    try { message = (await response.json()).error ?? message; } catch { /* not JSON: keep the status */ }
    throw new Error(message);
  }
  return response;
}

let progressTimer = null;
function showProgress(on) {
  clearTimeout(progressTimer);
  // Quick updates do not flash the indicator; longer work shows it.
  if (on) progressTimer = setTimeout(() => { $('progress').hidden = false; }, 150);
  else $('progress').hidden = true;
}
function setBusy(busy) {
  state.busy = busy;
  showProgress(busy);
}

async function loadSurface(reply) {
  state.session = reply.session;
  state.revision = 0;
  const repairs = reply.repairs.length ? ` — repaired: ${reply.repairs.join('; ')}` : '';
  $('mesh-name').textContent = `${reply.name}: ${reply.faces} faces${repairs}`;
  const buffer = await (await api(`/api/result/${reply.session}/surface.bin`)).arrayBuffer();
  const { geometry } = parseView(buffer);
  state.surfaceBox = geometry.boundingBox.clone();
  showSpacing();
  surfaceObject = replace(surfaceObject, new THREE.Mesh(geometry, surfaceMaterial));
  resultObject = replace(resultObject, null);
  applySurfaceStyle();
  fit();
  await make();
}

async function upload(file) {
  const info = await (await api('/api/info')).json();
  if (file.size > info.max_upload) {
    showError(`upload too large: ${file.size} bytes (this server's --max-upload is ${info.max_upload} bytes)`);
    return;
  }
  const form = new FormData();
  form.append('mesh', file, file.name);
  await openSurface(() => api('/api/mesh', { method: 'POST', body: form }));
}

async function openSurface(request) {
  showError(null);
  showProgress(true);
  let reply;
  try {
    reply = await (await request()).json();
  } catch (e) {
    showError(e.message);
    return;
  } finally {
    showProgress(false);
  }
  try {
    await loadSurface(reply);
  } catch (e) {
    showError(e.message);
  }
}

// The model size's millimetres, as the server reads it (120mm, 12cm, 0.1m, 4.7in, a bare
// number of millimetres); null when the field is empty.
function modelSizeMillimetres() {
  const match = $('model-size').value.trim().match(/^([0-9.eE+-]+)\s*(mm|cm|m|in)?$/);
  if (!match) return null;
  return Number(match[1]) * { mm: 1, cm: 10, m: 1000, in: 25.4 }[match[2] ?? 'mm'];
}

// The spacing slider is logarithmic, from 1/300 to 1/10 of the model's diagonal, in the
// model's units or, with a model size, in millimetres (what the server reads then).
function spacingValue() {
  const box = state.surfaceBox;
  if (!box || box.isEmpty()) return null;
  const size = box.getSize(new THREE.Vector3());
  const millimetres = modelSizeMillimetres();
  const scale = millimetres ? millimetres / Math.max(size.x, size.y, size.z) : 1;
  const t = Number($('spacing').value) / 100;
  return size.length() * scale * 10 ** (Math.log10(1 / 300) + t * (Math.log10(1 / 10) - Math.log10(1 / 300)));
}
function showSpacing() {
  const value = spacingValue();
  $('spacing-value').textContent = value === null ? '' : `${value.toPrecision(3)}${modelSizeMillimetres() ? ' mm' : ''}`;
}

function params() {
  const mode = $('mode').value;
  const sized = modelSizeMillimetres() !== null;
  return {
    session: state.session,
    mode,
    model_size: sized ? $('model-size').value.trim() : 'none',
    spacing: $('spacing-on').checked && spacingValue() !== null ? spacingValue() : 'none',
    branches: $('branches-on').checked ? Number($('branches').value) : 'none',
    nozzle: Number($('nozzle').value),
    quad: $('quad').value,
    tree: $('tree').value,
    seed: Number($('seed').value),
    smooth: $('smooth').value,
    samples: Number($('samples').value),
    radius: $('radius-auto').checked ? 'auto' : Number($('radius').value),
    sides: Number($('sides').value),
    s: Number($('s').value),
    t: Number($('t').value),
    thickness: Number($('thickness').value),
    levels: Number($('levels').value),
    rule: $('rule').value,
    colors: `${$('color0').value},${$('color1').value}`,
    tiles: $('tiles').value,
    texture_size: Number($('texture-size').value),
    subdivide: Number($('subdivide').value),
  };
}

// One request at a time; changes made meanwhile are coalesced: at most one preview and
// one full result follow, the preview first. A preview is the server's quick version:
// fewer samples and levels, no printability report.
async function make(preview = false) {
  if (!state.session) return;
  if (state.busy) {
    const asked = preview ? 'preview' : 'full';
    state.pending = !state.pending || state.pending === asked ? asked : 'both';
    return;
  }
  state.pending = false;
  setBusy(true);
  const start = performance.now();
  const phases = {};
  let mark = start;
  const lap = (name) => { const now = performance.now(); phases[name] = now - mark; mark = now; };
  try {
    const stats = await (await api('/api/make', {
      method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ ...params(), preview }),
    })).json();
    lap('make');
    const buffer = await (await api(`/api/result/${state.session}/view.bin`)).arrayBuffer();
    lap('fetch');
    const { geometry, lines, textured } = parseView(buffer);
    lap('parse');
    // The atlas depends on the tile options alone (stats.texture names them): it is
    // fetched only when they change, not on every seed or subdivision change.
    if (textured && stats.texture !== loadedTexture) {
      const texture = await new THREE.TextureLoader().loadAsync(`/api/result/${state.session}/texture.png?r=${stats.revision}`);
      texture.colorSpace = THREE.SRGBColorSpace;
      texture.anisotropy = renderer.capabilities.getMaxAnisotropy();
      duotoneMaterial.map?.dispose();
      duotoneMaterial.map = texture;
      duotoneMaterial.needsUpdate = true;
      loadedTexture = stats.texture;
      lap('texture');
    }
    const material = lines ? curveMaterial : textured ? duotoneMaterial : resultMaterial;
    resultObject = replace(resultObject, lines ? new THREE.LineSegments(geometry, material) : new THREE.Mesh(geometry, material));
    // The update ends when the frame showing it is drawn: the geometry's upload and the
    // first draw are part of it.
    draw();
    renderer.getContext().finish();
    lap('draw');
    state.lastUpdateMs = performance.now() - start;
    state.phases = phases;
    state.revision = stats.revision;
    state.stats = stats;
    showStats(stats);
    showError(null);
  } catch (e) {
    showError(e.message);
  } finally {
    setBusy(false);
    updateDownloads();
    const next = state.pending;
    if (next) make(next !== 'full');
    if (next === 'both') make(false);
  }
}

function showStats(stats) {
  const yesNo = (b) => (b ? 'yes' : 'no');
  const rows = [
    ['stats of', stats.preview ? 'preview (the full result follows)' : 'full result'],
    ['triangles', stats.triangles.toLocaleString()],
    [stats.mode === 'duotone' ? 'separating curves' : 'curves', stats.curves],
    ['curve length', stats.curve_length.toPrecision(5)],
  ];
  if (stats.mode === 'duotone') {
    rows.push(['quads', stats.quads.toLocaleString()], ['faces', stats.faces.toLocaleString()]);
  } else if (stats.mode !== 'curve') {
    rows.push(['faces', stats.faces.toLocaleString()]);
    if (!stats.preview) rows.push(['watertight', yesNo(stats.watertight)], ['self-intersection', yesNo(stats.self_intersecting)]);
    // As `meander wire` notes: where the surface itself crosses itself, no settings clear the wire.
    if (stats.surface_crossings > 0) {
      rows.push(['surface', `crosses itself (${stats.surface_crossings.toLocaleString()} of the cycle's triangles): a wire that follows it cannot be clear there`]);
    }
    // As `meander wire --method variable` notes: the mesh it was made on had large polygons
    // split and caps flipped (or cut off on the boundary).
    if (stats.stars > 0) rows.push(['polygons split', `${stats.stars.toLocaleString()} of 5 or more sides, into triangles`]);
    if (stats.cap_flips > 0) rows.push(['caps flipped', `${stats.cap_flips.toLocaleString()} edges (flat triangles fold the slabs)`]);
    if (stats.cap_cuts > 0) rows.push(['caps cut off', `${stats.cap_cuts.toLocaleString()} triangles on the boundary`]);
    if (stats.needle_collapses > 0) rows.push(['needles collapsed', `${stats.needle_collapses.toLocaleString()} short edges (needles and folded triangles fold the slabs)`]);
    if (stats.radius) rows.push(['radius', stats.radius.toPrecision(4)]);
  }
  if (stats.gap_median !== undefined) {
    rows.push(['median gap', `${stats.gap_median.toPrecision(3)} (CV ${stats.gap_cv.toFixed(2)})`]);
  }
  if (stats.leaves !== undefined) rows.push(['branch tips', stats.leaves.toLocaleString()]);
  rows.push(['made in', `${(stats.seconds * 1000).toFixed(0)} ms`], ['update', `${state.lastUpdateMs.toFixed(0)} ms`]);
  $('stats').innerHTML = rows.map(([k, v]) => `<tr><th>${k}</th><td>${v}</td></tr>`).join('');
}

function updateDownloads() {
  const curve = $('mode').value === 'curve';
  for (const a of document.querySelectorAll('#downloads a')) {
    // A preview is not offered for download: the full result follows it.
    const enabled = state.revision > 0 && !state.stats?.preview && !(curve && a.hasAttribute('data-mesh'));
    a.classList.toggle('disabled', !enabled);
    a.href = enabled ? `/api/result/${state.session}/${a.dataset.file}` : '#';
    a.toggleAttribute('download', enabled);
  }
}

// ---- controls -----------------------------------------------------------------------------
let debounce = null;
function changed(event) {
  clearTimeout(debounce);
  // A slider being dragged fires 'input' (previews only); letting it go fires 'change'
  // (the full result, whose preview is on screen already). Any other change shows its
  // preview first, then the full result: the view follows within the preview's time
  // even where the full result (a wire's printability report) takes seconds.
  const slider = event?.target?.type === 'range';
  const dragging = slider && event.type === 'input', released = slider && event.type === 'change';
  debounce = setTimeout(() => {
    debounce = null;
    if (!released) make(true);
    if (!dragging) make(false);
  }, 30);
}

function showModeControls() {
  const mode = $('mode').value;
  for (const el of document.querySelectorAll('[data-modes]')) el.hidden = !el.dataset.modes.split(' ').includes(mode);
  updateDownloads();
}

for (const output of document.querySelectorAll('output[for]')) {
  const input = $(output.htmlFor.value);
  const show = () => { output.textContent = input.value; };
  input.addEventListener('input', show);
  show();
}
for (const id of ['mode', 'model-size', 'spacing-on', 'spacing', 'branches-on', 'branches', 'quad', 'tree', 'seed', 'smooth',
  'samples', 'radius', 'radius-auto', 'sides', 'nozzle', 's', 't', 'thickness', 'levels', 'rule', 'color0', 'color1', 'tiles',
  'texture-size', 'subdivide']) {
  $(id).addEventListener('input', changed);
  if ($(id).type === 'range') $(id).addEventListener('change', changed);
}
// Duotone starts from its command's default quads (Catmull-Clark topology), the others
// from dual-simplest, as `meander duotone` and `meander curve`/`wire` do. Variable wires
// and ribbons start from the shaped tree, as `meander wire --method variable` does (their
// slabs fold where the cycle turns round in a thin triangle), unless another tree than
// the previous mode's default was chosen.
let previousMode = $('mode').value;
const defaultTree = (mode) => (mode.startsWith('variable') ? 'shaped' : 'random');
$('mode').addEventListener('input', () => {
  const mode = $('mode').value;
  if ((mode === 'duotone') !== (previousMode === 'duotone')) $('quad').value = mode === 'duotone' ? 'catmull-clark' : 'dual-simplest';
  if ($('tree').value === defaultTree(previousMode)) $('tree').value = defaultTree(mode);
  previousMode = mode;
  showModeControls();
});
$('radius-auto').addEventListener('input', () => { $('radius').disabled = $('radius-auto').checked; });
$('spacing-on').addEventListener('input', () => { $('spacing').disabled = !$('spacing-on').checked; });
$('branches-on').addEventListener('input', () => { $('branches').disabled = !$('branches-on').checked; });
for (const id of ['spacing', 'model-size']) $(id).addEventListener('input', showSpacing);
$('new-seed').addEventListener('click', () => {
  $('seed').value = Math.floor(Math.random() * 2 ** 31);
  changed();
});
$('surface').addEventListener('input', applySurfaceStyle);
$('fit').addEventListener('click', fit);
$('demo').addEventListener('click', () => openSurface(() => api('/api/demo', { method: 'POST' })));
$('file').addEventListener('change', (e) => { if (e.target.files[0]) upload(e.target.files[0]); });
const drop = $('drop');
for (const name of ['dragenter', 'dragover']) drop.addEventListener(name, (e) => { e.preventDefault(); drop.classList.add('over'); });
for (const name of ['dragleave', 'drop']) drop.addEventListener(name, () => drop.classList.remove('over'));
drop.addEventListener('drop', (e) => {
  e.preventDefault();
  if (e.dataTransfer.files[0]) upload(e.dataTransfer.files[0]);
});
showModeControls();

// Each control's help is its parameter's, the text `meander curve|wire|duotone --help` gives.
api('/api/parameters').then((reply) => reply.json()).then((modes) => {
  for (const list of Object.values(modes)) {
    for (const p of list) {
      const label = $(p.name === 'colors' ? 'color0' : p.name.replaceAll('_', '-'))?.closest('label');
      if (label && !label.title) label.title = p.help;
    }
  }
}).catch(() => {}); // help only: the controls work without it
