// surfgrow view: the page's script (three.js r111). It decodes the data embedded in the page
// (docs/viewer.md), builds one three.js object per layer and draws on demand: only when the view
// or a switch changed, so an idle page costs nothing, whatever the size of the cloud.
(function () {
  'use strict';

  // What tests and scripts can ask the page (docs/viewer.md, "Testing hooks").
  const api = (window.surfgrowView = { ready: false, error: null, frames: 0, layers: [] });
  const panel = document.getElementById('sg-panel');

  function fail(message) {
    api.error = message;
    const div = document.createElement('div');
    div.className = 'error';
    div.textContent = message;
    panel.appendChild(div);
    console.error('surfgrow view: ' + message);
  }

  // ---- Data: base64 blocks to typed arrays (little-endian, as written) ----
  function bytesOf(id) {
    const text = document.getElementById(id).textContent;
    const bin = atob(text);
    const out = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; ++i) out[i] = bin.charCodeAt(i);
    return out;
  }
  function floatsOf(id) {
    const b = bytesOf(id);
    return new Float32Array(b.buffer, 0, b.length >> 2);
  }

  const meta = JSON.parse(document.getElementById('sg-meta').textContent);
  const L = meta.layers;
  const R = meta.radius;
  // Disks seen from behind, and their points: 0 shown, 1 ghosted, 2 hidden (the panel switches).
  const backFaces = { value: { show: 0, ghost: 1, hide: 2 }[meta.back_faces] || 0 };

  // ---- Layers ----
  // Disks: one circle instanced per surface; the vertex shader places, orients and lights it
  // (two-sided Lambert from a light fixed to the camera, as in the PNG renderer). Disks seen from
  // behind (normals face the scanner) are shown, ghosted or hidden (uBack 0, 1, 2), as the PNG's
  // BackFaces; the ghosts are drawn in passes of their own (surfacesLayer).
  const diskVertex = [
    'invariant gl_Position;',  // the same depth in every pass: the ghost pass tests for equality
    'attribute vec3 iCenter;', 'attribute vec3 iNormal;', 'attribute float iRadius;',
    'attribute vec3 iColor;', 'attribute vec3 iPlaneColor;',
    'uniform vec3 uLight;', 'uniform float uByPlane;', 'uniform float uBack;', 'uniform float uGhost;',
    'varying vec3 vColor;', 'varying float vRim;',
    'void main() {',
    '  vec3 n = normalize(iNormal);',
    '  vec3 a = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);',
    '  vec3 u = normalize(cross(n, a));',
    '  vec3 v = cross(n, u);',
    '  vec3 p = iCenter + iRadius * (position.x * u + position.y * v);',
    '  vec4 mv = modelViewMatrix * vec4(p, 1.0);',
    '  vec3 nv = normalize(normalMatrix * n);',
    '  vec4 c = modelViewMatrix * vec4(iCenter, 1.0);',
    '  bool back = dot(nv, -c.xyz) < 0.0;',
    '  if (back) nv = -nv;',
    '  vec3 base = mix(iColor, iPlaneColor, uByPlane);',
    '  vColor = base * (0.36 + 0.64 * max(dot(nv, uLight), 0.0));',
    '  if (uGhost > 0.5) vColor = mix(vColor, vec3(1.0), 0.5);',
    '  vRim = length(position.xy);',
    '  gl_Position = projectionMatrix * mv;',
    '  bool drawn = uGhost > 0.5 ? back && uBack > 0.5 && uBack < 1.5 : !back || uBack < 0.5;',
    '  if (!drawn) gl_Position = vec4(0.0, 0.0, 2.0, 1.0);',  // outside the clip volume
    '}'].join('\n');
  const diskFragment = [
    'uniform float uGhost;', 'varying vec3 vColor;', 'varying float vRim;',
    'void main() {',
    '  vec3 c = vRim > 0.86 && uGhost < 0.5 ? vColor * 0.8 : vColor;',
    '  gl_FragColor = vec4(c, uGhost > 0.5 ? 0.35 : 1.0);',
    '}'].join('\n');

  function surfacesLayer() {
    const n = L.surfaces.count;
    const d = floatsOf(L.surfaces.disks);
    const circle = new THREE.CircleBufferGeometry(1, 20);
    const g = new THREE.InstancedBufferGeometry();
    g.setIndex(circle.index);
    g.setAttribute('position', circle.getAttribute('position'));
    const per = new THREE.InstancedInterleavedBuffer(d, 7, 1);
    g.setAttribute('iCenter', new THREE.InterleavedBufferAttribute(per, 3, 0));
    g.setAttribute('iNormal', new THREE.InterleavedBufferAttribute(per, 3, 3));
    g.setAttribute('iRadius', new THREE.InterleavedBufferAttribute(per, 1, 6));
    const color = new THREE.InstancedBufferAttribute(bytesOf(L.surfaces.color), 3, true);
    g.setAttribute('iColor', color);
    g.setAttribute('iPlaneColor', L.surfaces.plane_color
      ? new THREE.InstancedBufferAttribute(bytesOf(L.surfaces.plane_color), 3, true) : color);
    g.maxInstancedCount = n;
    const uniforms = {
      uLight: { value: new THREE.Vector3(-0.45, 0.65, 0.6).normalize() },
      uByPlane: { value: L.surfaces.plane_color ? 1 : 0 },
      uBack: backFaces,
    };
    // Passes: solid disks; ghosts' depth only; ghosts' colour where their depth is the nearest.
    // So exactly one ghost layer tints each pixel, however many ghosts overlap there (the PNG's
    // screen door does the same), and the solid disks behind stay readable.
    const group = new THREE.Group();
    const passes = [
      [0, {}],
      [1, { colorWrite: false }],
      [1, { transparent: true, depthWrite: false, depthFunc: THREE.EqualDepth }],
    ];
    passes.forEach(([ghost, options], k) => {
      const m = new THREE.ShaderMaterial(Object.assign({
        uniforms: Object.assign({ uGhost: { value: ghost } }, uniforms),
        vertexShader: diskVertex,
        fragmentShader: diskFragment,
        side: THREE.DoubleSide,
      }, options));
      const mesh = new THREE.Mesh(g, m);
      mesh.frustumCulled = false;  // the circle's bounds are not the instances' bounds
      mesh.renderOrder = k;
      group.add(mesh);
    });
    // The ghost passes cost as much as the solid one: skip them unless ghosting.
    const setBack = (mode) => {
      uniforms.uBack.value = mode;
      group.children[1].visible = group.children[2].visible = mode === 1;
    };
    setBack(uniforms.uBack.value);
    return { object: group, count: n, data: d, uniforms, setBack };
  }

  function normalsLayer(disks) {
    const n = disks.count, d = disks.data;
    const xyz = new Float32Array(6 * n);
    for (let i = 0; i < n; ++i) {
      const k = 7 * i, r = d[k + 6];
      for (let a = 0; a < 3; ++a) {
        xyz[6 * i + a] = d[k + a];
        xyz[6 * i + 3 + a] = d[k + a] + r * d[k + 3 + a];
      }
    }
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(xyz, 3));
    return { object: new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0xc82828 })) };
  }

  // Points: pushed back along the line of sight by the typical disk radius, so the points of a
  // surface stay beneath its disk and only the rest (noise, gaps) show through, as in the PNG;
  // the points of a disk seen from behind are left out when it is ghosted or hidden, as there.
  const pointVertex = [
    'attribute vec3 color;', 'attribute vec3 aNormal;',
    'uniform float uSize;', 'uniform float uBias;', 'uniform float uBack;', 'varying vec3 vColor;',
    'void main() {',
    '  vec4 mv = modelViewMatrix * vec4(position, 1.0);',
    '  vec3 nv = normalMatrix * aNormal;',  // its surface's normal; zero for unregistered points
    '  bool back = dot(nv, nv) > 0.25 && dot(nv, -mv.xyz) < 0.0;',
    '  mv.xyz *= 1.0 + uBias / max(length(mv.xyz), 1e-20);',
    '  vColor = color;',
    '  gl_PointSize = uSize;',
    '  gl_Position = projectionMatrix * mv;',
    '  if (back && uBack > 0.5) gl_Position = vec4(0.0, 0.0, 2.0, 1.0);',  // go with their disk
    '}'].join('\n');
  const pointFragment = [
    'varying vec3 vColor;',
    'void main() { gl_FragColor = vec4(vColor, 1.0); }'].join('\n');

  const roundFragment = [
    'varying vec3 vColor;',
    'void main() {',
    '  if (length(gl_PointCoord - vec2(0.5)) > 0.5) discard;',
    '  gl_FragColor = vec4(vColor, 1.0);',
    '}'].join('\n');

  function cloudLayer() {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(floatsOf(L.cloud.position), 3));
    g.setAttribute('color', new THREE.BufferAttribute(bytesOf(L.cloud.color), 3, true));
    const nrm = bytesOf(L.cloud.normal);
    g.setAttribute('aNormal', new THREE.BufferAttribute(new Int8Array(nrm.buffer), 3, true));
    const m = new THREE.ShaderMaterial({
      uniforms: {
        uSize: { value: (L.cloud.count > 300000 ? 1.5 : 2.5) * (window.devicePixelRatio || 1) },
        uBias: { value: L.surfaces ? L.surfaces.median_radius : 0 },
        uBack: backFaces,
      },
      vertexShader: pointVertex,
      fragmentShader: pointFragment,
    });
    return { object: new THREE.Points(g, m), count: L.cloud.count, material: m };
  }

  // Bound planes: each polygon (with holes) triangulated in its own plane, drawn see-through,
  // with a darker outline.
  function planesLayer() {
    const v = floatsOf(L.planes.vertices);
    const pos = [], col = [], index = [], lines = [], lineCol = [];
    let at = 0;
    const vec = (i) => new THREE.Vector3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    for (const poly of L.planes.polygons) {
      const rings = [poly.outline].concat(poly.holes);
      const ringStart = [];
      let total = 0;
      for (const count of rings) { ringStart.push(at + total); total += count; }
      // Newell's normal of the outline, then a basis of the plane.
      const nrm = new THREE.Vector3();
      for (let i = 0; i < poly.outline; ++i) {
        const p = vec(at + i), q = vec(at + (i + 1) % poly.outline);
        nrm.x += (p.y - q.y) * (p.z + q.z);
        nrm.y += (p.z - q.z) * (p.x + q.x);
        nrm.z += (p.x - q.x) * (p.y + q.y);
      }
      nrm.normalize();
      const u = new THREE.Vector3(Math.abs(nrm.x) < 0.9 ? 1 : 0, Math.abs(nrm.x) < 0.9 ? 0 : 1, 0);
      u.sub(nrm.clone().multiplyScalar(u.dot(nrm))).normalize();
      const w = new THREE.Vector3().crossVectors(nrm, u);
      const flat = (i) => { const p = vec(i); return new THREE.Vector2(p.dot(u), p.dot(w)); };
      const contour = [], holes = [];
      for (let i = 0; i < poly.outline; ++i) contour.push(flat(ringStart[0] + i));
      for (let h = 0; h < poly.holes.length; ++h) {
        const hole = [];
        for (let i = 0; i < poly.holes[h]; ++i) hole.push(flat(ringStart[h + 1] + i));
        holes.push(hole);
      }
      const base = pos.length / 3;
      const c = poly.color.map((x) => x / 255);
      for (let i = 0; i < total; ++i) {
        pos.push(v[3 * (at + i)], v[3 * (at + i) + 1], v[3 * (at + i) + 2]);
        col.push(c[0], c[1], c[2]);
      }
      for (const tri of THREE.ShapeUtils.triangulateShape(contour, holes))
        index.push(base + tri[0], base + tri[1], base + tri[2]);
      rings.forEach((count, r) => {
        for (let i = 0; i < count; ++i) {
          const a = ringStart[r] + i, b = ringStart[r] + (i + 1) % count;
          lines.push(v[3 * a], v[3 * a + 1], v[3 * a + 2], v[3 * b], v[3 * b + 1], v[3 * b + 2]);
          lineCol.push(0.6 * c[0], 0.6 * c[1], 0.6 * c[2], 0.6 * c[0], 0.6 * c[1], 0.6 * c[2]);
        }
      });
      at += total;
    }
    const group = new THREE.Group();
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(pos, 3));
    g.setAttribute('color', new THREE.Float32BufferAttribute(col, 3));
    g.setIndex(index);
    group.add(new THREE.Mesh(g, new THREE.MeshBasicMaterial({
      vertexColors: THREE.VertexColors, transparent: true, opacity: 0.35,
      side: THREE.DoubleSide, depthWrite: false,
    })));
    const lg = new THREE.BufferGeometry();
    lg.setAttribute('position', new THREE.Float32BufferAttribute(lines, 3));
    lg.setAttribute('color', new THREE.Float32BufferAttribute(lineCol, 3));
    group.add(new THREE.LineSegments(lg, new THREE.LineBasicMaterial({ vertexColors: THREE.VertexColors })));
    return { object: group, count: L.planes.polygons.length };
  }

  // Coverage path: the goals in order, joined, shaded from the first (green) to the last (purple).
  const pathStart = [0.1, 0.62, 0.2], pathEnd = [0.55, 0.12, 0.7];
  function pathLayer() {
    const xyz = floatsOf(L.path.goals), n = L.path.count;
    const col = new Float32Array(3 * n);
    for (let i = 0; i < n; ++i) {
      const t = n > 1 ? i / (n - 1) : 0;
      for (let a = 0; a < 3; ++a) col[3 * i + a] = pathStart[a] + t * (pathEnd[a] - pathStart[a]);
    }
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(xyz, 3));
    g.setAttribute('color', new THREE.BufferAttribute(col, 3));
    const group = new THREE.Group();
    group.add(new THREE.Line(g, new THREE.LineBasicMaterial({ vertexColors: THREE.VertexColors })));
    group.add(new THREE.Points(g, new THREE.ShaderMaterial({
      uniforms: {
        uSize: { value: 7 * (window.devicePixelRatio || 1) }, uBias: { value: 0 }, uBack: { value: 0 },
      },
      vertexShader: pointVertex,
      fragmentShader: roundFragment,
    })));
    return { object: group, count: n };
  }

  // ---- Scene, camera, controls ----
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true });
  } catch (e) {
    fail('WebGL is not available in this browser (' + e.message + ')');
  }
  const host = document.getElementById('sg-canvas');
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xffffff);
  const camera = new THREE.PerspectiveCamera(35, 1, R / 100, R * 10);
  camera.up.set(0, 0, 1);  // the world is z-up; OrbitControls keeps camera.up up

  const layers = {};
  function addLayer(name, make) {
    try {
      layers[name] = make();
      // The first view shows the surfaces (by bound plane) and planes; normals, the path
      // (which would hide the surfaces) and the cloud under the surfaces are switched on by hand.
      layers[name].object.visible =
        name !== 'normals' && name !== 'path' && !(name === 'cloud' && L.surfaces);
      scene.add(layers[name].object);
    } catch (e) {
      fail('cannot show the ' + name + ' layer: ' + e.message);
    }
  }
  if (renderer) {
    if (L.cloud) addLayer('cloud', cloudLayer);
    if (L.surfaces) addLayer('surfaces', surfacesLayer);
    if (layers.surfaces) addLayer('normals', () => normalsLayer(layers.surfaces));
    if (L.planes) addLayer('planes', planesLayer);
    if (L.path) addLayer('path', pathLayer);
  }

  let controls = null;
  let pending = false;
  function draw() {
    const d = camera.position.distanceTo(controls.target);
    camera.near = Math.max(d / 200, R * 1e-6);
    camera.far = d + 4 * R + Math.min(meta.reach || R, 100 * R);
    camera.updateProjectionMatrix();
    renderer.render(scene, camera);
    api.frames += 1;
  }
  function redraw() {
    if (pending || !controls) return;
    pending = true;
    requestAnimationFrame(() => { pending = false; draw(); });
  }
  // The panel covers the left of the window: the scene is centred in the rest (a view offset).
  function panelShift() {
    const pw = panel.offsetWidth + 20;
    return window.innerWidth > 2.5 * pw && !panel.classList.contains('collapsed') ? pw : 0;
  }
  function resize() {
    const w = window.innerWidth, h = window.innerHeight;
    renderer.setSize(w, h);
    camera.aspect = w / h;
    camera.setViewOffset(w, h, -panelShift() / 2, 0, w, h);
    camera.updateProjectionMatrix();
  }
  // The starting view: from the front-right-above corner, as the PNG's iso view, fitted to the
  // bulk of the disks as the PNG is (the page's data is centred on it).
  function home() {
    const vfov = camera.fov * Math.PI / 180;
    const free = (window.innerWidth - panelShift()) / window.innerHeight;
    const hfov = 2 * Math.atan(Math.tan(vfov / 2) * free);
    const dist = R / Math.sin(Math.min(vfov, hfov) / 2);
    camera.position.set(1, -1, 1).normalize().multiplyScalar(dist);
    controls.target.set(0, 0, 0);
    controls.update();
  }

  // ---- Panel ----
  const fmt = (n) => n.toLocaleString('en-US');
  function el(tag, attrs, text) {
    const e = document.createElement(tag);
    for (const k in attrs) e.setAttribute(k, attrs[k]);
    if (text !== undefined) e.textContent = text;
    return e;
  }
  function swatch(css) {
    const s = el('span', { class: 'swatch' });
    s.style.background = css;
    return s;
  }
  const layerInfo = [
    ['cloud', 'Cloud', () => fmt(L.cloud.count) + ' points', '#8c8c8c', 'not in the page (--cloud)'],
    ['surfaces', 'Surfaces', () => fmt(L.surfaces.count) + ' disks', '#9aa7c7', 'no surfaces'],
    ['normals', 'Normals', () => '', '#c82828', 'no surfaces'],
    ['planes', 'Bound planes', () => fmt(L.planes.polygons.length) + ' polygons', '#c9b27c',
      'no planes.json'],
    ['path', 'Coverage path', () => fmt(L.path.count) + ' goals',
      'linear-gradient(90deg, rgb(26,158,51), rgb(140,31,179))', 'no coverage.json'],
  ];
  function buildPanel() {
    const h1 = el('h1', { title: 'click to fold' }, meta.title || 'surfgrow view');
    h1.addEventListener('click', () => { panel.classList.toggle('collapsed'); resize(); redraw(); });
    panel.appendChild(h1);
    if (meta.legend) panel.appendChild(el('div', { class: 'legend' }, meta.legend));
    for (const note of meta.notes) panel.appendChild(el('div', { class: 'note' }, note));
    const set = el('fieldset');
    set.appendChild(el('legend', { hidden: '' }, 'Layers'));
    layerInfo.forEach(([name, label, count, color, absent], k) => {
      const on = !!layers[name];
      const box = el('input', { type: 'checkbox', id: 'sg-layer-' + name });
      const row = el('label', { title: on ? 'key ' + (k + 1) : absent });
      box.checked = on && layers[name].object.visible;
      box.disabled = !on;
      box.addEventListener('change', () => { layers[name].object.visible = box.checked; redraw(); });
      row.appendChild(box);
      row.appendChild(swatch(on ? color : '#ddd'));
      row.appendChild(document.createTextNode(label + (on && count() ? ' (' + count() + ')' : '')));
      if (!on) { row.className = 'absent'; row.appendChild(document.createTextNode(' (' + absent + ')')); }
      set.appendChild(row);
    });
    panel.appendChild(set);
    if (layers.surfaces) {
      const u = layers.surfaces.uniforms;
      if (L.surfaces.plane_color) {
        const row = el('div', { class: 'row' }, 'Colour: ');
        for (const [value, text] of [['0', 'by surface'], ['1', 'by bound plane']]) {
          const r = el('input', { type: 'radio', name: 'sg-colour', id: 'sg-colour-' + value, value });
          r.checked = Number(value) === u.uByPlane.value;
          r.addEventListener('change', () => { u.uByPlane.value = Number(value); redraw(); });
          const lab = el('label', { style: 'display:inline' });
          lab.appendChild(r);
          lab.appendChild(document.createTextNode(text + ' '));
          row.appendChild(lab);
        }
        panel.appendChild(row);
      }
      const back = el('div', { class: 'row', title: 'disks seen from behind: their normals face away, towards the scanner' }, 'Back faces: ');
      for (const [value, text] of [[0, 'show'], [1, 'ghost'], [2, 'hide']]) {
        const r = el('input', { type: 'radio', name: 'sg-back', id: 'sg-back-' + text });
        r.checked = u.uBack.value === value;
        r.addEventListener('change', () => { layers.surfaces.setBack(value); redraw(); });
        const lab = el('label', { style: 'display:inline' });
        lab.appendChild(r);
        lab.appendChild(document.createTextNode(text + ' '));
        back.appendChild(lab);
      }
      panel.appendChild(back);
    }
    if (layers.cloud) {
      const u = layers.cloud.material.uniforms, ratio = window.devicePixelRatio || 1;
      const row = el('label', { class: 'row' }, 'Point size ');
      const size = el('input', { type: 'range', id: 'sg-point-size', min: '1', max: '8', step: '0.5' });
      size.value = String(u.uSize.value / ratio);
      size.addEventListener('input', () => { u.uSize.value = Number(size.value) * ratio; redraw(); });
      row.appendChild(size);
      panel.appendChild(row);
    }
    const reset = el('button', { type: 'button', id: 'sg-reset' }, 'Reset view');
    reset.addEventListener('click', () => { home(); redraw(); });
    const row = el('div', { class: 'row' });
    row.appendChild(reset);
    panel.appendChild(row);
    panel.appendChild(el('div', { class: 'help' },
      'Drag: orbit. Right-drag or shift-drag: pan. Wheel: zoom. Keys: R reset, 1-5 layers. ' +
      'Lengths in ' + (meta.units || '?') + '. three.js r' + THREE.REVISION + '.'));
  }

  // ---- Start ----
  buildPanel();
  if (renderer) {
    host.appendChild(renderer.domElement);
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.screenSpacePanning = true;
    controls.addEventListener('change', redraw);
    resize();
    home();
    window.addEventListener('resize', () => { resize(); redraw(); });
    window.addEventListener('keydown', (e) => {
      if (e.target.tagName === 'INPUT' && e.target.type === 'range') return;
      if (e.key === 'r' || e.key === 'R') { home(); redraw(); }
      const k = Number(e.key) - 1;
      if (k >= 0 && k < layerInfo.length) {
        const box = document.getElementById('sg-layer-' + layerInfo[k][0]);
        if (box && !box.disabled) box.click();
      }
    });
    draw();
    // Where a point of the result (file coordinates) lands in the window, in CSS pixels.
    api.project = (x, y, z) => {
      const o = meta.origin;
      const v = new THREE.Vector3(x - o[0], y - o[1], z - o[2]).project(camera);
      return [(v.x + 1) / 2 * window.innerWidth, (1 - v.y) / 2 * window.innerHeight];
    };
    // Draws now and waits for the GPU: milliseconds per frame, for measurements.
    api.timeFrame = () => {
      const gl = renderer.getContext(), pixel = new Uint8Array(4);
      const t0 = performance.now();
      draw();
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);  // waits for the frame
      return performance.now() - t0;
    };
    api.layers = Object.keys(layers);
    api.visible = (name) => !!layers[name] && layers[name].object.visible;
    api.ready = api.error === null;
  }
})();
