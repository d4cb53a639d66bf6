// Renders a scene with three.js itself, in headless Chromium (WebGL2 on SwiftShader), into a
// float render target, and writes the linear pixels: the reference that the crate's own
// render of the same scene is compared with.
//
// node render.cjs SCENE_JSON OUT_F32 MODULES_DIR
// SCENE_JSON describes the scene (the schema of tests/three_js/scene.json). OUT_F32 gets
// raw little-endian f32, RGBA, width * height * 4 values, top row first, no header.
// MODULES_DIR holds playwright-core and three (scripts/ensure-browser.sh installs them
// there). No server runs: the page, scene.mjs, the scene and three's module files are served
// from disk to requests on a made-up origin. Exits 1 with a message on a page error, an
// error in the page's console, a browser without WebGL2 or EXT_color_buffer_float, or a
// render that has not finished within the time limit.
"use strict";
const fs = require("fs");
const path = require("path");
const { launch } = require("../browser/chromium.cjs");

const [scenePath, outPath, modules] = process.argv.slice(2);
if (modules === undefined) {
  console.error("usage: node render.cjs SCENE_JSON OUT_F32 MODULES_DIR");
  process.exit(2);
}
const { chromium } = require(require.resolve("playwright-core", { paths: [modules] }));
// three's package.json exports no "./package.json": its folder is found by name.
const threeDir = path.resolve(modules, "three");
if (!fs.existsSync(path.join(threeDir, "build", "three.module.js"))) {
  console.error(`three.js render failed: no three.js in ${modules} (scripts/ensure-browser.sh installs it)`);
  process.exit(1);
}

// Compiling the two shaders in software WebGL2 takes seconds; this leaves room for a slow
// machine.
const RENDER_TIMEOUT_MS = 300_000;
const ORIGIN = "http://three.test";

const CONTENT_TYPES = { ".html": "text/html", ".mjs": "text/javascript", ".js": "text/javascript" };

// The file that a request on ORIGIN stands for, or null: the page and its module from this
// folder, three's files (only those inside its package) under /three/.
function fileFor(url) {
  const { pathname } = new URL(url);
  if (pathname === "/" || pathname === "/index.html") return path.join(__dirname, "page.html");
  if (pathname === "/scene.mjs") return path.join(__dirname, "scene.mjs");
  if (pathname.startsWith("/three/")) {
    const file = path.resolve(threeDir, decodeURIComponent(pathname.slice("/three/".length)));
    if (file.startsWith(threeDir + path.sep)) return file;
  }
  return null;
}

async function main() {
  const scene = JSON.parse(fs.readFileSync(scenePath, "utf8"));
  const { context, close } = await launch(chromium, { width: 400, height: 300 });
  let failure = null;
  const fail = (message) => {
    failure = failure ?? message;
  };
  let result = null;
  try {
    // Every request is answered here: ORIGIN's from disk, any other one refused.
    await context.route("**/*", async (route) => {
      const url = route.request().url();
      const file = url.startsWith(`${ORIGIN}/`) ? fileFor(url) : null;
      if (file === null || !fs.existsSync(file)) {
        fail(`the page requested ${url}, which is not served`);
        await route.fulfill({ status: 404, body: "" });
        return;
      }
      await route.fulfill({
        status: 200,
        contentType: CONTENT_TYPES[path.extname(file)] ?? "application/octet-stream",
        body: fs.readFileSync(file),
      });
    });
    const page = context.pages()[0] ?? (await context.newPage());
    page.on("console", (message) => {
      console.log(`page ${message.type()}: ${message.text()}`);
      if (message.type() === "error") fail(`the page logged an error: ${message.text()}`);
    });
    page.on("pageerror", (error) => fail(`the page threw: ${error.message}`));

    const started = Date.now();
    await page.goto(`${ORIGIN}/`);
    const deadline = started + RENDER_TIMEOUT_MS;
    // The module script sets window.renderScene once three.js and scene.mjs have loaded.
    while (failure === null && !(await page.evaluate(() => typeof window.renderScene === "function"))) {
      if (Date.now() > deadline) fail(`three.js had not loaded after ${RENDER_TIMEOUT_MS / 1000} s`);
      else await page.waitForTimeout(100);
    }
    if (failure === null) {
      let timer;
      const timeout = new Promise((_, reject) => {
        timer = setTimeout(
          () => reject(new Error(`the render had not finished after ${RENDER_TIMEOUT_MS / 1000} s`)),
          Math.max(0, deadline - Date.now()),
        );
      });
      try {
        result = await Promise.race([page.evaluate((json) => window.renderScene(json), scene), timeout]);
      } catch (error) {
        fail(`the render failed: ${error.message}`);
      } finally {
        clearTimeout(timer);
      }
    }
  } finally {
    await close();
  }
  if (failure !== null) {
    console.error(`three.js render failed: ${failure}`);
    process.exit(1);
  }

  const { revision, width, height } = result;
  const bytes = Buffer.from(result.pixels, "base64");
  if (bytes.length !== width * height * 16) {
    console.error(`three.js render failed: ${bytes.length} bytes read back, not ${width * height * 16}`);
    process.exit(1);
  }
  // The page's floats are in the platform's byte order, rows bottom to top; the file's are
  // little-endian, rows top to bottom.
  const floats = new Float32Array(bytes.buffer, bytes.byteOffset, width * height * 4);
  const out = Buffer.alloc(bytes.length);
  const row = width * 4;
  for (let y = 0; y < height; y++) {
    const from = (height - 1 - y) * row;
    for (let i = 0; i < row; i++) out.writeFloatLE(floats[from + i], (y * row + i) * 4);
  }
  fs.mkdirSync(path.dirname(path.resolve(outPath)), { recursive: true });
  fs.writeFileSync(outPath, out);
  console.log(`three.js r${revision} rendered ${width}x${height} into ${outPath}`);
}

main().catch((error) => {
  console.error(`three.js render failed: ${error.message}`);
  process.exit(1);
});
