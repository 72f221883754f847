// ucsio view: the 3D view of the scene in #ucsio-scene, drawn with three.js.
// Orthographic camera (so the scale bar is true everywhere), Z up (robot world).
(function () {
"use strict";
const S = JSON.parse(document.getElementById("ucsio-scene").textContent);
const C = S.center, R = S.marker, RW = S.size * 0.012;   // points; working and plan marks
const MARK = 0xe6007e, ROBOT = 0x555555, RESID = 0xff7f0e;
const AXES = [0xd62728, 0x2ca02c, 0x1f77b4];
const el = document.getElementById("view3d"), labelsEl = document.getElementById("labels");
const info = document.getElementById("info");

const renderer = new THREE.WebGLRenderer({antialias: false, preserveDrawingBuffer: true});
renderer.setPixelRatio(1);
renderer.setClearColor(0xffffff);
el.appendChild(renderer.domElement);
const scene = new THREE.Scene();
const camera = new THREE.OrthographicCamera(-1, 1, 1, -1, -S.size * 100, S.size * 100);
camera.up.set(0, 0, 1);

const local = p => new THREE.Vector3(p[0] - C[0], p[1] - C[1], p[2] - C[2]);
const pickable = [], labels = [];
const fmt = (v, n) => (v === null || v === undefined) ? "–" : Number(v).toFixed(n === undefined ? 3 : n);
const xyz = p => p.map(v => fmt(v)).join(", ");

function ball(p, radius, colour, onTop) {
  const m = new THREE.Mesh(new THREE.SphereGeometry(radius, 20, 14),
                           new THREE.MeshBasicMaterial({color: colour, depthTest: !onTop}));
  m.position.copy(local(p));
  if (onTop) m.renderOrder = 10;
  scene.add(m);
  return m;
}
function box(p, size, colour) {
  const m = new THREE.Mesh(new THREE.BoxGeometry(size, size, size),
                           new THREE.MeshBasicMaterial({color: colour}));
  m.position.copy(local(p));
  scene.add(m);
  return m;
}
function diamond(p, size, colour) {
  const m = new THREE.Mesh(new THREE.OctahedronGeometry(size),
                           new THREE.MeshBasicMaterial({color: colour}));
  m.position.copy(local(p));
  scene.add(m);
  return m;
}
function line(a, b, colour, dashed) {
  const g = new THREE.BufferGeometry().setFromPoints([local(a), local(b)]);
  const mat = dashed ? new THREE.LineDashedMaterial({color: colour, dashSize: S.size / 60,
                                                     gapSize: S.size / 90})
                     : new THREE.LineBasicMaterial({color: colour});
  const l = new THREE.Line(g, mat);
  if (dashed) l.computeLineDistances();
  scene.add(l);
  return l;
}
function label(p, text, cls) {
  const d = document.createElement("div");
  d.className = "label " + (cls || "");
  d.textContent = text;
  labelsEl.appendChild(d);
  labels.push({at: local(p), el: d});
}
function pick(mesh, kind, name, text) {
  mesh.userData = {kind: kind, name: name, info: text};
  pickable.push(mesh);
}
const plus = (a, b, k) => [0, 1, 2].map(i => a[i] + b[i] * k);

// the measured points: tracker (mapped through the fit), robot, residual magnified
for (const p of S.points) {
  const text = `${p.name}${p.used ? "" : " (excluded" + (p.excluded_by ? ", " + p.excluded_by : "") + ")"}
residual ${fmt(p.residual)} mm (dx ${fmt(p.d[0])}, dy ${fmt(p.d[1])}, dz ${fmt(p.d[2])})
laser (UCS) ${xyz(p.laser)}
tracker via fit ${xyz(p.tracker)}
robot ${xyz(p.robot)}`;
  pick(ball(p.tracker, R, MARK, true), "tracker", p.name, text);
  pick(ball(p.robot, R * 0.6, ROBOT, false), "robot", p.name, text);
  line(p.tracker, plus(p.tracker, p.drawn, 1), RESID);
  if (!p.used) {
    const ring = ball(p.tracker, R * 1.6, 0x000000, true);
    ring.renderOrder = 9;
    label(p.tracker, `${p.name} excluded, ${fmt(p.residual, 2)} mm` +
                     (p.clipped ? " (arrow shortened)" : ""), "excluded");
  } else {
    label(p.tracker, p.name);
  }
}

// frames: X red, Y green, Z blue; the simulated one dashed, Δ between the origins
function frame(f, dashed, name) {
  f.axes.forEach((a, k) => line(f.origin, plus(f.origin, a, S.axis_length), AXES[k], dashed));
  label(plus(f.origin, f.axes[0], S.axis_length), name);     // at X: frames turned about Z part there
}
frame(S.measured, false, "measured");
if (S.simulated) {
  frame(S.simulated, true, "simulated " + (S.simulated.name || ""));
  line(S.simulated.origin, S.measured.origin, 0x555555, true);
  const mid = plus(S.simulated.origin, S.measured.origin.map((v, i) => v - S.simulated.origin[i]), 0.5);
  const d = S.delta;
  label(mid, `Δ ${fmt(d.dist)} mm, ${fmt(d.angle, 4)}° (dx ${fmt(d.dx)}, dy ${fmt(d.dy)}, dz ${fmt(d.dz)})`, "delta");
}

// working points: green (lowest predicted 95 % error) to red (highest); the worst named
const errs = S.working.map(w => w.at_95).filter(v => v !== null && isFinite(v));
const top = errs.length ? Math.max(...errs) : 1, low = errs.length ? Math.min(...errs) : 0;
for (const w of S.working) {
  const f = (w.at_95 === null || top === low) ? 1 : (w.at_95 - low) / (top - low);
  const colour = new THREE.Color().setRGB(0.17 + 0.67 * f, 0.63 - 0.48 * f, 0.17 - 0.01 * f);
  pick(box(w.at, RW * 1.4, colour), "working", w.name,
       `${w.name}: predicted 95 % error ${fmt(w.at_95)} mm\nat ${xyz(w.at)}`);
  if (w.worst) label(w.at, `worst: ${w.name} ${fmt(w.at_95)} mm (95 %)`, "worst");
}

// a plan: planned points, the suggested point, the point it would drop
if (S.plan) {
  for (const p of S.plan.points) {
    pick(diamond(p.at, RW * 1.2, 0x17becf), "planned", p.name, `planned ${p.name}\n${xyz(p.at)}`);
    if (p.name === S.plan.drop) label(p.at, `drop ${p.name}`, "excluded");
  }
  if (S.plan.add) {
    const a = S.plan.add;
    pick(diamond(a.at, RW * 1.6, 0x2ca02c), "add", a.name,
         `add ${a.name}: worst after ${fmt(a.worst_after)} mm\n${xyz(a.at)}`);
    label(a.at, `add ${a.name}`);
  }
}

// the camera: orbit about a target (drag), pan (right- or shift-drag), zoom (wheel)
const view = {az: -0.9, el: 0.5, target: new THREE.Vector3(), zoom: 1};
function place() {
  const w = el.clientWidth || 1, h = el.clientHeight || 1, half = S.size * 0.75;
  renderer.setSize(w, h);
  Object.assign(camera, {left: -half * w / h, right: half * w / h, top: half, bottom: -half,
                         zoom: view.zoom});
  const d = S.size * 10, ce = Math.cos(view.el);
  camera.position.set(view.target.x + d * ce * Math.cos(view.az),
                      view.target.y + d * ce * Math.sin(view.az),
                      view.target.z + d * Math.sin(view.el));
  camera.lookAt(view.target);
  camera.updateProjectionMatrix();
}
function nice(x) {
  const k = Math.pow(10, Math.floor(Math.log10(x)));
  return [5, 2, 1].map(m => m * k).find(v => v <= x) || k;
}
function render() {
  place();
  renderer.render(scene, camera);
  const w = el.clientWidth, h = el.clientHeight;
  for (const l of labels) {
    const v = l.at.clone().project(camera);
    l.el.style.left = ((v.x + 1) / 2 * w) + "px";
    l.el.style.top = ((1 - v.y) / 2 * h) + "px";
  }
  const pxPerMm = h * view.zoom / (S.size * 1.5), len = nice(120 / pxPerMm);
  document.getElementById("scale-bar").style.width = (len * pxPerMm) + "px";
  document.getElementById("scale-text").textContent = `${len} mm`;
}
function reset() { Object.assign(view, {az: -0.9, el: 0.5, zoom: 1}); view.target.set(0, 0, 0); render(); }
document.getElementById("reset").addEventListener("click", reset);

let drag = null;
el.addEventListener("contextmenu", e => e.preventDefault());
el.addEventListener("pointerdown", e => { drag = {x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey, moved: false}; });
window.addEventListener("pointerup", e => { if (drag && !drag.moved) show(e, true); drag = null; });
window.addEventListener("pointermove", e => {
  if (!drag) { show(e, false); return; }
  const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
  if (Math.abs(dx) + Math.abs(dy) > 2) drag.moved = true;
  drag.x = e.clientX; drag.y = e.clientY;
  if (drag.pan) {
    const k = S.size * 1.5 / (el.clientHeight * view.zoom);
    const right = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0);
    const up = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 1);
    view.target.addScaledVector(right, -dx * k).addScaledVector(up, dy * k);
  } else {
    view.az -= dx * 0.01;
    view.el = Math.max(-1.55, Math.min(1.55, view.el + dy * 0.01));
  }
  render();
});
el.addEventListener("wheel", e => {
  e.preventDefault();
  view.zoom = Math.max(0.05, Math.min(200, view.zoom * Math.exp(-e.deltaY * 0.001)));
  render();
}, {passive: false});

const ray = new THREE.Raycaster();
function show(e, sticky) {
  const b = renderer.domElement.getBoundingClientRect();
  if (e.clientX < b.left || e.clientX > b.right || e.clientY < b.top || e.clientY > b.bottom) return;
  ray.setFromCamera(new THREE.Vector2((e.clientX - b.left) / b.width * 2 - 1,
                                      1 - (e.clientY - b.top) / b.height * 2), camera);
  const hit = ray.intersectObjects(pickable, false)[0];
  if (hit) info.textContent = hit.object.userData.info;
  else if (sticky) info.textContent = "hover or click a point for its numbers";
}
window.addEventListener("resize", render);

// what tests and scripts read back: the drawn markers, in the scene's coordinates
window.ucsioView = {
  scene: scene, camera: camera, render: render, reset: reset,
  markers: kind => pickable.filter(m => !kind || m.userData.kind === kind).map(m => ({
    kind: m.userData.kind, name: m.userData.name,
    at: [m.position.x + C[0], m.position.y + C[1], m.position.z + C[2]]})),
};
render();
document.body.dataset.ready = "1";
})();
