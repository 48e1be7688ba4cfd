// Browser half of tests/report/viewer_3d.sh: drives headless chromium on a
// report folder, asserts what a browser alone can tell, and writes what
// the shell half checks against pri.ply (the picked face, the screenshot).
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

    // Back to the overview; a click at the canvas centre picks a face and
    // the panel shows its value.
    await page.click('.mnv-side button.mnv-item:has-text("Overview")');
    const box = await canvas.boundingBox();
    await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
    const picked = await page.evaluate(() => window.meshnbvViewer.lastPicked());
    assert.ok(picked, 'clicking the canvas centre picked no face');
    const shown = await page.textContent('.mnv-picked .mnv-pri');
    const expected = await page.evaluate((p) => (p === null ? '—' : String(Number(p.toPrecision(4)))), picked.pri);
    assert.equal(shown, expected, 'the panel shows the picked face value');
    assert.ok((await page.textContent('.mnv-picked')).includes(`face${picked.face}`), 'the panel names the face');

    assert.deepEqual(errors, [], 'console errors');
    assert.deepEqual(requests, [], 'requests other than file:// and data:');
    fs.writeFileSync(resultPath, JSON.stringify({ screenshot, pose, picked: { ...picked, shown } }, null, 1));
    console.log(`pose of ${s.label} matched; picked face ${picked.face}`);
  } finally {
    await browser.close();
  }
}

main().catch((e) => {
  console.error(`FAIL: ${e.message}`);
  process.exit(1);
});
