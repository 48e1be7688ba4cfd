// Browser half of tests/report/viewer_3d.sh: drives headless chromium on a
// report folder, asserts what a browser alone can tell, and writes what
// the shell half checks against pri.ply (the picked faces, the screenshot).
// The interaction level of detail: while the camera turns (a real mouse
// drag) every frame draws the interaction mesh, after the rest delay the
// display mesh (three.js's triangle count of each frame, read back through
// window.meshnbvViewer); a face picked while the interaction mesh is on
// screen is still the display mesh's.
// Usage: node viewer_test.cjs <chromium> <report folder> <result.json>
const assert = require('node:assert/strict');
const fs = require('node:fs');
const path = require('node:path');
const { pathToFileURL } = require('node:url');
const { chromium } = require('playwright-core');

const [executablePath, folder, resultPath] = process.argv.slice(2);

// SwiftShader: software WebGL, the same on every machine (no GPU in CI).
const ARGS = ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'];

function close(a, b, what) {
  const scale = Math.max(1, ...b.map(Math.abs));
  a.forEach((v, k) => assert.ok(Math.abs(v - b[k]) <= 1e-6 * scale, `${what}: ${a} against ${b}`));
}

async function main() {
  const browser = await chromium.launch({ executablePath, args: ARGS });
  try {
    const page = await browser.newPage({ viewport: { width: 1200, height: 900 } });
    const errors = [];
    const requests = [];
    page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
    page.on('pageerror', (e) => errors.push(e.message));
    page.on('request', (r) => {
      if (!/^(file|data):/.test(r.url())) requests.push(r.url());
    });
    await page.goto(pathToFileURL(path.join(folder, 'report.html')).href);
    await page.waitForFunction(() => window.meshnbvViewer, null, { timeout: 60000 });
    const canvas = await page.$('#meshnbv-viewer canvas');
    assert.ok(canvas, 'no canvas in #meshnbv-viewer');
    const screenshot = path.join(path.dirname(resultPath), 'viewer.png');
    await canvas.screenshot({ path: screenshot });

    // The first suggestion, clicked in the list: the camera at its pose.
    const suggestions = JSON.parse(fs.readFileSync(path.join(folder, 'suggestions.json'), 'utf8')).suggestions;
    assert.ok(suggestions.length > 0, 'no suggestion in suggestions.json');
    await page.click('.mnv-side button.mnv-item:has-text("nbv_1:")');
    const pose = await page.evaluate(() => window.meshnbvViewer.cameraPose());
    const s = suggestions[0];
    assert.equal(pose.mode, 'view');
    assert.equal(pose.suggestion, s.label);
    close(pose.position, s.centre, 'camera centre');
    close(pose.direction, s.camera.R[2], 'viewing direction');
    close(pose.up, s.camera.R[1].map((v) => -v), 'camera up');
    close([pose.fov], [(2 * Math.atan(s.camera.height / (2 * s.camera.fy)) * 180) / Math.PI], 'vertical field of view');
    close([pose.intrinsics.fx, pose.intrinsics.fy, pose.intrinsics.cx, pose.intrinsics.cy],
      [s.camera.fx, s.camera.fy, s.camera.cx, s.camera.cy], 'intrinsics');

    // Back to the overview: the display mesh is drawn (a jump, not a turn).
    await page.click('.mnv-side button.mnv-item:has-text("Overview")');
    const api = await page.evaluate(() => {
      const v = window.meshnbvViewer;
      return { displayFaces: v.displayFaces, interactionFaces: v.interactionFaces, restMs: v.restMs };
    });
    assert.ok(Number.isInteger(api.interactionFaces) && api.interactionFaces > 0 && api.interactionFaces < api.displayFaces,
      `an interaction mesh coarser than the display mesh (the test scene is above its budget): ${JSON.stringify(api)}`);
    const status = await page.textContent('.mnv-status');
    assert.ok(status.includes(`${api.displayFaces} faces`) && status.includes(`${api.interactionFaces} faces while turning`),
      `the view states both face counts: ${status}`);
    assert.ok((await page.textContent('body')).includes(`coarser copy of ${api.interactionFaces} faces`),
      'the page states the interaction mesh');
    const atRest = await page.evaluate(() => window.meshnbvViewer.whenRested());
    assert.equal(atRest.level, 'full', 'at rest the display mesh is drawn');
    assert.equal(atRest.triangles, api.displayFaces, 'at rest every display face is drawn');

    // Each level draws every face in its own colour (flat, from its
    // provoking vertex): at a grid of pixels, the drawn colour is the
    // colour (in the data) of the face a ray through the pixel hits, times
    // the lighting (0.55..1); stripes off. A pixel on an edge between faces
    // may disagree, so 90% of them must agree.
    const cb = await canvas.boundingBox();
    const grid = [];
    for (let i = 1; i < 24; ++i) for (let j = 1; j < 18; ++j) grid.push([(cb.width * i) / 24, (cb.height * j) / 18]);
    const drawn = await page.evaluate((points) => {
      const v = window.meshnbvViewer;
      v.toggle('weak', false);
      const full = v.drawnAt(points);
      v.orbitFrames(1, 0);
      const coarse = v.drawnAt(points);
      v.toggle('weak', true);
      return { full, coarse };
    }, grid);
    await page.evaluate(() => window.meshnbvViewer.whenRested());
    const lit = ({ rgb, colour }) => {
      const top = Math.max(...colour);
      if (top === 0) return Math.max(...rgb) <= 3;
      const f = rgb[colour.indexOf(top)] / top;
      return f >= 0.53 && f <= 1.01 && rgb.every((c, k) => Math.abs(c - f * colour[k]) <= 3);
    };
    const agreement = {};
    for (const [level, samples] of [['full', drawn.full], ['interaction', drawn.coarse]]) {
      const onMesh = samples.filter((p) => p.face !== null);
      assert.ok(samples.every((p) => p.level === level), `drawn at the ${level} level`);
      assert.ok(onMesh.length >= 50, `${level}: ${onMesh.length} grid pixels on the mesh`);
      const agree = onMesh.filter(lit).length;
      assert.ok(agree >= 0.9 * onMesh.length,
        `${level}: ${agree} of ${onMesh.length} pixels show their face's colour: ${JSON.stringify(onMesh.filter((p) => !lit(p)).slice(0, 3))}`);
      agreement[level] = `${agree}/${onMesh.length}`;
    }

    // A real drag (OrbitControls): while it turns, the interaction mesh;
    // after the rest delay, the display mesh again.
    const box = await canvas.boundingBox();
    // Start the drag on the canvas itself (not on a suggestion's label).
    const y = await page.evaluate(({ x, top, height }) => {
      const c = document.querySelector('#meshnbv-viewer canvas');
      const row = [0.7, 0.8, 0.6, 0.9, 0.5].find((f) => document.elementFromPoint(x, top + f * height) === c);
      return row === undefined ? null : top + row * height;
    }, { x: box.x + box.width * 0.3, top: box.y, height: box.height });
    assert.ok(y !== null, 'no point of the canvas free to start a drag');
    const dragStart = await page.evaluate(() => performance.now());
    await page.mouse.move(box.x + box.width * 0.3, y);
    await page.mouse.down();
    for (let k = 1; k <= 12; ++k) await page.mouse.move(box.x + box.width * (0.3 + 0.02 * k), y);
    await page.mouse.up();
    const rested = await page.evaluate(() => window.meshnbvViewer.whenRested());
    const frames = (await page.evaluate(() => window.meshnbvViewer.recentFrames())).filter((f) => f.at > dragStart);
    const turning = frames.filter((f) => f.at < rested.at);
    // A frame drawn less than the rest delay after a move shows the
    // interaction mesh; one drawn later (the drag stalled: a loaded machine)
    // rightly shows the display mesh.
    const moving = turning.filter((f) => f.sinceChange < api.restMs);
    assert.ok(moving.length >= 2, `frames drawn while turning: ${JSON.stringify(turning)}`);
    for (const f of turning) {
      const [level, triangles] = f.sinceChange < api.restMs ? ['interaction', api.interactionFaces] : ['full', api.displayFaces];
      assert.equal(f.level, level, `a frame ${Math.round(f.sinceChange)} ms after a move: ${JSON.stringify(f)}`);
      assert.equal(f.triangles, triangles, `a frame ${Math.round(f.sinceChange)} ms after a move draws the ${level} mesh`);
    }
    assert.equal(rested.level, 'full', 'after the drag the display mesh is drawn again');
    assert.equal(rested.triangles, api.displayFaces, 'after the drag every display face is drawn');
    assert.ok(rested.sinceChange >= api.restMs - 1, `the display mesh only once the camera rests: ${JSON.stringify(rested)}`);

    // A face picked while the interaction mesh is on screen (a turn and the
    // pick in one task, so the rest delay cannot pass between them) is the
    // display mesh's: the shell half checks it against pri.ply.
    const pickedMoving = await page.evaluate(({ x, y }) => {
      const v = window.meshnbvViewer;
      v.orbitFrames(2, 1);
      const drawn = v.lastFrame();
      return { drawn, picked: v.pickAt(x, y) };
    }, { x: box.x + box.width / 2, y: box.y + box.height / 2 });
    assert.equal(pickedMoving.drawn.level, 'interaction', 'the interaction mesh is on screen for the pick');
    assert.equal(pickedMoving.drawn.triangles, api.interactionFaces);
    assert.ok(pickedMoving.picked, 'a pick at the canvas centre while turning found no face');
    assert.equal(pickedMoving.picked.on_screen, 'interaction');
    await page.evaluate(() => window.meshnbvViewer.whenRested());

    // Back to the overview; a click at the canvas centre picks a face and
    // the panel shows its value.
    await page.click('.mnv-side button.mnv-item:has-text("Overview")');
    await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
    const picked = await page.evaluate(() => window.meshnbvViewer.lastPicked());
    assert.ok(picked, 'clicking the canvas centre picked no face');
    const shown = await page.textContent('.mnv-picked .mnv-pri');
    const expected = await page.evaluate((p) => (p === null ? '—' : String(Number(p.toPrecision(4)))), picked.pri);
    assert.equal(shown, expected, 'the panel shows the picked face value');
    assert.ok((await page.textContent('.mnv-picked')).includes(`face${picked.face}`), 'the panel names the face');

    assert.deepEqual(errors, [], 'console errors');
    assert.deepEqual(requests, [], 'requests other than file:// and data:');
    fs.writeFileSync(resultPath, JSON.stringify({
      screenshot, pose, picked: { ...picked, shown }, picked_while_turning: pickedMoving.picked, lod: api,
    }, null, 1));
    console.log(`pose of ${s.label} matched; ${moving.length} of ${turning.length} frames of the drag with ${api.interactionFaces} faces, `
      + `${rested.triangles} after ${Math.round(rested.sinceChange)} ms at rest; picked face ${picked.face}, `
      + `face ${pickedMoving.picked.face} while turning; pixels in their face's colour: ${JSON.stringify(agreement)}`);
  } finally {
    await browser.close();
  }
}

main().catch((e) => {
  console.error(`FAIL: ${e.message}`);
  process.exit(1);
});
