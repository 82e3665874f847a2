// Drawing a highlight's outline in the tuning page, end to end in headless Chromium: on a copy
// of shots/sphere_ops.ron, draw mode is entered, a triangle's corners clicked on the sphere (one
// corner dragged into place, a stray one removed) and the outline finished with Enter; the shot
// file must then hold an Outline of three points, and the re-rendered matte of the highlight
// must have its corners within 2 px of the clicked pixels. A corner off the sphere is refused on
// the page and writes nothing. Screenshots go to target/page-tests/.

import { readFileSync, rmSync } from "node:fs";
import { join } from "node:path";
import { artefacts, check, copyShot, launchBrowser, readPng, runGlint, startTune, until } from "./common.mjs";

const SIZE = 240;
const { folder, shot } = copyShot("sphere_ops.ron", ["sphere.ron"]);
const original = readFileSync(shot, "utf8");
const tune = await startTune(shot, ["--size", `${SIZE}x${SIZE}`]);
const browser = await launchBrowser();
let failed = false;

/** The page position of image pixel (x, y)'s centre. */
async function pagePoint(page, x, y) {
  const box = await page.locator("#view").boundingBox();
  return { x: box.x + (x + 0.5) * box.width / SIZE, y: box.y + (y + 0.5) * box.height / SIZE };
}

async function clickPixel(page, [x, y], shift = false) {
  const p = await pagePoint(page, x, y);
  if (shift) await page.keyboard.down("Shift");
  await page.mouse.click(p.x, p.y);
  if (shift) await page.keyboard.up("Shift");
}

async function waitForFile(predicate, what) {
  for (let i = 0; i < 600; i++) {
    const text = readFileSync(shot, "utf8");
    if (predicate(text)) return text;
    await new Promise((r) => setTimeout(r, 50));
  }
  throw new Error(`timed out waiting for the shot file to ${what}`);
}

/**
 * How the matte of the shot's frame 1, rendered by glint, fits the triangle `corners`: for each
 * corner, the distance from it of the covered pixel (matte ≥ ½) farthest toward it from the
 * matte's centroid (a triangle's extreme toward a corner is the corner), and the matte's area
 * over the triangle's.
 */
function triangleFit(corners) {
  const out = join(folder, "check", "d.####.png");
  runGlint(["render", shot, "--frames", "1", "--size", `${SIZE}x${SIZE}`, "--aov", "matte", "--out", out]);
  const matte = readPng(join(folder, "check", "d.0001.matte.png"));
  const covered = [];
  let [sum, sx, sy] = [0, 0, 0];
  for (let y = 0; y < matte.height; y++) {
    for (let x = 0; x < matte.width; x++) {
      const m = matte.data[(y * matte.width + x) * matte.channels] / 255;
      sum += m; sx += m * x; sy += m * y;
      if (m >= 0.5) covered.push([x, y]);
    }
  }
  check(covered.length > 20, `the rendered highlight covers only ${covered.length} pixels`);
  const [cx, cy] = [sx / sum, sy / sum];
  const misses = corners.map(([x, y]) => {
    let best = null;
    let most = -Infinity;
    for (const p of covered) {
      const along = (p[0] - cx) * (x - cx) + (p[1] - cy) * (y - cy);
      if (along > most) { most = along; best = p; }
    }
    return Math.hypot(best[0] - x, best[1] - y);
  });
  const [a, b, c] = corners;
  const triangle = Math.abs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) / 2;
  return { misses, ratio: sum / triangle };
}

try {
  const page = await browser.newPage({ viewport: { width: 1200, height: 720 } });
  page.on("pageerror", (e) => { throw e; });
  await page.goto(tune.url);
  await until(page, () => window.glintTune.paints >= 1, undefined, "the first frame");

  // Draw mode, by its button; the key D toggles it too.
  await page.locator("#draw").click();
  await until(page, () => window.glintTune.drawing.on, undefined, "draw mode");

  // The corners of a triangle around the highlight at frame 1; the third is clicked off its
  // place and dragged there, and a stray fourth is removed with Shift+click.
  const corners = [[135, 75], [157, 114], [113, 114]];
  await clickPixel(page, corners[0]);
  await clickPixel(page, corners[1]);
  await clickPixel(page, [120, 108]);
  const from = await pagePoint(page, 120, 108);
  const to = await pagePoint(page, corners[2][0], corners[2][1]);
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  await page.mouse.move((from.x + to.x) / 2, (from.y + to.y) / 2);
  await page.mouse.move(to.x, to.y);
  await page.mouse.up();
  await clickPixel(page, [100, 90]);
  check((await page.evaluate(() => window.glintTune.drawing.points.length)) === 4, "the stray corner was not added");
  await clickPixel(page, [100, 90], true);
  const drawn = await page.evaluate(() => window.glintTune.drawing.points.map((p) => [p.x, p.y]));
  check(drawn.length === 3, `the overlay holds ${drawn.length} corners, not 3`);
  drawn.forEach((p, i) => check(Math.hypot(p[0] - corners[i][0], p[1] - corners[i][1]) < 0.01,
    `corner ${i} is at (${p}), not (${corners[i]})`));
  await page.screenshot({ path: join(artefacts, "11-drawing.png") });

  // Finished with Enter: the file holds the outline of three corners.
  const paints = await page.evaluate(() => window.glintTune.paints);
  await page.keyboard.press("Enter");
  const written = await waitForFile((t) => t !== original, "change when the outline is finished");
  const outline = written.match(/shape: Outline\(\[(.*)\]\)/);
  check(outline, `no Outline in the file:\n${written}`);
  const points = [...outline[1].matchAll(/\((-?[0-9.]+), (-?[0-9.]+)\)/g)];
  check(points.length === 3, `the written outline has ${points.length} points: ${outline[0]}`);
  check(written.replace(/\n\s*shape: Outline\(\[.*\]\),/, "") === original, "drawing changed more than the layer's shape");
  await until(page, (n) => window.glintTune.paints > n, paints, "the frame drawn again");
  await until(page, () => !document.getElementById("status").textContent, undefined, "no error shown");
  await until(page, () => (document.getElementById("shape") || {}).textContent?.startsWith("shape: outline"), undefined, "the panel to show the outline");
  await page.screenshot({ path: join(artefacts, "12-drawn.png") });

  // The re-rendered matte has its corners where they were clicked.
  const { misses, ratio } = triangleFit(corners);
  console.log(`matte corners ${misses.map((m) => m.toFixed(2)).join(", ")} px from the clicked ones; area ${ratio.toFixed(3)} of the triangle`);
  misses.forEach((m, i) => check(m <= 2, `the matte's corner ${i} is ${m.toFixed(2)} px from the clicked pixel`));
  check(Math.abs(ratio - 1) < 0.1, `the matte's area is ${ratio.toFixed(3)} of the triangle's`);

  // A corner off the sphere: refused on the page, nothing written.
  await clickPixel(page, [4, 4]);
  await page.keyboard.press("Enter");
  // The error line shows the refusal until it is dismissed.
  await until(page, () => /shows no patch/.test(window.glintTune.lastError), undefined, "the refusal on the page");
  await new Promise((r) => setTimeout(r, 300));
  const shown = await page.evaluate(() => document.getElementById("status").textContent);
  check(/shows no patch/.test(shown), `the refusal left the page: "${shown}"`);
  check(readFileSync(shot, "utf8") === written, "a refused outline changed the file");
  await page.screenshot({ path: join(artefacts, "13-refused.png") });
  console.log("page test passed: an outline drawn, edited, written and rendered; a bad corner refused");
} catch (error) {
  failed = true;
  console.error("page test failed: " + error.message);
  console.error(tune.stderr());
} finally {
  await browser.close();
  tune.child.kill();
  rmSync(folder, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
