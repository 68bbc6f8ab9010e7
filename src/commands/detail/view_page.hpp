#pragma once
// The page of `terraweave view`: @THREE@ becomes three.module.min.js in base64, @DATA@ the
// run's data as JSON. Once the first frame is drawn, window.__terraweaveReady holds its time
// since the navigation started, the title turns to "terraweave view: ready in N ms" and the
// console says so (what bench/view_load.sh waits for).
namespace tw::detail {

inline constexpr const char* kViewPage = R"html(<!doctype html>
<html><head><meta charset="utf-8"><title>terraweave view: loading</title>
<style>
html,body{margin:0;height:100%;overflow:hidden;background:#9db4c8;font:13px sans-serif}
#ui{position:absolute;top:8px;left:8px;background:#fffd;padding:6px 10px;border-radius:4px}
#ui label{display:block}
</style></head><body>
<div id="ui"><b id="name"></b>
<label><input type="checkbox" id="splat" checked> splat</label>
<label><input type="checkbox" id="avoidance"> avoidance</label>
<label><input type="checkbox" id="features" checked> features</label></div>
<script id="three" type="text/plain">@THREE@</script>
<script id="data" type="application/json">@DATA@</script>
<script type="module">
const t0 = performance.now();
const bytes = s => Uint8Array.from(atob(s), c => c.charCodeAt(0));
const THREE = await import(URL.createObjectURL(new Blob(
    [bytes(document.getElementById('three').textContent.trim())], {type: 'text/javascript'})));
const D = JSON.parse(document.getElementById('data').textContent);
document.getElementById('name').textContent = D.name;
const W = D.grid.width * D.grid.pixel_size[0], H = D.grid.height * D.grid.pixel_size[1];
const mw = D.mesh.width, mh = D.mesh.height, z = D.mesh.heights;
let lo = Infinity, hi = -Infinity;
for (const v of z) if (v !== null) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
const heightAt = (x, y) => {  // world metres -> bilinear mesh height
  const u = Math.min(Math.max((x - D.grid.origin[0]) / W * (mw - 1), 0), mw - 1);
  const v = Math.min(Math.max((D.grid.origin[1] - y) / H * (mh - 1), 0), mh - 1);
  const i = Math.floor(u), j = Math.floor(v), a = u - i, b = v - j;
  const at = (c, r) => z[Math.min(r, mh - 1) * mw + Math.min(c, mw - 1)] ?? lo;
  return (at(i, j) * (1 - a) + at(i + 1, j) * a) * (1 - b) +
         (at(i, j + 1) * (1 - a) + at(i + 1, j + 1) * a) * b;
};
// Relief drawn at least a tenth of the world's extent, so a gentle DEM still reads in 3D.
const exaggeration = Math.max(D.exaggeration, 0.1 * Math.max(W, H) / Math.max(hi - lo, 1));
const geometry = new THREE.PlaneGeometry(W, H, mw - 1, mh - 1);
const pos = geometry.attributes.position;
for (let k = 0; k < pos.count; ++k) pos.setZ(k, ((z[k] ?? lo) - lo) * exaggeration);
// Nodata is no terrain: only triangles whose three corners have heights are drawn.
const corners = geometry.index.array, kept = [];
for (let k = 0; k < corners.length; k += 3) {
  if (z[corners[k]] !== null && z[corners[k + 1]] !== null && z[corners[k + 2]] !== null)
    kept.push(corners[k], corners[k + 1], corners[k + 2]);
}
geometry.setIndex(kept);
document.body.dataset.triangles = kept.length / 3;  // for the tests (and the curious)
geometry.rotateX(-Math.PI / 2);
geometry.computeVertexNormals();
const texture = (rgba, w, h) => {
  const t = new THREE.DataTexture(rgba, w, h, THREE.RGBAFormat);
  t.colorSpace = THREE.SRGBColorSpace; t.magFilter = THREE.LinearFilter;
  t.needsUpdate = true; return t;
};
// Rows south first (a DataTexture's first row is at v = 0, the plane's south edge).
const tw = D.texture.width, th = D.texture.height, rgb = bytes(D.texture.rgb);
const forbidden = bytes(D.avoidance.mask);
const layers = (splat, avoid) => {
  const out = new Uint8Array(tw * th * 4);
  for (let p = 0; p < tw * th; ++p) {
    let c = splat ? [rgb[3 * p], rgb[3 * p + 1], rgb[3 * p + 2]] : [200, 200, 200];
    if (avoid && forbidden[p]) c = [c[0] / 2 + 120, c[1] / 2, c[2] / 2];
    out.set([c[0], c[1], c[2], 255], 4 * p);
  }
  return texture(out, tw, th);
};
const material = new THREE.MeshLambertMaterial({map: layers(true, false)});
const scene = new THREE.Scene();
scene.add(new THREE.Mesh(geometry, material));
scene.add(new THREE.AmbientLight(0xffffff, 0.9));
const sun = new THREE.DirectionalLight(0xffffff, 2.2);
sun.position.set(-W, Math.max(W, H), -H); scene.add(sun);
const lines = new THREE.Group();
const colours = {road: 0xffe070, river: 0x2060ff, ridge: 0xffffff};
for (const f of D.features) {
  const pts = f.points.map(([x, y]) => new THREE.Vector3(
      x - D.grid.origin[0] - W / 2, (heightAt(x, y) - lo) * exaggeration + 2,
      (D.grid.origin[1] - y) - H / 2));
  lines.add(new THREE.Line(new THREE.BufferGeometry().setFromPoints(pts),
                           new THREE.LineBasicMaterial({color: colours[f.kind] ?? 0xff00ff})));
}
scene.add(lines);
const camera = new THREE.PerspectiveCamera(45, innerWidth / innerHeight, 1, 20 * Math.max(W, H));
const renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
renderer.setClearColor(0x9db4c8);
renderer.setSize(innerWidth, innerHeight);
document.body.appendChild(renderer.domElement);
let azimuth = 0.6, elevation = 0.75, distance = 1.3 * Math.max(W, H);
const draw = () => {
  camera.position.set(distance * Math.cos(elevation) * Math.sin(azimuth),
                      distance * Math.sin(elevation), distance * Math.cos(elevation) * Math.cos(azimuth));
  camera.lookAt(0, (hi - lo) * exaggeration / 3, 0);
  renderer.render(scene, camera);
};
let drag = null;
addEventListener('pointerdown', e => { if (e.target === renderer.domElement) drag = [e.clientX, e.clientY]; });
addEventListener('pointerup', () => drag = null);
addEventListener('pointermove', e => {
  if (!drag) return;
  azimuth -= (e.clientX - drag[0]) * 0.005;
  elevation = Math.min(1.5, Math.max(0.05, elevation + (e.clientY - drag[1]) * 0.005));
  drag = [e.clientX, e.clientY]; draw();
});
addEventListener('wheel', e => { distance *= Math.exp(e.deltaY * 0.001); draw(); });
addEventListener('resize', () => {
  camera.aspect = innerWidth / innerHeight; camera.updateProjectionMatrix();
  renderer.setSize(innerWidth, innerHeight); draw();
});
const toggle = () => {
  material.map.dispose();
  material.map = layers(document.getElementById('splat').checked,
                        document.getElementById('avoidance').checked);
  lines.visible = document.getElementById('features').checked; draw();
};
for (const id of ['splat', 'avoidance', 'features']) document.getElementById(id).onchange = toggle;
draw();
// The frame is on screen at the next animation frame; performance.now() counts from the
// navigation's start, so the stamp is the page's whole load (parse, three.js, data, mesh).
requestAnimationFrame(() => {
  window.__terraweaveReady = performance.now();
  document.title = `terraweave view: ready in ${Math.round(window.__terraweaveReady)} ms`;
  console.log(`${document.title} (script ${Math.round(window.__terraweaveReady - t0)} ms)`);
});
</script></body></html>
)html";

}  // namespace tw::detail
