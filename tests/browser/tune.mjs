// The tuning page end to end in headless Chromium: a copy of shots/sphere_ops.ron is opened
// with `glint tune`, the highlight dragged on the sphere and released, a slider moved, the
// timeline scrubbed, a change undone and the file edited from outside — each checked in the
// shot file on disk and on the page; then draw.mjs, drawing an outline, and shade.mjs, dragging
// a shadow's edge, each run in a process of its own. Screenshots go to target/page-tests/.

import { execFileSync } from "node:child_process";
import { readFileSync, rmSync, writeFileSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import { artefacts, check, copyShot, launchBrowser, readPng, runGlint, startTune, until } from "./common.mjs";

const SIZE = 240;
const { folder, shot } = copyShot("sphere_ops.ron", ["sphere.ron"]);
const original = readFileSync(shot, "utf8");
const tune = await startTune(shot, ["--size", `${SIZE}x${SIZE}`]);
const browser = await launchBrowser();
let failed = false;

const canvasHash = (page) => page.evaluate(() => {
  const c = document.getElementById("view");
  const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
  let h = 0;
  for (let i = 0; i < d.length; i++) h = (Math.imul(h, 31) + d[i]) >>> 0;
  return h;
});

/** The page position of image pixel (x, y)'s centre. */
async function pagePoint(page, x, y) {
  const box = await page.locator("#view").boundingBox();
  return { x: box.x + (x + 0.5) * box.width / SIZE, y: box.y + (y + 0.5) * box.height / SIZE };
}

async function waitForFile(predicate, what) {
  for (let i = 0; i < 300; i++) {
    const text = readFileSync(shot, "utf8");
    if (predicate(text)) return text;
    await new Promise((r) => setTimeout(r, 50));
  }
  throw new Error(`timed out waiting for the shot file to ${what}`);
}

async function settle(page, paints) {
  await until(page, (n) => window.glintTune.paints > n, paints, "a new frame on the page");
}

try {
  const page = await browser.newPage({ viewport: { width: 1200, height: 720 } });
  page.on("pageerror", (e) => { throw e; });
  await page.goto(tune.url);
  await until(page, () => window.glintTune.paints >= 1, undefined, "the first frame");
  await page.screenshot({ path: join(artefacts, "01-open.png") });

  // The selected layer's centres are crossed on the frame: one on the sphere, and no note.
  await until(page, () => Array.isArray(window.glintTune.centres), undefined, "the layer's centres");
  const centres = await page.evaluate(() => window.glintTune.centres);
  check(centres.length === 1 && centres[0][2] === 1, `the sphere's layer has centres ${JSON.stringify(centres)}, not one in view`);
  check(await page.locator("#centres-note").textContent() === "", "a note of centres for a layer with one");

  // A request without the token is refused, and the page's own requests carry it.
  const refused = await page.evaluate(() => fetch("/api/state").then((r) => r.status));
  check(refused === 401, `a request without the token answered ${refused}, not 401`);

  // Drag the highlight from the sphere's centre to the drop point and release.
  const drop = { x: 150, y: 100 };
  let paints = await page.evaluate(() => window.glintTune.paints);
  const alphaField = 'input[data-number="highlights[0].layers[0].stack[0].alpha"]';
  const alphaBefore = await page.locator(alphaField).inputValue();
  const start = await pagePoint(page, 120, 120);
  await page.mouse.move(start.x, start.y);
  await page.mouse.down();
  for (let i = 1; i <= 8; i++) {
    const p = await pagePoint(page, 120 + (drop.x - 120) * i / 8, 120 + (drop.y - 120) * i / 8);
    await page.mouse.move(p.x, p.y);
    await new Promise((r) => setTimeout(r, 30));
  }
  // The α field follows the drag before it is released.
  await until(page, ([field, was]) => document.querySelector(field).value !== was,
    [alphaField, alphaBefore], "the α field to follow the drag");
  await page.mouse.up();
  const dragged = await waitForFile((t) => t !== original, "change after the drop");
  await settle(page, paints);
  await page.screenshot({ path: join(artefacts, "02-dragged.png") });

  // The file holds keys of the translation at frame 1 ...
  const listed = runGlint(["key", shot, "--list"]);
  const alpha = listed.split("\n").find((l) => l.startsWith("highlights[0].layers[0].stack[0].alpha"));
  const beta = listed.split("\n").find((l) => l.startsWith("highlights[0].layers[0].stack[0].beta"));
  check(alpha && /\(1, -?[0-9.e-]+\)/.test(alpha), `no key of alpha at frame 1: ${alpha}`);
  check(beta && /\(1, -?[0-9.e-]+\)/.test(beta), `no key of beta at frame 1: ${beta}`);
  // ... whose render puts the highlight's matte centroid on the drop point.
  const out = join(folder, "check", "c.####.png");
  runGlint(["render", shot, "--frames", "1", "--size", `${SIZE}x${SIZE}`, "--aov", "matte", "--out", out]);
  const matte = readPng(join(folder, "check", "c.0001.matte.png"));
  let [sum, sx, sy] = [0, 0, 0];
  for (let y = 0; y < matte.height; y++) {
    for (let x = 0; x < matte.width; x++) {
      const m = matte.data[(y * matte.width + x) * matte.channels] / 255;
      sum += m; sx += m * x; sy += m * y;
    }
  }
  check(sum > 20, `the rendered highlight covers only ${sum} pixels`);
  const centroid = { x: sx / sum, y: sy / sum };
  const miss = Math.hypot(centroid.x - drop.x, centroid.y - drop.y);
  console.log(`drop at (${drop.x}, ${drop.y}); matte centroid (${centroid.x.toFixed(2)}, ${centroid.y.toFixed(2)}), ${miss.toFixed(2)} px away`);
  check(miss <= 2, `the matte centroid is ${miss.toFixed(2)} px from the drop point`);

  // Move the ε slider: the file and the image change. The slider is logarithmic over ε's legal
  // range from 10⁻⁴: its position is log10 ε.
  const before = await canvasHash(page);
  paints = await page.evaluate(() => window.glintTune.paints);
  const epsilon = page.locator('input[type=range][data-path="highlights[0].layers[0].epsilon"]');
  const scale = await epsilon.evaluate((el) => [el.dataset.scale, Number(el.min), Number(el.max)]);
  check(scale[0] === "log" && Math.abs(scale[1] + 4) < 1e-9 && Math.abs(scale[2] - Math.log10(2)) < 1e-6,
    `the ε slider is ${scale[0]} over [${scale[1]}, ${scale[2]}], not log10 over [-4, log10 2]`);
  const slide = (el, position) => {
    el.value = String(position);
    el.dispatchEvent(new Event("input", { bubbles: true }));
    el.dispatchEvent(new Event("change", { bubbles: true }));
  };
  await epsilon.evaluate(slide, Math.log10(0.06));
  const widened = await waitForFile((t) => /epsilon: 0\.06\b/.test(t), "hold epsilon: 0.06");
  await settle(page, paints);
  await until(page, () => !document.getElementById("status").textContent, undefined, "no error shown");
  const after = await canvasHash(page);
  check(after !== before, "the image did not change when epsilon moved");
  check(widened.replace("epsilon: 0.06", "epsilon: 0.025") === dragged, "the slider changed more than epsilon");
  await page.screenshot({ path: join(artefacts, "03-slider.png") });
  // ε of a small glint is within the slider's reach, as a short decimal.
  await epsilon.evaluate(slide, Math.log10(0.0004));
  await waitForFile((t) => /epsilon: 0\.0004\b/.test(t), "hold epsilon: 0.0004");
  await epsilon.evaluate(slide, Math.log10(0.06));
  await waitForFile((t) => t === widened, "hold epsilon: 0.06 again");

  // A refused value: its message stays on the page over later frames until dismissed.
  const epsilonField = page.locator('input[data-number="highlights[0].layers[0].epsilon"]');
  await epsilonField.fill("-1");
  await epsilonField.dispatchEvent("change");
  await until(page, () => /epsilon/.test(document.getElementById("status").textContent), undefined, "the refusal on the page");
  check(readFileSync(shot, "utf8") === widened, "a refused ε changed the file");
  paints = await page.evaluate(() => window.glintTune.paints);
  await page.evaluate(() => { document.getElementById("overlay-seams").click(); });
  await settle(page, paints);
  await new Promise((r) => setTimeout(r, 300));
  const kept = await page.evaluate(() => document.getElementById("status").textContent);
  check(/epsilon/.test(kept), `the refusal was cleared by a new frame: "${kept}"`);
  await page.locator("#dismiss").click();
  await until(page, () => !document.getElementById("status").textContent, undefined, "the dismissed refusal to go");
  await page.evaluate(() => { document.getElementById("overlay-seams").click(); });

  // Scrub the timeline to frame 12: a new image, and the selected parameter's keys marked.
  // Frames are compared at final quality, each once the page has painted it: a preview and the
  // final frame that follows it arrive in turn, whatever the build's speed.
  const finalOf = async (frame) => {
    await until(page, (f) => {
      const last = window.glintTune.last;
      return last && last.frame === f && last.quality === "final";
    }, frame, `the final frame ${frame}`);
    return canvasHash(page);
  };
  const finalOne = await finalOf(1);
  await page.locator('input[type=range][data-path="highlights[0].layers[0].stack[0].alpha"]').focus();
  const keys = await page.locator("#keys span").count();
  check(keys === 3, `the timeline marks ${keys} keys of alpha, not 3`);
  paints = await page.evaluate(() => window.glintTune.paints);
  await page.locator("#frame").evaluate((el) => {
    el.value = "12";
    el.dispatchEvent(new Event("input", { bubbles: true }));
  });
  await settle(page, paints);
  await until(page, () => document.getElementById("frame-number").value === "12", undefined, "frame 12");
  check((await finalOf(12)) !== finalOne, "frame 12 looks like frame 1");
  await page.locator("#next-key").click();
  await until(page, () => document.getElementById("frame-number").value === "24", undefined, "the next key, 24");
  await page.screenshot({ path: join(artefacts, "04-timeline.png") });

  // Undo the slider's three moves, one by one: the file is as it was after the drag.
  await page.locator("#undo").click();
  await waitForFile((t) => /epsilon: 0\.0004\b/.test(t), "hold epsilon: 0.0004 again");
  await page.locator("#undo").click();
  await waitForFile((t) => t === widened, "hold epsilon: 0.06 again");
  await page.locator("#undo").click();
  await waitForFile((t) => t === dragged, "be as it was after the drag");

  // An edit saved from a text editor reaches the page.
  writeFileSync(shot, dragged.replace("epsilon: 0.025", "epsilon: 0.03"));
  await until(page, () => {
    const field = document.querySelector('input[data-number="highlights[0].layers[0].epsilon"]');
    return field && field.value === "0.03";
  }, undefined, "the page to show the file's new epsilon");
  // The history the page had is gone, and the page says why.
  await until(page, () => {
    const undo = document.getElementById("undo");
    return undo.disabled && /changed outside tune/.test(undo.title)
      && document.getElementById("history-note").textContent === "history cleared";
  }, undefined, "undo greyed out with the reason");

  // Overlays.
  await page.locator("#overlay-seams").check();
  await page.locator("#overlay-matte").check();
  paints = await page.evaluate(() => window.glintTune.paints);
  await settle(page, paints);
  await page.screenshot({ path: join(artefacts, "05-overlays.png") });

  // Play: frames shown in order, each rendered once ahead of the playhead and kept, so that the
  // second time round the loop shows what was kept and renders nothing.
  const last = await page.evaluate(() => window.glintTune.played.length === 0 && page.state.frames[1]);
  check(last === 120, `the shot's last frame is ${last}, not 120, or playback already ran`);
  await page.locator("#play").click();
  await until(page, (n) => window.glintTune.played.length >= n, last + 40, "playback past one loop");
  await page.locator("#play").click();
  const played = await page.evaluate(() => window.glintTune.played.map(([f]) => f));
  const renders = await page.evaluate(() => window.glintTune.playbackRenders);
  played.slice(1).forEach((f, i) => {
    const expected = played[i] >= last ? 1 : played[i] + 1;
    check(f === expected, `playback showed frame ${f} after ${played[i]}, not ${expected}`);
  });
  console.log(`playback showed ${played.length} frames and rendered ${renders}`);
  check(renders <= last, `playback rendered ${renders} frames for ${played.length} shown: the loop was not kept`);

  // A mask drawn as a rectangle: its bounds are the (u, v) under the drag's two corners, each
  // of which glint probe puts back on its pixel; removed, the file is as it was.
  const unmasked = readFileSync(shot, "utf8");
  check(!/mask: \(/.test(unmasked), "the layer had a mask before");
  await page.locator("#mask-mode").click();
  const corners = [[100, 96], [142, 131]];
  const [c0, c1] = [await pagePoint(page, ...corners[0]), await pagePoint(page, ...corners[1])];
  await page.mouse.move(c0.x, c0.y);
  await page.mouse.down();
  await page.mouse.move((c0.x + c1.x) / 2, (c0.y + c1.y) / 2);
  await page.mouse.move(c1.x, c1.y);
  await page.mouse.up();
  const masked = await waitForFile((t) => /mask: \(/.test(t), "hold a mask");
  const mask = masked.match(/mask: \(u: \(([0-9.e-]+), ([0-9.e-]+)\), v: \(([0-9.e-]+), ([0-9.e-]+)\)/);
  check(mask, `no mask of u and v bounds in the file:\n${masked}`);
  const [u0, u1, v0, v1] = mask.slice(1, 5).map(Number);
  check(u0 < u1 && v0 < v1, `the mask's bounds are u (${u0}, ${u1}), v (${v0}, ${v1})`);
  for (const [x, y] of corners) {
    const near = [[u0, v0], [u0, v1], [u1, v0], [u1, v1]].some(([u, v]) => {
      const probed = JSON.parse(runGlint(["probe", shot, "--patch", "ball/sphere", "--uv", `${u},${v}`,
        "--frame", "1", "--size", `${SIZE}x${SIZE}`]));
      const p = probed[0].image.pixel;
      return Math.hypot(p[0] - x, p[1] - y) <= 1;
    });
    check(near, `no corner of the mask lands on pixel (${x}, ${y})`);
  }
  await page.locator("#mask-mode").click();
  await until(page, () => document.getElementById("remove-mask"), undefined, "the mask in the panel");
  await page.locator("#remove-mask").click();
  await waitForFile((t) => t === unmasked, "be as it was before the mask");

  // Pinned from the page: a click picks the point, "pin here" writes the pin, and the page
  // shows the placing translation as solved by the pin, not as values to set.
  await page.locator("#overlay-seams").uncheck();
  await page.locator("#overlay-matte").uncheck();
  const centre = await pagePoint(page, 120, 120);
  await page.mouse.click(centre.x, centre.y);
  await until(page, () => !document.getElementById("pin-here").disabled, undefined, "pin here to be offered");
  const unpinned = readFileSync(shot, "utf8");
  check(!/pin:/.test(unpinned), "the layer was pinned before the button");
  await page.locator("#pin-here").click();
  const pinned = await waitForFile((t) => /pin: \(/.test(t), "hold a pin");
  const pin = pinned.match(/pin: \(patch: "([^"]+)", u: ([0-9.e-]+), v: ([0-9.e-]+)/);
  check(pin, `no pin of a patch and (u, v) in the file:\n${pinned}`);
  // The pin is the point under the clicked pixel: glint probe puts it back on that pixel.
  const probe = JSON.parse(runGlint(["probe", shot, "--patch", pin[1], "--uv", `${pin[2]},${pin[3]}`,
    "--frame", "1", "--size", `${SIZE}x${SIZE}`]));
  const at = (probe.points || probe)[0].image.pixel;
  check(Math.hypot(at[0] - 120, at[1] - 120) <= 1, `the pin lands on pixel (${at}), not (120, 120)`);
  const alphaSlider = 'input[type=range][data-path="highlights[0].layers[0].stack[0].alpha"]';
  await until(page, (sel) => {
    const slider = document.querySelector(sel);
    return slider && slider.disabled && /pin/.test(slider.title);
  }, alphaSlider, "α to show as solved by the pin");
  const betaDisabled = await page.locator('input[data-number="highlights[0].layers[0].stack[0].beta"]').isDisabled();
  check(betaDisabled, "β's field can still be edited on a pinned layer");
  // The pinned layer holds the shape of the frame shown, and lets it go again.
  const holdFrame = await page.locator("#frame-number").inputValue();
  await page.locator("#hold").click();
  await waitForFile((t) => new RegExp(`pin: \\([^)]*, hold: ${holdFrame}\\)`).test(t), `hold the shape of frame ${holdFrame}`);
  await until(page, () => /let go/.test(document.getElementById("hold").textContent), undefined, "the hold to show");
  await page.locator("#hold").click();
  await waitForFile((t) => t === pinned, "be pinned without a hold");
  // Unpinned: the file is as it was, and α and β can be set again.
  await page.locator("#unpin").click();
  await waitForFile((t) => t === unpinned, "be as it was before the pin");
  await until(page, (sel) => !document.querySelector(sel).disabled, alphaSlider, "α to be editable again");
  console.log("page test passed: the layer's centre, drag, slider, a refused value, timeline, undo, an outside edit and why undo went, a mask drawn, pin, hold and unpin");
} catch (error) {
  failed = true;
  console.error("page test failed: " + error.message);
  console.error(tune.stderr());
} finally {
  await browser.close();
  tune.child.kill();
  rmSync(folder, { recursive: true, force: true });
}
// Drawing an outline, and dragging a shadow's edge: each on a fresh copy of its shot and a
// server of its own.
for (const script of ["draw.mjs", "shade.mjs"]) {
  if (failed) break;
  try {
    execFileSync(process.execPath, [join(dirname(fileURLToPath(import.meta.url)), script)], { stdio: "inherit" });
  } catch (_) {
    failed = true;
  }
}
process.exit(failed ? 1 : 0);
