// The screenshots of docs/tune.md: the turntable teapot in the tuning page, its body highlight
// picked, then dragged with the seams and matte shown.
//
//   node tests/browser/screenshots.mjs

import { copyFileSync, mkdirSync, rmSync } from "node:fs";
import { join } from "node:path";
import { copyShot, launchBrowser, root, startTune, until } from "./common.mjs";

const { folder, shot } = copyShot("teapot_turntable.ron", ["teapot.bpt", "teapot.parts.ron"]);
mkdirSync(join(folder, "shots", "looks"));
copyFileSync(join(root, "shots/looks/studio.ron"), join(folder, "shots/looks/studio.ron"));
const tune = await startTune(shot, ["--size", "640x360"]);
const browser = await launchBrowser();
const out = join(root, "docs", "tune");
mkdirSync(out, { recursive: true });

/** Waits for the final frame after the last change. */
async function settled(page) {
  await new Promise((r) => setTimeout(r, 300));
  await until(page, () => window.glintTune.last && window.glintTune.last.quality === "final", undefined, "the final frame");
}

try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 760 } });
  await page.goto(tune.url);
  await until(page, () => window.glintTune.paints >= 1, undefined, "the first frame");
  await settled(page);
  const box = await page.locator("#view").boundingBox();
  const at = (x, y) => ({ x: box.x + (x + 0.5) * box.width / 640, y: box.y + (y + 0.5) * box.height / 360 });
  // Pick the body.
  let p = at(300, 215);
  await page.mouse.click(p.x, p.y);
  await until(page, () => document.getElementById("selection").textContent.includes("teapot/"), undefined, "the pick");
  await page.screenshot({ path: join(out, "page.png") });
  // Drag its pinned highlight up and to the left, with seams and matte on.
  await page.locator("#overlay-seams").check();
  await page.locator("#overlay-matte").check();
  await page.mouse.move(p.x, p.y);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) {
    p = at(300 - 4 * i, 215 - 3 * i);
    await page.mouse.move(p.x, p.y);
    await new Promise((r) => setTimeout(r, 40));
  }
  await page.mouse.up();
  await settled(page);
  await page.screenshot({ path: join(out, "dragged.png") });
  console.log(`screenshots written to ${out}`);
} finally {
  await browser.close();
  tune.child.kill();
  rmSync(folder, { recursive: true, force: true });
}
