// The Amos-SLAM viewer page: loads the whole state (api/state), then applies the updates the server pushes
// (api/events, Server-Sent Events) to a three.js scene and the side panel. The same page shows a finished run
// (`amos-slam view`), which sends no updates. Dense layers (the live dense cloud of `run --dense`, a finished run's
// mesh.ply, cloud.ply and removed_points.ply) are binary blocks fetched from api/dense/NAME.bin when the state
// names a new version of them; once all named ones are drawn the page sets document.body.dataset.dense to their
// names. Once the 3D view has drawn something that is not background (checked
// with readPixels) the page sets document.body.dataset.drawn = "1"; script errors are collected in
// document.body.dataset.errors (the browser test reads both).
'use strict';
(function () {
  const errors = [];
  function noteError(text) {
    errors.push(String(text));
    document.body.dataset.errors = errors.join(' | ');
  }
  window.addEventListener('error', (e) => noteError(e.message));
  window.addEventListener('unhandledrejection', (e) => noteError(e.reason));
  const $ = (id) => document.getElementById(id);
  const BACKGROUND = 0x15181d;
  const FRUSTUM_DEPTH = 0.06;  // metres

  // ---------------------------------------------------------------- state as the page holds it
  let info = {};
  let seq = 0;
  const keyframes = new Map();  // id -> [x, y, z, qx, qy, qz, qw]
  let trajectory = [];          // [t, x, y, z]
  let groundTruth = [];
  let lastFrame = null;
  let fitted = false;
  let userMoved = false;  // the user turned, zoomed or panned: nothing refits the view by itself any more
  let lastFit = 0;        // when the view was last fitted by itself (ms)

  // A growing point cloud with removal by id: positions live in one buffer, a removed point's slot is filled by
  // the last point.
  class PointCloud {
    constructor(color, size) {
      this.index = new Map();
      this.ids = [];
      this.data = new Float32Array(3 * 4096);
      this.geometry = new THREE.BufferGeometry();
      this.attribute = new THREE.BufferAttribute(this.data, 3);
      this.geometry.setAttribute('position', this.attribute);
      this.geometry.setDrawRange(0, 0);
      this.object = new THREE.Points(this.geometry,
          new THREE.PointsMaterial({color: color, size: size, sizeAttenuation: false}));
      this.object.frustumCulled = false;
    }
    get count() { return this.ids.length; }
    set(id, x, y, z) {
      let i = this.index.get(id);
      if (i === undefined) {
        i = this.ids.length;
        if (3 * (i + 1) > this.data.length) this.grow();
        this.ids.push(id);
        this.index.set(id, i);
      }
      this.data[3 * i] = x; this.data[3 * i + 1] = y; this.data[3 * i + 2] = z;
    }
    remove(id) {
      const i = this.index.get(id);
      if (i === undefined) return;
      const last = this.ids.length - 1;
      if (i !== last) {
        const moved = this.ids[last];
        this.ids[i] = moved;
        this.index.set(moved, i);
        this.data.copyWithin(3 * i, 3 * last, 3 * last + 3);
      }
      this.ids.pop();
      this.index.delete(id);
    }
    grow() {
      const bigger = new Float32Array(this.data.length * 2);
      bigger.set(this.data);
      this.data = bigger;
      this.attribute = new THREE.BufferAttribute(this.data, 3);
      this.geometry.setAttribute('position', this.attribute);
    }
    clear() { this.ids = []; this.index.clear(); }
    commit() {
      this.attribute.needsUpdate = true;
      this.geometry.setDrawRange(0, this.ids.length);
      this.geometry.computeBoundingSphere();
    }
  }

  // ---------------------------------------------------------------- the 3D view
  let renderer = null, scene, camera, controls, world, cloud, culled, trajLine, gtLine, kfLines, camLines;
  // name -> {version, loading, object, xyz}: the dense layers (live, mesh, cloud, removed).
  const dense = new Map();
  const DENSE_TOGGLE = {live: 'show-cloud', cloud: 'show-cloud', mesh: 'show-mesh', removed: 'show-removed'};
  const REMOVED_COLOUR = 0xff40ff;
  let dirty = true, drawnChecked = false, drawnRetries = 0;

  function lineObject(color) {
    const line = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({color: color}));
    line.frustumCulled = false;
    return line;
  }
  function segmentsObject(color) {
    const s = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({color: color}));
    s.frustumCulled = false;
    return s;
  }

  function initScene() {
    if (typeof THREE === 'undefined') {
      $('message').textContent = 'three.js is not available (install libjs-three): no 3D view';
      return;
    }
    const canvas = $('canvas3d');
    try {
      renderer = new THREE.WebGLRenderer({canvas: canvas, antialias: true, preserveDrawingBuffer: true});
    } catch (e) {
      $('message').textContent = 'WebGL is not available: ' + e.message;
      renderer = null;
      return;
    }
    renderer.setClearColor(BACKGROUND);
    scene = new THREE.Scene();
    camera = new THREE.PerspectiveCamera(60, 1, 0.01, 1000);
    camera.position.set(0, 1.5, 3);
    // The meshes are lit from the viewer's side (a light carried by the camera) and a little from everywhere.
    scene.add(camera);
    scene.add(new THREE.AmbientLight(0xffffff, 0.55));
    const headlight = new THREE.DirectionalLight(0xffffff, 0.6);
    headlight.position.set(0.3, 0.5, 1);
    camera.add(headlight);
    controls = new THREE.OrbitControls(camera, canvas);
    // Drawn at once, not at the next animation frame: a hidden or headless page gets few of those, and input
    // events already come at most once per frame.
    controls.addEventListener('change', redraw);
    controls.addEventListener('start', () => { userMoved = true; });
    // SLAM's world is the first camera's frame (x right, y down, z forward): turned half a turn about x, so that
    // "up" in the picture is up in the room.
    world = new THREE.Group();
    world.rotation.x = Math.PI;
    scene.add(world);
    cloud = new PointCloud(0xe8e8e8, 2);
    culled = new PointCloud(0xff4040, 3);
    trajLine = lineObject(0x40d060);
    gtLine = lineObject(0x909090);
    kfLines = segmentsObject(0x4090ff);
    camLines = segmentsObject(0xffd040);
    for (const o of [cloud.object, culled.object, trajLine, gtLine, kfLines, camLines]) world.add(o);
    world.add(new THREE.AxesHelper(0.2));
    window.addEventListener('resize', () => { dirty = true; });
    const toggles = {'show-points': [cloud.object], 'show-culled': [culled.object], 'show-traj': [trajLine],
                     'show-gt': [gtLine], 'show-kf': [kfLines]};
    for (const [id, objects] of Object.entries(toggles)) {
      $(id).addEventListener('change', (e) => {
        for (const o of objects) o.visible = e.target.checked;
        redraw();
      });
    }
    for (const id of ['show-mesh', 'show-cloud', 'show-removed']) {
      $(id).addEventListener('change', () => { showDenseToggles(); redraw(); });
    }
    $('fit').addEventListener('click', () => { fitView(false); });
    $('fit-trajectory').addEventListener('click', () => { fitView(true); });
    window.addEventListener('keydown', (e) => {
      if (e.ctrlKey || e.metaKey || e.altKey) return;
      if (e.key === 'f' || e.key === 'F') fitView(false);
      if (e.key === 't' || e.key === 'T') fitView(true);
    });
    requestAnimationFrame(frameLoop);
  }

  function redraw() {
    dirty = true;
    drawIfChanged();
  }

  function frameLoop() {
    requestAnimationFrame(frameLoop);
    drawIfChanged();
  }

  // Also called straight after a whole state arrives: the first picture (and the drawn mark) does not wait for the
  // next animation frame, which a busy or headless browser may deliver late.
  function drawIfChanged() {
    if (!renderer) return;
    const canvas = renderer.domElement;
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== w || canvas.height !== h) {
      renderer.setSize(w, h, false);
      camera.aspect = w / Math.max(1, h);
      camera.updateProjectionMatrix();
      dirty = true;
    }
    if (!dirty) return;
    dirty = false;
    renderer.render(scene, camera);
    if (!drawnChecked && (cloud.count > 0 || trajectory.length > 1 || dense.size > 0)) checkDrawn();
  }

  // Sets the DOM mark once the canvas shows anything but the background.
  function checkDrawn() {
    const gl = renderer.getContext();
    const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    const pixels = new Uint8Array(4 * w * h);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
    const r = (BACKGROUND >> 16) & 255, g = (BACKGROUND >> 8) & 255, b = BACKGROUND & 255;
    let different = 0;
    for (let i = 0; i < pixels.length; i += 4) {
      if (Math.abs(pixels[i] - r) + Math.abs(pixels[i + 1] - g) + Math.abs(pixels[i + 2] - b) > 30) different++;
    }
    if (different > 20) {
      drawnChecked = true;
      document.body.dataset.drawn = '1';
      document.body.dataset.drawnPixels = String(different);
    } else if (drawnRetries++ < 40) {
      // The first pictures can come out blank while a software GL context is still starting, and a headless or
      // hidden page gets few animation frames: draw again shortly, for up to 10 s.
      setTimeout(() => { dirty = true; drawIfChanged(); }, 250);
    }
  }

  // The values below which shares q0 and q1 of `values` lie.
  function quantiles(values, q0, q1) {
    const sorted = Float64Array.from(values).sort();
    const at = (q) => sorted[Math.min(sorted.length - 1, Math.max(0, Math.round(q * (sorted.length - 1))))];
    return [at(q0), at(q1)];
  }

  // The points the view must show, in the scene's frame. The whole scene: the points (map points and dense
  // layers, at most 20000 of each sampled evenly) inside their 2nd-98th percentile box, so that a few far outliers
  // do not shrink the scene to a dot, with the whole trajectory and the keyframes. Or (trajectoryOnly) the
  // trajectory and the ground truth alone, for a camera that moved little in a large room. The points themselves,
  // not their box: the corners of a box seen obliquely reach far beyond what is in it.
  function fitPoints(trajectoryOnly) {
    world.updateMatrixWorld(true);
    const xs = [], ys = [], zs = [];
    const sample = (data, count, budget) => {
      const step = Math.max(1, Math.ceil(count / budget));
      for (let i = 0; i < count; i += step) {
        const x = data[3 * i], y = data[3 * i + 1], z = data[3 * i + 2];
        if (Number.isFinite(x) && Number.isFinite(y) && Number.isFinite(z)) { xs.push(x); ys.push(y); zs.push(z); }
      }
    };
    if (!trajectoryOnly) {
      sample(cloud.data, cloud.count, 20000);
      for (const [name, layer] of dense) if (layer.xyz && name !== 'removed') sample(layer.xyz, layer.xyz.length / 3, 20000);
    }
    const inside = new THREE.Box3(new THREE.Vector3(-Infinity, -Infinity, -Infinity), new THREE.Vector3(Infinity, Infinity, Infinity));
    if (xs.length >= 20) {
      const [x0, x1] = quantiles(xs, 0.02, 0.98), [y0, y1] = quantiles(ys, 0.02, 0.98), [z0, z1] = quantiles(zs, 0.02, 0.98);
      inside.min.set(x0, y0, z0);
      inside.max.set(x1, y1, z1);
    }
    const out = [];
    const p = new THREE.Vector3();
    const step = Math.max(1, Math.ceil(xs.length / 4000));  // enough to place the camera, cheap to project
    for (let i = 0; i < xs.length; i += step)
      if (inside.containsPoint(p.set(xs[i], ys[i], zs[i]))) out.push(world.localToWorld(p.clone()));
    const take = (x, y, z) => {
      if (Number.isFinite(x) && Number.isFinite(y) && Number.isFinite(z)) out.push(world.localToWorld(new THREE.Vector3(x, y, z)));
    };
    const path = trajectoryOnly ? trajectory.concat(groundTruth) : trajectory;
    const pathStep = Math.max(1, Math.ceil(path.length / 2000));
    for (let i = 0; i < path.length; i += pathStep) take(path[i][1], path[i][2], path[i][3]);
    if (!trajectoryOnly) for (const k of keyframes.values()) take(k[0], k[1], k[2]);
    return out;
  }

  // Puts the points in the picture, as large as they fit: the camera looks from behind and above the first camera
  // (a fixed direction), at the least distance at which every point is inside the field of view with a margin;
  // the target is then moved sideways so that the points' extremes lie symmetric in the picture, and the distance
  // found again (three shifts suffice).
  function fitView(trajectoryOnly) {
    if (!renderer) return;
    const points = fitPoints(trajectoryOnly === true);
    if (!points.length) return;
    const box = new THREE.Box3().setFromPoints(points);
    const centre = box.getCenter(new THREE.Vector3());
    const size = Math.max(0.1, box.getSize(new THREE.Vector3()).length());
    const back = new THREE.Vector3(0.3, 0.55, 0.78).normalize();  // from the target towards the camera
    const right = new THREE.Vector3(0, 1, 0).cross(back).normalize();
    const up = back.clone().cross(right);
    const canvas = renderer.domElement;
    const aspect = Math.max(0.1, canvas.clientWidth / Math.max(1, canvas.clientHeight));
    const tanV = Math.tan(camera.fov * Math.PI / 360), tanH = tanV * aspect;
    const margin = 1.08;
    let distance = 0;
    for (let round = 0; round < 4; ++round) {
      distance = 0;
      for (const p of points) {
        const d = p.clone().sub(centre);
        const x = Math.abs(d.dot(right)), y = Math.abs(d.dot(up)), z = d.dot(back);
        distance = Math.max(distance, z + margin * x / tanH, z + margin * y / tanV);
      }
      distance = Math.max(distance, 0.05);
      if (round === 3) break;
      // Where the extremes fall (tangents of their angles off the axis) and the shift that centres them.
      let ax0 = Infinity, ax1 = -Infinity, ay0 = Infinity, ay1 = -Infinity;
      for (const p of points) {
        const d = p.clone().sub(centre);
        const depth = Math.max(1e-6, distance - d.dot(back));
        const ax = d.dot(right) / depth, ay = d.dot(up) / depth;
        ax0 = Math.min(ax0, ax); ax1 = Math.max(ax1, ax); ay0 = Math.min(ay0, ay); ay1 = Math.max(ay1, ay);
      }
      centre.addScaledVector(right, distance * (ax0 + ax1) / 2).addScaledVector(up, distance * (ay0 + ay1) / 2);
    }
    controls.target.copy(centre);
    camera.position.copy(centre).addScaledVector(back, distance);
    camera.near = Math.max(1e-3, distance / 1000);
    camera.far = (distance + size) * 20;
    camera.aspect = aspect;
    camera.updateProjectionMatrix();
    controls.update();
    redraw();
  }

  // The image corners at depth FRUSTUM_DEPTH, in the camera's frame.
  function frustumCorners() {
    const c = info.camera || {fx: 525, fy: 525, cx: 319.5, cy: 239.5, width: 640, height: 480};
    const d = FRUSTUM_DEPTH;
    return [[0, 0], [c.width, 0], [c.width, c.height], [0, c.height]].map(
        ([u, v]) => new THREE.Vector3((u - c.cx) / c.fx * d, (v - c.cy) / c.fy * d, d));
  }
  // Line segments of camera frusta (apex to corners, then the image rectangle) for poses [x,y,z,qx,qy,qz,qw].
  function frustaGeometry(poses) {
    const corners = frustumCorners();
    const out = [];
    const q = new THREE.Quaternion(), t = new THREE.Vector3(), p = new THREE.Vector3();
    for (const pose of poses) {
      t.set(pose[0], pose[1], pose[2]);
      q.set(pose[3], pose[4], pose[5], pose[6]);
      const w = corners.map((c) => p.copy(c).applyQuaternion(q).add(t).toArray());
      for (let i = 0; i < 4; i++) out.push(t.x, t.y, t.z, ...w[i]);
      for (let i = 0; i < 4; i++) out.push(...w[i], ...w[(i + 1) % 4]);
    }
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(out, 3));
    return g;
  }
  function setGeometry(object, geometry) {
    object.geometry.dispose();
    object.geometry = geometry;
  }
  function polylineGeometry(samples) {
    const out = [];
    for (const s of samples) out.push(s[1], s[2], s[3]);
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(out, 3));
    return g;
  }

  // ---------------------------------------------------------------- the top view of the trajectory

  // The estimate (green) and the ground truth (grey) seen from above (SLAM x to the right, z, the first camera's
  // viewing direction, upwards), at one scale for both axes, with a scale bar: readable however large the room.
  let topviewTime = 0, topviewTimer = null;
  function showTopView() {
    const now = Date.now();
    if (now - topviewTime < 1000) {  // at most once a second while a run goes
      if (!topviewTimer) topviewTimer = setTimeout(() => { topviewTimer = null; showTopView(); }, 1000);
      return;
    }
    topviewTime = now;
    const W = 394, H = 240, M = 12;
    const all = trajectory.concat(groundTruth).filter((s) => Number.isFinite(s[1]) && Number.isFinite(s[3]));
    if (all.length < 2) { $('topview').innerHTML = ''; return; }
    let x0 = Infinity, x1 = -Infinity, z0 = Infinity, z1 = -Infinity;
    for (const s of all) { x0 = Math.min(x0, s[1]); x1 = Math.max(x1, s[1]); z0 = Math.min(z0, s[3]); z1 = Math.max(z1, s[3]); }
    const k = Math.min((W - 2 * M) / Math.max(x1 - x0, 1e-3), (H - 2 * M - 14) / Math.max(z1 - z0, 1e-3));
    const X = (x) => W / 2 + (x - (x0 + x1) / 2) * k, Y = (z) => (H - 14) / 2 - (z - (z0 + z1) / 2) * k;
    const path = (samples) => samples.filter((s) => Number.isFinite(s[1]) && Number.isFinite(s[3]))
        .map((s, i) => (i ? 'L' : 'M') + X(s[1]).toFixed(1) + ' ' + Y(s[3]).toFixed(1)).join('');
    const bar = [0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50].filter((m) => m * k <= W / 3).pop() || 0.01;
    let svg = '<svg xmlns="http://www.w3.org/2000/svg" width="100%" viewBox="0 0 ' + W + ' ' + H + '">';
    if (groundTruth.length) svg += '<path d="' + path(groundTruth) + '" fill="none" stroke="#909090" stroke-width="2.5"/>';
    svg += '<path d="' + path(trajectory) + '" fill="none" stroke="#40d060" stroke-width="1.5"/>';
    if (trajectory.length) svg += '<circle cx="' + X(trajectory[0][1]) + '" cy="' + Y(trajectory[0][3]) + '" r="3" fill="#ffd040"/>';
    svg += '<line x1="' + M + '" x2="' + (M + bar * k) + '" y1="' + (H - 8) + '" y2="' + (H - 8) + '" stroke="#d8dde6" stroke-width="2"/>' +
           '<text x="' + (M + bar * k + 6) + '" y="' + (H - 4) + '">' + (bar < 1 ? bar * 100 + ' cm' : bar + ' m') +
           ' &middot; x right, z forward; yellow: start</text></svg>';
    $('topview').innerHTML = svg;
  }

  // ---------------------------------------------------------------- dense layers

  // Shows the toggles of the dense layers there are and applies them.
  function showDenseToggles() {
    for (const [name, layer] of dense) {
      const toggle = $(DENSE_TOGGLE[name]);
      toggle.parentElement.hidden = false;
      if (layer.object) layer.object.visible = toggle.checked;
    }
  }

  // A layer's binary block (dense_layer.h) as a three.js object: a lit mesh with its colours, a cloud with its
  // colours, or the removed points in one colour.
  function denseObject(name, buffer) {
    const head = new Uint32Array(buffer, 0, 2);
    const vertices = head[0], triangles = head[1];
    const xyz = new Float32Array(buffer, 8, 3 * vertices);
    const indices = new Uint32Array(buffer, 8 + 12 * vertices, 3 * triangles);
    const rgb = new Uint8Array(buffer, 8 + 12 * vertices + 12 * triangles, 3 * vertices);
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(xyz, 3));
    let object;
    if (name === 'removed') {
      object = new THREE.Points(g, new THREE.PointsMaterial({color: REMOVED_COLOUR, size: 2, sizeAttenuation: false}));
    } else {
      g.setAttribute('color', new THREE.BufferAttribute(rgb, 3, true));
      if (triangles > 0) {
        g.setIndex(new THREE.BufferAttribute(indices, 1));
        g.computeVertexNormals();
        object = new THREE.Mesh(g, new THREE.MeshLambertMaterial({vertexColors: THREE.VertexColors, side: THREE.DoubleSide}));
      } else {
        object = new THREE.Points(g, new THREE.PointsMaterial({vertexColors: THREE.VertexColors, size: 2, sizeAttenuation: false}));
      }
    }
    object.frustumCulled = false;
    return {object, xyz};
  }

  // Fetches the layers whose version changed (one fetch per layer at a time; a newer version that arrives
  // meanwhile is fetched after it).
  function updateDense(layers) {
    for (const [name, meta] of Object.entries(layers || {})) {
      if (!(name in DENSE_TOGGLE)) continue;
      let layer = dense.get(name);
      if (!layer) { layer = {version: 0, wanted: 0, loading: false, object: null, xyz: null}; dense.set(name, layer); }
      layer.wanted = meta.version;
      loadDense(name, layer);
    }
    showDenseToggles();
  }
  async function loadDense(name, layer) {
    if (layer.loading || layer.version === layer.wanted || !renderer) return;
    layer.loading = true;
    const version = layer.wanted;
    try {
      const response = await fetch('api/dense/' + name + '.bin?v=' + version, {cache: 'no-store'});
      if (!response.ok) throw new Error('api/dense/' + name + '.bin: HTTP ' + response.status);
      const made = denseObject(name, await response.arrayBuffer());
      if (layer.object) { world.remove(layer.object); layer.object.geometry.dispose(); }
      layer.object = made.object;
      layer.xyz = made.xyz;
      layer.version = version;
      world.add(layer.object);
      showDenseToggles();
      if (!userMoved) fitView(false);
      dirty = true;
      drawIfChanged();
      const ready = [...dense.entries()].filter(([, l]) => l.object).map(([n]) => n).sort();
      if (ready.length === dense.size) document.body.dataset.dense = ready.join(',');
      showStatus();
    } catch (e) {
      noteError('dense layer ' + name + ': ' + e);
    } finally {
      layer.loading = false;
    }
    if (layer.wanted !== layer.version) loadDense(name, layer);
  }

  // ---------------------------------------------------------------- applying state and updates
  function apply(u, whole) {
    if (u.info) info = u.info;
    if (whole) {
      keyframes.clear();
      trajectory = [];
      if (renderer) { cloud.clear(); culled.clear(); }
    }
    if (renderer) {
      for (const p of u.points || []) cloud.set(p[0], p[1], p[2], p[3]);
      for (const id of u.removed || []) cloud.remove(id);
      for (const p of u.culled || []) culled.set(p[0], p[1], p[2], p[3]);
      cloud.commit();
      culled.commit();
    }
    for (const k of u.keyframes || []) keyframes.set(k[0], k.slice(1));
    for (const id of u.removed_keyframes || []) keyframes.delete(id);
    if (u.trajectory_reset) trajectory = [];
    if (u.trajectory) trajectory = trajectory.concat(u.trajectory);
    if (u.ground_truth) groundTruth = u.ground_truth;
    if (u.frame && u.frame.index !== undefined) lastFrame = u.frame;
    if (renderer) {
      if (u.keyframes || u.removed_keyframes || whole) setGeometry(kfLines, frustaGeometry(keyframes.values()));
      if (u.trajectory || whole) setGeometry(trajLine, polylineGeometry(trajectory));
      if (u.ground_truth || whole) setGeometry(gtLine, polylineGeometry(groundTruth));
      if (lastFrame) setGeometry(camLines, frustaGeometry([lastFrame.T_wc]));
      dirty = true;
      if (!fitted && (cloud.count > 50 || (!info.live && trajectory.length > 1))) {
        fitView(false);
        fitted = true;
        lastFit = Date.now();
      } else if (fitted && info.live && !userMoved && Date.now() - lastFit > 3000) {
        // A live run's scene grows: the view follows it every 3 s until the user takes the camera.
        fitView(false);
        lastFit = Date.now();
      }
    }
    if (u.trajectory || u.ground_truth || whole) showTopView();
    if (u.dense) updateDense(u.dense);
    if (u.frame_image) refreshImage();
    if (u.summary && Object.keys(u.summary).length) showSummary(u.summary);
    showStatus();
  }

  let imageBusy = false;
  function refreshImage() {
    if (imageBusy) return;  // the previous image is still loading: skip, the next update brings a newer one
    imageBusy = true;
    $('frame').src = 'api/frame.jpg?seq=' + seq;
  }

  function row(name, value, cls) {
    return '<tr><td>' + name + '</td><td class="num ' + (cls || '') + '">' + value + '</td></tr>';
  }
  function fixed(v, digits) { return typeof v === 'number' ? v.toFixed(digits) : '-'; }

  function showStatus() {
    $('mode').textContent = info.mode ? 'mode ' + info.mode : '';
    let source = (info.live ? 'live: ' : 'finished run: ') + (info.sequence || '');
    const m = info.loaded_map;
    if (m) {
      source += ' · started from the map ' + m.file + ' (' + m.keyframes + ' keyframes, ' + m.points + ' points)' +
                (m.localize ? ', localising only' : ', extended by this run');
    }
    $('sequence').textContent = source;
    const f = lastFrame;
    let html = '';
    if (f) {
      html += row('frame', (f.index + 1) + (f.total ? ' / ' + f.total : ''));
      const state = String(f.state).toUpperCase();
      html += row('tracking', state, 'state-' + state);
      html += row('frames per second', fixed(f.fps, 1));
      html += row('inliers', f.inliers);
      html += row('keypoints kept / removed', (f.keypoints - f.removed) + ' / ' + f.removed);
    }
    html += row('map points', renderer ? cloud.count : '-');
    html += row('removed as dynamic (shown)', renderer ? culled.count : '-');
    html += row('keyframes', keyframes.size);
    html += row('trajectory poses', trajectory.length);
    html += row('ground truth', info.has_ground_truth === false ? 'none' : groundTruth.length + ' poses');
    for (const [name, layer] of dense) {
      if (!layer.xyz) continue;
      const label = {live: 'dense cloud points', cloud: 'dense cloud points', mesh: 'dense mesh vertices',
                     removed: 'dense points left out'}[name];
      html += row(label, layer.xyz.length / 3);
    }
    $('status').innerHTML = html;
    if (!info.live && summaryStages) {
      // A finished run: the stage times over the whole run (stats.json).
      const st = (key) => summaryStages[key] || {};
      const both = (key) => fixed(st(key).median_ms, 1) + ' / ' + fixed(st(key).p95_ms, 1);
      $('times-title').textContent = 'ms per frame (median / 95th percentile over the run)';
      $('times').innerHTML = row('ORB extraction', both('frame.extract')) + row('frame build (mask)', both('frame.build')) +
          row('tracking', both('frame.track')) + row('whole frame', both('frame.total'));
    } else if (f && f.times_ms) {
      const t = f.times_ms;
      $('times').innerHTML = row('ORB extraction', fixed(t.extract, 1)) + row('frame build (mask)', fixed(t.build, 1)) +
          row('tracking', fixed(t.track, 1)) + row('whole frame (1 / fps)', fixed(t.frame, 1));
    }
    $('frame-box').style.display = (f || info.live) ? '' : 'none';
  }

  let summaryStages = null;
  function showSummary(s) {
    if (s.stages) summaryStages = s.stages;
    let html = '<h2>Run</h2><table>';
    if (s.end) html += row('ended', s.end.status || s.end);
    if (s.frames !== undefined) html += row('frames', s.frames);
    if (s.tracked !== undefined) html += row('tracked / lost', s.tracked + ' / ' + s.lost);
    if (s.wall_time_s !== undefined) html += row('wall time', fixed(s.wall_time_s, 2) + ' s');
    if (s.fps !== undefined) html += row('frames per second', fixed(s.fps, 1));
    if (s.removed_keypoint_fraction && s.removed_keypoint_fraction.median !== undefined)
      html += row('keypoints removed by the mask (median)', fixed(100 * s.removed_keypoint_fraction.median, 1) + ' %');
    if (s.mapping && s.mapping.dynamic_points_culled !== undefined)
      html += row('map points culled as dynamic', s.mapping.dynamic_points_culled);
    const e = s.evaluation;
    if (e) {
      html += row('ATE RMSE', fixed(e.ate_rmse_m * 100, 2) + ' cm');
      if (e.rpe_trans_rmse_m !== null) html += row('RPE (1 s)', fixed(e.rpe_trans_rmse_m * 100, 2) + ' cm, ' + fixed(e.rpe_rot_rmse_deg, 2) + ' deg');
    }
    $('summary').innerHTML = html + '</table>';
  }

  // The mask overlays: files of the run (paths), or images report.html carried ({src: data URL, title}).
  function showFiles(files) {
    if (!files || !files.length) return;
    const esc = (t) => String(t).replace(/[&<>"]/g, (c) => ({'&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;'}[c]));
    $('overlays').innerHTML = '<h2>Mask overlays</h2>' + files.map((f) => {
      const src = typeof f === 'string' ? 'files/' + encodeURI(f) : f.src;
      const title = typeof f === 'string' ? f : f.title;
      return '<img loading="lazy" src="' + esc(src) + '" title="' + esc(title) + '">';
    }).join('');
  }

  // ---------------------------------------------------------------- talking to the server
  let events = null;
  async function loadState() {
    const response = await fetch('api/state', {cache: 'no-store'});
    useState(await response.json());
  }
  function useState(s) {
    seq = s.seq;
    apply(s, true);
    showFiles(s.files);
    drawIfChanged();
    // ?nofollow: the state as it is now, no live updates (a still picture, e.g. a headless browser's screenshot).
    if (info.live && !new URLSearchParams(location.search).has('nofollow')) connect();
  }
  function connect() {
    if (events) events.close();
    events = new EventSource('api/events?since=' + seq);
    events.addEventListener('update', (e) => {
      const u = JSON.parse(e.data);
      seq = u.seq;
      apply(u, false);
      $('message').textContent = '';
    });
    events.addEventListener('reload', () => { events.close(); loadState(); });
    events.onerror = () => { $('message').textContent = 'no connection to the run (it may have ended)'; };
  }

  $('frame').addEventListener('load', () => { imageBusy = false; });
  $('frame').addEventListener('error', () => { imageBusy = false; });
  initScene();
  if (window.amosInitialState) {
    useState(window.amosInitialState);
  } else {
    loadState().catch((e) => noteError('loading the state: ' + e));
  }
})();
