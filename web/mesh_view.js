// The BSSRDF on a mesh (Bitterli 2013 §3.1.2, §3.6): the multiple-scattering exitance M that the
// server evaluates at the mesh's vertices from its point cloud (POST /api/mesh_exitance), drawn
// with three.js. The radiance towards the camera is L = M w(cos θ_o), w = F_t(η, cos θ_o) /
// (π 4 C_φ(1/η)) (Bitterli eqs. 2.16, 2.29), read per vertex from the table the server sends, then
// scaled by the exposure and encoded as sRGB (IEC 61966-2-1).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const $ = (id) => document.getElementById(id);
const TABLE = 65;  // entries of the exit factor's table (the server's kExitWeightSteps + 1)

const view = {
  renderer: null, scene: null, camera: null, controls: null, mesh: null, arrow: null,
  material: null, meshKey: null, autoScale: 1, needAuto: true, seq: 0, timer: null, shapes: [],
};

const vertexShader = `
attribute vec3 exitance;
uniform float weights[${TABLE}];
uniform float exposure;
varying vec3 radiance;
void main() {
  vec4 world = modelMatrix * vec4(position, 1.0);
  vec3 n = normalize(mat3(modelMatrix) * normal);
  float c = clamp(dot(n, normalize(cameraPosition - world.xyz)), 0.0, 1.0) * ${TABLE - 1}.0;
  int k = int(min(floor(c), ${TABLE - 2}.0));
  float w = mix(weights[k], weights[k + 1], c - float(k));
  radiance = exitance * w * exposure;
  gl_Position = projectionMatrix * viewMatrix * world;
}`;

const fragmentShader = `
varying vec3 radiance;
void main() {
  vec3 c = clamp(radiance, 0.0, 1.0);
  vec3 srgb = mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
  gl_FragColor = vec4(srgb, 1.0);
}`;

function setup() {
  const canvas = $('mesh-canvas');
  view.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  view.renderer.setPixelRatio(window.devicePixelRatio);
  view.renderer.setClearColor(0x1d2229);
  view.scene = new THREE.Scene();
  view.camera = new THREE.PerspectiveCamera(30, 1, 0.01, 1000);
  view.camera.up.set(0, 0, 1);  // the render scenes' z up
  view.controls = new OrbitControls(view.camera, canvas);
  view.controls.addEventListener('change', draw);
  view.material = new THREE.ShaderMaterial({
    uniforms: { weights: { value: new Array(TABLE).fill(0) }, exposure: { value: 1 } },
    vertexShader, fragmentShader,
  });
  new ResizeObserver(resize).observe($('mesh-view'));
  resize();
}

function resize() {
  const box = $('mesh-view');
  view.renderer.setSize(box.clientWidth, box.clientHeight, false);
  view.camera.aspect = box.clientWidth / Math.max(box.clientHeight, 1);
  view.camera.updateProjectionMatrix();
  draw();
}

function draw() {
  if (view.renderer) view.renderer.render(view.scene, view.camera);
}

function exposureScale() {
  return view.autoScale * Math.pow(2, Number($('mesh-exposure').value));
}

function meshRequest() {
  const value = $('mesh-shape').value;
  const normals = $('mesh-flat').checked ? 'flat' : 'interpolated';
  if (value.startsWith('obj:')) return { shape: 'obj', path: value.slice(4), normals };
  return { shape: value, normals };
}

function request(geometry) {
  return {
    mesh: meshRequest(),
    points: Number($('mesh-points').value),
    media: [0, 1, 2].map((c) => window.mediumOf(c)),
    scale: window.scale(),
    model: $('mesh-model').value,
    parameters: window.textParameters(),
    light: { azimuth: Number($('light-azimuth').value), elevation: Number($('light-elevation').value) },
    occlusion: $('mesh-occlusion').checked,
    cluster_angle: Number($('mesh-epsilon').value),
    geometry,
  };
}

function showLabels() {
  $('light-azimuth-value').textContent = `${$('light-azimuth').value}°`;
  $('light-elevation-value').textContent = `${$('light-elevation').value}°`;
  const stops = Number($('mesh-exposure').value);
  $('mesh-exposure-value').textContent = `${stops >= 0 ? '+' : ''}${stops.toFixed(1)} stops`;
}

// A new mesh from the server's answer: its triangles, normals and the camera around it.
function buildMesh(answer) {
  if (view.mesh) {
    view.scene.remove(view.mesh);
    view.mesh.geometry.dispose();
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(answer.mesh.positions, 3));
  geometry.setAttribute('normal', new THREE.Float32BufferAttribute(answer.mesh.normals, 3));
  geometry.setAttribute('exitance', new THREE.Float32BufferAttribute(answer.mesh.vertices * 3, 3));
  geometry.setIndex(answer.mesh.indices);
  view.mesh = new THREE.Mesh(geometry, view.material);
  view.scene.add(view.mesh);
  view.meshKey = answer.mesh.key;
  const [lo, hi] = answer.mesh.bounds;
  const centre = new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
  const radius = 0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  view.radius = radius;
  view.centre = centre;
  view.camera.position.copy(centre).add(new THREE.Vector3(0, -4.2 * radius, 1.6 * radius));
  view.camera.near = radius / 100;
  view.camera.far = radius * 100;
  view.camera.updateProjectionMatrix();
  view.controls.target.copy(centre);
  view.controls.update();
}

function applyExitance(answer) {
  const attribute = view.mesh.geometry.getAttribute('exitance');
  const n = answer.mesh.vertices, channels = answer.channels;
  for (let v = 0; v < n; ++v) {
    for (let c = 0; c < 3; ++c) attribute.array[3 * v + c] = answer.exitance[channels * v + Math.min(c, channels - 1)];
  }
  attribute.needsUpdate = true;
  view.material.uniforms.weights.value = answer.exit_weight.weight;
  if (view.needAuto) {
    // Auto exposure: the 99th percentile of the brightest channel's radiance seen head-on at 0.8.
    const w1 = answer.exit_weight.weight[TABLE - 1];
    const peaks = [];
    for (let v = 0; v < n; ++v) peaks.push(Math.max(attribute.array[3 * v], attribute.array[3 * v + 1], attribute.array[3 * v + 2]) * w1);
    peaks.sort((a, b) => a - b);
    const high = peaks[Math.floor(0.99 * (peaks.length - 1))];
    view.autoScale = high > 0 ? 0.8 / high : 1;
    view.needAuto = false;
  }
  view.material.uniforms.exposure.value = exposureScale();
  // The light: an arrow from its side towards the mesh's centre.
  const to = new THREE.Vector3(...answer.light.to_light);
  if (view.arrow) view.scene.remove(view.arrow);
  const r = view.radius;
  view.arrow = new THREE.ArrowHelper(to.clone().negate(), view.centre.clone().addScaledVector(to, 2.0 * r), 0.8 * r, 0xffd24a, 0.25 * r, 0.12 * r);
  view.scene.add(view.arrow);
  draw();
}

function describe(answer, elapsed) {
  const u = window.plotUnit();
  const ms = answer.ms;
  $('mesh-title').textContent = `Multiple-scattering radiance L = M · F_t(η, cos θ_o) / (4π C_φ(1/η)) ` +
    `(Bitterli eq. 2.16), ${answer.model}, light E_0 = 1 W/${u}² from azimuth ${answer.light.azimuth}°, ` +
    `elevation ${answer.light.elevation}°; mesh lengths in ${u}`;
  const cloud = answer.cloud;
  $('mesh-timing').textContent = `${answer.mesh.source}, drawn with ${answer.mesh.vertices} vertices; ` +
    `${cloud.points} points (${cloud.lit_points} lit${cloud.cached ? ', cached' : ''}), ` +
    `${answer.evaluations_per_vertex.toFixed(0)} R_d evaluations per vertex; server ms: ` +
    `cloud ${ms.mesh_and_cloud.toFixed(1)}, irradiance ${ms.irradiance.toFixed(1)}, ` +
    `octree ${ms.octree.toFixed(1)}, vertices ${ms.vertices.toFixed(1)}, total ${ms.total.toFixed(1)}; ` +
    `round trip ${elapsed.toFixed(1)} ms`;
}

async function update() {
  if (!$('mesh-on').checked || typeof state === "undefined" || !state.channels || !window.explore.ready) return;
  const seq = ++view.seq;
  const key = JSON.stringify([meshRequest(), $('mesh-points').value]);
  const geometry = view.requestKey !== key;
  const started = performance.now();
  try {
    const answer = await window.api('/api/mesh_exitance', request(geometry));
    if (seq !== view.seq) return;
    if (geometry) buildMesh(answer);
    view.requestKey = key;
    applyExitance(answer);
    describe(answer, performance.now() - started);
    window.explore.meshUpdates = (window.explore.meshUpdates || 0) + 1;
    window.explore.mesh = { key: answer.mesh.key, vertices: answer.mesh.vertices, ms: answer.ms, light: answer.light, model: answer.model };
    window.reportFailure('mesh', null);
  } catch (error) {
    // The channel its message names is found from the value it quotes (explore.js, inputFor).
    if (seq === view.seq) window.reportFailure('mesh', error);
  }
}

function schedule(delay = 60) {
  clearTimeout(view.timer);
  view.timer = setTimeout(update, delay);
}

async function start() {
  let meshes;
  try {
    meshes = await window.api('/api/meshes');
  } catch (error) {
    $('mesh-timing').textContent = `no mesh view: ${error.message}`;
    $('mesh-controls').disabled = true;
    return;
  }
  const select = $('mesh-shape');
  for (const shape of meshes.shapes) select.add(new Option(shape.replace('_', ' '), shape));
  for (const file of meshes.obj_files) select.add(new Option(`${file.name} (${file.folder})`, `obj:${file.path}`));
  setup();
  showLabels();
  for (const id of ['light-azimuth', 'light-elevation']) $(id).addEventListener('input', () => { showLabels(); schedule(0); });
  $('mesh-exposure').addEventListener('input', () => {
    showLabels();
    view.material.uniforms.exposure.value = exposureScale();
    draw();
  });
  $('mesh-auto-exposure').addEventListener('click', () => { view.needAuto = true; $('mesh-exposure').value = 0; showLabels(); schedule(0); });
  for (const id of ['mesh-shape', 'mesh-points', 'mesh-model', 'mesh-flat']) {
    $(id).addEventListener('change', () => { view.needAuto = true; schedule(0); });
  }
  for (const id of ['mesh-occlusion', 'mesh-epsilon', 'mesh-on']) $(id).addEventListener('change', () => schedule(0));
  window.meshView = { materialChanged: () => { view.needAuto = true; schedule(150); }, update };
  // explore.js loads the material first; its update() calls materialChanged.
  schedule(0);
}

start();
