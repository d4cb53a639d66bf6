// Headless Chromium as the browser tests launch it (scripts/browser/screenshot.cjs,
// scripts/three/render.cjs): Debian's /usr/bin/chromium, WebGL2 on ANGLE over SwiftShader
// (Chromium's software Vulkan: no GPU needed), no network chatter, a fresh profile.
"use strict";
const fs = require("fs");
const os = require("os");
const path = require("path");

const FLAGS = [
  "--headless",
  "--no-sandbox",
  "--disable-gpu",
  "--disable-quic",
  "--no-first-run",
  "--disable-background-networking",
  "--disable-component-update",
  "--disable-sync",
  // WebGL2 without a GPU: ANGLE on SwiftShader, Chromium's software Vulkan.
  "--use-angle=swiftshader",
  "--enable-unsafe-swiftshader",
];

// A persistent context of `chromium` (playwright-core's) in a new temporary profile, its
// page `viewport` pixels large, and `close()`, which closes it and removes the profile.
async function launch(chromium, viewport) {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), "bevy-phong-chromium-"));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: "/usr/bin/chromium",
    headless: true,
    // Playwright adds its own flags (the profile, the pipe it drives Chromium through).
    args: FLAGS,
    viewport,
    deviceScaleFactor: 1,
  });
  const close = async () => {
    await context.close();
    fs.rmSync(profile, { recursive: true, force: true });
  };
  return { context, close };
}

module.exports = { launch };
