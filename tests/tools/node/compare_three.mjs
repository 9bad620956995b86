// Loads two .glb files of one stand with three.js's GLTFLoader (as a browser would) and compares
// them vertex by vertex in world space: the default stand.glb and the compact one
// (--glb-compact). Organ ids: the default's `_ORGAN` (FLOAT, or VEC2 id = x + 65536 y); the
// compact's `_ORGAN` plus extras.first_organ of its plant node (three.js: userData).
// Prints one JSON line; exits 1 when an organ id differs, a count differs, or a vertex is farther
// than TOLERANCE metres (per axis) from its twin.
// Usage: node compare_three.mjs DEFAULT.glb COMPACT.glb TOLERANCE
import fs from 'fs';
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

const load = (file) => new Promise((resolve, reject) => {
  const b = fs.readFileSync(file);
  new GLTFLoader().parse(b.buffer.slice(b.byteOffset, b.byteOffset + b.byteLength), '', resolve, reject);
});

// Per mesh in scene order: world positions and organ ids of its vertices, and its triangles.
function meshes(gltf) {
  const out = [];
  gltf.scene.updateMatrixWorld(true);
  gltf.scene.traverse((o) => {
    if (!o.isMesh) return;
    const g = o.geometry, p = g.attributes.position, id = g.attributes._organ;
    let base = 0;
    for (let n = o; n; n = n.parent) if (n.userData && n.userData.first_organ !== undefined) { base = n.userData.first_organ; break; }
    const v = new THREE.Vector3(), pos = new Float64Array(3 * p.count), ids = new Float64Array(p.count);
    for (let i = 0; i < p.count; ++i) {
      v.fromBufferAttribute(p, i).applyMatrix4(o.matrixWorld);
      pos[3 * i] = v.x, pos[3 * i + 1] = v.y, pos[3 * i + 2] = v.z;
      ids[i] = base + (id.itemSize === 2 ? id.getX(i) + 65536 * id.getY(i) : id.getX(i));
    }
    out.push({ pos, ids, triangles: g.index ? g.index.count / 3 : p.count / 3 });
  });
  return out;
}

const [a, b] = await Promise.all([load(process.argv[2]), load(process.argv[3])]).catch((e) => {
  console.error('three.js could not load:', e.message || e);
  process.exit(1);
});
const tolerance = Number(process.argv[4]);
const ma = meshes(a), mb = meshes(b);
let vertices = 0, triangles = 0, idDiffer = 0, far = 0, worst = 0, countsDiffer = ma.length !== mb.length;
for (let m = 0; m < Math.min(ma.length, mb.length); ++m) {
  const x = ma[m], y = mb[m];
  if (x.ids.length !== y.ids.length || x.triangles !== y.triangles) { countsDiffer = true; continue; }
  vertices += x.ids.length, triangles += x.triangles;
  for (let i = 0; i < x.ids.length; ++i) {
    if (x.ids[i] !== y.ids[i]) ++idDiffer;
    let d = 0;
    for (let k = 0; k < 3; ++k) d = Math.max(d, Math.abs(x.pos[3 * i + k] - y.pos[3 * i + k]));
    worst = Math.max(worst, d);
    if (!(d <= tolerance)) ++far;
  }
}
console.log(JSON.stringify({ meshes: mb.length, vertices, triangles, counts_differ: countsDiffer, ids_differ: idDiffer,
                             farther_than_tolerance: far, max_difference_m: worst }));
process.exit(countsDiffer || idDiffer || far ? 1 : 0);
