#pragma once
// The drawing page of `terraweave view RUN --serve --exemplar ...` (docs/networks.md, "Drawing"):
// @DATA@ becomes the run's map as JSON (its colours as RGB rows north first, its grid and CRS,
// its feature lines, where the drawing is saved). The page draws strokes in map coordinates,
// asks the server (POST /complete) to complete a region by the method chosen, turned to the lead
// chosen (none, the long axis, the nearest road, the contours or a bearing), and names in its
// status line the method that made the suggestions ("completed by layout (automatic chose it)")
// and the bearing the lead gave,
// lets the user accept the suggestions (all, one by a click, or those inside a lasso) or reject
// them, undo the last stroke or accept (Ctrl+Z), and saves (POST /save). On loading it shows the
// drawing saved before (GET /drawing) as accepted lines; a stroke's ends within a few pixels of a
// line are joined to it.
// window.__network exposes the state (lines, suggestions, the map's transform) for the tests.
namespace tw::detail {

inline constexpr const char* kNetworkPage = R"html(<!doctype html>
<html><head><meta charset="utf-8"><title>terraweave network drawing</title>
<style>
html,body{margin:0;height:100%;background:#ddd;font:13px sans-serif}
#bar{position:absolute;top:0;left:0;right:0;height:34px;background:#fff;padding:4px 8px;
  box-sizing:border-box;display:flex;gap:4px;align-items:center}
#bar button,#bar select,#bar input{white-space:nowrap;font:12px sans-serif;padding:1px 4px}
#bar button.on{background:#246;color:#fff}
#map{position:absolute;top:34px;left:0;cursor:crosshair;touch-action:none}
#status{margin-left:8px;color:#333;white-space:nowrap;overflow:hidden}
</style></head><body>
<div id="bar">
<button id="draw" class="on" title="draw strokes with the pointer">draw</button>
<button id="region" title="drag a box: the region to complete">region</button>
<button id="area" title="draw a loop: the region to complete">region by lasso</button>
<select id="method" title="how the region is completed: growth from the drawn ends, quilting of exemplar blocks or growth from the exemplar's laid-out long strokes (a region without drawn lines), or automatic (the closest to the exemplar's style; growth where lines are drawn)">
<option>automatic</option><option>growth</option><option>quilt</option><option>layout</option></select>
<select id="lead" title="the direction the exemplar is turned to over the region, as a pipeline's network lead: none (as drawn), the region's long axis, the run's nearest road, the terrain's contours, or a compass bearing">
<option value="">no lead</option><option value="long_axis">long axis</option><option value="nearest_road">road</option><option value="contours">contours</option><option value="bearing">bearing</option></select>
<input id="bearing" type="number" value="0" step="any" title="the lead's compass bearing in degrees (lead: bearing)" style="width:3.5em;display:none">
<button id="complete" title="ask for suggestions in the region">complete</button>
<button id="pick" title="click a suggestion to accept it">accept one</button>
<button id="lasso" title="draw a loop: suggestions inside it are accepted">accept by lasso</button>
<button id="all" title="accept every suggestion">accept all</button>
<button id="reject" title="drop the suggestions not accepted">reject</button>
<button id="undo" title="undo the last stroke or accept (Ctrl+Z)">undo</button>
<button id="save">save</button>
<span id="status"></span>
</div>
<canvas id="map"></canvas>
<script id="data" type="application/json">@DATA@</script>
<script>
const D = JSON.parse(document.getElementById('data').textContent);
const canvas = document.getElementById('map'), ctx = canvas.getContext('2d');
const W = D.image.width, H = D.image.height;
// The image enlarged by a whole factor to fill the window (at least 1).
const k = Math.max(1, Math.floor(Math.min(innerWidth / W, (innerHeight - 34) / H)));
canvas.width = W * k; canvas.height = H * k;
// Canvas pixel (column, row from the top) <-> map coordinates: the run's grid on the canvas.
const sx = D.grid.pixel_size[0] * D.grid.width / (W * k);
const sy = D.grid.pixel_size[1] * D.grid.height / (H * k);
const toMap = (px, py) => [D.grid.origin[0] + px * sx, D.grid.origin[1] - py * sy];
const toPixel = ([x, y]) => [(x - D.grid.origin[0]) / sx, (D.grid.origin[1] - y) / sy];
const rgb = Uint8Array.from(atob(D.image.rgb), c => c.charCodeAt(0));
const image = document.createElement('canvas');
image.width = W; image.height = H;
const pixels = image.getContext('2d').createImageData(W, H);
for (let r = 0; r < H; ++r)
  for (let c = 0; c < W; ++c) {
    const i = (r * W + c) * 3, o = (r * W + c) * 4;
    pixels.data[o] = rgb[i]; pixels.data[o + 1] = rgb[i + 1]; pixels.data[o + 2] = rgb[i + 2];
    pixels.data[o + 3] = 255;
  }
image.getContext('2d').putImageData(pixels, 0, 0);
// history: what undo takes back, last first: {kind: 'stroke', inserted: [[line, vertex], ...]}
// (the stroke is the last line; vertices its snapped ends added to other lines) or
// {kind: 'accept', count} (the last `count` lines, accepted suggestions).
const S = {lines: [], origins: [], suggestions: [], region: null, mode: 'draw', saved: null,
           history: [], transform: {origin: D.grid.origin, pixel: [sx, sy]}};
window.__network = S;
const status = t => { document.getElementById('status').textContent = t; };
const path = (pts, close) => {
  ctx.beginPath();
  pts.forEach((p, k) => { const [u, v] = toPixel(p); k ? ctx.lineTo(u, v) : ctx.moveTo(u, v); });
  if (close) ctx.closePath();
};
let live = null;  // the stroke, box or lasso being drawn (map coordinates)
const redraw = () => {
  ctx.imageSmoothingEnabled = true;
  ctx.drawImage(image, 0, 0, W * k, H * k);
  ctx.lineCap = ctx.lineJoin = 'round';
  ctx.strokeStyle = '#444'; ctx.lineWidth = 2;  // the run's features
  for (const f of D.features) if (f.length > 1) { path(f); ctx.stroke(); }
  if (S.region) {
    path(S.region, true); ctx.fillStyle = '#fff3'; ctx.fill();
    ctx.setLineDash([6, 4]); ctx.strokeStyle = '#fff'; ctx.stroke(); ctx.setLineDash([]);
  }
  ctx.strokeStyle = '#2c9a3c'; ctx.lineWidth = 2;
  for (const s of S.suggestions) { path(s); ctx.stroke(); }
  S.lines.forEach((l, k) => {
    ctx.strokeStyle = S.origins[k] === 'drawn' ? '#111' : '#146'; ctx.lineWidth = 3;
    path(l); ctx.stroke();
  });
  if (live && live.points.length > 1) {
    ctx.strokeStyle = live.kind === 'lasso' ? '#e80' : live.kind === 'area' ? '#fff' : '#111';
    ctx.lineWidth = 2;
    path(live.kind === 'region' ? box(live.points) : live.points, live.kind !== 'draw');
    ctx.stroke();
  }
  document.body.dataset.lines = S.lines.length;
  document.body.dataset.suggestions = S.suggestions.length;
};
const box = pts => {
  const [a, b] = [pts[0], pts[pts.length - 1]];
  const x0 = Math.min(a[0], b[0]), x1 = Math.max(a[0], b[0]);
  const y0 = Math.min(a[1], b[1]), y1 = Math.max(a[1], b[1]);
  return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
};
const setMode = m => {
  S.mode = m;
  for (const id of ['draw', 'region', 'area', 'pick', 'lasso'])
    document.getElementById(id).classList.toggle('on', id === m);
};
for (const id of ['draw', 'region', 'area', 'pick', 'lasso'])
  document.getElementById(id).onclick = () => setMode(id);
const canvasPixel = e => {
  const r = canvas.getBoundingClientRect();
  return [(e.clientX - r.left) * canvas.width / r.width, (e.clientY - r.top) * canvas.height / r.height];
};
const at = e => toMap(...canvasPixel(e));
const inside = (p, ring) => {  // even-odd rule
  let c = false;
  for (let i = 0, j = ring.length - 1; i < ring.length; j = i++)
    if ((ring[i][1] > p[1]) !== (ring[j][1] > p[1]) &&
        p[0] < (ring[j][0] - ring[i][0]) * (p[1] - ring[i][1]) / (ring[j][1] - ring[i][1]) +
               ring[i][0])
      c = !c;
  return c;
};
const accept = keep => {  // suggestions for which keep(s) holds join the lines
  const rest = [];
  for (const s of S.suggestions)
    if (keep(s)) { S.lines.push(s); S.origins.push('suggested'); } else rest.push(s);
  const n = S.suggestions.length - rest.length;
  S.suggestions = rest;
  if (n > 0) S.history.push({kind: 'accept', count: n});
  status(`${n} accepted, ${rest.length} suggestions left`);
  redraw();
};
// A stroke's end within SNAP canvas pixels of a line of the drawing is joined to it exactly: onto
// the nearest line end, else the nearest vertex of the nearest segment, else the point of that
// segment nearest to it, inserted into the line as a vertex (both lines then hold the same
// doubles: a T-junction the server's noding sees). Insertions are recorded in `inserted`.
const SNAP = 6;
const snapEnd = (stroke, which, inserted) => {
  const [u, v] = toPixel(stroke[which]);
  const far = q => { const [a, b] = toPixel(q); return Math.hypot(a - u, b - v); };
  let end = null, endD = SNAP;
  for (const l of S.lines)
    for (const q of [l[0], l[l.length - 1]])
      if (far(q) <= endD) { endD = far(q); end = q; }
  if (end) { stroke[which] = end.slice(); return; }
  let near = null, nearD = SNAP;
  S.lines.forEach((l, i) => {
    for (let k = 0; k + 1 < l.length; ++k) {
      const [a, b] = [toPixel(l[k]), toPixel(l[k + 1])];
      const dx = b[0] - a[0], dy = b[1] - a[1];
      const t = Math.max(0, Math.min(1, ((u - a[0]) * dx + (v - a[1]) * dy) /
                                            Math.max(dx * dx + dy * dy, 1e-12)));
      const d = Math.hypot(a[0] + t * dx - u, a[1] + t * dy - v);
      if (d <= nearD) { nearD = d; near = {i, k, t}; }
    }
  });
  if (!near) return;
  const l = S.lines[near.i], a = l[near.k], b = l[near.k + 1];
  const vertex = far(a) <= far(b) ? a : b;
  if (far(vertex) <= SNAP) { stroke[which] = vertex.slice(); return; }
  const q = [a[0] + near.t * (b[0] - a[0]), a[1] + near.t * (b[1] - a[1])];
  l.splice(near.k + 1, 0, q);
  inserted.push([near.i, near.k + 1]);
  stroke[which] = q.slice();
};
const undo = () => {
  const last = S.history.pop();
  if (!last) { status('nothing to undo'); return; }
  if (last.kind === 'stroke') {
    S.lines.pop(); S.origins.pop();
    for (const [i, k] of last.inserted.reverse()) S.lines[i].splice(k, 1);
    status('stroke undone');
  } else {
    S.suggestions.push(...S.lines.splice(S.lines.length - last.count, last.count));
    S.origins.splice(S.origins.length - last.count, last.count);
    status(`${last.count} accepted lines back among the suggestions`);
  }
  document.body.dataset.undone = (+document.body.dataset.undone || 0) + 1;
  redraw();
};
document.getElementById('undo').onclick = undo;
document.addEventListener('keydown', e => {
  if ((e.ctrlKey || e.metaKey) && !e.shiftKey && e.key.toLowerCase() === 'z') {
    e.preventDefault();
    undo();
  }
});
canvas.addEventListener('pointerdown', e => {
  canvas.setPointerCapture(e.pointerId);
  if (S.mode === 'pick') {
    const [u, v] = canvasPixel(e);
    let best = null, bestD = 8;  // pixels
    for (const s of S.suggestions)
      for (let k = 0; k + 1 < s.length; ++k) {
        const [a, b] = [toPixel(s[k]), toPixel(s[k + 1])];
        const dx = b[0] - a[0], dy = b[1] - a[1];
        const t = Math.max(0, Math.min(1, ((u - a[0]) * dx + (v - a[1]) * dy) /
                                              Math.max(dx * dx + dy * dy, 1e-12)));
        const d = Math.hypot(a[0] + t * dx - u, a[1] + t * dy - v);
        if (d < bestD) { bestD = d; best = s; }
      }
    if (best) accept(s => s === best);
    return;
  }
  live = {kind: S.mode, points: [at(e)]};
});
canvas.addEventListener('pointermove', e => {
  if (!live) return;
  live.points.push(at(e));
  redraw();
});
canvas.addEventListener('pointerup', e => {
  if (!live) return;
  const done = live; live = null;
  if (done.points.length < 2) { redraw(); return; }
  if (done.kind === 'draw') {
    const inserted = [];
    snapEnd(done.points, 0, inserted);
    snapEnd(done.points, done.points.length - 1, inserted);
    S.lines.push(done.points); S.origins.push('drawn');
    S.history.push({kind: 'stroke', inserted});
  }
  if (done.kind === 'region') S.region = box(done.points);
  if (done.kind === 'area' && done.points.length > 2) S.region = done.points;
  if (done.kind === 'lasso') accept(s => s.every(p => inside(p, done.points)));
  redraw();
});
const post = async (url, body) => {
  const r = await fetch(url, {method: 'POST', headers: {'Content-Type': 'application/json'},
                              body: JSON.stringify(body)});
  const answer = await r.json();
  if (!r.ok) throw new Error(answer.error);
  return answer;
};
document.getElementById('complete').onclick = async () => {
  if (!S.region) { status('drag a region first'); return; }
  status('completing...');
  try {
    const lead = document.getElementById('lead').value;
    const a = await post('complete', {lines: S.lines, region: S.region,
                                      method: document.getElementById('method').value,
                                      lead: lead === 'bearing'
                                          ? {bearing: +document.getElementById('bearing').value}
                                          : lead || null});
    S.suggestions = a.suggestions;
    const asked = a.method === a.chosen ? '' : ` (${a.method} chose it)`;
    const turned = a.lead_bearing_deg === null ? '' : `, turned to ${a.lead_bearing_deg.toFixed(1)}°`;
    const warned = a.warning ? ` (${a.warning})` : '';
    status(`${a.suggestions.length} suggestions, completed by ${a.chosen}${asked}${turned}${warned}`);
  } catch (err) { status(err.message); }
  document.body.dataset.completed = (+document.body.dataset.completed || 0) + 1;
  redraw();
};
document.getElementById('lead').onchange = e => {
  document.getElementById('bearing').style.display = e.target.value === 'bearing' ? '' : 'none';
};
document.getElementById('all').onclick = () => accept(() => true);
document.getElementById('reject').onclick = () => {
  status(`${S.suggestions.length} rejected`); S.suggestions = []; redraw();
};
document.getElementById('save').onclick = async () => {
  try {
    const a = await post('save', {lines: S.lines, origins: S.origins});
    S.saved = a.path;
    status(`saved ${a.lines} lines to ${a.path}`);
  } catch (err) { status(err.message); }
  redraw();
};
status(`${D.name}: lines are saved to ${D.save_path}`);
redraw();
// The drawing saved before, if any, as accepted lines (before anything drawn meanwhile).
fetch('drawing').then(async r => {
  const a = await r.json();
  if (!r.ok) throw new Error(a.error);
  const n = a.lines.length;
  S.lines = a.lines.concat(S.lines);
  S.origins = a.origins.concat(S.origins);
  for (const h of S.history) if (h.inserted) h.inserted = h.inserted.map(([i, k]) => [i + n, k]);
  if (n) status(`${n} saved lines shown from ${D.save_path}`);
  document.body.dataset.loaded = n;
  redraw();
}).catch(err => { status(err.message); document.body.dataset.loaded = 'error'; });
</script></body></html>
)html";

}  // namespace tw::detail
