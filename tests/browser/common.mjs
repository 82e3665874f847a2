// What the page tests share: a copy of a shipped shot in a temporary folder, `glint tune`
// started on it, headless Chromium (Debian's, driven by playwright-core), and a PNG reader for
// the frames glint writes.

import { spawn, execFileSync } from "node:child_process";
import { mkdtempSync, mkdirSync, copyFileSync, readFileSync, existsSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { inflateSync } from "node:zlib";
import { chromium } from "playwright-core";

export const root = resolve(dirname(fileURLToPath(import.meta.url)), "../..");
// The release build, as .ci/run makes it; GLINT_BINARY names another (a debug build, say).
export const glint = process.env.GLINT_BINARY || join(root, "target/release/glint");
export const artefacts = join(root, "target/page-tests");

// The flags this machine's Chromium needs to start headless without reaching out.
const CHROMIUM_FLAGS = [
  "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
  "--disable-background-networking", "--disable-component-update", "--disable-sync",
];

export function check(condition, message) {
  if (!condition) throw new Error(message);
}

/** A temporary folder holding `shots/NAME` and the files it names under `patches/`. */
export function copyShot(name, patches) {
  check(existsSync(glint), `${glint} is missing: run cargo build --release first`);
  const folder = mkdtempSync(join(tmpdir(), "glint-page-"));
  mkdirSync(join(folder, "shots"));
  mkdirSync(join(folder, "patches"));
  copyFileSync(join(root, "shots", name), join(folder, "shots", name));
  for (const p of patches) copyFileSync(join(root, "patches", p), join(folder, "patches", p));
  return { folder, shot: join(folder, "shots", name) };
}

/** `glint tune SHOT ARGS…` started; resolves with the URL it prints and the process. */
export function startTune(shot, args = []) {
  return new Promise((resolvePromise, reject) => {
    const child = spawn(glint, ["tune", shot, "--no-open", ...args], { stdio: ["ignore", "pipe", "pipe"] });
    let out = "";
    let err = "";
    const timer = setTimeout(() => reject(new Error("glint tune printed no address in 60 s: " + err)), 60000);
    child.stdout.on("data", (d) => {
      out += d;
      const m = out.match(/glint tune: (http:\/\/\S+)/);
      if (m) { clearTimeout(timer); resolvePromise({ url: m[1], child, stderr: () => err }); }
    });
    child.stderr.on("data", (d) => { err += d; });
    child.on("exit", (code) => { clearTimeout(timer); reject(new Error(`glint tune exited ${code}: ${err}`)); });
  });
}

export async function launchBrowser() {
  mkdirSync(artefacts, { recursive: true });
  // playwright starts the browser with a new empty user-data folder of its own.
  return chromium.launch({ executablePath: "/usr/bin/chromium", args: CHROMIUM_FLAGS, headless: true });
}

/** Runs glint with `args`; its standard output. */
export function runGlint(args) {
  return execFileSync(glint, args, { encoding: "utf8" });
}

/** A PNG file's pixels: `{width, height, channels, data}` (8-bit, non-interlaced). */
export function readPng(path) {
  const bytes = readFileSync(path);
  check(bytes.subarray(1, 4).toString() === "PNG", `${path} is not a PNG`);
  let at = 8;
  let width = 0, height = 0, depth = 0, type = 0;
  const idat = [];
  while (at < bytes.length) {
    const length = bytes.readUInt32BE(at);
    const kind = bytes.subarray(at + 4, at + 8).toString();
    const body = bytes.subarray(at + 8, at + 8 + length);
    if (kind === "IHDR") {
      width = body.readUInt32BE(0);
      height = body.readUInt32BE(4);
      depth = body[8];
      type = body[9];
      check(body[12] === 0, "interlaced PNGs are not read here");
    } else if (kind === "IDAT") {
      idat.push(body);
    }
    at += 12 + length;
  }
  check(depth === 8, `${path}: only 8-bit PNGs are read here`);
  const channels = { 0: 1, 2: 3, 4: 2, 6: 4 }[type];
  const raw = inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  const data = new Uint8Array(height * stride);
  for (let y = 0; y < height; y++) {
    const filter = raw[y * (stride + 1)];
    const line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let x = 0; x < stride; x++) {
      const a = x >= channels ? data[y * stride + x - channels] : 0;
      const b = y > 0 ? data[(y - 1) * stride + x] : 0;
      const c = x >= channels && y > 0 ? data[(y - 1) * stride + x - channels] : 0;
      let value = line[x];
      if (filter === 1) value += a;
      else if (filter === 2) value += b;
      else if (filter === 3) value += (a + b) >> 1;
      else if (filter === 4) {
        const p = a + b - c;
        const pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
        value += pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      data[y * stride + x] = value & 255;
    }
  }
  return { width, height, channels, data };
}

/** Waits until `predicate()` (run in the page) is true. */
export async function until(page, predicate, arg, what) {
  try {
    await page.waitForFunction(predicate, arg, { timeout: 30000 });
  } catch (error) {
    throw new Error(`timed out waiting for ${what}`);
  }
}
