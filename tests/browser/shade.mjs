// Dragging a cel shadow's edge in the tuning page, end to end in headless Chromium: on a copy
// of shots/shade_design.ron, shade mode is entered with its key, the edge between the body's
// shadow and its lit band is grabbed and dropped 10 px into the lit band; the shot file must
// then hold the body entry's translation keyed at the frame (α changed, β keyed where it was a
// constant), and the frame rendered again by glint must have the band edge within 2 px of the
// drop point. Screenshots go to target/page-tests/.

import { copyFileSync, mkdirSync, mkdtempSync, readFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { artefacts, check, launchBrowser, readPng, root, runGlint, startTune, until } from "./common.mjs";

const [W, H] = [320, 180];
const folder = mkdtempSync(join(tmpdir(), "glint-page-"));
for (const sub of ["shots/looks", "patches"]) mkdirSync(join(folder, sub), { recursive: true });
for (const file of ["shots/shade_design.ron", "shots/looks/studio.ron", "patches/teapot.bpt", "patches/teapot.parts.ron"]) {
  copyFileSync(join(root, file), join(folder, file));
}
const shot = join(folder, "shots/shade_design.ron");
const original = readFileSync(shot, "utf8");
const tune = await startTune(shot, ["--size", `${W}x${H}`]);
const browser = await launchBrowser();
let failed = false;

// The glaze's colours in the shot (linear RGB): its shadow, and its first lit band.
const SHADOW = [0.12, 0.16, 0.34];
const LIT = [0.40, 0.55, 0.90];
const srgb = (c) => 255 * (c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055);

/** Frame 1 rendered by glint under the final preset: per pixel "shadow", "lit" or null. */
function bands(name) {
  const out = join(folder, "check", `${name}.####.png`);
  runGlint(["render", shot, "--frames", "1", "--size", `${W}x${H}`, "--preset", "final", "--out", out]);
  const image = readPng(join(folder, "check", `${name}.0001.png`));
  const [shadow, lit] = [SHADOW.map(srgb), LIT.map(srgb)];
  const classes = [];
  for (let i = 0; i < W * H; i++) {
    const p = [0, 1, 2].map((c) => image.data[i * image.channels + c]);
    const near = (q) => Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) < 6;
    classes.push(image.data[i * image.channels + 3] < 255 ? null : near(shadow) ? "shadow" : near(lit) ? "lit" : null);
  }
  return classes;
}

/** Whether every pixel within `r` of (x, y) is shadow or lit. */
function clean(classes, x, y, r) {
  for (let dy = -r; dy <= r; dy++) {
    for (let dx = -r; dx <= r; dx++) {
      const [px, py] = [x + dx, y + dy];
      if (px < 0 || py < 0 || px >= W || py >= H || classes[py * W + px] === null) return false;
    }
  }
  return true;
}

async function pagePoint(page, x, y) {
  const box = await page.locator("#view").boundingBox();
  return { x: box.x + (x + 0.5) * box.width / W, y: box.y + (y + 0.5) * box.height / H };
}

async function pick(page, x, y) {
  return page.evaluate(async ([x, y]) => {
    const token = new URLSearchParams(location.search).get("token");
    const response = await fetch("/api/pick", {
      method: "POST", headers: { "X-Glint-Token": token, "Content-Type": "application/json" },
      body: JSON.stringify({ frame: 1, x, y }),
    });
    return response.ok ? response.json() : null;
  }, [x, y]);
}

try {
  const page = await browser.newPage({ viewport: { width: 1200, height: 720 } });
  page.on("pageerror", (e) => { throw e; });
  await page.goto(tune.url);
  await until(page, () => window.glintTune.paints >= 1, undefined, "the first frame");

  // Where the body's shadow meets its lit band: a shadow pixel with the band a few pixels to
  // its side, and a pixel 10 px on, well inside the band, to drop the edge on.
  const before = bands("before");
  let grab = null;
  for (let y = 8; y < H - 8 && !grab; y++) {
    for (let x = 12; x < W - 12 && !grab; x++) {
      for (const side of [1, -1]) {
        const drop = [x + 10 * side, y];
        // The edge is drawn anti-aliased: the shadow's last pixel and the band's first are up
        // to 3 px apart.
        const litNear = [1, 2, 3].some((d) => before[y * W + x + d * side] === "lit");
        if (before[y * W + x] !== "shadow" || !litNear) continue;
        if (!clean(before, drop[0], drop[1], 3) || before[y * W + drop[0]] !== "lit") continue;
        const picked = await pick(page, x, y);
        const dropped = await pick(page, drop[0], drop[1]);
        if (picked && dropped && picked.parts.includes("teapot/body") && dropped.patch === picked.patch) {
          grab = { from: [x, y], to: drop };
          break;
        }
      }
    }
  }
  check(grab, "no edge between the body's shadow and its lit band found at frame 1");
  console.log(`grabbing the shadow's edge at (${grab.from}) and dropping it at (${grab.to})`);

  await page.keyboard.press("s");
  await until(page, () => document.getElementById("shade-mode").classList.contains("on"), undefined, "shade mode");
  await until(page, () => document.getElementById("shade-choice") !== null, undefined, "the shade panel");
  const from = await pagePoint(page, ...grab.from);
  const to = await pagePoint(page, ...grab.to);
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  await new Promise((r) => setTimeout(r, 200));
  for (let k = 1; k <= 5; k++) {
    await page.mouse.move(from.x + (to.x - from.x) * k / 5, from.y + (to.y - from.y) * k / 5);
    await new Promise((r) => setTimeout(r, 60));
  }
  await page.screenshot({ path: join(artefacts, "21-shade-dragging.png") });
  await page.mouse.up();

  let written = original;
  for (let i = 0; i < 600 && written === original; i++) {
    await new Promise((r) => setTimeout(r, 50));
    written = readFileSync(shot, "utf8");
  }
  check(written !== original, "the drag wrote nothing");
  // The body's shade entry: the first translation after the shot's `shade:` (the highlights
  // before it have their own).
  const shadeList = written.slice(written.indexOf("\n    shade: ["));
  const translate = shadeList.match(/Translate\(alpha: (\[[^\]]*\]|[-0-9.e]+), beta: (\[[^\]]*\]|[-0-9.e]+)\)/);
  check(translate, `no translation in the written shot:\n${written}`);
  const alphaKey = translate[1].match(/\(1, (-?[0-9.e-]+)\)/);
  const betaKey = translate[2].match(/\(1, (-?[0-9.e-]+)\)/);
  check(alphaKey && betaKey, `α and β are not keyed at frame 1: ${translate[0]}`);
  check(translate[1].includes("(48, 0.45)") && translate[1].includes("(96, 0.0)"), `α's other keys changed: ${translate[1]}`);
  check(Number(alphaKey[1]) !== 0 || Number(betaKey[1]) !== 0.1, `the translation did not move: ${translate[0]}`);
  await until(page, () => !document.getElementById("status").textContent, undefined, "no error shown");
  await page.screenshot({ path: join(artefacts, "22-shade-dropped.png") });

  // The frame rendered again: the band edge passes within 2 px of the drop point.
  const after = bands("after");
  const [dx, dy] = grab.to;
  let [shadow, lit] = [0, 0];
  for (let y = dy - 2; y <= dy + 2; y++) {
    for (let x = dx - 2; x <= dx + 2; x++) {
      if (Math.hypot(x - dx, y - dy) > 2) continue;
      shadow += after[y * W + x] === "shadow";
      lit += after[y * W + x] === "lit";
    }
  }
  check(shadow > 0 && lit > 0, `within 2 px of the drop point: ${shadow} shadow and ${lit} lit pixels`);
  check(before[dy * W + dx] === "lit", "the drop point was lit before");
  console.log(`page test passed: the shadow's edge dragged, α and β keyed at frame 1 (${translate[0]}), the edge rendered within 2 px of the drop point (${shadow} shadow, ${lit} lit pixels there)`);
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
