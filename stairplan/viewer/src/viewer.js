// The stairplan viewer page: draws the scene the `view` command embedded (stairs, map regions,
// footsteps, body path, the robot's shapes posed per frame, violations, a simulated run) with
// three.js. All kinematics happened in C++; here shapes are only placed at their recorded poses.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

const COLORS = {
  robot: 0x1f5fd0,        // the plan's robot (the viewer test looks for this blue)
  sim: 0xff8c1a,          // the simulated robot, translucent
  violation: 0xff00cc,    // violation markers, unlit (the viewer test looks for this magenta)
  impact: 0x00b8d9,       // the MuJoCo run's impacts and where their responses sent the foot
  stairs: 0xc8c8c8,
  nosing: 0x9a9a9a,
  step: 0x2ca02c,
  collision: 0xd62728,
  body: 0x202020,
  legs: { LF: 0xe6ab02, RF: 0xa6761d, LH: 0x1b9e77, RH: 0x555555 },
};

const data = JSON.parse(document.getElementById('scene-data').textContent);

// A shape builder per type; a mesh type joins here when robots with meshes arrive.
const SHAPE_BUILDERS = {
  box: (s) => new THREE.BoxGeometry(s[0], s[1], s[2]),
  cylinder: (s) => new THREE.CylinderGeometry(s[0], s[0], s[2], 20).rotateX(Math.PI / 2),  // URDF axis: z
  sphere: (s) => new THREE.SphereGeometry(s[0], 20, 14),
};

function buildRobot(scene, shapes, material) {
  return shapes.map((shape) => {
    const build = SHAPE_BUILDERS[shape.type];
    if (!build) throw new Error(`no drawing for shape type ${shape.type} (link ${shape.link})`);
    const mesh = new THREE.Mesh(build(shape.size), material);
      scene.add(mesh);
    return mesh;
  });
}

// The last frame at or before t (frames are in time order).
function frameAt(times, t) {
  let lo = 0, hi = times.length - 1;
  if (t <= times[0]) return 0;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (times[mid] <= t) lo = mid; else hi = mid - 1;
  }
  return lo;
}

function poseRobot(meshes, frames, t) {
  const k = frameAt(frames.t, t);
  const n = meshes.length;
  const p = frames.poses;
  for (let i = 0; i < n; ++i) {
    const o = (k * n + i) * 7;
    meshes[i].position.set(p[o], p[o + 1], p[o + 2]);
    meshes[i].quaternion.set(p[o + 3], p[o + 4], p[o + 5], p[o + 6]);
  }
}

function addPolygon(scene, points, z, color, opacity) {
  const shape = new THREE.Shape(points.map((q) => new THREE.Vector2(q[0], q[1])));
  const mesh = new THREE.Mesh(new THREE.ShapeGeometry(shape),
    new THREE.MeshBasicMaterial({ color, transparent: true, opacity, side: THREE.DoubleSide, depthWrite: false }));
  mesh.position.z = z;
  scene.add(mesh);
}

function buildWorld(scene) {
  for (const b of data.stairs) {
    const size = [0, 1, 2].map((i) => b.max[i] - b.min[i]);
    const mesh = new THREE.Mesh(new THREE.BoxGeometry(...size),
      new THREE.MeshLambertMaterial({ color: b.nosing ? COLORS.nosing : COLORS.stairs }));
    mesh.position.set(...[0, 1, 2].map((i) => 0.5 * (b.max[i] + b.min[i])));
    scene.add(mesh);
  }
  for (const r of data.regions) {
    addPolygon(scene, r.step, r.z + 0.002, COLORS.step, 0.35);
    for (const c of r.collision) addPolygon(scene, c.polygon, r.z + 0.003, COLORS.collision, 0.35);
  }
  const path = data.body.map((b) => new THREE.Vector3(b[1], b[2], b[3]));
  if (path.length > 1) {
    scene.add(new THREE.Line(new THREE.BufferGeometry().setFromPoints(path),
      new THREE.LineBasicMaterial({ color: COLORS.body })));
  }
}

function buildFootsteps(scene) {
  const disc = new THREE.CylinderGeometry(0.022, 0.022, 0.006, 16).rotateX(Math.PI / 2);
  return data.footsteps.map((f) => {
    const mesh = new THREE.Mesh(disc, new THREE.MeshBasicMaterial({
      color: COLORS.legs[f.leg] ?? 0x000000, transparent: true, opacity: 1.0 }));
    mesh.position.set(f.p[0], f.p[1], f.p[2] + 0.004);
    scene.add(mesh);
    return { mesh, t: f.t };
  });
}

function buildViolations(scene) {
  const ball = new THREE.SphereGeometry(0.04, 16, 12);
  const ring = new THREE.TorusGeometry(0.08, 0.012, 8, 32);
  return data.violations.map((v) => {
    const material = new THREE.MeshBasicMaterial({ color: COLORS.violation, depthTest: false });
    const group = new THREE.Group();
    group.add(new THREE.Mesh(ball, material), new THREE.Mesh(ring, material));
    group.position.set(...v.p);
    group.renderOrder = 10;
    group.children.forEach((c) => { c.renderOrder = 10; });
    scene.add(group);
    return { group, t: v.t };
  });
}

// The MuJoCo run's impacts (seed 000 [0053]-[0068]): a touchdown is a small dot in its leg's colour
// where the foot landed; any other event a cone pointing down at the foot, and when its response
// moved the swing's target, a line from the foot to the new target.
function buildImpacts(scene) {
  if (!data.sim || !data.sim.impacts) return [];
  const dot = new THREE.SphereGeometry(0.012, 10, 8);
  const cone = new THREE.ConeGeometry(0.025, 0.06, 12).rotateX(-Math.PI / 2);
  return data.sim.impacts.map((e) => {
    const group = new THREE.Group();
    if (e.kind === 'touchdown') {
      group.add(new THREE.Mesh(dot, new THREE.MeshBasicMaterial({ color: COLORS.legs[e.leg] ?? 0x000000 })));
      group.position.set(...e.p);
    } else {
      const material = new THREE.MeshBasicMaterial({ color: COLORS.impact, depthTest: false });
      const marker = new THREE.Mesh(cone, material);
      marker.position.set(e.p[0], e.p[1], e.p[2] + 0.04);
      marker.renderOrder = 9;
      group.add(marker);
      const moved = Math.hypot(e.target[0] - e.p[0], e.target[1] - e.p[1], e.target[2] - e.p[2]) > 0.005;
      if (e.executed && moved) {
        const line = new THREE.Line(new THREE.BufferGeometry().setFromPoints(
          [new THREE.Vector3(...e.p), new THREE.Vector3(...e.target)]), new THREE.LineBasicMaterial({ color: COLORS.impact }));
        const end = new THREE.Mesh(dot, material);
        end.position.set(...e.target);
        group.add(line, end);
      }
    }
    scene.add(group);
    return { group, t: e.t, touchdown: e.kind === 'touchdown' };
  });
}

function setupCamera(renderer) {
  const lo = new THREE.Vector3(Infinity, Infinity, Infinity);
  const hi = new THREE.Vector3(-Infinity, -Infinity, -Infinity);
  for (const b of data.stairs) {
    lo.min(new THREE.Vector3(...b.min));
    hi.max(new THREE.Vector3(...b.max));
  }
  const center = lo.clone().add(hi).multiplyScalar(0.5);
  const extent = Math.max(hi.x - lo.x, hi.z - lo.z, 1.0);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 100);
  camera.up.set(0, 0, 1);
  camera.position.set(center.x - 0.1 * extent, center.y - 0.95 * extent, center.z + 0.45 * extent);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(center);
  controls.update();
  return { camera, controls };
}

function main() {
  const canvas = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf4f6f8);
  scene.add(new THREE.AmbientLight(0xffffff, 1.2));
  const sun = new THREE.DirectionalLight(0xffffff, 2.0);
  sun.position.set(-1, -2, 4);
  scene.add(sun);

  buildWorld(scene);
  const footsteps = buildFootsteps(scene);
  const markers = buildViolations(scene);
  const impacts = buildImpacts(scene);
  const robot = buildRobot(scene, data.robot.shapes, new THREE.MeshLambertMaterial({ color: COLORS.robot }));
  // Pulled towards the camera so that where the run follows the plan exactly it tints the plan's robot.
  const sim = data.sim ? buildRobot(scene, data.robot.shapes, new THREE.MeshLambertMaterial({
    color: COLORS.sim, transparent: true, opacity: 0.35, depthWrite: false,
    polygonOffset: true, polygonOffsetFactor: -2, polygonOffsetUnits: -8 })) : null;
  const { camera, controls } = setupCamera(renderer);

  const ui = {
    play: document.getElementById('play'),
    slider: document.getElementById('time'),
    label: document.getElementById('time-label'),
    speed: document.getElementById('speed'),
  };
  const tMin = data.sim ? Math.min(0, data.sim.t[0]) : 0;
  const tMax = Math.max(data.duration, data.sim ? data.sim.t[data.sim.t.length - 1] : 0);
  ui.slider.min = tMin;
  ui.slider.max = tMax;
  ui.slider.step = 0.01;

  let t = 0;
  let playing = true;
  const hash = new URLSearchParams(window.location.hash.slice(1));
  if (hash.has('t')) {
    t = Math.min(Math.max(parseFloat(hash.get('t')) || 0, tMin), tMax);
    playing = false;
  }

  function resize() {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== Math.floor(w * renderer.getPixelRatio()) || canvas.height !== Math.floor(h * renderer.getPixelRatio())) {
      renderer.setSize(w, h, false);
      camera.aspect = w / Math.max(h, 1);
      camera.updateProjectionMatrix();
    }
  }

  function draw() {
    resize();
    poseRobot(robot, data.frames, Math.min(Math.max(t, 0), data.duration));
    if (sim) poseRobot(sim, data.sim, t);
    for (const f of footsteps) f.mesh.material.opacity = f.t <= t ? 1.0 : 0.3;
    for (const m of markers) m.group.scale.setScalar(Math.abs(m.t - t) < 0.3 ? 1.8 : 1.0);
    for (const e of impacts) {
      e.group.visible = e.t <= t || !e.touchdown;
      e.group.scale.setScalar(!e.touchdown && Math.abs(e.t - t) < 0.3 ? 1.8 : 1.0);
    }
    ui.slider.value = t;
    ui.label.textContent = `t = ${t.toFixed(2)} s / ${tMax.toFixed(2)} s`;
    ui.play.textContent = playing ? 'pause' : 'play';
    renderer.render(scene, camera);
  }

  ui.play.addEventListener('click', () => {
    if (!playing && t >= tMax) t = tMin;
    playing = !playing;
    draw();
  });
  ui.slider.addEventListener('input', () => { t = parseFloat(ui.slider.value); playing = false; draw(); });
  controls.addEventListener('change', draw);
  window.addEventListener('resize', draw);
  for (const item of document.querySelectorAll('[data-t]')) {
    item.addEventListener('click', () => { t = parseFloat(item.dataset.t); playing = false; draw(); });
  }

  let last = null;
  function tick(now) {
    if (playing && last !== null) {
      t += ((now - last) / 1000) * parseFloat(ui.speed.value);
      if (t >= tMax) { t = tMax; playing = false; }
      draw();
    }
    last = now;
    requestAnimationFrame(tick);
  }
  draw();
  requestAnimationFrame(tick);
}

main();
