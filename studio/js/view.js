// The 3-D view (docs/studio.md, "The page"): the preview mesh of GET /api/mesh
// on a ground plane, orbit controls, and where an altitude lands on the page so
// the graphs beside it share the rock's height scale.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { $, showMessage } from './dom.js';
import { state } from './state.js';

const container = $('view');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
container.appendChild(renderer.domElement);
const scene = new THREE.Scene();
const background = new THREE.Color(0x30343a);
scene.background = background;
const camera = new THREE.PerspectiveCamera(35, 1, 0.01, 1000);
camera.up.set(0, 0, 1);
const controls = new OrbitControls(camera, renderer.domElement);
controls.enableDamping = false;
scene.add(new THREE.HemisphereLight(0xdfe8ff, 0x4a4036, 1.2));
const sun = new THREE.DirectionalLight(0xffffff, 2.0);
sun.position.set(3, -4, 6);
scene.add(sun);
const ground = new THREE.Mesh(new THREE.PlaneGeometry(1, 1), new THREE.MeshStandardMaterial({ color: 0x4d4a45, roughness: 1 }));
scene.add(ground);
const surfaceMaterial = new THREE.MeshStandardMaterial({ vertexColors: true, roughness: 0.9, side: THREE.DoubleSide });
const rockMesh = new THREE.Mesh(new THREE.BufferGeometry(), surfaceMaterial);
const colluviumMesh = new THREE.Mesh(new THREE.BufferGeometry(), surfaceMaterial);
scene.add(rockMesh, colluviumMesh);
let framed = false;

function resize() {
  const w = container.clientWidth, h = container.clientHeight;
  renderer.setSize(w, h);
  camera.aspect = w / Math.max(1, h);
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);

function frameCamera() {
  const g = state.server.grid;
  const [sx, sy, sz] = state.server.preset.grid.size;
  const target = new THREE.Vector3(sx / 2, sy / 2, sz / 2);
  controls.target.copy(target);
  const distance = 1.9 * Math.max(sx, sy, sz) / Math.tan(THREE.MathUtils.degToRad(camera.fov / 2)) / 2;
  camera.position.set(target.x + distance * 0.75, target.y - distance * 0.65, target.z + distance * 0.18);
  ground.scale.set(sx * 2.5, sy * 2.5, 1);
  ground.position.set(sx / 2, sy / 2, -0.002 * g.h);
  controls.update();
  framed = true;
}

// One frame of the view (framed on the rock the first time).
export function renderView() {
  if (!framed) { resize(); frameCamera(); }
  controls.update();
  renderer.render(scene, camera);
}

export function showColluvium(visible) {
  colluviumMesh.visible = visible && !finalModel?.visible;
  if (finalModel) finalModel.traverse((o) => { if (o.isMesh && isColluvium(o)) o.visible = visible; });
}

// Frees a model's GPU buffers and textures (a final bake's LOD0 maps are up to 8K each).
function dispose(model) {
  model.traverse((o) => {
    if (!o.isMesh) return;
    o.geometry.dispose();
    for (const material of [o.material].flat()) {
      for (const value of Object.values(material)) if (value?.isTexture) value.dispose();
      material.dispose();
    }
  });
}

// The final bake's LOD0 as its GLB has it (GET /api/final/rock.glb, the maps beside it): the look
// the bake made on its refined surface, which the live preview does not have (docs/studio.md).
// glTF is y-up and in metres; the view is z-up in world units (units_per_meter of them a metre).
let finalModel = null;
// The rock's and the colluvium's meshes by their names, under every delivery profile's prefixes
// (rock_lod0 or SM_<name>_rock_lod0; materials <name>_rock or M_<name>_rock).
const named = (o, part) => new RegExp(`(^|_)${part}(_lod\\d+)?$`).test(o.name) || new RegExp(`(^|_)${part}$`).test(o.material?.name ?? '');
const isColluvium = (o) => named(o, 'colluvium');

// Loads bake number `done` (state.final.done when it was asked for); shows it if the final view is
// still the one chosen, and loads the newer bake if another finished meanwhile.
export async function showFinalBake(done) {
  const final = state.final;
  if (final.loading) return;
  final.loading = true;
  const chosen = () => $('view-mode').value === 'final';
  try {
    const gltf = await new GLTFLoader().loadAsync(`/api/final/rock.glb?bake=${done}`);
    const model = new THREE.Group();
    model.add(gltf.scene);
    model.rotation.x = Math.PI / 2;
    model.scale.setScalar(state.server.preset.units_per_meter ?? 1);
    // The bake's meshes are about its footprint's centre on the ground (docs/meshes.md): its rock
    // stands where the live preview's rock stands, which is the rock it baked unless the run has
    // moved on since (then the two are side by side in time, not in space).
    model.updateMatrixWorld(true);
    const baked = new THREE.Box3();
    gltf.scene.traverse((o) => { if (o.isMesh && named(o, 'rock')) baked.expandByObject(o); });
    rockMesh.geometry.computeBoundingBox();
    const live = rockMesh.geometry.boundingBox;
    if (!baked.isEmpty() && !live.isEmpty()) {
      const bc = baked.getCenter(new THREE.Vector3()), lc = live.getCenter(new THREE.Vector3());
      model.position.set(lc.x - bc.x, lc.y - bc.y, live.min.z - baked.min.z);
    }
    if (finalModel) {
      scene.remove(finalModel);
      dispose(finalModel);
    }
    finalModel = model;
    scene.add(model);
    let triangles = 0, textured = false, history = false;
    gltf.scene.traverse((o) => {
      if (!o.isMesh || !named(o, 'rock')) return;
      const g = o.geometry;
      triangles += (g.index ? g.index.count : g.attributes.position.count) / 3;
      textured ||= Boolean(o.material.map);
      history ||= Boolean(g.attributes._history);
    });
    Object.assign(final, { shown: done, triangles, textured, history });
    showFinal(chosen());
  } catch (e) {
    showMessage(`cannot show the final bake: ${e.message}`);
    showFinal(false);
    $('view-mode').value = 'live';
  } finally {
    final.loading = false;
    if (chosen() && final.done !== final.shown && final.shown !== 0) showFinalBake(final.done);
  }
}

// The final bake's model in place of the live preview, or the live preview back.
export function showFinal(on) {
  if (finalModel) finalModel.visible = on;
  rockMesh.visible = !on;
  showColluvium($('show-colluvium').checked);
}

// Binary preview mesh (docs/studio.md, GET /api/mesh): "RBPM", version, cycle, then
// rock and colluvium: vertex count, triangle count, positions, linear RGB colours, indices.
function readMeshes(buffer) {
  const data = new DataView(buffer);
  const magic = String.fromCharCode(...new Uint8Array(buffer, 0, 4));
  if (magic !== 'RBPM') throw new Error('not a preview mesh');
  let offset = 12;
  const meshes = [];
  for (let m = 0; m < 2; ++m) {
    const vertices = data.getUint32(offset, true);
    const triangles = data.getUint32(offset + 4, true);
    offset += 8;
    const positions = new Float32Array(buffer.slice(offset, offset + 12 * vertices)); offset += 12 * vertices;
    const colours = new Float32Array(buffer.slice(offset, offset + 12 * vertices)); offset += 12 * vertices;
    const indices = new Uint32Array(buffer.slice(offset, offset + 12 * triangles)); offset += 12 * triangles;
    meshes.push({ positions, colours, indices });
  }
  return meshes;
}

function setGeometry(mesh, data) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(data.positions, 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(data.colours, 3));
  geometry.setIndex(new THREE.BufferAttribute(data.indices, 1));
  geometry.computeVertexNormals();
  mesh.geometry.dispose();
  mesh.geometry = geometry;
}

// Fetches the preview mesh when the rock or the palette changed since the one shown.
export async function updateMesh() {
  const shown = state.mesh;
  if (!state.server || shown.loading) return;
  const palette = $('palette').value;
  if (shown.version === state.server.mesh_version && shown.palette === palette) return;
  shown.loading = true;
  try {
    const response = await fetch(`/api/mesh?palette=${palette}`);
    if (!response.ok) {
      const refusal = await response.json().catch(() => ({}));
      throw new Error(refusal.error || `GET /api/mesh: HTTP ${response.status}`);
    }
    const version = Number(response.headers.get('X-Mesh-Version'));
    const [rock, colluvium] = readMeshes(await response.arrayBuffer());
    setGeometry(rockMesh, rock);
    setGeometry(colluviumMesh, colluvium);
    Object.assign(shown, { version, palette, triangles: rock.indices.length / 3 });
  } catch (e) {
    showMessage(e.message);
  } finally {
    shown.loading = false;
  }
}

// Page y (CSS pixels) of altitude a (0 ground, 1 top of grid.size) above the grid's centre.
export function altitudeToPageY(a) {
  const [sx, sy, sz] = state.server.preset.grid.size;
  const p = new THREE.Vector3(sx / 2, sy / 2, a * sz).project(camera);
  const rect = renderer.domElement.getBoundingClientRect();
  return rect.top + (1 - (p.y + 1) / 2) * rect.height;
}

// Page rectangle the rock's bounds cover in the view (the final bake's when it is shown), and the
// background colour.
export function rockScreenBox() {
  let box;
  if (finalModel && finalModel.visible) {
    finalModel.updateMatrixWorld(true);
    box = new THREE.Box3();
    finalModel.traverse((o) => { if (o.isMesh && named(o, 'rock')) box.expandByObject(o); });
  } else {
    rockMesh.geometry.computeBoundingBox();
    box = rockMesh.geometry.boundingBox;
  }
  const rect = renderer.domElement.getBoundingClientRect();
  let x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
  for (let i = 0; i < 8; ++i) {
    const p = new THREE.Vector3(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z).project(camera);
    const x = rect.left + (p.x + 1) / 2 * rect.width, y = rect.top + (1 - (p.y + 1) / 2) * rect.height;
    x0 = Math.min(x0, x); y0 = Math.min(y0, y); x1 = Math.max(x1, x); y1 = Math.max(y1, y);
  }
  return { x0, y0, x1, y1, background: '#' + background.getHexString() };
}
