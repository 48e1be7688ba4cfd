// Browser half of bench/report/run.sh: opens a report in headless chromium
// (software WebGL: SwiftShader) `loads` times and measures the time from
// navigation start to the first frame with the mesh (the viewer's
// firstFrameMs: rendered and read back), then the frame time while turning
// the model (orbitFrames: 60 frames of 6 degrees, each rendered to
// completion). Prints one JSON object.
// Usage: NODE_PATH=<node_modules> node measure.cjs <chromium> <report folder> [loads]
const path = require('node:path');
const { pathToFileURL } = require('node:url');
const { chromium } = require('playwright-core');

const median = (v) => {
  const s = [...v].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};
const quantile = (v, q) => [...v].sort((a, b) => a - b)[Math.min(v.length - 1, Math.floor(q * v.length))];

async function main() {
  const [executablePath, folder, loadsArg] = process.argv.slice(2);
  const loads = Number(loadsArg || 3);
  const browser = await chromium.launch({
    executablePath, args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
  });
  const runs = [];
  let info = null;
  try {
    for (let k = 0; k < loads; ++k) {
      const page = await browser.newPage({ viewport: { width: 1200, height: 900 } });
      const errors = [];
      page.on('pageerror', (e) => errors.push(e.message));
      page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
      await page.goto(pathToFileURL(path.join(folder, 'report.html')).href, { timeout: 120000 });
      await page.waitForFunction(() => window.meshnbvViewer, null, { timeout: 120000 });
      if (errors.length) throw new Error(errors.join('; '));
      const r = await page.evaluate(() => {
        const v = window.meshnbvViewer;
        const frames = v.orbitFrames(60, 6);
        const canvas = document.querySelector('#meshnbv-viewer canvas');
        return {
          first_frame_ms: v.firstFrameMs, frames_ms: frames, faces: v.originalFaces, display_faces: v.displayFaces,
          decimated: v.decimated, canvas: [canvas.width, canvas.height],
          renderer: (() => {
            const gl = canvas.getContext('webgl2');
            const ext = gl.getExtension('WEBGL_debug_renderer_info');
            return gl.getParameter(ext ? ext.UNMASKED_RENDERER_WEBGL : gl.RENDERER);
          })(),
        };
      });
      runs.push({ first_frame_ms: r.first_frame_ms, frame_median_ms: median(r.frames_ms), frame_p90_ms: quantile(r.frames_ms, 0.9) });
      info = r;
      await page.close();
    }
  } finally {
    await browser.close();
  }
  console.log(JSON.stringify({
    faces: info.faces,
    display_faces: info.display_faces,
    decimated: info.decimated,
    canvas_pixels: info.canvas,
    renderer: info.renderer,
    loads: runs,
    first_frame_ms_median: median(runs.map((r) => r.first_frame_ms)),
    frame_ms_median: median(runs.map((r) => r.frame_median_ms)),
    frame_ms_p90: median(runs.map((r) => r.frame_p90_ms)),
  }, null, 1));
}

main().catch((e) => {
  console.error(`bench/report: ${e.message}`);
  process.exit(1);
});
