// Where the 3-D view's frame time goes (bench/report/run.sh runs it after
// measure.cjs on the same report): headless chromium, software WebGL
// (SwiftShader). One page; each variant changes one thing about the frame
// (what is drawn, the shader, the vertex count, the canvas size) and is
// timed over frames turning 6 degrees each, every frame rendered to
// completion (a one-pixel read back), in interleaved rounds (so that the
// changing load of a shared machine falls on every variant alike): median
// and fastest frame, and the GPU process's CPU time per frame (gpu_cpu.cjs).
// Variants reach the viewer through its read-back API's internals(); only
// `full` and `interaction` are what the viewer ships. Prints one JSON object.
// Usage: NODE_PATH=<node_modules> node profile.cjs <chromium> <report folder> [frames per round] [rounds]
//        [regular expression: only the variants it matches]
const path = require('node:path');
const { pathToFileURL } = require('node:url');
const { chromium } = require('playwright-core');
const { gpuCpuMs, gpuProcesses } = require('./gpu_cpu.cjs');

async function main() {
  const [executablePath, folder, framesArg, roundsArg, only] = process.argv.slice(2);
  const frames = Number(framesArg || 5);
  const rounds = Number(roundsArg || 5);
  const browser = await chromium.launch({
    executablePath, args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
  });
  try {
    const page = await browser.newPage({ viewport: { width: 1200, height: 900 } });
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(pathToFileURL(path.join(folder, 'report.html')).href, { timeout: 120000 });
    await page.waitForFunction(() => window.meshnbvViewer, null, { timeout: 120000 });
    if (errors.length) throw new Error(errors.join('; '));
    const result = await page.evaluate(({ n, rounds, only }) => {
      const v = window.meshnbvViewer.internals();
      v.ensureProxy();
      v.settle();
      v.renderNow();
      const full = v.surface.mesh;
      const proxy = v.proxy ? v.proxy.mesh : null;
      const Geometry = full.geometry.constructor;
      const Attribute = full.geometry.getAttribute('position').constructor;
      const Material = full.material.constructor;
      const MeshType = full.constructor;
      const angle = (6 * Math.PI) / 180;
      // Variants are registered here, then timed from node in interleaved
      // rounds (runOne).
      const time = (setup, undo) => ({ setup, undo, triangles: 0 });
      const cleanups = [];
      // One (variant, round): an untimed frame (uploads, compiles), then
      // n timed ones.
      const runOne = (name) => {
        const entry = out[name];
        entry.setup();
        const samples = [];
        for (let k = 0; k < n + 1; ++k) {
          const offset = v.camera.position.clone().sub(v.controls.target).applyAxisAngle(v.up, angle);
          v.camera.position.copy(v.controls.target).add(offset);
          v.camera.lookAt(v.controls.target);
          const t0 = performance.now();
          v.renderer.render(v.scene, v.camera);
          v.syncGpu();
          if (k >= 1) samples.push(performance.now() - t0);
        }
        entry.triangles = v.renderer.info.render.triangles;
        entry.undo();
        return { samples, triangles: entry.triangles };
      };
      // One untimed frame of a variant (before a CPU-timed run).
      const warm = (name) => {
        const entry = out[name];
        entry.setup();
        v.renderer.render(v.scene, v.camera);
        v.syncGpu();
        entry.undo();
      };
      const show = (mesh, others) => () => {
        full.visible = mesh === full;
        if (proxy) proxy.visible = mesh === proxy;
        for (const o of others) o.visible = true;
      };
      const reset = () => { full.visible = true; if (proxy) proxy.visible = false; };
      const frustums = [v.existing, v.suggested];
      const hideFrustums = () => frustums.forEach((f) => { f.visible = false; });
      const showFrustums = () => frustums.forEach((f) => { f.visible = true; });
      const out = {};
      const faces = full.geometry.getAttribute('position').count / 3;
      out.full = time(show(full, []), reset);
      out.nothing = time(() => { full.visible = false; hideFrustums(); }, () => { reset(); showFrustums(); });
      out.frustums_only = time(() => { full.visible = false; }, reset);
      out.full_no_frustums = time(hideFrustums, showFrustums);
      out.full_no_stripes = time(() => { v.material.uniforms.markWeak.value = 0; }, () => { v.material.uniforms.markWeak.value = 1; });
      for (const share of [0.25, 0.5]) {
        out[`full_first_${share * 100}pct_faces`] = time(() => full.geometry.setDrawRange(0, 3 * Math.round(share * faces)),
          () => full.geometry.setDrawRange(0, Infinity));
      }
      // The shader: colour only (no derivatives, lighting, stripes).
      const plain = new Material({
        vertexShader: 'attribute vec4 faceColour; varying vec3 vColour; void main(){ vColour = faceColour.rgb; gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0); }',
        fragmentShader: 'varying vec3 vColour; void main(){ gl_FragColor = vec4(vColour, 1.0); }',
        side: full.material.side,
      });
      out.full_plain_shader = time(() => { full.material = plain; }, () => { full.material = v.material; });
      if (proxy) {
        out.interaction_plain_shader = time(() => { full.visible = false; proxy.visible = true; proxy.material = plain; },
          () => { proxy.material = v.material; reset(); });
      }
      const extra = (geometry, material) => {
        const m = new MeshType(geometry, material);
        m.visible = false;
        v.scene.add(m);
        cleanups.push(() => { v.scene.remove(m); geometry.dispose(); });
        return () => time(() => { full.visible = false; if (proxy) proxy.visible = false; m.visible = true; },
          () => { m.visible = false; reset(); });
      };
      // Shaded per fragment, as before this bench (the face normal from
      // screen-space derivatives, the lighting on every fragment), on the
      // same geometry: what shading per face in the vertex shader saves.
      const fragmentShading = new Material({
        vertexShader: `attribute vec4 faceColour; attribute vec4 faceNormal;
varying vec3 vColour; varying vec3 vViewPosition; varying float vWeak; varying float vHighlight;
void main() { float code = floor(faceNormal.w * 127.0 + 0.5); vColour = faceColour.rgb;
  vWeak = floor(mod(code, 8.0) / 2.0) > 0.0 ? 1.0 : 0.0; vHighlight = floor(code / 8.0);
  vec4 mv = modelViewMatrix * vec4(position, 1.0); vViewPosition = mv.xyz; gl_Position = projectionMatrix * mv; }`,
        fragmentShader: `uniform float markWeak; uniform vec3 light;
varying vec3 vColour; varying vec3 vViewPosition; varying float vWeak; varying float vHighlight;
void main() { vec3 n = normalize(cross(dFdx(vViewPosition), dFdy(vViewPosition))); if (dot(n, vViewPosition) > 0.0) n = -n;
  vec3 l = normalize((viewMatrix * vec4(light, 0.0)).xyz); float diffuse = max(0.0, dot(n, l)); vec3 base = vColour;
  if (vHighlight > 1.5) base = vec3(0.0, 0.85, 1.0); else if (vHighlight > 0.5) base = vec3(1.0, 0.0, 1.0);
  vec3 c = base * (0.55 + 0.45 * diffuse);
  if (markWeak > 0.5 && vWeak > 0.5 && vHighlight < 0.5) { if (mod(gl_FragCoord.x + gl_FragCoord.y, 8.0) < 2.0) c = mix(c, vec3(0.1, 0.1, 0.18), 0.55); }
  gl_FragColor = vec4(c, 1.0); }`,
        uniforms: v.material.uniforms,
        side: full.material.side,
      });
      out.full_fragment_shading_before = time(() => { full.material = fragmentShading; }, () => { full.material = v.material; });
      if (proxy) {
        out.interaction_fragment_shading_before = time(() => { full.visible = false; proxy.visible = true; proxy.material = fragmentShading; },
          () => { proxy.material = v.material; reset(); });
      }
      // Shared vertices (indexed: a third of the vertices), plain colour:
      // what the vertices' count weighs.
      {
        const data = v.data;
        const ig = new Geometry();
        ig.setAttribute('position', new Attribute(data.array('positions'), 3));
        ig.setIndex(new Attribute(data.array('indices'), 1));
        out.full_shared_vertices_plain = extra(ig, new Material({
          vertexShader: 'void main(){ gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0); }',
          fragmentShader: 'void main(){ gl_FragColor = vec4(0.5, 0.7, 0.5, 1.0); }',
          side: full.material.side,
        }))();
      }
      // Canvas of a quarter of the pixels.
      {
        const { w, h } = v.size;
        out.full_quarter_pixels = time(() => v.renderer.setSize(Math.round(w / 2), Math.round(h / 2), false),
          () => v.renderer.setSize(w, h, false));
        if (proxy) {
          out.interaction_quarter_pixels = time(() => {
            full.visible = false; proxy.visible = true; v.renderer.setSize(Math.round(w / 2), Math.round(h / 2), false);
          }, () => { v.renderer.setSize(w, h, false); reset(); });
        }
      }
      if (proxy) out.interaction = time(show(proxy, []), reset);
      const names = Object.keys(out).filter((name) => !only || new RegExp(only).test(name));
      window.mnvProfile = { runOne, warm, names, cleanups };
      const canvas = v.renderer.domElement;
      return {
        display_faces: faces, interaction_faces: proxy ? proxy.geometry.getAttribute('position').count / 3 : null,
        canvas: [canvas.width, canvas.height], antialias: v.renderer.getContextAttributes().antialias,
        pixel_ratio: v.renderer.getPixelRatio(), frames: n, rounds, names,
      };
    }, { n: frames, rounds, only });
    // Interleaved rounds; each (variant, round) one evaluation, with the GPU
    // process's CPU time around it (less the untimed first frame's, which
    // runs in a warm-up evaluation just before).
    const pids = gpuProcesses();
    const per = Object.fromEntries(result.names.map((name) => [name, { samples: [], cpu: [], triangles: 0 }]));
    for (let r = 0; r < rounds; ++r) {
      for (const name of result.names) {
        await page.evaluate((nm) => window.mnvProfile.warm(nm), name);
        const c0 = gpuCpuMs(pids);
        const one = await page.evaluate((nm) => window.mnvProfile.runOne(nm), name);
        const c1 = gpuCpuMs(pids);
        per[name].samples.push(...one.samples);
        per[name].cpu.push((c1 - c0) / (one.samples.length + 1));
        per[name].triangles = one.triangles;
      }
    }
    const median = (t) => { const s = [...t].sort((a, b) => a - b); return s[Math.floor(s.length / 2)]; };
    const round1 = (x) => Math.round(x * 10) / 10;
    result.variants = {};
    for (const [name, p] of Object.entries(per)) {
      result.variants[name] = {
        ms: round1(median(p.samples)), min_ms: round1(Math.min(...p.samples)),
        gpu_process_cpu_ms: round1(median(p.cpu)), triangles: p.triangles,
      };
    }
    delete result.names;
    console.log(JSON.stringify(result, null, 1));
  } finally {
    await browser.close();
  }
}

main().catch((e) => {
  console.error(`bench/report/profile: ${e.message}`);
  process.exit(1);
});
