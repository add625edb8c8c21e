// The 3D replay (three.js): the robot drawn from its model's geoms, posed from the simulator's
// recorded body poses; the planned footprints and the planned CoM trajectory overlaid as in the
// paper's Fig. 1; play/pause, a time slider, and a camera that follows the pelvis.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const SIDE_COLOR = { left: 0x1f77b4, right: 0xd62728 };
const PLAN_COLOR = 0x2ca02c, TRUE_COM_COLOR = 0x8c564b;

const css = (color) => `#${color.toString(16).padStart(6, '0')}`;

// What the overlay's colours mean, under the view.
function legend() {
  const box = document.createElement('div');
  box.id = 'replay-legend';
  const entries = [
    ['footprint', SIDE_COLOR.left, 'left foot, planned'],
    ['footprint', SIDE_COLOR.right, 'right foot, planned (bright: the steps in the plan now; faint: stepped on)'],
    ['line', PLAN_COLOR, 'planned CoM trajectory'],
    ['dashed', PLAN_COLOR, 'its ground projection'],
    ['ball', PLAN_COLOR, 'planned CoM now'],
    ['ball', TRUE_COM_COLOR, 'true CoM (simulator) and its drop line to the ground'],
  ];
  for (const [kind, color, text] of entries) {
    const item = document.createElement('span');
    item.className = 'legend-item';
    const swatch = document.createElement('span');
    swatch.className = `swatch ${kind}`;
    swatch.style.setProperty('--color', css(color));
    item.append(swatch, text);
    box.appendChild(item);
  }
  return box;
}

// MuJoCo's geom sizes (half-sizes, radius and half-length along z) to three.js geometries.
function geometryOf(geom) {
  const [a, b, c] = geom.size;
  switch (geom.type) {
    case 'box': return new THREE.BoxGeometry(2 * a, 2 * b, 2 * c);
    case 'sphere': return new THREE.SphereGeometry(a, 24, 16);
    case 'ellipsoid': return new THREE.SphereGeometry(1, 24, 16).scale(a, b, c);
    case 'capsule': return new THREE.CapsuleGeometry(a, 2 * b, 8, 16).rotateX(Math.PI / 2);
    case 'cylinder': return new THREE.CylinderGeometry(a, a, 2 * b, 24).rotateX(Math.PI / 2);
    case 'mesh': {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(geom.mesh.vert, 3));
      g.setIndex(geom.mesh.face);
      g.computeVertexNormals();
      return g;
    }
    default: return null;
  }
}

function meshOf(geom) {
  if (geom.type === 'plane') {
    // An infinite plane (size 0) is drawn 200 m wide. Its 1 m grid is a texture, not lines: some
    // software renderers drop lines that cross the near plane.
    const w = geom.size[0] > 0 ? 2 * geom.size[0] : 200, h = geom.size[1] > 0 ? 2 * geom.size[1] : 200;
    const cell = document.createElement('canvas');
    cell.width = cell.height = 128;
    const ctx = cell.getContext('2d');
    ctx.fillStyle = '#eceef1';
    ctx.fillRect(0, 0, 128, 128);
    ctx.strokeStyle = '#a4a9b1';
    ctx.lineWidth = 3;
    ctx.strokeRect(0, 0, 128, 128);
    const texture = new THREE.CanvasTexture(cell);
    texture.wrapS = texture.wrapT = THREE.RepeatWrapping;
    texture.repeat.set(w, h);
    texture.anisotropy = 8;
    texture.colorSpace = THREE.SRGBColorSpace;
    return new THREE.Mesh(new THREE.PlaneGeometry(w, h), new THREE.MeshLambertMaterial({ map: texture }));
  }
  const geometry = geometryOf(geom);
  if (!geometry) return null;
  const [r, g, b, alpha] = geom.rgba;
  const material = new THREE.MeshStandardMaterial({
    color: new THREE.Color(r, g, b), roughness: 0.6, metalness: 0.1,
    transparent: alpha < 1, opacity: alpha,
  });
  return new THREE.Mesh(geometry, material);
}

function place(object, pos, quat) {
  object.position.set(pos[0], pos[1], pos[2]);
  object.quaternion.set(quat[1], quat[2], quat[3], quat[0]);  // MuJoCo stores w first
}

function footprint(data, fp) {
  const sole = data.model.soles.find((s) => s.side === fp.side);
  const w = sole.x_max - sole.x_min, h = sole.y_max - sole.y_min;
  const shape = new THREE.PlaneGeometry(w, h).translate(0.5 * (sole.x_max + sole.x_min), 0.5 * (sole.y_max + sole.y_min), 0);
  const group = new THREE.Group();
  const fill = new THREE.Mesh(shape, new THREE.MeshBasicMaterial({
    color: SIDE_COLOR[fp.side], transparent: true, opacity: 0.35, depthWrite: false,
  }));
  const outline = new THREE.LineSegments(new THREE.EdgesGeometry(shape),
    new THREE.LineBasicMaterial({ color: SIDE_COLOR[fp.side] }));
  group.add(fill, outline);
  group.position.set(fp.x, fp.y, 0.003);
  group.rotation.z = fp.yaw;
  return { group, fill, outline, fp };
}

export function createReplay(viewer, controls, data, cursor, setTime) {
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  viewer.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf6f7f9);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.8);
  sun.position.set(3, -4, 6);
  scene.add(sun);

  const camera = new THREE.PerspectiveCamera(40, 1, 0.05, 500);
  camera.up.set(0, 0, 1);
  const orbit = new OrbitControls(camera, renderer.domElement);

  // Bodies (their recorded poses) and the world's static geoms.
  const bodies = data.model.bodies.map((name) => {
    const g = new THREE.Group();
    g.name = name;
    scene.add(g);
    return g;
  });
  for (const geom of data.model.geoms) {
    const mesh = meshOf(geom);
    if (!mesh) continue;
    place(mesh, geom.pos, geom.quat);
    (geom.body >= 0 ? bodies[geom.body] : scene).add(mesh);
  }

  // Fig. 1's overlay: footprints of the plan, the planned CoM trajectory, the CoM now.
  const footprints = data.footprints.map((fp) => footprint(data, fp));
  for (const f of footprints) scene.add(f.group);
  const L = data.log;
  const comPath = [];
  for (let i = 0; i < L.t.length; ++i) comPath.push(new THREE.Vector3(L.com_des_x[i], L.com_des_y[i], L.com_des_z[i]));
  const comLine = new THREE.Line(new THREE.BufferGeometry().setFromPoints(comPath),
    new THREE.LineBasicMaterial({ color: PLAN_COLOR }));
  scene.add(comLine);
  const groundPath = comPath.map((p) => new THREE.Vector3(p.x, p.y, 0.004));
  scene.add(new THREE.Line(new THREE.BufferGeometry().setFromPoints(groundPath),
    new THREE.LineDashedMaterial({ color: PLAN_COLOR, dashSize: 0.03, gapSize: 0.02 })).computeLineDistances());
  const comMarker = new THREE.Mesh(new THREE.SphereGeometry(0.025, 16, 12), new THREE.MeshBasicMaterial({ color: TRUE_COM_COLOR }));
  const comDesiredMarker = new THREE.Mesh(new THREE.SphereGeometry(0.02, 16, 12), new THREE.MeshBasicMaterial({ color: PLAN_COLOR }));
  const comDrop = new THREE.Line(new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(), new THREE.Vector3()]),
    new THREE.LineBasicMaterial({ color: TRUE_COM_COLOR }));
  scene.add(comMarker, comDesiredMarker, comDrop);

  // Pose at time t: the recorded frames, interpolated.
  const R = data.replay, stride = 7;
  const qa = new THREE.Quaternion(), qb = new THREE.Quaternion();
  function pose(t) {
    let hi = R.t.findIndex((v) => v >= t);
    if (hi < 0) hi = R.t.length - 1;
    const lo = Math.max(0, hi - 1);
    const s = hi === lo ? 0 : Math.min(1, Math.max(0, (t - R.t[lo]) / (R.t[hi] - R.t[lo])));
    const a = R.frames[lo], b = R.frames[hi];
    bodies.forEach((body, k) => {
      const o = k * stride;
      body.position.set(a[o] + s * (b[o] - a[o]), a[o + 1] + s * (b[o + 1] - a[o + 1]), a[o + 2] + s * (b[o + 2] - a[o + 2]));
      qa.set(a[o + 4], a[o + 5], a[o + 6], a[o + 3]);
      qb.set(b[o + 4], b[o + 5], b[o + 6], b[o + 3]);
      body.quaternion.slerpQuaternions(qa, qb, s);
    });
    let i = L.t.findIndex((v) => v >= t);
    if (i < 0) i = L.t.length - 1;
    comMarker.position.set(L.com_x[i], L.com_y[i], L.com_z[i]);
    comDesiredMarker.position.copy(comPath[i]);
    comDrop.geometry.setFromPoints([comMarker.position, new THREE.Vector3(L.com_x[i], L.com_y[i], 0)]);
    // Footprints: those in the plan now stand out; the ones stepped on stay faint; later ones, and
    // those replanned elsewhere, are hidden.
    for (const f of footprints) {
      const planned = f.fp.first <= t && t <= f.fp.last;
      f.group.visible = planned || (f.fp.first <= t && !f.fp.superseded);
      f.fill.material.opacity = planned ? 0.55 : 0.15;
      f.outline.visible = planned;
    }
  }

  // Camera: starts beside the robot looking at the pelvis; then moves along with it.
  const pelvis = bodies[data.model.pelvis];
  pose(0);
  const target = pelvis.position.clone();
  orbit.target.copy(target);
  camera.position.copy(target).add(new THREE.Vector3(1.2, -3.0, 0.8));
  orbit.update();
  let follow = true;
  function followPelvis() {
    if (!follow) return;
    const delta = pelvis.position.clone().sub(orbit.target);
    delta.z = 0;
    orbit.target.add(delta);
    camera.position.add(delta);
    orbit.update();
  }

  function resize() {
    const w = viewer.clientWidth, h = viewer.clientHeight;
    renderer.setSize(w, h, false);
    renderer.domElement.style.width = `${w}px`;
    renderer.domElement.style.height = `${h}px`;
    camera.aspect = w / Math.max(1, h);
    camera.updateProjectionMatrix();
  }
  resize();
  window.addEventListener('resize', resize);

  function render() {
    pose(cursor.t);
    followPelvis();
    renderer.render(scene, camera);
  }
  orbit.addEventListener('change', () => renderer.render(scene, camera));

  // The walking state machine's state at time t, beside the time.
  const stateAt = (t) => {
    let i = L.t.findIndex((v) => v > t);
    i = i < 0 ? L.t.length - 1 : Math.max(0, i - 1);
    return L.states[L.state[i]] ?? '';
  };

  // Controls: play/pause, time slider, speed, camera follow.
  const t0 = R.t[0] ?? 0, t1 = R.t[R.t.length - 1] ?? 0;
  const button = document.createElement('button');
  button.id = 'play';
  button.textContent = 'Play';
  const slider = document.createElement('input');
  Object.assign(slider, { type: 'range', id: 'time', min: t0, max: t1, step: 0.001, value: t0 });
  const label = document.createElement('span');
  label.id = 'time-label';
  const speed = document.createElement('select');
  for (const v of [0.1, 0.25, 0.5, 1, 2]) speed.add(new Option(`${v}×`, v, v === 1, v === 1));
  const followBox = document.createElement('input');
  Object.assign(followBox, { type: 'checkbox', checked: true, id: 'follow' });
  const followLabel = document.createElement('label');
  followLabel.append(followBox, ' camera follows');
  controls.append(button, slider, label, speed, followLabel);
  controls.after(legend());

  let playing = false, last = 0;
  function frame(now) {
    if (!playing) return;
    const dt = Math.min(0.1, (now - last) / 1000);
    last = now;
    if (cursor.t >= t1) {
      playing = false;
      button.textContent = 'Play';
      return;
    }
    setTime(cursor.t + dt * Number(speed.value));
    requestAnimationFrame(frame);
  }
  button.addEventListener('click', () => {
    playing = !playing;
    button.textContent = playing ? 'Pause' : 'Play';
    if (playing) {
      if (cursor.t >= t1) setTime(t0);
      last = performance.now();
      requestAnimationFrame(frame);
    }
  });
  slider.addEventListener('input', () => setTime(Number(slider.value)));
  followBox.addEventListener('change', () => { follow = followBox.checked; render(); });
  cursor.listeners.push((t) => {
    slider.value = t;
    label.textContent = `t = ${t.toFixed(2)} s, ${stateAt(t)}`;
    render();
  });

  return {
    canvas: renderer.domElement,
    render,
    bodyPosition: (name) => {
      const b = bodies.find((g) => g.name === name);
      return b ? b.position.toArray() : null;
    },
  };
}
