// Browser half of bench/report/run.sh: opens a report in headless chromium
// (software WebGL: SwiftShader) `loads` times, each in a new page, and
// measures on each load:
// - time to first frame: from navigation start to the first frame with the
//   mesh (the viewer's firstFrameMs: rendered and read back);
// - turning: 60 frames of 6 degrees through the viewer's camera-move path
//   (orbitFrames: the interaction mesh is drawn), each rendered to
//   completion;
// - rest: the display mesh drawn again after the last of those moves
//   (whenRested): its render time, and the time from the last move to its
//   completion (the viewer's rest delay included);
// - turning at full detail: 30 frames with the display mesh (orbitFrames
//   with level 'full': the view without its interaction mesh), for comparison;
// - a real drag: the mouse dragged across the canvas (OrbitControls), every
//   frame drawn timed; then the rest frame again.
// Medians over the loads. Prints one JSON object.
// Usage: NODE_PATH=<node_modules> node measure.cjs <chromium> <report folder> [loads]
const path = require('node:path');
const { pathToFileURL } = require('node:url');
const { chromium } = require('playwright-core');

const median = (v) => {
  const s = [...v].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};
const quantile = (v, q) => [...v].sort((a, b) => a - b)[Math.min(v.length - 1, Math.floor(q * v.length))];
const round1 = (x) => Math.round(x * 10) / 10;
const levels = (frames) => {
  const count = {};
  for (const f of frames) count[f.level] = (count[f.level] || 0) + 1;
  return count;
};

async function load(browser, folder) {
  const page = await browser.newPage({ viewport: { width: 1200, height: 900 } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  try {
    await page.goto(pathToFileURL(path.join(folder, 'report.html')).href, { timeout: 120000 });
    await page.waitForFunction(() => window.meshnbvViewer, null, { timeout: 120000 });
    if (errors.length) throw new Error(errors.join('; '));
    const r = await page.evaluate(async () => {
      const v = window.meshnbvViewer;
      // The page settled: the interaction mesh is built and warmed up after
      // the first frame (a display mesh frame rendered to completion waits
      // for that work).
      await new Promise((resolve) => { setTimeout(resolve, 100); });
      await v.whenRested();
      const turning = v.orbitFrames(60, 6);
      const rest = await v.whenRested();
      const full = v.orbitFrames(30, 6, { level: 'full' });
      const canvas = document.querySelector('#meshnbv-viewer canvas');
      const gl = canvas.getContext('webgl2');
      const ext = gl.getExtension('WEBGL_debug_renderer_info');
      return {
        first_frame_ms: v.firstFrameMs, turning, rest, full, faces: v.originalFaces, display_faces: v.displayFaces,
        interaction_faces: v.interactionFaces, rest_delay_ms: v.restMs, decimated: v.decimated,
        canvas: [canvas.width, canvas.height], renderer: gl.getParameter(ext ? ext.UNMASKED_RENDERER_WEBGL : gl.RENDERER),
        status: document.querySelector('.mnv-status').textContent,
      };
    });
    // A real drag across the canvas.
    const canvas = await page.$('#meshnbv-viewer canvas');
    await canvas.scrollIntoViewIfNeeded();
    const box = await canvas.boundingBox();
    const y = box.y + box.height * 0.6;
    await page.evaluate(() => window.meshnbvViewer.setTiming(true));
    await page.mouse.move(box.x + box.width * 0.3, y);
    await page.mouse.down();
    for (let k = 1; k <= 40; ++k) await page.mouse.move(box.x + box.width * (0.3 + 0.01 * k), y);
    await page.mouse.up();
    const dragRest = await page.evaluate(() => window.meshnbvViewer.whenRested());
    const drag = (await page.evaluate(() => window.meshnbvViewer.setTiming(false))).filter((f) => f.at < dragRest.at);
    if (errors.length) throw new Error(errors.join('; '));
    return { ...r, drag, drag_rest: dragRest };
  } finally {
    await page.close();
  }
}

async function main() {
  const [executablePath, folder, loadsArg] = process.argv.slice(2);
  const loads = Number(loadsArg || 5);
  const browser = await chromium.launch({
    executablePath, args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
  });
  const runs = [];
  let info = null;
  try {
    for (let k = 0; k < loads; ++k) {
      const r = await load(browser, folder);
      const ms = (frames) => frames.map((f) => f.ms);
      runs.push({
        first_frame_ms: round1(r.first_frame_ms),
        turning_levels: levels(r.turning),
        turning_triangles: [...new Set(r.turning.map((f) => f.triangles))],
        turning_ms_median: round1(median(ms(r.turning))),
        turning_ms_p10: round1(quantile(ms(r.turning), 0.1)),
        turning_ms_p90: round1(quantile(ms(r.turning), 0.9)),
        turning_ms_max: round1(Math.max(...ms(r.turning))),
        rest_level: r.rest.level,
        rest_triangles: r.rest.triangles,
        rest_render_ms: round1(r.rest.ms),
        rest_done_after_last_move_ms: round1(r.rest.doneAfterChange),
        full_turning_ms_median: round1(median(ms(r.full))),
        full_turning_ms_p10: round1(quantile(ms(r.full), 0.1)),
        full_turning_ms_p90: round1(quantile(ms(r.full), 0.9)),
        drag_frames: r.drag.length,
        drag_levels: levels(r.drag),
        drag_ms_median: r.drag.length ? round1(median(ms(r.drag))) : null,
        drag_rest_level: r.drag_rest.level,
        drag_rest_render_ms: round1(r.drag_rest.ms),
        drag_rest_done_after_last_move_ms: round1(r.drag_rest.doneAfterChange),
      });
      info = r;
    }
  } finally {
    await browser.close();
  }
  const med = (key) => round1(median(runs.map((r) => r[key])));
  console.log(JSON.stringify({
    faces: info.faces,
    display_faces: info.display_faces,
    interaction_faces: info.interaction_faces,
    decimated: info.decimated,
    rest_delay_ms: info.rest_delay_ms,
    status: info.status,
    canvas_pixels: info.canvas,
    renderer: info.renderer,
    loads: runs,
    first_frame_ms_median: med('first_frame_ms'),
    turning_ms_median: med('turning_ms_median'),
    turning_ms_p90: med('turning_ms_p90'),
    turning_ms_p10: med('turning_ms_p10'),
    rest_render_ms_median: med('rest_render_ms'),
    rest_done_after_last_move_ms_median: med('rest_done_after_last_move_ms'),
    full_turning_ms_median: med('full_turning_ms_median'),
    full_turning_ms_p90: med('full_turning_ms_p90'),
    full_turning_ms_p10: med('full_turning_ms_p10'),
    drag_ms_median: med('drag_ms_median'),
    drag_rest_done_after_last_move_ms_median: med('drag_rest_done_after_last_move_ms'),
  }, null, 1));
}

main().catch((e) => {
  console.error(`bench/report: ${e.message}`);
  process.exit(1);
});
