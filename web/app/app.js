// The web app of `gproj serve`: open a mesh (a shipped example, a file, or one dropped on the
// page), choose a problem, set its options (a form built from GET /api/schema), run it with the
// iterations streamed (GET /api/runs/{id}/events), see the faces coloured by the problem's
// measure relative to the tolerance, fix vertices by clicking them and drag one to re-solve from
// the last result (POST /api/runs/{id}/resolve).
//
// <body data-status> is idle, running, converged, not-converged or failed; the URL
// /?example=NAME&problem=NAME&run=1 opens an example, picks a problem and runs it. window.gproj
// exposes the state and a few helpers (vertexOnScreen) for scripts and tests.

import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import GUI from 'lil-gui';

const params = new URLSearchParams(location.search);
const token = params.get('token');
const DRAG_TOLERANCE = 1e-3;  // re-solves while a vertex is dragged stop here (the release's at the run's)

// ---------------------------------------------------------------------------------------------
// The service

async function api(path, body, method) {
  const headers = {};
  if (token) headers.Authorization = 'Bearer ' + token;
  const init = { method: method || (body === undefined ? 'GET' : 'POST'), headers };
  if (body !== undefined) {
    headers['Content-Type'] = 'application/json';
    init.body = JSON.stringify(body);
  }
  const response = await fetch(path, init);
  const answer = await response.json().catch(() => ({ error: `${path}: HTTP ${response.status}` }));
  if (!response.ok) throw new Error(answer.error || `${path}: HTTP ${response.status}`);
  return answer;
}

// Follows a run's events until its end; onRecord(record, columns) for each iteration,
// onIterate(vertices) for each iterate the service sends. Resolves with GET /api/runs/{id}
// (status, report, result).
function follow(id, onRecord, onIterate) {
  return new Promise((resolve, reject) => {
    const source = new EventSource(`/api/runs/${id}/events` + (token ? `?token=${encodeURIComponent(token)}` : ''));
    let columns = [];
    let ended = false;
    source.addEventListener('columns', (e) => { columns = JSON.parse(e.data).columns || []; });
    source.addEventListener('record', (e) => onRecord && onRecord(JSON.parse(e.data), columns));
    source.addEventListener('iterate', (e) => {
      const data = JSON.parse(e.data);
      if (onIterate && Array.isArray(data.vertices)) onIterate(data.vertices);
    });
    source.addEventListener('end', () => {
      ended = true;
      source.close();
      api(`/api/runs/${id}`).then(resolve, reject);
    });
    source.onerror = () => {
      if (ended) return;
      source.close();
      // The stream went away (a restart, a proxy): the run's state still says how it ended.
      api(`/api/runs/${id}`).then((run) => {
        if (['queued', 'running'].includes(run.status)) reject(new Error('the event stream was cut'));
        else resolve(run);
      }, reject);
    };
  });
}

// ---------------------------------------------------------------------------------------------
// State

const state = {
  schema: null,
  examples: [],
  inputs: {},          // the open example's inputs as a run takes them (input name -> value)
  main: null,          // which of them `start` shows (null: start is a file opened)
  exampleOutputs: [],  // optional outputs the example asks for
  problem: null,       // its schema entry
  options: {},         // option name -> value shown in the form
  start: null,         // the mesh opened: {vertices, faces}
  result: null,        // the last result's mesh of the same connectivity, or null
  surface: null,       // a result's surface mesh (hnet), or null
  figure: null,        // a result's picture beside the view (weingarten's curvature diagram)
  faceTable: null,     // the result's per-face values (face_values): {name: [value per face]}
  colourBy: '',        // the column of faceTable the faces are coloured by
  report: null,
  fixed: new Set(),
  showing: 'after',    // or 'before'
  base: null,          // the finished run a drag re-solves from
  runs: 0,             // runs finished (first runs and re-solves)
  resolves: 0,         // re-solves finished
  iterates: 0,         // iterates of first runs shown while they ran
  status: 'idle',
  measure: null,       // {name, value, tolerance}
  target: null,        // {key, measure, tolerance}: what the tolerance bounds, from the last report
  records: [],
  error: '',
};

function setStatus(status, message) {
  state.status = status;
  document.body.dataset.status = status;
  document.getElementById('state').textContent = status;
  if (message !== undefined) setMessage(message);
}

function setMessage(message) {
  state.error = message;
  document.getElementById('message').textContent = message;
}

// ---------------------------------------------------------------------------------------------
// The view

const container = document.getElementById('view');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
container.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x2a2d31);
const camera = new THREE.PerspectiveCamera(40, 1, 0.001, 1000);
const controls = new OrbitControls(camera, renderer.domElement);
scene.add(new THREE.HemisphereLight(0xffffff, 0x444444, 2.0));
const sun = new THREE.DirectionalLight(0xffffff, 1.5);
scene.add(sun);
const model = new THREE.Group();
scene.add(model);

function resize() {
  const w = container.clientWidth, h = container.clientHeight;
  renderer.setSize(w, h);
  camera.aspect = w / Math.max(1, h);
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);
resize();

function frameMesh(mesh) {
  const box = new THREE.Box3();
  for (const p of mesh.vertices) box.expandByPoint(new THREE.Vector3(p[0], p[1], p[2]));
  const centre = box.getCenter(new THREE.Vector3());
  const radius = Math.max(1e-9, box.getSize(new THREE.Vector3()).length() / 2);
  camera.near = radius / 100;
  camera.far = radius * 100;
  camera.position.copy(centre).add(new THREE.Vector3(0.9, -1.6, 1.3).multiplyScalar(radius * 1.4));
  camera.up.set(0, 0, 1);
  camera.updateProjectionMatrix();
  controls.target.copy(centre);
  controls.update();
  sun.position.copy(centre).add(new THREE.Vector3(1, -1, 2).multiplyScalar(radius * 4));
}

// Colour of t in [0, 1]: blue, green, yellow, red.
function ramp(t) {
  const stops = [[0.2, 0.35, 0.85], [0.2, 0.75, 0.45], [0.95, 0.85, 0.25], [0.85, 0.2, 0.2]];
  const x = Math.min(1, Math.max(0, t)) * (stops.length - 1);
  const i = Math.min(stops.length - 2, Math.floor(x));
  const f = x - i;
  return stops[i].map((c, k) => c + f * (stops[i + 1][k] - c));
}

// How values map to colours. Distances (planarity, star planarity, concyclicity, relative to
// the mean edge) on a log scale: at the tolerance green-yellow, three decades below blue, three
// above red. Angles (kink_deg, min_angle_deg) linearly over their range, the worse end red.
function scaleOf(name, values) {
  if (!name.endsWith('_deg')) return { log: true, tolerance: toleranceOf() };
  let lo = Infinity, hi = -Infinity;
  for (const v of values) if (v !== null && Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  if (!(hi > lo)) hi = lo + 1;
  return { log: false, lo, hi, reversed: name.startsWith('min_') };
}

function colourOf(value, scale) {
  if (value === null || !Number.isFinite(value)) return [0.6, 0.6, 0.6];
  if (scale.log) return ramp((Math.log10(Math.max(value, 1e-300)) - Math.log10(scale.tolerance) + 3) / 6);
  const t = (value - scale.lo) / (scale.hi - scale.lo);
  return ramp(scale.reversed ? 1 - t : t);
}

function disposeModel() {
  for (const child of [...model.children]) {
    model.remove(child);
    child.geometry && child.geometry.dispose();
    child.material && child.material.dispose();
  }
}

function draw() {
  disposeModel();
  const mesh = shownMesh();
  if (!mesh) return;
  const [name, values] = shownValues();
  const scale = values ? scaleOf(name, values) : null;
  const positions = [], colours = [], edges = [];
  mesh.faces.forEach((face, f) => {
    const c = values ? colourOf(values[f], scale) : [0.75, 0.75, 0.78];
    for (let k = 1; k + 1 < face.length; ++k)
      for (const v of [face[0], face[k], face[k + 1]]) {
        positions.push(...mesh.vertices[v]);
        colours.push(...c);
      }
    for (let k = 0; k < face.length; ++k) {
      const a = face[k], b = face[(k + 1) % face.length];
      if (a < b || !sharedEdge(mesh, a, b)) edges.push(...mesh.vertices[a], ...mesh.vertices[b]);
    }
  });
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
  geometry.setAttribute('color', new THREE.Float32BufferAttribute(colours, 3));
  geometry.computeVertexNormals();
  const faces = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({
    vertexColors: true, side: THREE.DoubleSide, flatShading: true, roughness: 0.8,
    polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
    transparent: !!(state.surface && state.showing === 'after'), opacity: state.surface ? 0.35 : 1 }));
  model.add(faces);
  const lines = new THREE.BufferGeometry();
  lines.setAttribute('position', new THREE.Float32BufferAttribute(edges, 3));
  model.add(new THREE.LineSegments(lines, new THREE.LineBasicMaterial({ color: 0x202020 })));
  if (state.surface && state.showing === 'after') {
    const s = state.surface, p = [];
    for (const face of s.faces)
      for (let k = 1; k + 1 < face.length; ++k)
        for (const v of [face[0], face[k], face[k + 1]]) p.push(...s.vertices[v]);
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(p, 3));
    g.computeVertexNormals();
    model.add(new THREE.Mesh(g, new THREE.MeshStandardMaterial({
      color: 0xb8c4d8, side: THREE.DoubleSide, roughness: 0.5, metalness: 0.1 })));
  }
  if (state.fixed.size) {
    const p = [];
    for (const v of state.fixed) if (v < mesh.vertices.length) p.push(...mesh.vertices[v]);
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(p, 3));
    model.add(new THREE.Points(g, new THREE.PointsMaterial({ color: 0xff3030, size: 9, sizeAttenuation: false, depthTest: false })));
  }
  drawLegend(name, values, scale);
}

// Whether edge (a, b) also belongs to another face (then it is drawn once, from its a < b side).
let edgeSets = new WeakMap();
function sharedEdge(mesh, a, b) {
  let set = edgeSets.get(mesh.faces);
  if (!set) {
    set = new Set();
    for (const face of mesh.faces)
      for (let k = 0; k < face.length; ++k) set.add(face[k] + ',' + face[(k + 1) % face.length]);
    edgeSets.set(mesh.faces, set);
  }
  return set.has(b + ',' + a);
}

function shownMesh() {
  return state.showing === 'after' && state.result ? state.result : state.start;
}

// [name, value per face] of what the faces are coloured by, or [name, null].
function shownValues() {
  const mesh = shownMesh();
  if (!mesh) return ['', null];
  if (state.showing === 'after' && state.result && state.faceTable && state.faceTable[state.colourBy])
    return [state.colourBy, state.faceTable[state.colourBy]];
  return ['planarity', planarityShown() ? quadPlanarity(mesh) : null];
}

// Whether faces are coloured by quad planarity when the service sent no values of its own (the
// input of planarize; marionette's input and result).
function planarityShown() {
  return !!state.problem && ['planarize', 'marionette'].includes(state.problem.name);
}

// Planarity of each quad of `mesh` as gproj measures it: the distance between its diagonals over
// the mesh's mean edge length (null for other faces). The result's values come from the service.
function quadPlanarity(mesh) {
  if (!state.problem || !mesh.faces.every((f) => f.length === 4)) return null;
  const P = (i) => new THREE.Vector3(...mesh.vertices[i]);
  let total = 0, count = 0;
  for (const face of mesh.faces)
    for (let k = 0; k < 4; ++k) { total += P(face[k]).distanceTo(P(face[(k + 1) % 4])); ++count; }
  const mean = total / Math.max(1, count);
  return mesh.faces.map(([a, b, c, d]) => {
    const u = P(c).sub(P(a)), v = P(d).sub(P(b)), w = P(b).sub(P(a));
    const n = new THREE.Vector3().crossVectors(u, v);
    return n.length() > 0 ? Math.abs(n.dot(w)) / n.length() / mean : 0;
  });
}

// The measure the problem's tolerance bounds and the bound: what the last run of the same problem
// and options reported (tolerance_measure), else the problem's first live measure and its
// tolerance option.
function targetOf() {
  const key = state.problem ? state.problem.name + JSON.stringify(optionValues()) : '';
  return state.target && state.target.key === key ? state.target : null;
}

function toleranceOf() {
  const target = targetOf();
  if (target) return target.tolerance;
  const t = Number(state.options.tolerance);
  return Number.isFinite(t) && t > 0 ? t : 1e-3;
}

function drawLegend(name, values, scale) {
  const bar = document.getElementById('legend-bar');
  const g = bar.getContext('2d');
  for (let x = 0; x < bar.width; ++x) {
    const [r, gr, b] = ramp(x / (bar.width - 1));
    g.fillStyle = `rgb(${r * 255},${gr * 255},${b * 255})`;
    g.fillRect(x, 0, 1, bar.height);
  }
  const measure = name.replace(/_/g, ' ');
  const min = document.getElementById('legend-min'), max = document.getElementById('legend-max');
  const label = document.getElementById('legend-name');
  bar.style.visibility = values ? 'visible' : 'hidden';
  if (!values) {
    min.textContent = max.textContent = label.textContent = '';
    return;
  }
  if (scale.log) {
    let largest = 0;
    for (const v of values) if (v !== null && v > largest) largest = v;
    const edge = meanEdge(shownMesh());
    min.textContent = `≤ ${(scale.tolerance / 1e3).toExponential(0)}`;
    max.textContent = `≥ ${(scale.tolerance * 1e3).toExponential(0)}`;
    label.textContent = `${measure} / mean edge (tolerance ${scale.tolerance.toExponential(0)} in the middle); ` +
      `largest ${largest.toExponential(2)} = ${(largest * edge).toExponential(2)} model units`;
  } else {
    min.textContent = `${(scale.reversed ? scale.hi : scale.lo).toFixed(2)}°`;
    max.textContent = `${(scale.reversed ? scale.lo : scale.hi).toFixed(2)}°`;
    label.textContent = `${measure.replace(/ deg$/, '')} (degrees)`;
  }
}

function meanEdge(mesh) {
  if (!mesh) return 0;
  let total = 0, count = 0;
  for (const face of mesh.faces)
    for (let k = 0; k < face.length; ++k) {
      const a = mesh.vertices[face[k]], b = mesh.vertices[face[(k + 1) % face.length]];
      total += Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
      ++count;
    }
  return total / Math.max(1, count);
}

function animate() {
  requestAnimationFrame(animate);
  renderer.render(scene, camera);
}
animate();

// ---------------------------------------------------------------------------------------------
// The chart of the problem's measure, one point per iteration (log scale), with the tolerance.

function drawChart() {
  const canvas = document.getElementById('chart');
  const g = canvas.getContext('2d');
  g.clearRect(0, 0, canvas.width, canvas.height);
  const name = measureName();
  const points = state.records.map((r) => r[name]).filter((v) => typeof v === 'number' && v > 0);
  if (!points.length) return;
  const tol = toleranceOf();
  const logs = points.map(Math.log10);
  const lo = Math.min(...logs, Math.log10(tol)) - 0.5, hi = Math.max(...logs, Math.log10(tol)) + 0.5;
  const X = (i) => 30 + (canvas.width - 40) * (points.length > 1 ? i / (points.length - 1) : 0);
  const Y = (l) => canvas.height - 14 - (canvas.height - 24) * (l - lo) / (hi - lo);
  g.strokeStyle = '#7c7'; g.setLineDash([4, 3]);
  g.beginPath(); g.moveTo(30, Y(Math.log10(tol))); g.lineTo(canvas.width - 10, Y(Math.log10(tol))); g.stroke();
  g.setLineDash([]); g.strokeStyle = '#6af'; g.lineWidth = 2;
  g.beginPath();
  logs.forEach((l, i) => (i ? g.lineTo(X(i), Y(l)) : g.moveTo(X(i), Y(l))));
  g.stroke();
  g.fillStyle = '#aaa'; g.font = '10px sans-serif';
  g.fillText(`1e${Math.round(hi)}`, 0, 10);
  g.fillText(`1e${Math.round(lo)}`, 0, canvas.height - 14);
  g.fillText(`${name} per iteration (tolerance dashed)`, 34, canvas.height - 2);
}

function measureName() {
  const target = targetOf();
  if (target) return target.measure;
  return state.problem && state.problem.log_measures && state.problem.log_measures.length
    ? state.problem.log_measures[0] : 'max_constraint';
}

function showMeasure(value) {
  const name = measureName();
  const el = document.getElementById('measure');
  state.measure = { name, value, tolerance: toleranceOf() };
  el.dataset.value = value === null || value === undefined ? '' : String(value);
  el.textContent = value === null || value === undefined ? '' :
    `${name} ${Number(value).toExponential(2)} (tolerance ${toleranceOf().toExponential(0)})`;
}

// ---------------------------------------------------------------------------------------------
// The panel

const gui = new GUI({ title: 'gproj', container: document.getElementById('panel') });
const actions = {
  example: '',
  problem: '',
  open: () => document.getElementById('file').click(),
  run: () => run(),
  cancel: () => cancel(),
  before: false,
  colourBy: '',
  clearFixed: () => { state.fixed.clear(); draw(); },
  downloadMesh: () => downloadMesh(),
  downloadReport: () => downloadReport(),
};
let exampleControl, problemControl, optionsFolder, runControl, colourControl;

const MAIN_KINDS = ['mesh', 'quad_mesh', 'bspline'];

// Problems that run on one mesh or B-spline, the rest of their inputs optional (marionette's
// plan is optional because a closed strip may replace it).
function usableProblems() {
  return state.schema.problems.filter((p) => {
    const main = mainInputOf(p);
    return main && p.inputs.every((i) => i === main || !i.required);
  });
}

// The input the view shows: the first mesh or B-spline input.
function mainInputOf(problem) {
  return problem.inputs.find((i) => MAIN_KINDS.includes(i.kind));
}

function buildPanel() {
  const examples = Object.fromEntries(state.examples.map((e) => [e.title, e.name]));
  exampleControl = gui.add(actions, 'example', { '(choose)': '', ...examples }).name('Example')
    .onChange((name) => name && opening(openExample(name)));
  gui.add(actions, 'open').name('Open a mesh file…');
  const names = usableProblems().map((p) => p.name);
  problemControl = gui.add(actions, 'problem', names).name('Problem').onChange((name) => selectProblem(name));
  optionsFolder = gui.addFolder('Options');
  runControl = gui.add(actions, 'run').name('Run');
  gui.add(actions, 'cancel').name('Cancel');
  // In a folder of its own: a menu whose choices change is replaced, at the end of its folder.
  colourControl = gui.addFolder('Faces').add(actions, 'colourBy', ['(after a run)']).name('Colour by');
  gui.add(actions, 'before').name('Show the input').onChange((b) => { state.showing = b ? 'before' : 'after'; draw(); });
  gui.add(actions, 'clearFixed').name('Free all vertices');
  gui.add(actions, 'downloadMesh').name('Download mesh (OBJ)');
  gui.add(actions, 'downloadReport').name('Download report (JSON)');
}

function selectProblem(name, presets) {
  state.problem = state.schema.problems.find((p) => p.name === name) || null;
  actions.problem = name;
  problemControl.updateDisplay();
  for (const c of [...optionsFolder.controllersRecursive()]) c.destroy();
  for (const f of [...optionsFolder.folders]) f.destroy();
  state.options = {};
  if (!state.problem) return;
  const folders = {};
  for (const option of state.problem.options) {
    let value = option.default;
    if (presets && option.name in presets) value = presets[option.name];
    const folder = option.group ? (folders[option.group] ||= optionsFolder.addFolder(option.group).close()) : optionsFolder;
    let control;
    if (option.type === 'choice') {
      state.options[option.name] = value;
      control = folder.add(state.options, option.name, option.choices);
    } else if (option.type === 'bool') {
      state.options[option.name] = !!value;
      control = folder.add(state.options, option.name);
    } else if (option.type === 'number' || option.type === 'int') {
      state.options[option.name] = value === null ? '' : value;
      control = value === null ? folder.add(state.options, option.name) : folder.add(state.options, option.name);
      if (option.type === 'int' && control.step) control.step(1);
    } else {
      // Lists and texts in the command line's spelling (e.g. "0.05,0.2"); empty: the default.
      state.options[option.name] = value === null || value === undefined ? '' : Array.isArray(value) ? value.join(',') : String(value);
      control = folder.add(state.options, option.name);
    }
    control.name(option.name + (option.unit ? ` [${option.unit}]` : ''));
    control.domElement.title = option.doc || '';
    control.onChange(() => draw());
  }
  draw();
}

// The options that differ from the schema's defaults, as the API takes them.
function optionValues() {
  const values = {};
  for (const option of state.problem.options) {
    let value = state.options[option.name];
    if (value === '' || value === undefined) continue;
    if (option.type === 'numbers') value = String(value).split(',').map(Number);
    else if (option.type === 'number' || option.type === 'int') value = Number(value);
    if (JSON.stringify(value) !== JSON.stringify(option.default)) values[option.name] = value;
  }
  return values;
}

// ---------------------------------------------------------------------------------------------
// Opening meshes

function setStart(mesh) {
  state.start = mesh;
  state.result = null;
  state.surface = null;
  state.figure = null;
  showFigure();
  state.faceTable = null;
  updateColourChoices();
  state.report = null;
  state.base = null;
  state.fixed.clear();
  state.records = [];
  drawChart();
  showMeasure(null);
  frameMesh(mesh);
  setStatus('idle', `${mesh.vertices.length} vertices, ${mesh.faces.length} faces`);
  draw();
}

async function openExample(name) {
  if (!state.examples.some((e) => e.name === name))
    throw new Error(`example: no example ${name} (${state.examples.map((e) => e.name).join(', ')})`);
  const example = await api(`/api/examples/${encodeURIComponent(name)}`);
  state.inputs = example.inputs;
  state.main = example.main;
  state.exampleOutputs = example.outputs || [];
  actions.example = name;
  exampleControl.updateDisplay();
  setStart(example.preview);
  selectProblem(example.problem, example.options);
  state.examplePresets = true;
}

async function openFile(file) {
  const format = file.name.split('.').pop().toLowerCase();
  if (!['obj', 'off', 'ply'].includes(format)) throw new Error(`${file.name}: not an OBJ, OFF or PLY file`);
  const bytes = new Uint8Array(await file.arrayBuffer());
  const text = new TextDecoder('latin1').decode(bytes);
  if (format === 'ply' && /format\s+binary/.test(text.slice(0, 512)))
    throw new Error(`${file.name}: binary PLY; the web app reads ASCII PLY, OBJ and OFF (gproj's command line reads binary PLY)`);
  const mesh = await api('/api/meshes', { name: file.name, [format]: new TextDecoder('utf-8').decode(bytes) });
  state.inputs = {};
  state.main = null;
  state.exampleOutputs = [];
  actions.example = '';
  exampleControl.updateDisplay();
  setStart(mesh);
  // A file starts from the problem's defaults: an example's options were for the example (and a
  // B-spline problem cannot take a mesh file).
  if (!state.problem || state.examplePresets || mainInputOf(state.problem).kind === 'bspline')
    selectProblem(state.problem && mainInputOf(state.problem).kind !== 'bspline' ? state.problem.name : 'planarize');
  state.examplePresets = false;
  setMessage(`${file.name}: ${mesh.vertices.length} vertices, ${mesh.faces.length} faces`);
}

document.getElementById('file').addEventListener('change', (e) => {
  const file = e.target.files[0];
  if (file) opening(openFile(file));
  e.target.value = '';
});
window.addEventListener('dragover', (e) => { e.preventDefault(); document.body.classList.add('dragging'); });
window.addEventListener('dragleave', () => document.body.classList.remove('dragging'));
window.addEventListener('drop', (e) => {
  e.preventDefault();
  document.body.classList.remove('dragging');
  const file = e.dataTransfer.files[0];
  if (file) opening(openFile(file));
});

function opening(promise) {
  ++loading;
  promise.catch((err) => setStatus('failed', err.message)).finally(() => --loading);
}

// ---------------------------------------------------------------------------------------------
// Runs

let following = null;  // the run id being followed
let loading = 0;       // meshes being opened

// The run request of the problem chosen: the mesh shown goes to its main input (a B-spline comes
// from the example that opened it), the example's other inputs by name.
function runRequest() {
  const main = mainInputOf(state.problem);
  const inputs = {};
  if (main.kind === 'bspline') {
    const surface = state.main && state.inputs[state.main];
    if (!surface || Array.isArray(surface.vertices))
      throw new Error(`${state.problem.name} takes a B-spline surface: open one of its examples (a mesh file is no B-spline)`);
    inputs[main.name] = surface;
  } else {
    if (state.main && !Array.isArray(state.inputs[state.main].vertices))
      throw new Error(`${state.problem.name} takes a mesh: open a mesh or one of its examples`);
    inputs[main.name] = state.start;
  }
  for (const [name, value] of Object.entries(state.inputs))
    if (name !== state.main && name !== main.name && state.problem.inputs.some((i) => i.name === name))
      inputs[name] = value;
  if (state.fixed.size && state.problem.inputs.some((i) => i.name === 'fixed'))
    inputs.fixed = [...state.fixed].sort((a, b) => a - b);
  const known = new Set(state.problem.outputs.map((o) => o.name));
  const outputs = ['face_values', 'surface_mesh', 'diagram', ...(state.exampleOutputs || [])].filter((o, i, all) => known.has(o) && all.indexOf(o) === i);
  return { problem: state.problem.name, inputs, options: optionValues(), outputs };
}

async function run() {
  if (following) return;
  if (!state.start || !state.problem) return setStatus('failed', 'open a mesh and choose a problem first');
  state.records = [];
  drawChart();
  setStatus('running', `${state.problem.name}…`);
  try {
    const answer = await api('/api/runs', runRequest());
    await finish(answer.id, false);
  } catch (e) {
    setStatus('failed', e.message);
  }
}

async function cancel() {
  if (following) await api(`/api/runs/${following}`, undefined, 'DELETE').catch(() => {});
}

// Follows run `id` to its end and shows its result.
async function finish(id, resolve) {
  following = id;
  const run = await follow(id, (record) => {
    if (following !== id) return;
    state.records.push(record);
    drawChart();
    showMeasure(record[measureName()]);
  }, (vertices) => {
    // A first run's iterates replace the view as they come (a re-solve's would fight the drag).
    if (following !== id || resolve || vertices.length !== state.start.vertices.length) return;
    state.result = { vertices, faces: state.start.faces };
    state.faceTable = null;
    state.iterates += 1;
    draw();
  });
  if (following !== id) return run;  // a newer run took over
  following = null;
  state.report = run.report || null;
  if (!resolve && state.report && state.report.tolerance_measure && state.report.tolerance > 0)
    state.target = { key: state.problem.name + JSON.stringify(optionValues()),
      measure: state.report.tolerance_measure, tolerance: state.report.tolerance };
  drawChart();
  const result = run.result || {};
  // The result shown against the start: the output mesh of the start's connectivity, or a
  // sampled surface of the start's sampling (weingarten); another surface is drawn over it (hnet).
  const sameAsStart = (m) => !!(m && Array.isArray(m.vertices) && Array.isArray(m.faces) &&
    m.vertices.length === state.start.vertices.length && m.faces.length === state.start.faces.length);
  const surface = result.surface_mesh && result.surface_mesh.vertices ? result.surface_mesh : null;
  const mesh = sameAsStart(result.output) ? result.output : sameAsStart(surface) ? surface : null;
  if (mesh) state.result = mesh;
  else if (resolve === false) state.result = null;
  state.surface = surface && surface !== mesh ? surface : null;
  state.figure = typeof result.diagram === 'string' ? result.diagram : null;
  showFigure();
  state.faceTable = result.face_values ? csvTable(result.face_values) : null;
  updateColourChoices();
  if (run.status === 'converged' || run.status === 'not-converged') state.base = id;
  state.runs += 1;
  if (resolve) state.resolves += 1;
  const final = state.report && state.report.final ? state.report.final[measureName()] : undefined;
  showMeasure(final !== undefined ? final : (state.records.length ? state.records[state.records.length - 1][measureName()] : null));
  const iterations = state.report ? state.report.iterations : undefined;
  setStatus(run.status, run.error ? run.error :
    `${resolve ? 're-solved' : state.problem.name} in ${iterations} iterations` +
    (state.report && state.report.seconds ? `, ${(state.report.seconds * 1000).toFixed(0)} ms` : ''));
  draw();
  return run;
}

// The result's picture (an SVG text) in its frame beside the view, or the frame hidden.
function showFigure() {
  const frame = document.getElementById('figure');
  frame.replaceChildren();
  frame.hidden = !state.figure;
  if (!state.figure) return;
  const image = document.createElement('img');
  image.src = 'data:image/svg+xml;charset=utf-8,' + encodeURIComponent(state.figure);
  image.alt = 'curvature diagram';
  frame.appendChild(image);
}

// A CSV text with a header -> {column name: [number or null per row]}.
function csvTable(text) {
  const [header, ...lines] = text.trim().split('\n');
  const names = header.split(',');
  const table = Object.fromEntries(names.map((n) => [n, []]));
  for (const line of lines)
    line.split(',').forEach((cell, k) => {
      const v = Number(cell);
      if (k < names.length) table[names[k]].push(Number.isFinite(v) ? v : null);
    });
  return table;
}

// The "Colour by" menu: the result's per-face columns (relative ones and angles); the default
// is the one the tolerance bounds (max_planarity -> planarity), else the first.
function updateColourChoices() {
  const names = state.faceTable
    ? Object.keys(state.faceTable).filter((n) => n !== 'face' && !n.endsWith('_abs')) : [];
  const target = measureName().replace(/^max_/, '');
  if (!names.includes(state.colourBy)) state.colourBy = names.includes(target) ? target : names[0] || '';
  actions.colourBy = state.colourBy;
  colourControl = colourControl.options(names.length ? names : ['(after a run)']).name('Colour by')
    .onChange((name) => { state.colourBy = name; draw(); });
  if (names.length) colourControl.setValue(state.colourBy);
}

// ---------------------------------------------------------------------------------------------
// Fixing and dragging vertices

const pointer = { down: null, vertex: -1, dragging: false, plane: null, pending: null, inFlight: false };

function vertexOnScreen(v) {
  const mesh = shownMesh();
  const p = new THREE.Vector3(...mesh.vertices[v]).project(camera);
  const rect = renderer.domElement.getBoundingClientRect();
  return { x: rect.left + (p.x + 1) / 2 * rect.width, y: rect.top + (1 - p.y) / 2 * rect.height, visible: p.z < 1 };
}

function nearestVertex(x, y) {
  const mesh = shownMesh();
  if (!mesh) return -1;
  let best = -1, bestDistance = 10;  // pixels
  for (let v = 0; v < mesh.vertices.length; ++v) {
    const s = vertexOnScreen(v);
    const d = Math.hypot(s.x - x, s.y - y);
    if (s.visible && d < bestDistance) { best = v; bestDistance = d; }
  }
  return best;
}

// Vertices can be fixed where the problem takes fixed vertices, and dragged where it also
// returns a mesh of the input's connectivity (the service re-solves those warm).
function fixable() {
  return !!state.problem && state.problem.inputs.some((i) => i.name === 'fixed' && i.kind === 'vertex_ids');
}

function draggable() {
  return fixable() && state.problem.outputs.some((o) => o.name === 'output' && o.kind === 'mesh');
}

container.addEventListener('pointerdown', (e) => {
  if (e.button !== 0 || state.showing !== 'after' || !fixable()) return;
  const v = nearestVertex(e.clientX, e.clientY);
  if (v < 0) return;
  e.stopPropagation();  // the vertex takes the gesture, not the orbit controls
  pointer.down = { x: e.clientX, y: e.clientY };
  pointer.vertex = v;
  pointer.dragging = false;
  const p = new THREE.Vector3(...shownMesh().vertices[v]);
  pointer.plane = new THREE.Plane().setFromNormalAndCoplanarPoint(camera.getWorldDirection(new THREE.Vector3()), p);
}, true);

window.addEventListener('pointermove', (e) => {
  if (!pointer.down) return;
  if (!pointer.dragging && Math.hypot(e.clientX - pointer.down.x, e.clientY - pointer.down.y) < 4) return;
  if (!state.base || !draggable()) {
    if (!pointer.dragging)
      setMessage(draggable() ? 'run the problem first: a drag re-solves from its result'
        : `${state.problem.name} has no warm re-solve: fix vertices by clicking and run again`);
    pointer.dragging = true;
    return;
  }
  pointer.dragging = true;
  const rect = renderer.domElement.getBoundingClientRect();
  const ndc = new THREE.Vector2((e.clientX - rect.left) / rect.width * 2 - 1, -(e.clientY - rect.top) / rect.height * 2 + 1);
  const ray = new THREE.Raycaster();
  ray.setFromCamera(ndc, camera);
  const to = new THREE.Vector3();
  if (!ray.ray.intersectPlane(pointer.plane, to)) return;
  state.result.vertices[pointer.vertex] = [to.x, to.y, to.z];
  state.fixed.add(pointer.vertex);
  draw();
  pointer.pending = { vertex: pointer.vertex, to: [to.x, to.y, to.z], final: false };
  pumpResolve();
});

window.addEventListener('pointerup', () => {
  if (!pointer.down) return;
  const v = pointer.vertex;
  if (!pointer.dragging) {
    if (state.fixed.has(v)) state.fixed.delete(v); else state.fixed.add(v);
    setMessage(`vertex ${v} ${state.fixed.has(v) ? 'fixed' : 'free'} (${state.fixed.size} fixed)`);
    draw();
  } else if (state.base && draggable() && pointer.pending) {
    pointer.pending.final = true;
    pumpResolve();
  } else if (state.base && draggable() && !pointer.pending) {
    const p = state.result.vertices[v];
    pointer.pending = { vertex: v, to: p, final: true };
    pumpResolve();
  }
  pointer.down = null;
});

// One re-solve in flight at a time, from the last finished one; while dragging to DRAG_TOLERANCE,
// on release to the run's tolerance.
async function pumpResolve() {
  if (pointer.inFlight || !pointer.pending || !state.base) return;
  const edit = pointer.pending;
  pointer.pending = null;
  pointer.inFlight = true;
  // The form's tolerance on release (null: the problem's default), looser while dragging.
  const own = Number(state.options.tolerance);
  const asked = state.options.tolerance !== '' && Number.isFinite(own) && own > 0 ? own : null;
  const tolerance = edit.final ? asked : Math.max(asked === null ? toleranceOf() : asked, DRAG_TOLERANCE);
  try {
    setStatus('running', `re-solving after vertex ${edit.vertex} moved…`);
    state.records = [];
    const answer = await api(`/api/runs/${state.base}/resolve`, {
      moved: [{ vertex: edit.vertex, to: edit.to }],
      fixed: [...state.fixed].filter((v) => v !== edit.vertex),
      options: { tolerance } });
    await finish(answer.id, true);
  } catch (e) {
    setStatus('failed', e.message);
  }
  pointer.inFlight = false;
  if (pointer.pending) pumpResolve();
}

// ---------------------------------------------------------------------------------------------
// Downloads

function save(name, text, type) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(new Blob([text], { type }));
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

function downloadMesh() {
  const mesh = shownMesh();
  if (!mesh) return;
  const lines = ['# gproj web app: ' + (state.problem ? state.problem.name : 'mesh')];
  for (const p of mesh.vertices) lines.push(`v ${p[0]} ${p[1]} ${p[2]}`);
  for (const f of mesh.faces) lines.push('f ' + f.map((v) => v + 1).join(' '));
  save(`${state.problem ? state.problem.name : 'mesh'}.obj`, lines.join('\n') + '\n', 'text/plain');
}

function downloadReport() {
  if (state.report) save(`${state.problem.name}_report.json`, JSON.stringify(state.report, null, 1), 'application/json');
}

// ---------------------------------------------------------------------------------------------
// Start

// Whether a run, a re-solve or an edit waiting for one is in flight.
function busy() {
  return !!(state.status === 'running' || following || pointer.inFlight || pointer.pending || pointer.down || loading);
}

window.gproj = { state, vertexOnScreen, run, openExample, selectProblem, busy };

async function start() {
  state.schema = await api('/api/schema');
  state.examples = (await api('/api/examples')).examples;
  buildPanel();
  const example = params.get('example');
  const problem = params.get('problem');
  if (example) await openExample(example);
  else if (state.examples.length) await openExample(state.examples[0].name);
  if (problem) {
    if (!usableProblems().some((p) => p.name === problem))
      throw new Error(`problem: ${problem} is not one the web app runs (${usableProblems().map((p) => p.name).join(', ')})`);
    if (problem !== state.problem.name) selectProblem(problem);
  }
  // Any other parameter named as an option of the problem sets it (?circular=true, tolerance=1e-9).
  for (const [name, text] of params) {
    if (['example', 'problem', 'run', 'token'].includes(name)) continue;
    const option = state.problem.options.find((o) => o.name === name);
    if (!option) throw new Error(`${name}: ${state.problem.name} has no such option (see GET /api/schema)`);
    state.options[name] = option.type === 'bool' ? ['1', 'true', 'yes'].includes(text.toLowerCase()) : text;
  }
  optionsFolder.controllersRecursive().forEach((c) => c.updateDisplay());
  draw();
  if (params.get('run') === '1') await run();
}

opening(start());
