// Helpers of the viewer's test: headless Chromium (Debian's, through puppeteer-core)
// on the page, and a screenshot's pixels.
import { PNG } from "pngjs";
import puppeteer from "puppeteer-core";
import { fileURLToPath } from "node:url";

export const chromiumPath = process.env.CHROMIUM || "/usr/bin/chromium";
export const pageUrl = new URL("../index.html", import.meta.url).href;
export const repoRoot = fileURLToPath(new URL("../../../../", import.meta.url));

export async function launch() {
  return puppeteer.launch({
    executablePath: chromiumPath,
    headless: true,
    // Root in a container has no user namespace for Chromium's sandbox.
    args: ["--no-sandbox", "--disable-gpu", "--allow-file-access-from-files"],
  });
}

/** Opens the viewer on the server at `wsUrl`; `query` adds to its query string. */
export async function openViewer(browser, wsUrl, query = "", { width = 960, height = 600 } = {}) {
  const page = await browser.newPage();
  await page.setViewport({ width, height, deviceScaleFactor: 1 });
  const errors = [];
  page.on("pageerror", (error) => errors.push(String(error)));
  await page.goto(`${pageUrl}?ws=${encodeURIComponent(wsUrl)}${query}`);
  return { page, errors };
}

/** The screenshot's pixel (x, y) as [r, g, b]. */
export function pixels(png) {
  const image = PNG.sync.read(Buffer.from(png));
  return {
    width: image.width,
    height: image.height,
    at(x, y) {
      const i = (image.width * y + x) * 4;
      return [image.data[i], image.data[i + 1], image.data[i + 2]];
    },
  };
}
