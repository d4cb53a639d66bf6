// Opens the showcase page in headless Chromium, waits until the app marks the page as drawn
// (`<body data-drawn>`, set by examples/support/web.rs), and screenshots its canvas.
//
// node screenshot.cjs URL PNG MODULES_DIR
// MODULES_DIR holds playwright-core (scripts/browser.sh installs it there). Exits 1 with a
// message when the page fails (a panic, a page error, data-failed) or has not drawn within
// the time limit.
"use strict";
const { launch } = require("./chromium.cjs");

const [url, png, modules] = process.argv.slice(2);
const { chromium } = require(require.resolve("playwright-core", { paths: [modules] }));

// Loading the wasm and compiling every shader in software WebGL2 takes about a minute on
// a 2-core machine; this leaves room for a slower one.
const DRAWN_TIMEOUT_MS = 600_000;
// The screenshot itself waits for the compositor's next frame, which software WebGL2 can
// take seconds to give while the app keeps drawing.
const SCREENSHOT_TIMEOUT_MS = 120_000;

async function main() {
  const { context, close } = await launch(chromium, { width: 1000, height: 600 });
  let failure = null;
  try {
    const page = context.pages()[0] ?? (await context.newPage());
    page.on("console", (message) => {
      // Bevy's log styles its lines with %c and CSS arguments; print them plain.
      const text = message
        .text()
        .replace(/%c/g, "")
        .replace(/(\s+(background|color|font-style|font-weight): [^;]*;?)+\s*$/, "");
      console.log(`page ${message.type()}: ${text}`);
      // A panic, a Bevy error, a resource that did not load: the page is not as it should be.
      if (message.type() === "error") {
        failure = failure ?? `the page logged an error: ${text}`;
      }
    });
    page.on("pageerror", (error) => {
      failure = failure ?? `the page threw: ${error.message}`;
    });
    const started = Date.now();
    await page.goto(url);
    const deadline = started + DRAWN_TIMEOUT_MS;
    while (failure === null) {
      const state = await page.evaluate(() => ({
        drawn: document.body.hasAttribute("data-drawn"),
        failed: document.body.getAttribute("data-failed"),
      }));
      if (state.failed !== null) failure = `the page failed: ${state.failed}`;
      else if (state.drawn) break;
      else if (Date.now() > deadline) {
        failure = `the app had not drawn after ${DRAWN_TIMEOUT_MS / 1000} s`;
      } else await page.waitForTimeout(250);
    }
    if (failure === null) {
      console.log(`drawn after ${((Date.now() - started) / 1000).toFixed(1)} s`);
      // The page's pixels inside the canvas's box: an element screenshot would first wait
      // for the canvas to be "stable" over two animation frames, each of which can take
      // seconds here.
      const clip = await page.locator("#bevy").boundingBox();
      if (clip === null) throw new Error("the page has no visible #bevy canvas");
      await page.screenshot({ path: png, clip, timeout: SCREENSHOT_TIMEOUT_MS });
      console.log(`wrote ${png}`);
    }
  } finally {
    await close();
  }
  if (failure !== null) {
    console.error(`browser test failed: ${failure}`);
    process.exit(1);
  }
}

main().catch((error) => {
  console.error(`browser test failed: ${error.message}`);
  process.exit(1);
});
