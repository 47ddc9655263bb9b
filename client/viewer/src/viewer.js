// SPDX-License-Identifier: AGPL-3.0-or-later
// dot's viewer: the mesh a dotctl command wrote (and, for a fill, the mesh
// before it), the filled patches highlighted, the holes in a table that
// flies the camera to each. All data is in the page (#dot-data, written by
// dotctl's view_page.cc); esbuild bundles this file with three.js.
import * as THREE from 'three';
import {OrbitControls} from 'three/examples/jsm/controls/OrbitControls.js';

const PATCH = 0xe07a1f, SELECTED = 0x1f8fe0, SURFACE = 0xb8bcc4,
      OPEN = 0xd0242b;

function decode(b64, Type) {
  if (!b64) return new Type(0);
  const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
  return new Type(bytes.buffer);
}

// "HOLE_STATUS_NO_TRIANGULATION" -> "no_triangulation"
function statusName(s) {
  return String(s || '').replace(/^HOLE_STATUS_/, '').toLowerCase();
}

// One mesh of the page: its surface (original faces in one draw group,
// each hole's patch in its own) and its open edges.
function buildMesh(m) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position',
                        new THREE.BufferAttribute(decode(m.positions, Float32Array), 3));
  geometry.setIndex(new THREE.BufferAttribute(decode(m.triangles, Uint32Array), 1));
  geometry.computeVertexNormals();
  geometry.computeBoundingSphere();
  const materials = [SURFACE, PATCH, SELECTED].map(
      (color) => new THREE.MeshStandardMaterial({
        color, roughness: 0.75, metalness: 0.0, side: THREE.DoubleSide,
        polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1}));
  // The file's own colours on its surface; patches keep theirs.
  if (m.colors) {
    geometry.setAttribute('color',
                          new THREE.BufferAttribute(decode(m.colors, Uint8Array), 3, true));
    materials[0].color.set(0xffffff);
    materials[0].vertexColors = true;
  }
  const groups = new Map();  // hole id -> its draw group
  const patches = new Map();  // hole id -> {center, normal} of its patch
  for (const g of m.groups || []) {
    geometry.addGroup(3 * g.start, 3 * g.count, g.hole < 0 ? 0 : 1);
    if (g.hole < 0) continue;
    groups.set(g.hole, geometry.groups[geometry.groups.length - 1]);
    patches.set(g.hole, patchFrame(geometry, g.start, g.count));
  }
  if (!m.groups || m.groups.length === 0) {
    geometry.addGroup(0, geometry.index.count, 0);
  }
  const surface = new THREE.Mesh(geometry, materials);
  const group = new THREE.Group();
  group.add(surface);
  // Open edges, loop by loop: each hole's rim turns SELECTED with it.
  const open = decode(m.open_edges, Uint32Array);
  const rims = new Map();  // hole id -> {groups, normal} of its rim loops
  if (open.length) {
    const lines = new THREE.BufferGeometry();
    lines.setAttribute('position', geometry.getAttribute('position'));
    lines.setIndex(new THREE.BufferAttribute(open, 1));
    for (const g of m.open_groups || []) {
      lines.addGroup(g.start, g.count, 0);
      if (g.hole < 0) continue;
      const rim = rims.get(g.hole) || {groups: [], normal: new THREE.Vector3()};
      rim.groups.push(lines.groups[lines.groups.length - 1]);
      rim.normal.add(new THREE.Vector3(...g.normal).multiplyScalar(g.count));
      rims.set(g.hole, rim);
    }
    if (lines.groups.length === 0) lines.addGroup(0, open.length, 0);
    group.add(new THREE.LineSegments(lines, [OPEN, SELECTED].map(
        (color) => new THREE.LineBasicMaterial({color}))));
  }
  const wire = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({
    color: 0x202020, wireframe: true, transparent: true, opacity: 0.25}));
  wire.visible = false;
  group.add(wire);
  return {group, surface, wire, groups, patches, rims, geometry};
}

// The side the surface around `at` faces: the area-weighted normal of the
// faces within `size` of it (a hole's rim, to look into the hole from).
function surfaceNormal(mesh, at, size) {
  const pos = mesh.geometry.getAttribute('position'), index = mesh.geometry.index.array;
  const a = new THREE.Vector3(), b = new THREE.Vector3(), c = new THREE.Vector3();
  const n = new THREE.Vector3(), sum = new THREE.Vector3();
  const r2 = size * size;
  for (let t = 0; t < index.length; t += 3) {
    a.fromBufferAttribute(pos, index[t]);
    if (a.distanceToSquared(at) > r2) continue;
    b.fromBufferAttribute(pos, index[t + 1]);
    c.fromBufferAttribute(pos, index[t + 2]);
    sum.add(n.crossVectors(b.sub(a), c.sub(a)));
  }
  return sum.lengthSq() > 0 ? sum : null;
}

// Where to look at a patch from: its area-weighted centre and normal (the
// side its faces face, so the camera sees the patch, not the far side).
function patchFrame(geometry, start, count) {
  const pos = geometry.getAttribute('position'), index = geometry.index.array;
  const a = new THREE.Vector3(), b = new THREE.Vector3(), c = new THREE.Vector3();
  const center = new THREE.Vector3(), normal = new THREE.Vector3();
  let area = 0;
  for (let t = start; t < start + count; ++t) {
    a.fromBufferAttribute(pos, index[3 * t]);
    b.fromBufferAttribute(pos, index[3 * t + 1]);
    c.fromBufferAttribute(pos, index[3 * t + 2]);
    const n = new THREE.Vector3().crossVectors(b.clone().sub(a), c.clone().sub(a));
    const twice = n.length();
    normal.add(n);
    center.addScaledVector(a.add(b).add(c), twice / 3);
    area += twice;
  }
  if (area > 0) center.divideScalar(area);
  return {center, normal: normal.lengthSq() > 0 ? normal.normalize() : null};
}

function main() {
  const data = JSON.parse(document.getElementById('dot-data').textContent);
  const report = data.report || {};
  const holes = report.holes || [];
  const center = data.center || [0, 0, 0];

  document.getElementById('title').textContent = data.title;
  document.getElementById('summary').textContent = data.summary || '';

  const view = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
  renderer.setPixelRatio(window.devicePixelRatio);
  view.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf4f4f2);
  const camera = new THREE.PerspectiveCamera(35, 1, 1e-3, 1e3);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x707070, 1.6));
  const light = new THREE.DirectionalLight(0xffffff, 1.8);
  light.position.set(0.5, 1, 2);
  camera.add(light);
  scene.add(camera);

  const after = buildMesh(data.after);
  const before = data.before ? buildMesh(data.before) : null;
  scene.add(after.group);
  if (before) {
    before.group.visible = false;
    scene.add(before.group);
  }
  const sphere = after.geometry.boundingSphere;
  const radius = Math.max(sphere.radius, 1e-9);
  camera.near = radius / 1000;
  camera.far = radius * 1000;
  camera.updateProjectionMatrix();
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.maxDistance = radius * 50;  // beyond, the mesh is a dot

  let frame = 0;  // frames drawn, for the page's tests
  function render() {
    renderer.render(scene, camera);
    ++frame;
  }
  function resize() {
    const w = view.clientWidth, h = view.clientHeight;
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(h, 1);
    camera.updateProjectionMatrix();
    render();
  }

  // Flies to `target` from `distance` away, along `from` (a direction) or
  // else the current view.
  let flight = null;
  function flyTo(target, distance, from) {
    const dir = from ? from.clone() : camera.position.clone().sub(controls.target);
    if (dir.lengthSq() === 0) dir.set(0.3, 0.4, 1);
    dir.normalize().multiplyScalar(distance);
    flight = {
      t0: performance.now(), ms: 450,
      fromTarget: controls.target.clone(), toTarget: target.clone(),
      fromPos: camera.position.clone(), toPos: target.clone().add(dir),
    };
    tick();
  }
  function tick() {
    if (!flight) return;
    const t = Math.min(1, (performance.now() - flight.t0) / flight.ms);
    const s = t * t * (3 - 2 * t);
    controls.target.lerpVectors(flight.fromTarget, flight.toTarget, s);
    camera.position.lerpVectors(flight.fromPos, flight.toPos, s);
    controls.update();
    render();
    if (t < 1) requestAnimationFrame(tick); else flight = null;
  }
  // The distance at which the bounding sphere fits the narrower of the
  // view's two angles, with a margin.
  function fitDistance() {
    const half = THREE.MathUtils.degToRad(camera.fov / 2);
    const narrow = Math.min(half, Math.atan(Math.tan(half) * camera.aspect));
    return 1.08 * radius / Math.sin(narrow);
  }
  function whole(animate) {
    const c = sphere.center, d = fitDistance();
    if (animate) return flyTo(c, d);
    controls.target.copy(c);
    camera.position.copy(c).add(new THREE.Vector3(0.35, 0.45, 1).normalize().multiplyScalar(d));
    controls.update();
    render();
  }

  // The tools: before/after, wireframe, whole mesh.
  const tools = document.getElementById('tools');
  function toggle(label, key, pressed, onChange) {
    const b = document.createElement('button');
    b.textContent = label;
    b.title = `key: ${key}`;
    b.setAttribute('aria-pressed', String(pressed));
    const flip = () => {
      const now = b.getAttribute('aria-pressed') !== 'true';
      b.setAttribute('aria-pressed', String(now));
      onChange(now);
      render();
    };
    b.addEventListener('click', flip);
    tools.appendChild(b);
    return {button: b, flip};
  }
  let showingBefore = false;
  const keys = {};
  if (before) {
    keys.b = toggle('Before', 'b', false, (on) => {
      showingBefore = on;
      before.group.visible = on;
      after.group.visible = !on;
    });
  }
  keys.w = toggle('Wireframe', 'w', false, (on) => {
    after.wire.visible = on;
    if (before) before.wire.visible = on;
  });
  const fit = document.createElement('button');
  fit.textContent = 'Whole mesh';
  fit.title = 'key: f';
  fit.addEventListener('click', () => whole(true));
  tools.appendChild(fit);
  window.addEventListener('keydown', (e) => {
    if (e.target.tagName === 'INPUT' || e.ctrlKey || e.metaKey || e.altKey) return;
    const key = e.key.toLowerCase();
    if (keys[key]) keys[key].flip();
    if (key === 'f') whole(true);
  });

  const legend = document.getElementById('legend');
  const hasPatches = after.groups.size > 0;
  for (const [name, color] of [['surface', SURFACE], ...(hasPatches ? [['patch', PATCH],
                               ['selected', SELECTED]] : []), ['open edges', OPEN]]) {
    const s = document.createElement('span');
    s.textContent = name;
    s.style.setProperty('--c', '#' + color.toString(16).padStart(6, '0'));
    legend.appendChild(s);
  }

  // The hole table: one row per hole of the report, in its order.
  const body = document.querySelector('#holes tbody');
  let selected = null;
  function select(id) {
    const hole = holes.find((h) => h.id === id);
    if (!hole) return false;
    for (const row of body.rows) row.classList.toggle('selected', Number(row.dataset.hole) === id);
    const owner = hole.joined_to !== undefined ? hole.joined_to : id;
    for (const [hid, g] of after.groups) g.materialIndex = hid === owner ? 2 : 1;
    for (const mesh of [after, before]) {
      if (!mesh) continue;
      for (const [hid, rim] of mesh.rims) {
        for (const g of rim.groups) g.materialIndex = hid === id ? 1 : 0;
      }
    }
    selected = id;
    // A filled hole: its patch, seen from the side it faces; an open one
    // (or the mesh before): its rim, seen from the side the rim faces (into
    // the hole), else from the side of the surface around it.
    const shown = showingBefore ? before : after;
    const frame = showingBefore ? null : after.patches.get(owner);
    const rim = shown.rims.get(id);
    const c = hole.centroid || [0, 0, 0];
    const target = frame ? frame.center
                         : new THREE.Vector3(c[0] - center[0], c[1] - center[1], c[2] - center[2]);
    const from = frame ? frame.normal
               : rim && rim.normal.lengthSq() > 0 ? rim.normal.clone().normalize()
                                                  : surfaceNormal(shown, target, hole.diameter);
    flyTo(target, Math.max(hole.diameter * 3.2, radius * 0.3), from);
    return true;
  }
  for (const h of holes) {
    const row = body.insertRow();
    row.dataset.hole = h.id;
    const status = statusName(h.status);
    const joins = (h.joined || []).length ? `joins ${h.joined.length > 1 ? 'islands' : 'island'} ${h.joined.join(', ')}` : '';
    const island = h.joined_to !== undefined && !(h.reason || '').startsWith('island of')
                       ? `island of hole ${h.joined_to}` : '';
    const note = [h.pinched ? 'pinched' : '', joins, island, h.reason || ''].filter(Boolean).join('; ');
    const cells = [[String(h.id), 'num'], [String(h.boundary_vertices), 'num'],
                   [status, 'status-' + status],
                   [Number(h.diameter).toPrecision(3), 'num'], [note, 'note']];
    for (const [text, cls] of cells) {
      const cell = row.insertCell();
      cell.textContent = text;
      cell.className = cls;
    }
    row.addEventListener('click', () => select(h.id));
    // Rows are reached with Tab and chosen with Enter or Space too.
    row.tabIndex = 0;
    row.addEventListener('keydown', (e) => {
      if (e.key === 'Enter' || e.key === ' ') {
        e.preventDefault();
        select(h.id);
      }
    });
  }
  if (holes.length === 0) {
    const cell = body.insertRow().insertCell();
    cell.colSpan = 5;
    cell.className = 'note';
    cell.textContent = data.report ? 'no holes' : 'holes not listed (see the notes of dotctl)';
  }

  document.getElementById('keys').textContent =
      (before ? 'b before/after, ' : '') + 'w wireframe, f whole mesh';

  controls.addEventListener('change', () => { if (!flight) render(); });
  new ResizeObserver(resize).observe(view);
  resize();
  whole(false);

  // For scripts and tests: what the page shows, and its controls.
  window.dotViewer = {
    ready: true,
    holes: () => [...body.rows].filter((r) => r.dataset.hole !== undefined).map(
        (r) => ({id: Number(r.dataset.hole), edges: Number(r.cells[1].textContent),
                 status: r.cells[2].textContent})),
    patchGroups: () => [...after.groups.keys()],
    rimHoles: (ofBefore) => [...(ofBefore ? before : after).rims.keys()],
    select,
    selected: () => selected,
    showBefore: (on) => { if (before && on !== showingBefore) keys.b.flip(); return showingBefore; },
    frames: () => frame,
    settled: () => flight === null,
  };
}

try {
  main();
} catch (e) {
  const box = document.getElementById('error');
  box.style.display = 'block';
  box.textContent = 'This page could not show the mesh: ' + e.message;
  throw e;
}
