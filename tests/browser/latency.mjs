// The tuning page's latency: from a slider change to the new frame decoded and on the canvas,
// teapot at 640×360, preview — with the pixels sent raw and as PNG, in alternating blocks on
// one server so both see the same machine. Prints the median and 95th percentile of each, and
// the medians of its parts: the render, the PNG encoding, the rest of the server's work
// (reading and checking the changed shot), the transfer, the decoding and the painting. Then a
// drag streamed as a hand makes one, a change every 16.7 ms (60 Hz) for 4 s whatever the page
// shows: the latency of each frame painted from the change it shows, and how many changes were
// dropped for newer ones rather than queued. Then playback of the whole shot: once round to
// render and keep its frames, then the frames per second shown the second time round, against
// the shot's fps. Everything goes to target/page-tests/latency.json as well.
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
        renders.push(last);
      }
    }
  }
  const report = {};
  console.log(`slider change → frame on the canvas, teapot 640×360 preview, ${blocks} blocks × ${perBlock} changes per format`);
  const PARTS = ["render", "encode", "server_other", "transfer", "decode", "paint"];
  console.log(`format   median ms   p95 ms   ${PARTS.map((p) => p.padStart(12)).join(" ")}   (medians, ms)`);
  const partsOf = (records) => Object.fromEntries(PARTS.map((p) => [p, percentile(records.map((r) => r.parts[p]), 0.5)]));
  for (const format of ["raw", "png"]) {
    const { latencies, renders } = pages[format];
    report[format] = {
      median_ms: percentile(latencies, 0.5),
      p95_ms: percentile(latencies, 0.95),
      parts_median_ms: partsOf(renders),
      samples: latencies.length,
    };
    const r = report[format];
    const parts = PARTS.map((p) => r.parts_median_ms[p].toFixed(1).padStart(12)).join(" ");
    console.log(`${format.padEnd(8)} ${r.median_ms.toFixed(1).padStart(9)} ${r.p95_ms.toFixed(1).padStart(8)}   ${parts}`);
  }
  console.log(`png / raw median: ${(report.png.median_ms / report.raw.median_ms).toFixed(2)}`);

  // A drag streamed at 60 Hz on the PNG page: changes sent whatever is shown.
  {
    const { page } = pages.png;
    await new Promise((r) => setTimeout(r, 1500));
    const start = await page.evaluate(() => window.glintTune.records.length);
    const sent = await page.evaluate(async (selector) => {
      const slider = document.querySelector(selector);
      let count = 0;
      await new Promise((done) => {
        const timer = setInterval(() => {
          slider.value = String(0.3 + 0.4 * (0.5 + 0.5 * Math.sin(count / 20)));
          slider.dispatchEvent(new Event("input", { bubbles: true }));
          count += 1;
          if (count >= 240) { clearInterval(timer); done(); }
        }, 1000 / 60);
      });
      return count;
    }, SLIDER);
    await new Promise((r) => setTimeout(r, 1000));
    const records = (await page.evaluate(() => window.glintTune.records)).slice(start);
    const totals = records.map((r) => r.totalMs);
    report.stream = {
      changes: sent,
      frames: records.length,
      dropped: sent - records.length,
      median_ms: percentile(totals, 0.5),
      p95_ms: percentile(totals, 0.95),
      parts_median_ms: partsOf(records),
    };
    const r = report.stream;
    console.log(`a drag streamed at 60 Hz for 4 s: ${r.changes} changes, ${r.frames} frames painted, ${r.dropped} dropped for newer ones; change → frame median ${r.median_ms.toFixed(1)} ms, p95 ${r.p95_ms.toFixed(1)} ms`);
    console.log(`  medians of its parts, ms: ${PARTS.map((p) => `${p} ${r.parts_median_ms[p].toFixed(1)}`).join(", ")}`);
    const tail = records.filter((x) => x.totalMs >= r.p95_ms);
    console.log(`  the slowest 5 %: ${tail.map((x) => `${x.totalMs.toFixed(0)} (waited ${x.parts.waited.toFixed(0)}, server ${(x.parts.render + x.parts.encode + x.parts.server_other).toFixed(0)}, transfer ${x.parts.transfer.toFixed(0)}, decode ${x.parts.decode.toFixed(0)})`).join("; ")}`);
  }
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
