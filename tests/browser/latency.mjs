// The tuning page's latency: from a slider change to the new frame decoded and on the canvas,
// teapot at 640×360, preview — with the pixels sent raw and as PNG, in alternating blocks on
// one server so both see the same machine. Prints the median and 95th percentile of each and
// writes them to target/page-tests/latency.json. Then playback of the whole shot: once round to
// render and keep its frames, then the frames per second shown the second time round, against
// the shot's fps.
//
//   node tests/browser/latency.mjs [CHANGES_PER_BLOCK] [BLOCKS]

import { mkdirSync, copyFileSync, rmSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { artefacts, copyShot, launchBrowser, root, startTune, until } from "./common.mjs";

const perBlock = Number(process.argv[2] || 25);
const blocks = Number(process.argv[3] || 4);
const { folder, shot } = copyShot("teapot_turntable.ron", ["teapot.bpt", "teapot.parts.ron"]);
mkdirSync(join(folder, "shots", "looks"));
copyFileSync(join(root, "shots/looks/studio.ron"), join(folder, "shots/looks/studio.ron"));
const tune = await startTune(shot, ["--size", "640x360"]);
const browser = await launchBrowser();
const SLIDER = 'input[type=range][data-path="highlights[1].layers[0].stack[0].delta"]';

function percentile(values, p) {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.min(sorted.length - 1, Math.floor(p * (sorted.length - 1) + 0.5))];
}

try {
  const pages = {};
  for (const format of ["raw", "png"]) {
    const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    await page.goto(tune.url + "&format=" + format);
    await until(page, () => window.glintTune.paints >= 1, undefined, "the first frame");
    await page.locator("#highlight-choice").selectOption("1");
    await page.locator(SLIDER).waitFor();
    pages[format] = { page, latencies: [], renders: [] };
  }
  let value = 0.3;
  for (let block = 0; block < blocks; block++) {
    for (const format of ["raw", "png"]) {
      const { page, latencies, renders } = pages[format];
      // Let a final frame asked for by either page finish before measuring.
      await new Promise((r) => setTimeout(r, 1500));
      for (let i = 0; i < perBlock; i++) {
        value = value > 0.5 ? 0.3 + (i % 7) * 0.01 : 0.7 - (i % 7) * 0.01;
        const before = await page.evaluate(() => window.glintTune.paints);
        await page.locator(SLIDER).evaluate((el, v) => {
          el.value = String(v);
          el.dispatchEvent(new Event("input", { bubbles: true }));
        }, value);
        await until(page, (n) => window.glintTune.paints > n && window.glintTune.last.quality === "preview", before, "the changed frame");
        const last = await page.evaluate(() => window.glintTune.last);
        latencies.push(last.totalMs);
        renders.push(last.renderMs);
      }
    }
  }
  const report = {};
  console.log(`slider change → frame on the canvas, teapot 640×360 preview, ${blocks} blocks × ${perBlock} changes per format`);
  console.log("format   median ms   p95 ms   render median ms");
  for (const format of ["raw", "png"]) {
    const { latencies, renders } = pages[format];
    report[format] = {
      median_ms: percentile(latencies, 0.5),
      p95_ms: percentile(latencies, 0.95),
      render_median_ms: percentile(renders, 0.5),
      samples: latencies.length,
    };
    const r = report[format];
    console.log(`${format.padEnd(8)} ${r.median_ms.toFixed(1).padStart(9)} ${r.p95_ms.toFixed(1).padStart(8)} ${r.render_median_ms.toFixed(1).padStart(12)}`);
  }
  console.log(`png / raw median: ${(report.png.median_ms / report.raw.median_ms).toFixed(2)}`);
  const { page } = pages.png;
  await new Promise((r) => setTimeout(r, 1500));
  const [frames, fps] = await page.evaluate(() => [page.state.frames[1] - page.state.frames[0] + 1, page.state.fps]);
  await page.locator("#play").click();
  await page.waitForFunction((n) => window.glintTune.played.length >= n, 2 * frames, { timeout: 120000 });
  await page.locator("#play").click();
  const played = await page.evaluate(() => window.glintTune.played);
  const second = played.slice(frames, 2 * frames);
  const shown = (second.length - 1) * 1000 / (second[second.length - 1][1] - second[0][1]);
  const first = (frames - 1) * 1000 / (played[frames - 1][1] - played[0][1]);
  report.playback = { frames, fps, first_loop_fps: first, kept_fps: shown };
  console.log(`playback of ${frames} frames at ${fps} fps: ${first.toFixed(1)} frames a second while rendering ahead, ${shown.toFixed(1)} once kept`);
  mkdirSync(artefacts, { recursive: true });
  writeFileSync(join(artefacts, "latency.json"), JSON.stringify(report, null, 2));
} finally {
  await browser.close();
  tune.child.kill();
  rmSync(folder, { recursive: true, force: true });
}
