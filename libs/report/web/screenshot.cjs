// A screenshot of a report's 3-D view (docs/images/report_3d.png): headless
// chromium with software WebGL, the view as it opens, a face picked at the
// canvas centre so that the panel shows its values.
// Usage: NODE_PATH=<node_modules> node screenshot.cjs <chromium> <report folder> <out.png>
const path = require('node:path');
const { pathToFileURL } = require('node:url');
const { chromium } = require('playwright-core');

async function main() {
  const [executablePath, folder, out] = process.argv.slice(2);
  if (!out) throw new Error('usage: node screenshot.cjs <chromium> <report folder> <out.png>');
  const browser = await chromium.launch({
    executablePath, args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
  });
  try {
    const page = await browser.newPage({ viewport: { width: 1150, height: 800 }, deviceScaleFactor: 1 });
    page.on('pageerror', (e) => { throw e; });
    await page.goto(pathToFileURL(path.join(folder, 'report.html')).href);
    await page.waitForFunction(() => window.meshnbvViewer, null, { timeout: 60000 });
    const canvas = await page.$('#meshnbv-viewer canvas');
    const box = await canvas.boundingBox();
    await page.mouse.click(box.x + box.width * 0.5, box.y + box.height * 0.55);
    await page.waitForTimeout(200);
    await (await page.$('#meshnbv-viewer')).screenshot({ path: out });
  } finally {
    await browser.close();
  }
}

main().catch((e) => {
  console.error(`screenshot: ${e.message}`);
  process.exit(1);
});
