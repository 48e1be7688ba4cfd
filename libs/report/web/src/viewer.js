// MeshNBV report: the interactive 3-D view. Builds itself inside
// #meshnbv-viewer from window.MESHNBV_REPORT (viewer/report_data.js): the
// mesh coloured by PRI (green best .. red worst over the 5th..95th
// percentiles, grey unobserved, weak evidence striped), the existing
// cameras (blue) and the suggestions (red .. yellow); orbit controls; a
// suggestion clicked puts the camera at its pose with its intrinsics; a
// face clicked shows its values; a region clicked is framed. Above the
// interaction budget (data.interaction), a coarser copy of the mesh is drawn
// while the camera moves and the display mesh again REST_MS after its last
// move; picking always uses the display mesh.
// window.meshnbvViewer is a small read-back API for tests and the bench.
import {
  PerspectiveCamera, Raycaster, Scene, Vector2, Vector3, WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

import { fitDistance, intrinsicProjection, quaternionOf, vec, verticalFov } from './camera_math.js';
import { reportData } from './data.js';
import {
  EXISTING_COLOUR, buildFrustums, centreOf, frustumCorners, suggestionColour,
} from './frustums.js';
import { Panel } from './panel.js';
import { addStyles } from './style.js';
import {
  HIGHLIGHT_PICKED, HIGHLIGHT_REGION, buildSurface, displayArrays, interactionArrays, setMarkWeak, surfaceMaterial,
} from './surface.js';

const ORBIT_FOV = 45;  // degrees, vertical, outside a suggestion's view
// The display mesh is drawn again this long after the camera's last move
// (the interaction mesh in between): long enough to span the gaps between
// the events of a drag, short enough to read as "as soon as it rests".
const REST_MS = 150;
const RECENT_FRAMES = 200;

class Viewer {
  constructor(container, data) {
    this.data = data;
    this.origin = data.origin;
    this.up = vec(data.up).normalize();
    this.mode = 'orbit';
    this.active = -1;  // suggestion looked through
    this.picked = null;
    this.regionShown = -1;

    addStyles(document);
    container.classList.add('mnv');
    container.textContent = '';
    this.stage = document.createElement('div');
    this.stage.className = 'mnv-stage';
    this.canvas = document.createElement('canvas');
    this.labels = document.createElement('div');
    this.frame = document.createElement('div');
    this.frame.className = 'mnv-frame';
    this.status = document.createElement('div');
    this.status.className = 'mnv-status';
    this.stage.append(this.canvas, this.labels, this.frame, this.status);
    container.appendChild(this.stage);
    this.panel = new Panel(container, data, {
      overview: () => this.overview(),
      lookThrough: (i) => this.lookThrough(i),
      frameRegion: (i) => this.frameRegion(i),
      toggle: (what, on) => this.toggle(what, on),
    });
    this.stage.appendChild(this.panel.legend);

    // Multisampling costs about half the frame time in software WebGL
    // (bench/results/report): kept for small meshes only.
    this.renderer = new WebGLRenderer({ canvas: this.canvas, antialias: data.display_faces <= 50000 });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.renderer.setClearColor(0xffffff, 1);
    this.scene = new Scene();
    this.material = surfaceMaterial();
    this.surface = buildSurface(displayArrays(data), this.material);
    this.scene.add(this.surface.mesh);
    this.proxy = null;  // the interaction mesh, built after the first frame
    this.interacting = false;  // the camera moved less than REST_MS ago
    this.restTimer = null;
    this.highlights = [];
    this.timing = false;  // each frame rendered to completion and logged (bench)
    this.frames = [];
    this.lastFrame = null;
    this.recent = [];  // the last RECENT_FRAMES frames drawn (read-back API)
    this.lastChange = 0;

    this.existing = buildFrustums(data.cameras.map((view) => ({
      view, centre: centreOf(view, this.origin), colour: EXISTING_COLOUR,
    })));
    const n = data.suggestions.length;
    this.suggested = buildFrustums(data.suggestions.map((view, i) => ({
      view, centre: centreOf(view, this.origin), colour: suggestionColour(i, n),
    })));
    this.scene.add(this.existing, this.suggested);
    this.labelElements = data.suggestions.map((s, i) => {
      const el = document.createElement('div');
      el.className = 'mnv-label';
      el.textContent = s.label;
      const [r, g, b] = suggestionColour(i, n);
      el.style.background = `rgb(${r},${g},${b})`;
      el.title = `look through ${s.label}`;
      el.addEventListener('click', () => this.lookThrough(i));
      this.labels.appendChild(el);
      return el;
    });

    // Everything the clipping planes must hold: the mesh and every camera.
    this.sceneRadius = vec(data.box.max).sub(vec(data.box.min)).length() / 2;
    for (const v of [...data.cameras, ...data.suggestions]) {
      this.sceneRadius = Math.max(this.sceneRadius, centreOf(v, this.origin).length());
    }

    this.camera = new PerspectiveCamera(ORBIT_FOV, 1, 0.01, 10);
    this.camera.up.copy(this.up);
    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.addEventListener('start', () => this.leaveView());
    // The user moved the camera (a programmatic jump sets this.jumping).
    this.controls.addEventListener('change', () => (this.jumping ? this.requestRender() : this.cameraMoved()));
    this.raycaster = new Raycaster();
    this.setupPicking();

    this.resize();
    new ResizeObserver(() => { this.resize(); this.requestRender(); }).observe(this.stage);
    this.overview();
    this.renderNow();
    // The first frame with the mesh, complete on the GPU (a one-pixel read
    // waits for it): what the bench calls time to first frame.
    this.syncGpu();
    this.firstFrameMs = performance.now();
    this.panel.setStatus(this.status, data);
    if (data.interaction) setTimeout(() => this.warmProxy(), 0);
  }

  // ------------------------------------------------------------ rendering

  resize() {
    const w = Math.max(1, this.stage.clientWidth);
    const h = Math.max(1, this.stage.clientHeight);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.size = { w, h };
  }

  requestRender() {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      this.renderNow();
    });
  }

  // The camera moves: the interaction mesh until REST_MS after the last move.
  cameraMoved() {
    this.lastChange = performance.now();
    if (this.data.interaction) {
      this.interacting = true;
      clearTimeout(this.restTimer);
      this.restTimer = setTimeout(() => this.rest(), REST_MS);
    }
    this.requestRender();
  }

  rest() {
    this.restTimer = null;
    this.interacting = false;
    this.requestRender();
  }

  // A jump (overview, a suggestion, a region): the display mesh at once.
  settle() {
    clearTimeout(this.restTimer);
    this.restTimer = null;
    this.interacting = false;
  }

  // Builds the interaction mesh on first use; false when there is none.
  ensureProxy() {
    if (!this.data.interaction) return false;
    if (!this.proxy) {
      this.proxy = buildSurface(interactionArrays(this.data), this.material);
      this.proxy.mesh.visible = false;
      this.proxyOf = this.data.array('interaction_face_of_display');
      this.scene.add(this.proxy.mesh);
      this.applyHighlights();
    }
    return true;
  }

  // Builds the interaction mesh and draws it once, then the display mesh
  // again in the same task (so the page only ever shows the latter): its
  // buffers' upload and first draw, hundreds of milliseconds in software
  // WebGL, are then not paid by the first frame of the first drag.
  warmProxy() {
    if (this.proxy || !this.ensureProxy()) return;
    this.surface.mesh.visible = false;
    this.proxy.mesh.visible = true;
    this.renderer.render(this.scene, this.camera);
    this.renderNow();
  }

  renderNow() {
    const t0 = performance.now();
    const coarse = this.interacting && this.ensureProxy();
    this.surface.mesh.visible = !coarse;
    if (this.proxy) this.proxy.mesh.visible = coarse;
    const distance = this.camera.position.length();
    const far = (distance + this.sceneRadius) * 1.5;
    const near = far / 20000;
    this.camera.near = near;
    this.camera.far = far;
    if (this.mode === 'view') {
      const view = this.data.suggestions[this.active];
      const { matrix, rect } = intrinsicProjection(view, this.size.w, this.size.h, near, far);
      this.camera.projectionMatrix.copy(matrix);
      this.camera.projectionMatrixInverse.copy(matrix).invert();
      Object.assign(this.frame.style, {
        display: 'block', left: `${rect.x}px`, top: `${rect.y}px`, width: `${rect.width}px`, height: `${rect.height}px`,
      });
    } else {
      this.camera.updateProjectionMatrix();
      this.frame.style.display = 'none';
    }
    this.renderer.render(this.scene, this.camera);
    // What was drawn, read back from three.js's own count.
    this.lastFrame = {
      level: coarse ? 'interaction' : 'full',
      triangles: this.renderer.info.render.triangles,
      at: t0,
      sinceChange: t0 - this.lastChange,
    };
    this.recent.push(this.lastFrame);
    if (this.recent.length > RECENT_FRAMES) this.recent.shift();
    this.placeLabels();
    if (this.timing) {
      this.syncGpu();
      this.lastFrame.ms = performance.now() - t0;
      this.frames.push(this.lastFrame);
    }
  }

  syncGpu() {
    const gl = this.renderer.getContext();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
  }

  placeLabels() {
    const show = this.suggested.visible;
    this.data.suggestions.forEach((s, i) => {
      const el = this.labelElements[i];
      const corner = frustumCorners(s, centreOf(s, this.origin), s.depth)[0];
      const p = corner.project(this.camera);
      const inside = show && i !== this.active && p.z > -1 && p.z < 1 && Math.abs(p.x) < 1 && Math.abs(p.y) < 1;
      el.style.display = inside ? 'block' : 'none';
      if (inside) {
        el.style.left = `${((p.x + 1) / 2) * this.size.w}px`;
        el.style.top = `${((1 - p.y) / 2) * this.size.h}px`;
      }
    });
  }

  // ------------------------------------------------------------ cameras

  // The mesh framed from azimuth 35 and elevation 35 degrees (as overview_1.png),
  // turning about the centre of its bounding box.
  overview() {
    const az = (35 * Math.PI) / 180;
    const el = (35 * Math.PI) / 180;
    let e1 = new Vector3(1, 0, 0).projectOnPlane(this.up);
    if (e1.length() < 0.1) e1 = new Vector3(0, 1, 0).projectOnPlane(this.up);
    e1.normalize();
    const e2 = new Vector3().crossVectors(this.up, e1);
    const dir = e1.multiplyScalar(Math.cos(el) * Math.cos(az))
      .addScaledVector(e2, Math.cos(el) * Math.sin(az))
      .addScaledVector(this.up, Math.sin(el));
    // Framed on the mesh's own vertices (a bounding box leaves wide margins),
    // at most 20000 of them.
    const positions = this.data.array('positions');
    const count = positions.length / 3;
    const step = Math.max(1, Math.floor(count / 20000));
    const points = [];
    for (let v = 0; v < count; v += step) points.push(new Vector3(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]));
    this.orbitAround(new Vector3(0, 0, 0), dir, fitDistance(points, dir, this.up, ORBIT_FOV, this.camera.aspect, 0.92));
    this.panel.setActive(-1, -1);
  }

  orbitAround(target, direction, distance) {
    this.leaveView();
    this.settle();
    this.camera.fov = ORBIT_FOV;
    this.controls.target.copy(target);
    this.camera.position.copy(target).addScaledVector(direction.clone().normalize(), Math.max(distance, 1e-9));
    this.camera.up.copy(this.up);
    this.camera.lookAt(target);
    this.jumping = true;
    this.controls.update();
    this.jumping = false;
    this.requestRender();
  }

  // The camera at suggestion i's exact pose, with its intrinsics.
  lookThrough(i) {
    const s = this.data.suggestions[i];
    if (!s) throw new Error(`no suggestion ${i}`);
    this.settle();
    this.mode = 'view';
    this.active = i;
    this.camera.position.copy(centreOf(s, this.origin));
    this.camera.quaternion.copy(quaternionOf(s.R));
    this.camera.updateMatrixWorld(true);
    // Orbiting from here turns around the point the suggestion looks at.
    this.controls.target.copy(centreOf({ centre: s.look_at }, this.origin));
    this.panel.setActive(i, -1);
    this.panel.showView(s);
    this.renderNow();
    return this.cameraPose();
  }

  // Leaving a suggestion's view (the user orbits): a plain perspective with
  // the same vertical field of view.
  leaveView() {
    if (this.mode !== 'view') return;
    this.camera.fov = verticalFov(this.data.suggestions[this.active]);
    this.mode = 'orbit';
    this.active = -1;
    this.panel.setActive(-1, this.regionShown);
  }

  // Region i framed: seen from its first suggestion's side (or along its
  // mean normal), its faces highlighted.
  frameRegion(i) {
    const r = this.data.regions[i];
    if (!r) throw new Error(`no region ${i}`);
    const centre = centreOf({ centre: r.centroid }, this.origin);
    const by = this.data.suggestions.find((s) => s.region === i);
    let dir = by ? centreOf(by, this.origin).sub(centre) : vec(r.normal);
    if (dir.length() < 1e-12) dir = this.camera.position.clone().sub(this.controls.target);
    dir.normalize();
    const diag = this.sceneRadius * 2;
    const radius = Math.max(r.radius, 0.02 * diag);
    const distance = (radius / Math.sin(((ORBIT_FOV / 2) * Math.PI) / 180)) * 1.3;
    this.regionShown = i;
    this.orbitAround(centre, dir, distance);
    this.highlight();
    this.panel.setActive(-1, i);
    this.panel.showRegion(i, r, this.data.suggestions.filter((s) => s.region === i).map((s) => s.label));
    return this.cameraPose();
  }

  toggle(what, on) {
    if (what === 'cameras') this.existing.visible = on;
    if (what === 'suggestions') this.suggested.visible = on;
    if (what === 'weak') setMarkWeak(this.material, on);
    this.requestRender();
  }

  // Pose in world coordinates: position, viewing direction, up, vertical
  // field of view (degrees) and, looking through a suggestion, its intrinsics.
  cameraPose() {
    const q = this.camera.quaternion;
    const direction = new Vector3(0, 0, -1).applyQuaternion(q);
    const up = new Vector3(0, 1, 0).applyQuaternion(q);
    const p = this.camera.position;
    const pose = {
      mode: this.mode,
      position: [p.x + this.origin[0], p.y + this.origin[1], p.z + this.origin[2]],
      direction: direction.toArray(),
      up: up.toArray(),
      fov: this.mode === 'view' ? verticalFov(this.data.suggestions[this.active]) : this.camera.fov,
    };
    if (this.mode === 'view') {
      const s = this.data.suggestions[this.active];
      pose.suggestion = s.label;
      pose.intrinsics = { fx: s.fx, fy: s.fy, cx: s.cx, cy: s.cy, width: s.width, height: s.height };
    }
    return pose;
  }

  // ------------------------------------------------------------ picking

  setupPicking() {
    let down = null;
    this.canvas.addEventListener('pointerdown', (e) => { down = { x: e.clientX, y: e.clientY, t: performance.now() }; });
    this.canvas.addEventListener('pointerup', (e) => {
      if (!down) return;
      const moved = Math.hypot(e.clientX - down.x, e.clientY - down.y);
      if (moved < 4 && performance.now() - down.t < 800 && e.button === 0) this.pickAt(e.clientX, e.clientY);
      down = null;
    });
  }

  // The face under a point of the window (client coordinates), shown in the
  // panel and returned (null when no face is there).
  pickAt(clientX, clientY) {
    const rect = this.canvas.getBoundingClientRect();
    const ndc = new Vector2(((clientX - rect.left) / rect.width) * 2 - 1, -((clientY - rect.top) / rect.height) * 2 + 1);
    this.raycaster.setFromCamera(ndc, this.camera);
    // Always the display mesh, whichever level is on screen.
    const hit = this.raycaster.intersectObject(this.surface.mesh, false)[0];
    if (!hit) {
      this.picked = null;
      this.highlight();
      this.panel.showPicked(null);
      return null;
    }
    const displayFace = hit.faceIndex;
    const face = this.originalFaceAt(displayFace, hit.point);
    this.picked = this.faceInfo(face, displayFace, hit.point);
    // The level on screen when picked (the pick itself is on the display mesh).
    this.picked.on_screen = this.lastFrame ? this.lastFrame.level : null;
    this.highlight();
    this.panel.showPicked(this.picked);
    return this.picked;
  }

  // The original face a display face stands for that is nearest the point
  // (by centroid; the display face itself when not decimated).
  originalFaceAt(displayFace, point) {
    if (!this.data.decimated) return displayFace;
    const begin = this.data.array('member_begin');
    const members = this.data.array('members');
    const q = this.data.array('centroids');
    const { centroid_min: min, centroid_extent: ext } = this.data.decimation;
    let best = -1;
    let bestDistance = Infinity;
    for (let k = begin[displayFace]; k < begin[displayFace + 1]; ++k) {
      const f = members[k];
      const dx = min[0] + (q[3 * f] / 65535) * ext[0] - point.x;
      const dy = min[1] + (q[3 * f + 1] / 65535) * ext[1] - point.y;
      const dz = min[2] + (q[3 * f + 2] / 65535) * ext[2] - point.z;
      const d = dx * dx + dy * dy + dz * dz;
      if (d < bestDistance) { bestDistance = d; best = f; }
    }
    return best;
  }

  // Display faces of original faces (the identity when not decimated).
  displayFaceOf(face) {
    if (!this.data.decimated) return face;
    if (!this.displayOf) {
      const begin = this.data.array('member_begin');
      const members = this.data.array('members');
      this.displayOf = new Uint32Array(this.data.faces);
      for (let d = 0; d + 1 < begin.length; ++d) {
        for (let k = begin[d]; k < begin[d + 1]; ++k) this.displayOf[members[k]] = d;
      }
    }
    return this.displayOf[face];
  }

  faceInfo(face, displayFace, point) {
    const d = this.data;
    const pri = d.array('face_pri')[face];
    const views = d.array('face_views')[face];
    const texture = d.array('face_texture')[face];
    const evidence = [];
    if (Number.isNaN(pri)) evidence.push('unobserved (fewer than two views compare it)');
    else {
      if (views === 2) evidence.push('2 views only');
      if (!(texture >= d.low_texture_below)) evidence.push('low texture');
    }
    if (!this.coveredBy) {
      this.coveredBy = new Map();
      for (const s of d.suggestions) {
        for (const f of s.seen_faces) {
          if (!this.coveredBy.has(f)) this.coveredBy.set(f, []);
          this.coveredBy.get(f).push(s.label);
        }
      }
      this.regionOf = new Map();
      d.regions.forEach((r, i) => r.faces.forEach((f) => this.regionOf.set(f, i)));
    }
    const begin = d.decimated ? d.array('member_begin') : null;
    return {
      face,
      display_face: displayFace,
      stands_for: begin ? begin[displayFace + 1] - begin[displayFace] : 1,
      point: [point.x + this.origin[0], point.y + this.origin[1], point.z + this.origin[2]],
      pri: Number.isNaN(pri) ? null : pri,
      views,
      pairs: d.array('face_pairs')[face],
      samples: d.array('face_samples')[face],
      texture: Number.isNaN(texture) ? null : texture,
      evidence,
      suggestions: this.coveredBy.get(face) || [],
      region: this.regionOf.has(face) ? this.regionOf.get(face) : null,
    };
  }

  highlight() {
    const list = [];
    if (this.regionShown >= 0) {
      for (const f of this.data.regions[this.regionShown].faces) list.push([this.displayFaceOf(f), HIGHLIGHT_REGION]);
    }
    if (this.picked) list.push([this.picked.display_face, HIGHLIGHT_PICKED]);
    this.highlights = list;
    this.applyHighlights();
    this.requestRender();
  }

  // The highlights on the display mesh, and on the interaction mesh the
  // faces that stand for them.
  applyHighlights() {
    this.surface.setHighlights(this.highlights);
    if (this.proxy) this.proxy.setHighlights(this.highlights.map(([f, kind]) => [this.proxyOf[f], kind]));
  }

  // ------------------------------------------------------------ bench

  // Turns the camera about the up axis through the target, `degrees` per
  // frame, as a drag does (each step a camera move: the interaction mesh),
  // rendering each frame to completion; per frame { level, triangles, ms }.
  // With { level: 'full' } every frame draws the display mesh (the view
  // without its interaction mesh, for comparison).
  orbitFrames(frames, degrees = 6, { level } = {}) {
    this.leaveView();
    if (level === 'full') this.settle();
    const timing = this.timing;
    this.timing = true;
    this.frames = [];
    const angle = (degrees * Math.PI) / 180;
    for (let k = 0; k < frames; ++k) {
      const offset = this.camera.position.clone().sub(this.controls.target).applyAxisAngle(this.up, angle);
      this.camera.position.copy(this.controls.target).add(offset);
      this.camera.lookAt(this.controls.target);
      if (level === 'full') this.lastChange = performance.now();
      else this.cameraMoved();
      this.renderNow();
    }
    this.jumping = true;
    this.controls.update();
    this.jumping = false;
    const out = this.frames;
    this.frames = [];
    this.timing = timing;
    return out;
  }

  // Resolves when the display mesh has been drawn again after the camera's
  // last move (drawn at once when the camera rests already and no such
  // frame was timed): that frame's { level, triangles, ms (rendered to
  // completion), sinceChange (from the last move to the frame's start),
  // doneAfterChange (to its completion) }.
  whenRested() {
    return new Promise((resolve) => {
      const timing = this.timing;
      this.timing = true;
      const done = (f) => f && f.level === 'full' && f.at >= this.lastChange && f.ms !== undefined;
      if (!this.interacting && !done(this.lastFrame)) this.renderNow();
      const check = () => {
        if (!this.interacting && done(this.lastFrame)) {
          this.timing = timing;
          const f = this.lastFrame;
          resolve({ ...f, doneAfterChange: f.at + f.ms - this.lastChange });
        } else setTimeout(check, 5);
      };
      check();
    });
  }

  // The frame as drawn at canvas points ([x, y] in CSS pixels of the
  // canvas), for tests: per point the pixel's rgb, and the face a ray
  // through the pixel's centre hits on the mesh on screen, with that face's
  // colour in the data (null where no face is hit).
  drawnAt(points) {
    this.renderNow();
    const level = this.lastFrame.level;
    const surface = level === 'interaction' ? this.proxy : this.surface;
    const colours = this.data.array(level === 'interaction' ? 'interaction_colours' : 'colours');
    const gl = this.renderer.getContext();
    const ratio = this.renderer.getPixelRatio();
    const pixel = new Uint8Array(4);
    return points.map(([x, y]) => {
      const px = Math.floor(x * ratio);
      const py = Math.floor(y * ratio);
      gl.readPixels(px, gl.drawingBufferHeight - 1 - py, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
      const ndc = new Vector2(((px + 0.5) / gl.drawingBufferWidth) * 2 - 1, -((py + 0.5) / gl.drawingBufferHeight) * 2 + 1);
      this.raycaster.setFromCamera(ndc, this.camera);
      const hit = this.raycaster.intersectObject(surface.mesh, false)[0];
      const face = hit ? hit.faceIndex : null;
      return {
        level, rgb: [pixel[0], pixel[1], pixel[2]], face, colour: hit ? Array.from(colours.subarray(3 * face, 3 * face + 3)) : null,
      };
    });
  }

  api() {
    return {
      version: 2,
      firstFrameMs: this.firstFrameMs,
      originalFaces: this.data.faces,
      displayFaces: this.data.display_faces,
      decimated: this.data.decimated,
      interactionFaces: this.data.interaction ? this.data.interaction.faces : null,
      restMs: REST_MS,
      // The last frame drawn: { level: 'interaction' | 'full', triangles
      // (three.js's count of what it drew), at, sinceChange, ms when timed }.
      lastFrame: () => (this.lastFrame ? { ...this.lastFrame } : null),
      // The last frames drawn (up to 200), oldest first, as lastFrame.
      recentFrames: () => this.recent.map((f) => ({ ...f })),
      // Each frame rendered to completion and timed (on), the frames so timed (off).
      setTiming: (on) => {
        this.timing = on;
        const frames = this.frames;
        this.frames = [];
        return frames;
      },
      whenRested: () => this.whenRested(),
      cameraPose: () => this.cameraPose(),
      lookThrough: (i) => this.lookThrough(i),
      frameRegion: (i) => this.frameRegion(i),
      overview: () => { this.overview(); this.renderNow(); return this.cameraPose(); },
      pickAt: (x, y) => this.pickAt(x, y),
      lastPicked: () => this.picked,
      orbitFrames: (n, degrees, options) => this.orbitFrames(n, degrees, options),
      drawnAt: (points) => this.drawnAt(points),
      toggle: (what, on) => this.toggle(what, on),
      internals: () => this,  // bench/report/profile.cjs only
    };
  }
}

function start() {
  const container = document.getElementById('meshnbv-viewer');
  if (!container) return;
  try {
    const viewer = new Viewer(container, reportData(window.MESHNBV_REPORT));
    window.meshnbvViewer = viewer.api();
  } catch (e) {
    container.textContent = '';
    const message = document.createElement('div');
    message.className = 'mnv-error';
    message.textContent = `3-D view unavailable: ${e.message}`;
    container.appendChild(message);
    console.error(`meshnbv viewer: ${e.message}`);
  }
}

if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', start);
else start();
