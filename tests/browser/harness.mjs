// SPDX-License-Identifier: BSD-3-Clause
// harness.mjs — what the browser tests (run.mjs, live.mjs, live_scene.mjs) share: the
// skip rule (exit 77, a failure under DYNKIT_REQUIRE_BROWSER=1, as CI sets), headless
// Chromium through playwright-core from this folder's node_modules (scripts/install-deps.sh
// installs both), and the checks' record.
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

export const SKIP = 77;

// Skipped, never failed, where the browser is missing; CI requires it.
export function skip(why) {
  if (process.env.DYNKIT_REQUIRE_BROWSER === '1') {
    console.log(`FAIL: ${why} (DYNKIT_REQUIRE_BROWSER=1)`);
    process.exit(1);
  }
  console.log(`SKIP: ${why}`);
  process.exit(SKIP);
}

// playwright-core's chromium and the browser's path (DYNKIT_CHROMIUM, else Debian's), or a skip.
export async function loadChromium(here) {
  const chromiumPath = process.env.DYNKIT_CHROMIUM || '/usr/bin/chromium';
  if (!fs.existsSync(chromiumPath))
    skip(`Chromium not found at ${chromiumPath} (install it with 'apt-get install chromium', or run scripts/install-deps.sh)`);
  try {
    const { chromium } = await import(pathToFileURL(path.join(here, 'node_modules', 'playwright-core', 'index.mjs')).href);
    return { chromium, chromiumPath };
  } catch (e) {
    skip(`playwright-core is not installed in ${here}/node_modules (run 'npm ci' there, or scripts/install-deps.sh)`);
  }
}

// Every check's verdict, printed as it is made and named by the page or case being checked
// (checks.current).
export const checks = { current: '', results: [] };
export function check(ok, what) {
  checks.results.push({ ok: !!ok, what: `${checks.current}: ${what}` });
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${checks.current}: ${what}`);
  return ok;
}
