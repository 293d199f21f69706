// The studio page: a three.js view of the surface and the result, the controls for every
// parameter of `meander curve`, `wire`, `duotone` and `image` (a picture drawn with one
// line, shown as its sheet), and the JSON API of docs/studio.md.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { MeshoptDecoder } from 'three/examples/jsm/libs/meshopt_decoder.module.js';

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

// The view's size when last shown: what render.png and curve.svg are drawn at, also
// while the sheet takes the view's place.
let viewSize = { w: 1200, h: 900 };
function resize() {
  const { clientWidth: w, clientHeight: h } = container;
  if (w > 0 && h > 0) viewSize = { w: Math.max(16, Math.round(w)), h: Math.max(16, Math.round(h)) };
  renderer.setSize(w, h, false);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
  redraw();
}
new ResizeObserver(resize).observe(container);
resize();

// The binary view format of studio.h (studio_view_bytes): "MND3", vertex, triangle and
// segment counts, flags (1: texture coordinates, 2: normals), 0, the bounding box; then
// each array compressed by meshoptimizer's codecs, as its byte count and bytes padded to
// 4: uint16 positions (steps of a 65,535th of the box's largest side from its low
// corner) and a zero, [int8 normals and a zero byte], [uint16 texture coordinates],
// [uint32 triangles], [uint32 segments]. The decoder (WebAssembly, from three.js) writes
// each array where the geometry uses it: no loop over the vertices here (computing
// normals in the page took longer than making a preview on the server).
async function parseView(buffer) {
  await MeshoptDecoder.ready;
  if (new TextDecoder().decode(new Uint8Array(buffer, 0, 4)) !== 'MND3') throw new Error('not a Meander view');
  const header = new DataView(buffer, 0, 24);
  const [v, t, s, flags] = [4, 8, 12, 16].map((at) => header.getUint32(at, true));
  const textured = (flags & 1) !== 0, shaded = (flags & 2) !== 0;
  const box = new Float32Array(buffer, 24, 6);
  let offset = 48;
  const next = (count, size, decode) => {
    const length = new DataView(buffer, offset, 4).getUint32(0, true);
    const target = new Uint8Array(count * size);
    decode(target, count, size, new Uint8Array(buffer, offset + 4, length));
    offset += 4 + Math.ceil(length / 4) * 4;
    return target.buffer;
  };
  const geometry = new THREE.BufferGeometry();
  // Positions come as 16-bit steps of the box's largest side: the object is scaled and
  // placed so (placed()).
  const positions = new THREE.InterleavedBuffer(new Uint16Array(next(v, 8, MeshoptDecoder.decodeVertexBuffer)), 4);
  geometry.setAttribute('position', new THREE.InterleavedBufferAttribute(positions, 3, 0, true));
  if (shaded) {
    const normals = new THREE.InterleavedBuffer(new Int8Array(next(v, 4, MeshoptDecoder.decodeVertexBuffer)), 4);
    geometry.setAttribute('normal', new THREE.InterleavedBufferAttribute(normals, 3, 0, true));
  }
  if (textured) geometry.setAttribute('uv', new THREE.BufferAttribute(new Uint16Array(next(v, 4, MeshoptDecoder.decodeVertexBuffer)), 2, true));
  const lines = t === 0;
  const index = lines ? (s > 0 ? new Uint32Array(next(2 * s, 4, MeshoptDecoder.decodeIndexSequence)) : new Uint32Array(0))
    : new Uint32Array(next(3 * t, 4, MeshoptDecoder.decodeIndexBuffer));
  geometry.setIndex(new THREE.BufferAttribute(index, 1));
  // The bounds three.js would otherwise compute with a loop over the positions (the
  // sphere when it first culls), in the geometry's own units: the box's circumscribed
  // sphere encloses them too.
  const low = new THREE.Vector3(box[0], box[1], box[2]), high = new THREE.Vector3(box[3], box[4], box[5]);
  const side = Math.max(high.x - low.x, high.y - low.y, high.z - low.z, 1e-30);
  geometry.boundingBox = low.x > high.x ? new THREE.Box3()
    : new THREE.Box3(new THREE.Vector3(), high.clone().sub(low).divideScalar(side));
  geometry.boundingSphere = geometry.boundingBox.isEmpty() ? new THREE.Sphere()
    : geometry.boundingBox.getBoundingSphere(new THREE.Sphere());
  // What places the object: its low corner and the step's scale.
  const placed = (object) => {
    if (low.x <= high.x) {
      object.position.copy(low);
      object.scale.setScalar(side);
    }
    return object;
  };
  return { geometry, lines, textured, placed };
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
  // The narrower of the two fields of view frames it (a phone's view is taller than wide).
  const vertical = THREE.MathUtils.degToRad(camera.fov);
  const horizontal = 2 * Math.atan(Math.tan(vertical / 2) * camera.aspect);
  const distance = sphere.radius / Math.sin(Math.min(vertical, horizontal) / 2) * 1.05;
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
  // A duotone is the surface itself, painted: drawn alone.
  surfaceObject.visible = style !== 'off' && resultObject?.material !== duotoneMaterial;
  surfaceMaterial.transparent = style === 'faint';
  surfaceMaterial.opacity = style === 'faint' ? 0.3 : 1;
  surfaceMaterial.depthWrite = style !== 'faint';
  surfaceMaterial.needsUpdate = true;
  redraw();
}

// ---- state and the API ------------------------------------------------------------------
const state = { session: null, picture: false, revision: 0, busy: false, lastUpdateMs: null, phases: null, error: null,
  stats: null, surfaceBox: null, full: null, stale: false, resultScale: 1 };
// What became of the full result asked after the last change (state.full): null (it is
// on screen, or none was asked), 'pending', 'stopped', 'refused' or 'failed'; and whether
// the view shows a result of other settings than the controls' (state.stale): a preview,
// or a result kept when the newer one was stopped or failed. Only a result that is not
// stale is offered for download.
window.studio = {
  state,
  // The latency script (latency.mjs) times a preview and a full update through this.
  make: (preview) => update([preview ? 'preview' : 'full']),
  // Nothing in flight or about to be asked (a change within the debounce, a plotter
  // drawing): what the browser test waits for, so that no pause of a busy machine can fool it.
  idle: () => !state.busy && debounce === null && plotterTicket === null,
  // For the browser test: the next request's job waits on the server until cancelled
  // (a server started with --test-hooks), so that a test holds it in flight.
  holdNext: () => { holdNext = true; },
  // What the browser test reads: the result in the scene, or the drawing in its place.
  resultInfo() {
    if (sheetShown()) {
      const img = $('drawing');
      return img.complete && img.naturalWidth > 0 ? { drawing: true, width: img.naturalWidth, height: img.naturalHeight } : null;
    }
    if (!resultObject) return null;
    const box = new THREE.Box3().setFromObject(resultObject);
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
let holdNext = false;

function showError(message) {
  state.error = message;
  $('error').textContent = message ?? '';
  $('error').hidden = !message;
}

function showNotice(message, offerFull = false) {
  $('notice-text').textContent = message ?? '';
  $('make-full').hidden = !offerFull;
  $('notice').hidden = !message;
}

const unreachable = 'The studio\'s server does not answer: it may have stopped. Run `meander serve` again, then reload this page.';

// The answer, or an Error with the server's message (status and whether the server
// cancelled the job kept on it).
async function api(path, options) {
  let response;
  try {
    response = await fetch(path, options);
  } catch (e) {
    if (e.name === 'AbortError') throw e;
    throw new Error(unreachable);
  }
  if (!response.ok) {
    let message = `HTTP ${response.status}`, cancelled = false;
    try {
      const body = await response.json();
      message = body.error ?? message;
      cancelled = body.cancelled === true;
    } catch { /* not JSON: keep the status */ }
    if (response.status === 404 && message.startsWith('unknown session')) message = 'This mesh is no longer on the server (it was restarted, or many meshes were opened since): open it again.';
    throw Object.assign(new Error(message), { status: response.status, cancelled });
  }
  return response;
}

const plural = (n, one, many) => `${n.toLocaleString()} ${n === 1 ? one : many}`;

// ---- progress and Stop --------------------------------------------------------------------
// The server's stage names, as a person reads them.
const stageNames = {
  remesh: 'remeshing evenly', 'slab mesh': 'preparing the slabs', connectivity: 'connecting the faces',
  quadrangulate: 'quadrangulating', cycle: 'finding the cycle', smooth: 'smoothing the curve', relax: 'evening the curve',
  project: 'placing the curve on the surface', evenness: 'measuring the gaps', radius: 'finding the radius',
  wire: 'making the wire', report: 'checking printability', duotone: 'colouring the quads', tiles: 'painting the tiles',
  subdivide: 'subdividing', 'separating curves': 'tracing the curve',
};
let progressTimer = null, progressPoll = null;
function showProgress(kind) {
  clearTimeout(progressTimer);
  clearInterval(progressPoll);
  if (!kind) {
    $('progress').hidden = true;
    return;
  }
  // Quick updates do not flash the indicator; longer work shows it, with the stage the
  // server is at.
  const label = kind === 'full' ? 'Making the full result' : kind === 'preview' ? 'Making a preview' : 'Opening the mesh';
  const fill = $('progress').querySelector('.fill');
  progressTimer = setTimeout(() => {
    $('progress-text').textContent = `${label}…`;
    fill.classList.remove('known');
    fill.style.width = '100%';
    $('stop').hidden = kind === 'upload';
    $('progress').hidden = false;
    if (kind === 'upload' || !state.session) return;
    const session = state.session;
    progressPoll = setInterval(async () => {
      try {
        const p = await (await fetch(`/api/progress/${session}`)).json();
        if (!p.busy || $('progress').hidden) return;
        const known = p.fraction >= 0;
        $('progress-text').textContent = `${label}: ${stageNames[p.stage] ?? p.stage}${known ? ` ${Math.round(p.fraction * 100)}%` : ''}…`;
        fill.classList.toggle('known', known);
        fill.style.width = known ? `${Math.max(2, p.fraction * 100)}%` : '100%';
      } catch { /* the request itself reports a lost server */ }
    }, 250);
  }, 150);
}

// ---- requests: each change replaces the work in flight ----------------------------------
// The chain of requests in flight: a preview then the full result, or one of them. A
// new change aborts it (the server cancels the job of an aborted request, and any newer
// request for the session cancels the older one's).
let job = null;

async function update(kinds) {
  if (!state.session) return;
  job?.controller.abort();
  const ticket = job = { controller: new AbortController(), kind: null };
  state.busy = true;
  state.stale = true;
  if (kinds.includes('full')) state.full = 'pending';
  try {
    for (const kind of kinds) {
      ticket.kind = kind;
      showProgress(kind);
      await makeOne(kind === 'preview', ticket);
      if (ticket !== job) return;
    }
    showNotice(null);
  } catch (e) {
    if (ticket !== job) return; // replaced: the newer request reports
    if (e.name === 'AbortError' || e.cancelled) return; // stopped: stop() says so
    const full = ticket.kind === 'full';
    state.full = e.status === 413 ? 'refused' : 'failed';
    const shown = state.stats?.preview ? 'the preview' : 'the result before the change';
    if (state.stats) {
      showStats(state.stats);
      showNotice(state.full === 'refused'
        ? `The view shows ${shown}: the ${full ? 'full result' : 'preview'} was refused as too large. Lower the setting the message names.`
        : `The view shows ${shown}: the ${full ? 'full result' : 'preview'} failed (see the message).`);
    }
    showError(e.message);
  } finally {
    if (ticket === job) {
      job = null;
      state.busy = false;
      showProgress(null);
      updateDownloads();
    }
  }
}

// One request: the result made, its view fetched and drawn.
async function makeOne(preview, ticket) {
  const { signal } = ticket.controller;
  const start = performance.now();
  const phases = {};
  let mark = start;
  const lap = (name) => { const now = performance.now(); phases[name] = now - mark; mark = now; };
  const body = { ...params(), preview };
  // A result made to a model size is in millimetres, scaled about the origin from the
  // surface (scaled_to_size): the view draws it back at the surface's scale.
  const sizeMm = state.picture ? null : modelSizeMillimetres();
  if (holdNext) {
    body.hold = true;
    holdNext = false;
  }
  const stats = await (await api('/api/make', {
    method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body), signal,
  })).json();
  lap('make');
  const current = () => ticket === job;
  if (state.picture) {
    // The sheet as drawing_image draws it at the size shown: a picture's SVG holds hundreds
    // of thousands of points, which the browser took seconds to draw (the download is the SVG).
    const ratio = window.devicePixelRatio || 1, box = $('sheet').getBoundingClientRect();
    const side = (pixels) => Math.min(4096, Math.max(16, Math.round(pixels * ratio)));
    const size = `${side(box.width - 32)}x${side(box.height - 44)}`;
    await showDrawing(await (await api(`/api/result/${state.session}/render.png?size=${size}`, { signal })).blob(), current);
    if (!current()) return;
    lap('draw');
    shown(stats, preview, start, phases);
    return;
  }
  const buffer = await (await api(`/api/result/${state.session}/view.bin`, { signal })).arrayBuffer();
  lap('fetch');
  if (ticket !== job) return;
  const { geometry, lines, textured, placed } = await parseView(buffer);
  lap('parse');
  if (ticket !== job) return;
  // The atlas depends on the tile options alone (stats.texture names them): it is
  // fetched only when they change, not on every seed or subdivision change.
  if (textured && stats.texture !== loadedTexture) {
    const texture = await new THREE.TextureLoader().loadAsync(`/api/result/${state.session}/texture.png?r=${stats.revision}`);
    if (ticket !== job) return;
    texture.colorSpace = THREE.SRGBColorSpace;
    texture.anisotropy = renderer.capabilities.getMaxAnisotropy();
    duotoneMaterial.map?.dispose();
    duotoneMaterial.map = texture;
    duotoneMaterial.needsUpdate = true;
    loadedTexture = stats.texture;
    lap('texture');
  }
  const material = lines ? curveMaterial : textured ? duotoneMaterial : resultMaterial;
  const object = placed(lines ? new THREE.LineSegments(geometry, material) : new THREE.Mesh(geometry, material));
  const size = state.surfaceBox?.getSize(new THREE.Vector3());
  state.resultScale = sizeMm && size ? Math.max(size.x, size.y, size.z) / sizeMm : 1;
  object.position.multiplyScalar(state.resultScale);
  object.scale.multiplyScalar(state.resultScale);
  resultObject = replace(resultObject, object);
  applySurfaceStyle();
  // The update ends when the frame showing it is drawn: the geometry's upload and the
  // first draw are part of it.
  draw();
  renderer.getContext().finish();
  lap('draw');
  if ($('plotter').checked) {
    await showDrawing(await (await api(`/api/result/${state.session}/curve.svg?${viewQuery()}`, { signal })).blob(), current);
    if (!current()) return;
    lap('plotter');
  }
  shown(stats, preview, start, phases);
}

// A result is on screen: the state and the stats say so.
function shown(stats, preview, start, phases) {
  state.lastUpdateMs = performance.now() - start;
  state.phases = phases;
  state.revision = stats.revision;
  state.stats = stats;
  if (!preview) state.full = null;
  state.stale = preview;
  showStats(stats);
  showError(null);
}

// A drawing (an SVG, or a picture's PNG) shown as an image of the sheet, unless
// `current()` says it is no longer wanted once decoded; the one before is let go.
let drawingUrl = null;
async function showDrawing(image, current) {
  const url = URL.createObjectURL(image);
  const img = new Image();
  img.src = url;
  try {
    await img.decode();
  } catch {
    URL.revokeObjectURL(url);
    throw new Error('the browser could not draw the drawing');
  }
  if (!current()) {
    URL.revokeObjectURL(url);
    return;
  }
  $('drawing').src = url;
  if (drawingUrl) URL.revokeObjectURL(drawingUrl);
  drawingUrl = url;
}

// Stops the work in flight: the view keeps what it shows.
function stop() {
  if (!job) return;
  job.controller.abort();
  job = null;
  state.busy = false;
  showProgress(null);
  fetch(`/api/cancel/${state.session}`, { method: 'POST' }).catch(() => {});
  state.full = 'stopped';
  if (state.stats) showStats(state.stats);
  showNotice(`Stopped: the view shows ${state.stats?.preview ? 'the preview' : 'the result before the change'}, and downloads wait for the full result.`, true);
  updateDownloads();
}

async function loadSurface(reply) {
  state.session = reply.session;
  state.revision = 0;
  state.stats = null;
  resultObject = replace(resultObject, null);
  $('drawing').removeAttribute('src');
  openedKind(reply.picture !== undefined);
  if (state.picture) {
    $('mesh-name').textContent = `${reply.name}: ${reply.picture.width.toLocaleString()} × ${reply.picture.height.toLocaleString()} pixels`;
    surfaceObject = replace(surfaceObject, null);
    state.surfaceBox = null;
  } else {
    const repairs = reply.repairs.length ? ` — repaired: ${reply.repairs.join('; ')}` : '';
    $('mesh-name').textContent = `${reply.name}: ${plural(reply.faces, 'face', 'faces')}${repairs}`;
    const buffer = await (await api(`/api/result/${reply.session}/surface.bin`)).arrayBuffer();
    const { geometry, placed } = await parseView(buffer);
    surfaceObject = replace(surfaceObject, placed(new THREE.Mesh(geometry, surfaceMaterial)));
    state.surfaceBox = new THREE.Box3().setFromObject(surfaceObject);
  }
  showSpacing();
  $('welcome').hidden = true;
  $('stats').innerHTML = '';
  applySurfaceStyle();
  fit();
  await update(['preview', 'full']);
}

// A picture takes picture mode alone, a mesh every other mode: the menu offers what the
// opened file takes, and a mode the file does not take gives way to one it does (the
// last mesh mode for a mesh).
let meshMode = 'curve';
function openedKind(picture) {
  state.picture = picture;
  for (const option of $('mode').options) option.disabled = (option.value === 'picture') !== picture;
  if (($('mode').value === 'picture') !== picture) {
    $('mode').value = picture ? 'picture' : meshMode;
    modeChanged();
    record();
  }
  showSheet();
}

// The sheet in place of the 3D view: a picture's drawing, or, with *Plotter drawing*
// checked, the drawing of the curve as the 3D view last showed it (uncheck to turn it).
const sheetShown = () => state.picture || $('plotter').checked;
function showSheet() {
  const sheet = sheetShown();
  $('view').hidden = sheet;
  $('sheet').hidden = !sheet;
  if (!sheet) resize();
}
let plotterTicket = null;
async function drawPlotter() {
  if (!sheetShown() || state.picture || state.revision === 0 || job) return;
  const ticket = plotterTicket = {};
  try {
    const svg = await (await api(`/api/result/${state.session}/curve.svg?${viewQuery()}`)).blob();
    await showDrawing(svg, () => ticket === plotterTicket);
  } catch (e) {
    showError(e.message);
  } finally {
    if (ticket === plotterTicket) plotterTicket = null;
  }
}

async function upload(file) {
  showNotice(null);
  let info;
  try {
    info = await (await api('/api/info')).json();
  } catch (e) {
    showError(e.message);
    return;
  }
  const extension = file.name.includes('.') ? file.name.slice(file.name.lastIndexOf('.')).toLowerCase() : '';
  if (!info.formats.includes(extension) && !info.pictures.includes(extension)) {
    showError(`${file.name}: not a mesh file or picture the studio reads (it reads ${info.formats.join(', ')}; ${info.pictures.join(', ')})`);
    return;
  }
  if (file.size > info.max_upload) {
    showError(`${file.name}: upload too large: ${file.size} bytes (this server's --max-upload is ${info.max_upload} bytes)`);
    return;
  }
  const form = new FormData();
  form.append('mesh', file, file.name);
  await openSurface(() => api('/api/mesh', { method: 'POST', body: form }));
}

async function openSurface(request) {
  job?.controller.abort();
  job = null;
  showError(null);
  showNotice(null);
  showProgress('upload');
  state.busy = true;
  let reply;
  try {
    reply = await (await request()).json();
  } catch (e) {
    showError(e.message);
    return;
  } finally {
    state.busy = false;
    showProgress(null);
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
// The bridges slider, the longest stretch of wire without a bridge, likewise from 1/40
// to 1/4 (about 4 spacings ties every pass; each bridge costs the full result time).
function sliderLength(id, smallest, largest) {
  const box = state.surfaceBox;
  if (!box || box.isEmpty()) return null;
  const size = box.getSize(new THREE.Vector3());
  const millimetres = modelSizeMillimetres();
  const scale = millimetres ? millimetres / Math.max(size.x, size.y, size.z) : 1;
  const t = Number($(id).value) / 100;
  return size.length() * scale * 10 ** (Math.log10(smallest) + t * (Math.log10(largest) - Math.log10(smallest)));
}
const spacingValue = () => sliderLength('spacing', 1 / 300, 1 / 10);
const bridgesValue = () => sliderLength('bridges', 1 / 40, 1 / 4);
function showSpacing() {
  const unit = modelSizeMillimetres() ? ' mm' : '';
  for (const [id, value] of [['spacing-value', spacingValue()], ['bridges-value', bridgesValue()]])
    $(id).textContent = value === null ? '' : `${value.toPrecision(3)}${unit}`;
}

function params() {
  const mode = $('mode').value;
  const sized = modelSizeMillimetres() !== null;
  // A picture's lengths are millimetres on paper; its job takes the shared curve controls.
  if (mode === 'picture') {
    return {
      session: state.session, mode, paper: $('paper').value, margin: Number($('margin').value), pen: Number($('pen').value),
      spacing: Number($('line-spacing').value), max_spacing: Number($('max-spacing').value), gamma: Number($('gamma').value),
      invert: $('invert').checked, branches: $('branches-on').checked ? Number($('branches').value) : 'none',
      tree: $('tree').value, seed: Number($('seed').value), smooth: $('smooth').value, samples: Number($('samples').value),
      colors: `${$('color0').value},${$('color1').value}`,
    };
  }
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
    bridges: $('bridges-on').checked && bridgesValue() !== null ? bridgesValue() : 'none',
    s: Number($('s').value),
    t: Number($('t').value),
    thickness: Number($('thickness').value),
    levels: Number($('levels').value),
    rule: $('rule').value,
    colors: `${$('color0').value},${$('color1').value}`,
    tiles: $('tiles').value,
    texture_size: Number($('texture-size').value),
    subdivide: Number($('subdivide').value),
    // Printed, a shell's wall is in millimetres: the model needs its size first.
    shell: $('shell-on').checked && sized ? Number($('shell').value) : 'none',
    clearance: $('shell-on').checked && sized ? Number($('clearance').value) : 0,
  };
}

function showStats(stats) {
  const yesNo = (b) => (b ? 'yes' : 'no');
  // A result made to a model size has its lengths in millimetres.
  const mm = stats.millimetres ? ' mm' : '';
  const what = { stopped: 'was stopped', refused: 'was refused', failed: 'failed' }[state.full];
  const of = stats.preview ? (state.full === 'pending' ? 'preview (the full result follows)' : what ? `preview (the full result ${what})` : 'preview')
    : state.stale && what ? `the result before the change (the new one ${what})` : 'full result';
  const rows = stats.mode === 'picture' ? [
    ['stats of', of],
    ['cells', stats.cells.toLocaleString()],
    ['sheet', `${stats.paper.map((x) => +x.toFixed(1)).join(' × ')} mm`],
    ['line length', `${(stats.curve_length / 1000).toPrecision(4)} m`],
    ['pen-up travel', `${stats.pen_up_travel.toFixed(0)} mm`],
  ] : [
    ['stats of', of],
    ['triangles', stats.triangles.toLocaleString()],
    [stats.mode === 'duotone' ? 'separating curves' : 'curves', stats.curves],
    ['curve length', `${stats.curve_length.toPrecision(5)}${mm}`],
  ];
  if (stats.mode === 'duotone') {
    rows.push(['quads', stats.quads.toLocaleString()], ['faces', stats.faces.toLocaleString()]);
    // As `meander duotone --shell`: the two solids, or why the surface has no shell.
    if (stats.shell?.volumes) {
      const below = stats.shell.below_floor_corners > 0 ? `, the wall thinner than the floor at ${plural(stats.shell.below_floor_corners, 'corner', 'corners')}` : '';
      const apart = stats.shell.apart !== undefined ? `, at least ${stats.shell.apart.toPrecision(2)} mm apart` : '';
      rows.push(['two-colour print', `2 solids of ${stats.shell.volumes.map((v) => v.toPrecision(4)).join(' and ')} mm³${apart}${below}`]);
    } else if (stats.shell?.refused) {
      rows.push(['two-colour print', `not made: ${stats.shell.refused}`]);
    }
  } else if (stats.mode !== 'curve' && stats.mode !== 'picture') {
    rows.push(['faces', stats.faces.toLocaleString()]);
    // Over the preview's budget a wire is previewed as its ribbon, a few times lighter, and
    // a variable one with a quad a triangle of the cycle instead of two.
    const lighter = [stats.preview_as_ribbon && 'its ribbon', stats.preview_rungs === 1 && 'a quad a triangle'].filter(Boolean);
    if (lighter.length) rows.push(['drawn as', `${lighter.join(', with ')}, until the full ${stats.mode.endsWith('wire') ? 'wire' : 'ribbon'} comes`]);
    if (!stats.preview) rows.push(['watertight', yesNo(stats.watertight)], ['self-intersection', yesNo(stats.self_intersecting)]);
    // As `meander wire` notes: where the surface itself crosses itself, no settings clear the wire.
    if (stats.surface_crossings > 0) {
      rows.push(['surface', `crosses itself (${stats.surface_crossings.toLocaleString()} of the cycle's triangles): a wire that follows it cannot be clear there`]);
    }
    // As `meander wire --method variable` notes: the mesh it was made on had large polygons
    // split and caps flipped (or cut off on the boundary).
    if (stats.stars > 0) rows.push(['polygons split', `${plural(stats.stars, 'polygon', 'polygons')} of 5 or more sides, into triangles`]);
    if (stats.cap_flips > 0) rows.push(['caps flipped', `${plural(stats.cap_flips, 'edge', 'edges')} (flat triangles fold the slabs)`]);
    if (stats.cap_cuts > 0) rows.push(['caps cut off', `${plural(stats.cap_cuts, 'triangle', 'triangles')} on the boundary`]);
    if (stats.needle_collapses > 0) rows.push(['needles collapsed', `${plural(stats.needle_collapses, 'short edge', 'short edges')} (needles and folded triangles fold the slabs)`]);
    if (stats.radius) rows.push(['radius', `${stats.radius.toPrecision(4)}${mm}`]);
    // As `meander wire --bridges`: how many, and whether they tie every pass.
    if (stats.bridges) {
      rows.push(['bridges', `${stats.bridges.count.toLocaleString()}, the longest stretch without one ${stats.bridges.longest_stretch.toPrecision(3)}${mm}${stats.bridges.every_pass_tied ? ': every pass tied' : ''}`]);
    }
  }
  if (stats.gap_median !== undefined) {
    rows.push(['median gap', `${stats.gap_median.toPrecision(3)}${mm} (CV ${stats.gap_cv.toFixed(2)})`]);
  }
  if (stats.leaves !== undefined) rows.push(['branch tips', stats.leaves.toLocaleString()]);
  rows.push(['made in', `${(stats.seconds * 1000).toFixed(0)} ms`], ['update', `${state.lastUpdateMs.toFixed(0)} ms`]);
  // On a phone only the first rows show (the stats must not cover the view).
  $('stats').innerHTML = rows.map(([k, v], i) => `<tr${i > 2 ? ' class="detail"' : ''}><th scope="row">${k}</th><td>${v}</td></tr>`).join('');
}

function updateDownloads() {
  const noMesh = ['curve', 'picture'].includes($('mode').value);
  for (const a of document.querySelectorAll('#downloads a')) {
    // A preview is not offered for download: the full result follows it.
    const enabled = state.revision > 0 && !state.busy && !state.stale && !(noMesh && a.hasAttribute('data-mesh')) &&
      !(a.hasAttribute('data-print') && !state.stats?.shell?.volumes);
    a.setAttribute('aria-disabled', String(!enabled));
    if (enabled) {
      a.href = `/api/result/${state.session}/${a.dataset.file}`;
      a.setAttribute('download', '');
    } else {
      // Not a link while disabled: not in the Tab order, nothing to follow.
      a.removeAttribute('href');
      a.removeAttribute('download');
    }
  }
}
// The render and the plotter drawing as the view shows them: the camera on screen, at the
// view's size (the drawing's sheet turned as the view is).
// A result in millimetres is seen from the camera in millimetres too.
function viewQuery() {
  const v = (vector) => vector.toArray().map((x) => x.toPrecision(7)).join(',');
  const mm = (point) => v(point.clone().divideScalar(state.resultScale));
  return `eye=${mm(camera.position)}&target=${mm(controls.target)}&up=${v(camera.up)}&fov=${camera.fov}&size=${viewSize.w}x${viewSize.h}`;
}
for (const file of ['render.png', 'curve.svg']) {
  $('downloads').querySelector(`a[data-file="${file}"]`).addEventListener('click', (e) => {
    const a = e.currentTarget;
    if (a.href) a.href = `/api/result/${state.session}/${file}?${viewQuery()}`;
  });
}

// ---- controls -----------------------------------------------------------------------------
// Every control the settings are made of, as the URL and the local storage keep them.
const settingIds = ['mode', 'model-size', 'spacing-on', 'spacing', 'branches-on', 'branches', 'quad', 'tree', 'seed', 'smooth',
  'samples', 'radius', 'radius-auto', 'sides', 'bridges-on', 'bridges', 'nozzle', 's', 't', 'thickness', 'levels', 'rule', 'color0', 'color1', 'tiles',
  'texture-size', 'subdivide', 'shell-on', 'shell', 'clearance', 'surface', 'plotter', 'paper', 'margin', 'pen', 'line-spacing', 'max-spacing', 'gamma', 'invert'];
const valueOf = (el) => (el.type === 'checkbox' ? (el.checked ? '1' : '0') : el.value);
const defaults = Object.fromEntries(settingIds.map((id) => [id, valueOf($(id))]));
function settings() {
  return Object.fromEntries(settingIds.map((id) => [id, valueOf($(id))]));
}
function applySettings(values) {
  for (const id of settingIds) {
    const el = $(id);
    let value = values[id] ?? defaults[id];
    // A menu keeps its default for a choice it does not have (an old or edited link).
    if (el.tagName === 'SELECT' && ![...el.options].some((o) => o.value === value)) value = defaults[id];
    if (el.type === 'checkbox') el.checked = value === '1';
    else el.value = value;
  }
  // The opened file keeps a mode it takes (an undo past the opening of a picture).
  if (state.session && ($('mode').value === 'picture') !== state.picture) $('mode').value = state.picture ? 'picture' : meshMode;
  previousMode = $('mode').value;
  syncControls();
}
// The URL's query holds the settings that differ from the defaults: a link shares them.
function saveSettings() {
  const values = settings();
  const query = new URLSearchParams(Object.entries(values).filter(([id, v]) => v !== defaults[id]));
  history.replaceState(null, '', query.size ? `?${query}` : location.pathname);
  try { localStorage.setItem('meander-studio', JSON.stringify(values)); } catch { /* private mode: the URL keeps them */ }
}
function restoreSettings() {
  const query = new URLSearchParams(location.search);
  let values = null;
  if ([...query.keys()].some((k) => settingIds.includes(k))) {
    values = Object.fromEntries([...query].filter(([k]) => settingIds.includes(k)));
  } else {
    try { values = JSON.parse(localStorage.getItem('meander-studio') ?? 'null'); } catch { values = null; }
  }
  if (values) applySettings(values);
}

// Undo and redo of parameter changes: each committed change is a snapshot.
const past = [], future = [];
let current = null;
function record() {
  const now = settings();
  if (current && JSON.stringify(now) === JSON.stringify(current)) return;
  if (current) past.push(current);
  future.length = 0;
  current = now;
  saveSettings();
  $('undo').disabled = past.length === 0;
  $('redo').disabled = true;
}
function travel(from, to) {
  if (from.length === 0) return;
  to.push(current);
  current = from.pop();
  applySettings(current);
  saveSettings();
  $('undo').disabled = past.length === 0;
  $('redo').disabled = future.length === 0;
  changed();
}
$('undo').addEventListener('click', () => travel(past, future));
$('redo').addEventListener('click', () => travel(future, past));
document.addEventListener('keydown', (e) => {
  // A text field keeps its own undo.
  if (!(e.ctrlKey || e.metaKey) || e.target.matches?.('input[type=text], input[type=number]')) return;
  const key = e.key.toLowerCase();
  if (key === 'z' && !e.shiftKey) travel(past, future);
  else if ((key === 'z' && e.shiftKey) || key === 'y') travel(future, past);
  else return;
  e.preventDefault();
});

let debounce = null;
function changed(event) {
  clearTimeout(debounce);
  // A slider being dragged fires 'input' (previews only); letting it go fires 'change'
  // (the full result, whose preview is on screen already). Any other change shows its
  // preview first, then the full result: the view follows within the preview's time
  // even where the full result (a wire's printability report) takes seconds.
  const slider = event?.target?.type === 'range';
  const dragging = slider && event.type === 'input', released = slider && event.type === 'change';
  if (!dragging) record();
  showNotice(null);
  debounce = setTimeout(() => {
    debounce = null;
    update(released ? ['full'] : dragging ? ['preview'] : ['preview', 'full']);
  }, 30);
}

function showModeControls() {
  const mode = $('mode').value;
  for (const el of document.querySelectorAll('[data-modes]')) el.hidden = !el.dataset.modes.split(' ').includes(mode);
  showHelp();
  updateDownloads();
}

// Which control the focus or the pointer is on shows its help, the text of the
// parameter's `--help` (GET /api/parameters, for the mode's command); the page's own
// controls have theirs here.
const pageHelp = {
  mode: 'what to make: the curve, a wire or ribbon along it (constant: a tube of one radius; variable: slabs that fill the surface), or a two-colour surface split by the curve; of a picture, its drawing with one closed line',
  'radius-auto': 'the largest radius that keeps the wire clear of itself',
  'bridges-on': 'fuse neighbouring passes with struts, so that the printed wire is one rigid piece (in the full result: a preview shows the wire without them)',
  'shell-on': 'thicken the surface inward into a shell cut along the curve into two solids, one per colour, for a two-extruder printer (the Two-colour print download; needs a model size)',
  surface: 'how the input surface is drawn behind the result',
  plotter: 'show the pen plotter\'s drawing of the curve as the view shows it, its back hidden, on A4 (the Plotter SVG download); uncheck to turn the view again',
  nozzle: 'the printer\'s nozzle width in millimetres: with a model size, the wire must be 2 nozzles thick and its parts a nozzle apart',
};
let parameterHelp = null;
function helpFor(id) {
  const name = $(id).dataset.help ?? id.replaceAll('-', '_');
  const mode = $('mode').value;
  const list = parameterHelp?.[['curve', 'duotone', 'picture'].includes(mode) ? mode : 'wire'];
  return list?.find((p) => p.name === name)?.help ?? pageHelp[id] ?? null;
}
function showHelp() {
  for (const id of settingIds) {
    const el = $(id), text = helpFor(id), help = $(`help-${id}`);
    if (!help || !text) continue;
    help.textContent = text;
    el.title = text;
  }
}
// A help text that goes away moves up what is below it. When a press moves the focus, the
// help of the control it leaves waits for the release, so that the click lands on what
// was pressed (else a checkbox below a focused field moved away under the pointer).
let pressed = false;
const released = [];
document.addEventListener('pointerdown', () => { pressed = true; }, true);
for (const end of ['pointerup', 'pointercancel']) {
  document.addEventListener(end, () => {
    pressed = false;
    setTimeout(() => released.splice(0).forEach((f) => f()));
  }, true);
}
const afterRelease = (f) => (pressed ? released.push(f) : f());
function addHelp() {
  for (const id of settingIds) {
    if (!helpFor(id) || $(`help-${id}`)) continue;
    const el = $(id);
    const help = document.createElement('small');
    help.id = `help-${id}`;
    help.className = 'help';
    help.hidden = true;
    // After the control, or after the row it sits in.
    const anchor = el.parentElement.classList.contains('row') ? el.parentElement : el;
    anchor.after(help);
    el.setAttribute('aria-describedby', help.id);
    const show = (on) => () => { help.hidden = !on && document.activeElement !== el; };
    el.addEventListener('focus', show(true));
    el.addEventListener('blur', () => afterRelease(show(false)));
    el.addEventListener('mouseenter', show(true));
    el.addEventListener('mouseleave', show(false));
  }
  showHelp();
}

for (const output of document.querySelectorAll('output[for]')) {
  const input = $(output.htmlFor.value);
  if (input.type !== 'range' || output.id) continue;
  const show = () => { output.textContent = input.value; };
  input.addEventListener('input', show);
  show();
}
for (const id of settingIds) {
  if (id === 'surface' || id === 'plotter') continue;
  const el = $(id);
  // Typed values apply on Enter or when the field is left, not at every keystroke.
  const typed = ['text', 'number', 'color'].includes(el.type);
  el.addEventListener(typed ? 'change' : 'input', changed);
  if (el.type === 'range') el.addEventListener('change', changed);
}
// Duotone starts from its command's default quads (Catmull-Clark topology), the others
// from dual-simplest, as `meander duotone` and `meander curve`/`wire` do. Variable wires
// and ribbons start from the shaped tree, as `meander wire --method variable` does (their
// slabs fold where the cycle turns round in a thin triangle), unless another tree than
// the previous mode's default was chosen.
let previousMode = $('mode').value;
const defaultTree = (mode) => (mode.startsWith('variable') ? 'shaped' : 'random');
function modeChanged() {
  const mode = $('mode').value;
  if ((mode === 'duotone') !== (previousMode === 'duotone')) $('quad').value = mode === 'duotone' ? 'catmull-clark' : 'dual-simplest';
  if ($('tree').value === defaultTree(previousMode)) $('tree').value = defaultTree(mode);
  previousMode = mode;
  if (mode !== 'picture') meshMode = mode;
  showModeControls();
}
$('mode').addEventListener('input', modeChanged, { capture: true });
// The enabled state of the controls that follow others.
function syncControls() {
  $('radius').disabled = $('radius-auto').checked;
  $('spacing').disabled = !$('spacing-on').checked;
  $('branches').disabled = !$('branches-on').checked;
  $('bridges').disabled = !$('bridges-on').checked;
  $('shell-on').disabled = modelSizeMillimetres() === null;
  $('shell').disabled = $('clearance').disabled = !$('shell-on').checked || $('shell-on').disabled;
  for (const output of document.querySelectorAll('output[for]')) if (!output.id) output.textContent = $(output.htmlFor.value).value;
  showSpacing();
  showModeControls();
  applySurfaceStyle();
  showSheet();
}
for (const id of ['radius-auto', 'spacing-on', 'branches-on', 'bridges-on', 'shell-on', 'model-size']) $(id).addEventListener('input', syncControls, { capture: true });
for (const id of ['spacing', 'bridges', 'model-size']) $(id).addEventListener('input', showSpacing);
$('new-seed').addEventListener('click', () => {
  $('seed').value = Math.floor(Math.random() * 2 ** 31);
  changed();
});
$('surface').addEventListener('input', () => {
  applySurfaceStyle();
  record();
});
$('plotter').addEventListener('input', () => {
  showSheet();
  record();
  drawPlotter();
});
$('fit').addEventListener('click', fit);
$('stop').addEventListener('click', stop);
$('make-full').addEventListener('click', () => {
  showNotice(null);
  update(['full']);
});
const openDemo = () => openSurface(() => api('/api/demo', { method: 'POST' }));
$('demo').addEventListener('click', openDemo);
$('welcome-demo').addEventListener('click', openDemo);
for (const id of ['drop', 'welcome-open']) $(id).addEventListener('click', () => $('file').click());
$('file').addEventListener('change', (e) => {
  if (e.target.files[0]) upload(e.target.files[0]);
  e.target.value = ''; // the same file again is a change too
});
// A file dropped anywhere on the page opens it (the browser would otherwise open the
// file in place of the studio).
let dragDepth = 0;
const carriesFiles = (e) => [...(e.dataTransfer?.types ?? [])].includes('Files');
document.addEventListener('dragenter', (e) => {
  if (!carriesFiles(e)) return;
  e.preventDefault();
  dragDepth += 1;
  $('drop-overlay').hidden = false;
});
document.addEventListener('dragover', (e) => { if (carriesFiles(e)) e.preventDefault(); });
document.addEventListener('dragleave', () => {
  dragDepth = Math.max(0, dragDepth - 1);
  if (dragDepth === 0) $('drop-overlay').hidden = true;
});
document.addEventListener('drop', (e) => {
  e.preventDefault();
  dragDepth = 0;
  $('drop-overlay').hidden = true;
  if (e.dataTransfer?.files[0]) upload(e.dataTransfer.files[0]);
});
// On a narrow screen the settings fold away under their button, leaving the view.
const narrow = window.matchMedia('(max-width: 700px)');
function foldPanel(folded) {
  $('panel').classList.toggle('collapsed', folded);
  $('panel-toggle').setAttribute('aria-expanded', String(!folded));
}
$('panel-toggle').addEventListener('click', () => foldPanel(!$('panel').classList.contains('collapsed')));
foldPanel(narrow.matches);
narrow.addEventListener('change', (e) => foldPanel(e.matches));
// Leaving the page stops its work on the server.
window.addEventListener('pagehide', () => { if (job && state.session) navigator.sendBeacon(`/api/cancel/${state.session}`); });

restoreSettings();
syncControls();
current = settings();
saveSettings();
updateDownloads();

api('/api/parameters').then((reply) => reply.json()).then((modes) => {
  parameterHelp = modes;
  addHelp();
}).catch(() => addHelp()); // the page's own help still shows
addHelp();
