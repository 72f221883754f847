// ucsio: a batch report's picture of one entry. The report's folder holds one
// page (view.html) and the entries' numbers (entries.js: window.UCSIO_ENTRIES,
// each solution's fit and point pairs as batch solved them); the page's hash
// (#12) names the entry. This builds the same scene as ucsio/picture/scene.py
// (tests/test_report_browser.py compares the two, entry by entry), fills the
// page's facts, legend and projections as page.py and svg.py write them, and
// leaves the scene in #ucsio-scene for viewer.js, which draws it in 3D.
(function () {
"use strict";
const all = window.UCSIO_ENTRIES || {};
const keys = Object.keys(all);
const key = location.hash.slice(1) in all ? location.hash.slice(1) : keys[0];
window.addEventListener("hashchange", () => location.reload());
const E = all[key];

function nice(x) {                        // 1, 2 or 5 x 10^k at or below x
  if (!(x > 0) || !isFinite(x)) return 1.0;
  const k = Math.floor(Math.log10(x));
  for (const m of [5, 2, 1]) if (m * 10 ** k <= x) return m * 10 ** k;
  return 10 ** k;
}
function matrix(q) {                      // unit quaternion w, x, y, z -> rotation rows
  const n = Math.hypot(q[0], q[1], q[2], q[3]);
  const [w, x, y, z] = q.map(v => v / n);
  return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
          [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
          [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]];
}
const apply = (R, t, p) => [0, 1, 2].map(i => R[i][0] * p[0] + R[i][1] * p[1] + R[i][2] * p[2] + t[i]);
const mul = (A, B) => A.map(r => [0, 1, 2].map(j => r[0] * B[0][j] + r[1] * B[1][j] + r[2] * B[2][j]));
const tr = A => [0, 1, 2].map(i => [A[0][i], A[1][i], A[2][i]]);
const frameOf = (R, t) => ({origin: t.slice(), axes: [0, 1, 2].map(k => [R[0][k], R[1][k], R[2][k]])});

function scene(e) {
  const R = matrix(e.frame.q), t = e.frame.t;
  const points = e.points.map(([name, laser, robot, used, excludedBy]) => {
    const tracker = apply(R, t, laser);
    const d = [0, 1, 2].map(k => robot[k] - tracker[k]);
    return {name: name, laser: laser, tracker: tracker, robot: robot, d: d,
            residual: Math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]),
            used: used !== false, excluded_by: excludedBy};
  });
  const s = {title: e.title, units: "mm", coordinates: "robot world (the measured frame's parent)",
             accepted: e.accepted, reason: e.reason, rms: e.rms, max: e.max, points: points,
             measured: frameOf(R, t), simulated: null, delta: null, plan: null,
             working: (e.working || []).map(w => ({name: w.name, at: apply(R, t, [w.x, w.y, w.z]),
                                                    at_95: w.at_95, worst: !!e.worst && w.name === e.worst.name}))};
  if (e.simulated) {                      // diff's frame, mapped as scene.simulated_in_world does
    const Rs = matrix(e.simulated.sim.q), Rm = matrix(e.simulated.mea.q);
    const B = mul(R, tr(Rm));             // basis = measured * mea^-1
    const Bt = [0, 1, 2].map(i => t[i] - (B[i][0] * e.simulated.mea.t[0] + B[i][1] * e.simulated.mea.t[1]
                                            + B[i][2] * e.simulated.mea.t[2]));
    s.simulated = frameOf(mul(B, Rs), apply(B, Bt, e.simulated.sim.t));
    s.simulated.name = e.simulated.name;
    s.delta = e.simulated.delta;
  }
  const xyz = points.map(p => p.tracker).concat(points.map(p => p.robot), s.working.map(w => w.at), [t]);
  if (s.simulated) xyz.push(s.simulated.origin);
  const lo = [0, 1, 2].map(k => Math.min(...xyz.map(p => p[k])));
  const hi = [0, 1, 2].map(k => Math.max(...xyz.map(p => p[k])));
  const size0 = Math.max(...[0, 1, 2].map(k => hi[k] - lo[k]));
  s.center = [0, 1, 2].map(k => (lo[k] + hi[k]) / 2);
  s.size = size0 > 0 ? size0 : 100.0;
  const used = points.filter(p => p.used).map(p => p.residual);
  const worst = (used.length ? Math.max(...used) : 0) || Math.max(0, ...points.map(p => p.residual));
  s.magnify = worst > 0 ? Math.max(1.0, nice(0.1 * s.size / worst)) : 1.0;
  s.axis_length = nice(0.35 * s.size);
  s.scale_bar = nice(0.25 * s.size);
  let r = 0.012 * s.size;
  const tk = points.map(p => p.tracker);
  if (tk.length <= 200) {
    let closest = Infinity;
    for (let i = 0; i < tk.length; i++) for (let j = i + 1; j < tk.length; j++)
      closest = Math.min(closest, Math.hypot(tk[i][0] - tk[j][0], tk[i][1] - tk[j][1], tk[i][2] - tk[j][2]));
    if (closest > 0 && isFinite(closest)) r = Math.min(r, 0.25 * closest);
  }
  s.marker = r;
  const longest = 0.4 * s.size;
  for (const p of points) {
    const v = p.d.map(c => c * s.magnify), n = Math.hypot(...v);
    p.clipped = n > longest;
    p.drawn = p.clipped ? v.map(c => c * longest / n) : v;
  }
  return s;
}

const esc = t => String(t).replace(/[&<>"']/g, c => ({"&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#x27;"}[c]));
const g = v => String(Number(v.toPrecision(6)));
function facts(s) {
  const n = s.points.length, used = s.points.filter(p => p.used).length;
  const parts = [`${n} points, ${used} used`, `residuals drawn ×${g(s.magnify)}`, `units mm, ${s.coordinates}`];
  if (s.rms !== null && s.rms !== undefined) parts.splice(1, 0, `rms ${s.rms.toFixed(3)} mm`);
  if (s.delta && s.delta.dist !== null && s.delta.dist !== undefined)
    parts.push(`Δ simulated → measured ${s.delta.dist.toFixed(3)} mm, ${s.delta.angle.toFixed(4)}°`);
  if (s.accepted === false) parts.push("REJECTED: " + (s.reason || ""));
  return parts.join(" · ");
}
function legend(s) {
  const items = [["swatch sw-tracker", "tracker point, mapped through the fit"],
                 ["swatch sw-robot", "robot point (flange · TCP)"],
                 ["swatch sw-residual", `residual robot − fit, drawn ×${g(s.magnify)}`],
                 ["swatch sw-excluded", "excluded point (named)"],
                 ["swatch sw-measured", "measured frame: X red, Y green, Z blue"]];
  if (s.simulated) items.push(["swatch sw-simulated", "simulated frame (dashed), Δ its offset"]);
  if (s.working.length) items.push(["swatch sw-working", "working point: predicted 95 % error, green low to red high; the worst named"]);
  return items.map(([c, t]) => `<li class="item"><span class="${c}"></span>${esc(t)}</li>`).join("");
}
const SIZE = 300, PAD = 30, AXIS = ["#d62728", "#2ca02c", "#1f77b4"];
function projection(s, name, i, j) {      // as svg.py draws one view
  const cx = s.center[i], cy = s.center[j], k = (SIZE - 2 * PAD) / (s.size * 1.3);
  const xy = p => [SIZE / 2 + (p[i] - cx) * k, SIZE / 2 - (p[j] - cy) * k];
  const f1 = v => v.toFixed(1);
  const out = [`<figure class="proj"><svg id="svg-${name}" viewBox="0 0 ${SIZE} ${SIZE}" width="${SIZE}" height="${SIZE}" role="img" aria-label="${name} view">`,
               `<rect class="bg" width="${SIZE}" height="${SIZE}"/>`];
  for (const [f, dash] of [[s.simulated, ' stroke-dasharray="4 3"'], [s.measured, ""]]) {
    if (!f) continue;
    const o = xy(f.origin);
    f.axes.forEach((a, m) => {
      const e = xy([0, 1, 2].map(c => f.origin[c] + a[c] * s.axis_length));
      out.push(`<line x1="${f1(o[0])}" y1="${f1(o[1])}" x2="${f1(e[0])}" y2="${f1(e[1])}" stroke="${AXIS[m]}" stroke-width="2"${dash}/>`);
    });
  }
  for (const w of s.working) {
    const [x, y] = xy(w.at);
    out.push(`<rect class="working" x="${f1(x - 3)}" y="${f1(y - 3)}" width="6" height="6"><title>${esc(w.name)}</title></rect>`);
  }
  for (const p of s.points) {
    const [x, y] = xy(p.tracker), e = xy([0, 1, 2].map(c => p.tracker[c] + p.drawn[c]));
    out.push(`<line class="residual" x1="${f1(x)}" y1="${f1(y)}" x2="${f1(e[0])}" y2="${f1(e[1])}"/>`);
    out.push(`<circle class="${p.used ? "point" : "point excluded"}" cx="${f1(x)}" cy="${f1(y)}" r="4" data-name="${esc(p.name)}"><title>${esc(p.name)}: ${p.residual.toFixed(3)} mm</title></circle>`);
    if (!p.used) out.push(`<text x="${f1(x + 6)}" y="${f1(y - 6)}">${esc(p.name)} ${p.residual.toFixed(2)} mm</text>`);
  }
  const bar = s.scale_bar * k;
  out.push(`<line class="scale" x1="10" y1="${SIZE - 10}" x2="${f1(10 + bar)}" y2="${SIZE - 10}"/><text x="10" y="${SIZE - 14}">${g(s.scale_bar)} mm</text>`);
  out.push(`<text x="${SIZE - 10}" y="16" text-anchor="end">${name}</text></svg><figcaption>${name}: ${name[0]} to the right, ${name[1]} up</figcaption></figure>`);
  return out.join("");
}

const S = scene(E);
const title = "ucsio view: " + S.title;
document.title = title;
document.querySelector("h1").textContent = title;
document.querySelector(".facts").textContent = facts(S);
document.getElementById("legend").innerHTML = legend(S);
document.getElementById("projections").innerHTML =
  [["XY", 0, 1], ["XZ", 0, 2], ["YZ", 1, 2]].map(([n, i, j]) => projection(S, n, i, j)).join("");
const block = document.createElement("script");
block.type = "application/json";
block.id = "ucsio-scene";
block.textContent = JSON.stringify(S);
document.body.appendChild(block);
})();
