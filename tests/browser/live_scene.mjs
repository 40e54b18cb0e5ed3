/* SPDX-License-Identifier: BSD-3-Clause */
// Checks of the pictures of dynkit's live pages in headless Chromium (playwright-core, as
// tests/browser/live.mjs), with the network off (every request but the page's file is
// aborted and counted):
// - a mechanism's scene (examples/mechanisms/double_pendulum.mech, 2D; fourbar.mech, with
//   constraint-force arrows; top.mech, 3D; rolling_disk.mech, a wheel): after dynkitLive.set and run, the poses of
//   the bodies and the numbers of the shapes the page draws (dynkitLive.scene()) differ from
//   those of the run the page was written with and equal those the tool computes for a
//   static page of `dynkit animate` with the page's command line (same run settings):
//   positions within 1e-8 of the mechanism's size and rotations within 1e-6 (the static
//   page writes 9 and 6 significant digits); the constraint-force arrows follow the live
//   run's multipliers;
// - an XPPAUT animation (examples/models/pendulum.ode, double_pendulum.ode and
//   examples/mechanisms/double_pendulum.mech with their .ani): after a change the numbers of
//   every primitive (dynkitLive.ani()) equal those of the static page of the same settings
//   (within 1e-5 of the window: its 6 digits) and its vtext strings are the same, and differ
//   from the first run's; an .ani beside a C model (spring_mass.c), which the module does not
//   compute, keeps its canvas and pixels and the page says it shows the original run;
// - a change redraws a mechanism's scene (2D, 3D) and an animation in place (the same canvas,
//   other pixels), and a long run is drawn in place as it computes;
// - `dynkit report --html FILE --live`: each of the homework's models chosen in the live
//   section runs in the page, and a change of a parameter gives `dynkit run`'s numbers with
//   the command line the page shows (within 1e-12 of each column's magnitude), and models
//   switched away from before their modules ran leave one worker running;
// - a mechanism file with a hostile title and an animation with hostile text run no script;
// - at 390 px wide nothing scrolls sideways; no console error.
// What failed is kept under ARTIFACTS/live-scene/.
//
// Usage: node live_scene.mjs DYNKIT_BINARY SOURCE_DIR [ARTIFACTS_DIR]; exit 0, 1 (a check
// failed), 77 (skipped: no Chromium, no node_modules, or dynkit without the WebAssembly
// library).
import { execFileSync, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { check, checks, loadChromium, skip } from './harness.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const dynkit = process.argv[2] && path.resolve(process.argv[2]);
const source = path.resolve(process.argv[3] || path.join(here, '..', '..'));
const artifacts = path.resolve(process.argv[4] || path.join(source, 'build', 'tests', 'artifacts'));
if (!dynkit || !fs.existsSync(dynkit)) {
  console.error(`usage: node live_scene.mjs DYNKIT_BINARY SOURCE_DIR [ARTIFACTS_DIR] (got '${dynkit}')`);
  process.exit(2);
}
const { chromium, chromiumPath } = await loadChromium(here);
const dir = path.join(artifacts, 'live-scene');
fs.mkdirSync(dir, { recursive: true });

const results = checks.results;

function pageData(file) {
  const html = fs.readFileSync(file, 'utf8');
  const m = /<script[^>]*id="dynkit-data"[^>]*>([\s\S]*?)<\/script>/.exec(html);
  return JSON.parse(m[1]);
}

// the command line of a page with the tool's path for 'dynkit'
const shellLine = cmd => cmd.replace(/^dynkit /, "'" + dynkit.replace(/'/g, "'\\''") + "' ");

// `dynkit run` with the page's command line: {names, rows}
function runCommand(cmd) {
  const text = execFileSync('sh', ['-c', shellLine(cmd).replace(/ -o run\.csv$/, ' -o -')], { encoding: 'utf8', maxBuffer: 1 << 28 });
  const rows = text.trim().split('\n');
  return { names: rows[0].split(','), rows: rows.slice(1).map(l => l.split(',').map(Number)) };
}

// every sample of a column of the page's data (a number: the same in all)
const samples = (x, n) => (typeof x === 'number' || x === null ? new Array(n).fill(x === null ? NaN : x) : x);

// The largest difference between two scenes {poses, values} over n samples: positions
// (pose columns 0-2, point coordinates) relative to size, rotations absolute.
function sceneDiff(a, b, n, size) {
  let pos = 0, rot = 0;
  a.poses.forEach((p, i) => p.forEach((col, q) => {
    const x = samples(col, n), y = samples(b.poses[i][q], n);
    for (let k = 0; k < n; k++) {
      const d = Math.abs(x[k] - y[k]);
      if (q < 3) pos = Math.max(pos, d / size); else rot = Math.max(rot, d);
    }
  }));
  a.values.forEach((v, i) => v.forEach((col, q) => {
    const x = samples(col, n), y = samples(b.values[i][q], n);
    for (let k = 0; k < n; k++) {
      if (Number.isNaN(x[k]) && Number.isNaN(y[k])) continue;
      pos = Math.max(pos, Math.abs(x[k] - y[k]) / size);
    }
  }));
  return { pos, rot };
}

function scaleOf(scene, n) {
  let s = 0;
  for (const p of scene.poses) for (let q = 0; q < 3; q++) for (const x of samples(p[q], n)) if (isFinite(x)) s = Math.max(s, Math.abs(x));
  return s || 1;
}

const hostileDir = fs.mkdtempSync(path.join(os.tmpdir(), 'dynkit-live-scene-'));
const hostile = path.join(hostileDir, 'hostile.mech');
fs.writeFileSync(hostile, fs.readFileSync(path.join(source, 'examples/mechanisms/double_pendulum.mech'), 'utf8')
  .replace(/^#: title .*$/m, '#: title </script><script>window.pwned=1</script><img src=x onerror="window.pwned=2">'));

const ex = p => path.join(source, p);
const mechs = [
  { name: 'double-pendulum', file: ex('examples/mechanisms/double_pendulum.mech'), set: { m2: 1.5 }, inPlace: 100 },
  { name: 'fourbar', file: ex('examples/mechanisms/fourbar.mech'), set: { g: 25 }, arrows: true },
  { name: 'top', file: ex('examples/mechanisms/top.mech'), set: {}, setFirstState: 1.3, inPlace: 100 },
  { name: 'rolling-disk', file: ex('examples/mechanisms/rolling_disk.mech'), set: { W: 6 } },
  { name: 'hostile', file: hostile, set: { m2: 1.5 }, hostile: true },
];
for (const p of mechs) {
  p.page = path.join(dir, p.name + '.html');
  const r = spawnSync(dynkit, ['animate', p.file, '--live', '-o', p.page], { encoding: 'utf8' });
  if (r.status !== 0 || /not live/.test(r.stderr)) {
    if (/built without the WebAssembly library/.test(r.stderr))
      skip(`dynkit was built without the WebAssembly library: ${r.stderr.trim()}`);
    checks.current = p.name;
    check(false, `dynkit animate --live: exit ${r.status}: ${r.stderr.trim()}`);
    p.failed = true;
  }
}

const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'dynkit-chromium-'));
const context = await chromium.launchPersistentContext(userDataDir, {
  executablePath: chromiumPath, headless: true, viewport: { width: 1280, height: 900 },
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});

// A page opened offline: {page, errors, requests}, or null when its module did not start.
async function open(file) {
  const page = await context.newPage();
  const errors = [], requests = [];
  const url = pathToFileURL(file).href;
  page.on('console', m => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', e => errors.push(String(e)));
  await page.route('**/*', route => {
    if (route.request().url() === url) return route.continue();
    requests.push(route.request().url());
    return route.abort();
  });
  await page.goto(url, { waitUntil: 'load' });
  await page.waitForSelector('body[data-live]', { timeout: 120000 }).catch(() => {});
  const state = await page.evaluate(() => document.body.dataset.live);
  const size = fs.statSync(file).size;
  check(size < 1e6, `the page is under 1 MB (${size} bytes)`);
  if (!check(state === 'ready', `the module runs in the page (${(size / 1024).toFixed(0)} KiB)`)) {
    console.log(errors.join('\n'));
    await page.close();
    return null;
  }
  return { page, errors, requests };
}

async function finish(o, name) {
  const { page, errors, requests } = o;
  await page.setViewportSize({ width: 390, height: 844 });
  await page.evaluate(() => window.dynkitLive.run());
  await page.waitForTimeout(150);
  const fit = await page.evaluate(() => ({ sw: document.documentElement.scrollWidth, w: innerWidth }));
  check(fit.sw <= fit.w, `at 390 px wide nothing scrolls sideways (${fit.sw} <= ${fit.w})`);
  await page.screenshot({ path: path.join(dir, name + '-390.png'), fullPage: true });
  await page.setViewportSize({ width: 1280, height: 900 });
  await page.screenshot({ path: path.join(dir, name + '.png'), fullPage: true });
  check(requests.length === 0, `no request but the page itself (${requests.length}: ${requests.slice(0, 3).join(' ')})`);
  check(errors.length === 0, `no console error${errors.length ? ': ' + errors.slice(0, 3).join(' | ') : ''}`);
  await page.close();
}

// The picture of selector's canvas at the fraction f of the player's span, the player paused
// there (a data URL of its pixels), and whether the canvas is the one marked before; mark:
// the canvas marked, to tell later whether it is kept.
async function drawnAt(page, selector, f, mark) {
  return page.evaluate(async ([sel, f, mark]) => {
    const c = document.querySelector(sel), player = window.DK.lastLive.player;
    if (!c) return null;
    const kept = c.dkKept;
    if (mark) c.dkKept = 'the same canvas';
    player.pause();
    player.seek(player.t0 + f * (player.t1 - player.t0));
    await new Promise(r => requestAnimationFrame(() => setTimeout(r, 0)));
    return { url: c.toDataURL(), t: player.t, kept };
  }, [selector, f, !!mark]);
}

// A long run (a span `times` the page's) drawn as it computes, in place: at its first drawing
// before its end, the player's span has grown past the old span but not to the run's end,
// the picture's canvas is the one marked (drawnAt), and what() of the hook has frames; the
// span set back after it (the run ended). The run goes to the worker (local_ms 0); one that
// ends within a frame of its start (an idle machine) is tried again 4 and 16 times longer.
async function longRunInPlace(page, selector, times, what) {
  return page.evaluate(async ([sel, times, what]) => {
    const L = window.dynkitLive, live = window.DK.lastLive, t0 = L.get('t0'), t1 = L.get('t1');
    let r = null;
    L.set('local_ms', 0);
    for (const k of [times, 4 * times, 16 * times]) {
      const before = L.timing();
      L.set('t1', t0 + k * (t1 - t0));
      const run = L.run();
      let ended = false, seen = null;
      run.then(() => { ended = true; });
      while (!ended && !seen) {
        await new Promise(r => requestAnimationFrame(r));
        if (L.timing().partial_draws > before.partial_draws) {
          const x = L[what](), frames = x ? (what === 'scene' ? x.poses[0][0].length : x.map(q => q.v.find(c => typeof c !== 'number')).find(Boolean).length) : 0;
          seen = { span: live.player.t1, kept: document.querySelector(sel).dkKept === 'the same canvas', frames };
        }
      }
      await run;
      r = { seen, end: live.player.t1, t1, longEnd: t0 + k * (t1 - t0), partial: L.timing().partial_draws - before.partial_draws };
      if (seen && seen.span < r.longEnd) break;
    }
    L.set('local_ms', null);
    L.set('t1', t1);
    await L.run();
    return r;
  }, [selector, times, what]);
}

function checkLongRun(r) {
  check(r.seen && r.seen.span > r.t1 && r.seen.span < r.longEnd && r.seen.kept && r.seen.frames > 1,
    `a long run is drawn in place as it computes (${r.partial} drawings before its end; the first up to t = ${r.seen && r.seen.span.toFixed(2)} of ${r.longEnd}, ${r.seen && r.seen.frames} frames, the same canvas: ${r.seen && r.seen.kept}); at its end the span is ${r.end}`);
}

// ---- mechanisms ----
for (const p of mechs.filter(q => !q.failed)) {
  checks.current = p.name;
  const o = await open(p.page);
  if (!o) continue;
  const { page } = o;
  const written = pageData(p.page);
  check(!!written.mech_plan && written.live.scene_inputs === true, 'the page carries the plan of its scene and the module writes its inputs');
  // a change: the parameters given, or the first initial value
  const set = Object.assign({}, p.set);
  if (p.setFirstState !== undefined) set[written.model.states[0].name] = p.setFirstState;
  const arrowsBefore = await page.evaluate(() => { const v = document.querySelector('#view'); return v && v.dataset.mechArrows; });
  const sceneCanvas = '#view canvas';
  const drawnBefore = await drawnAt(page, sceneCanvas, 0.5, true);
  for (const [k, v] of Object.entries(set)) await page.evaluate(([k, v]) => window.dynkitLive.set(k, v), [k, v]);
  const out = await page.evaluate(async () => {
    const r = await window.dynkitLive.run();
    const view = document.querySelector('#view');
    return { n: r.t.length, cmd: window.dynkitLive.command(), scene: window.dynkitLive.scene(), note: document.getElementById('messages').textContent, arrows: view && view.dataset.mechArrows };
  });
  if (!check(out.scene && out.scene.poses.length === written.mech.bodies.length, `the live run has a scene (${out.scene ? out.scene.poses.length : 0} bodies)`)) { await finish(o, p.name); continue; }
  check(!/scene shows the run the page was written with/.test(out.note), `the page does not say its scene is the original run's (${out.note || 'no note'})`);
  if (p.inPlace) {
    const drawnAfter = await drawnAt(page, sceneCanvas, 0.5);
    const kept = drawnAfter && drawnAfter.kept;
    check(kept === 'the same canvas' && drawnBefore && drawnAfter.url !== drawnBefore.url,
      `the change redraws the scene in place: the same canvas (${kept || 'a new one'}), another pose drawn at t = ${drawnAfter && drawnAfter.t.toFixed(3)}`);
  }

  const n0 = written.runs[0].data[0].length, size = scaleOf(written.mech.runs[0], n0);
  const n = out.scene.poses[0][0].length;
  // the tool's scene of the same settings: a static page of the command line
  const ref = path.join(dir, p.name + '-tool.html');
  const line = shellLine(out.cmd).replace(/^('[^']*') run /, '$1 animate ').replace(/ -o run\.csv$/, ` -o '${ref}'`);
  let tool = null;
  try { execFileSync('sh', ['-c', line], { encoding: 'utf8' }); tool = pageData(ref); } catch (e) { check(false, `dynkit animate with the page's settings failed: ${e.message}`); }
  if (tool) {
    const nt = tool.runs[0].data[0].length;
    check(nt === n, `as many frames as the tool's page of the same run (${n}, ${nt})`);
    const d = sceneDiff(out.scene, tool.mech.runs[0], Math.min(n, nt), size);
    const okd = check(d.pos <= 1e-8 && d.rot <= 1e-6, `the scene equals the tool's for the new settings (positions ${d.pos.toExponential(2)} of the size ${size.toPrecision(3)} m, rotations ${d.rot.toExponential(2)})`);
    const moved = sceneDiff(out.scene, written.mech.runs[0], Math.min(n, n0), size);
    check(moved.pos > 1e-3, `and differs from the run the page was written with (${moved.pos.toExponential(2)} of the size)`);
    if (!okd) fs.writeFileSync(path.join(dir, p.name + '-scene.json'), JSON.stringify({ page: out.scene, tool: tool.mech.runs[0] }));
  }
  if (p.arrows) {
    // the arrows are the multipliers of the live run: their scale follows the largest force
    check(/arrows: 1 m = /.test(out.arrows || '') && out.arrows !== arrowsBefore, `the constraint forces are drawn from the live run: their scale follows its multipliers (${arrowsBefore} -> ${out.arrows})`);
  }
  if (p.hostile) check(await page.evaluate(() => window.pwned === undefined), 'hostile text in the mechanism file runs no script');
  if (p.inPlace) checkLongRun(await longRunInPlace(page, sceneCanvas, p.inPlace, 'scene'));
  await finish(o, p.name);
}

// ---- an .ani the module does not compute (beside a C model) ----
// it stays, showing the run the page was written with (the same canvas and pixels at the
// same time of the player), and the page says so; the plots follow the live run
checks.current = 'c-model-ani';
{
  const cDir = fs.mkdtempSync(path.join(os.tmpdir(), 'dynkit-live-c-'));
  fs.copyFileSync(ex('examples/models/spring_mass.c'), path.join(cDir, 'spring_mass.c'));
  fs.writeFileSync(path.join(cDir, 'spring_mass.ani'), 'dimension -0.2;-0.1;0.2;0.1\nline 0;0;x;0;$BLACK;2\nfcircle x;0;0.02;$RED\nend\n');
  const file = path.join(dir, 'c-model-ani.html');
  const r = spawnSync(dynkit, ['animate', path.join(cDir, 'spring_mass.c'), '--live', '-o', file], { encoding: 'utf8' });
  const o = check(r.status === 0 && !/not live/.test(r.stderr), `dynkit animate spring_mass.c --live: exit ${r.status} ${r.stderr.trim()}`) ? await open(file) : null;
  if (o) {
    const { page } = o, written = pageData(file), sel = '#ani canvas.ani-canvas';
    check(!!written.ani && written.live.ani_outputs === false, 'the page carries the animation, which its module does not compute');
    const before = await drawnAt(page, sel, 0.5, true);
    const plotBefore = await drawnAt(page, '#plots canvas', 0.5, true);
    const out = await page.evaluate(async () => {
      window.dynkitLive.set('k', 4);
      await window.dynkitLive.run();
      return { note: document.getElementById('messages').textContent, ani: window.dynkitLive.ani() };
    });
    const after = await drawnAt(page, sel, 0.5), plotAfter = await drawnAt(page, '#plots canvas', 0.5);
    check(after && after.kept === 'the same canvas' && after.url === before.url && out.ani === null && /animation shows the run the page was written with/.test(out.note),
      `the .ani stays, with the run the page was written with (${after ? after.kept || 'a new canvas' : 'gone'}; ${out.note})`);
    check(plotAfter && plotAfter.kept === 'the same canvas' && plotAfter.url !== plotBefore.url, 'the plots follow the live run, in place');
    await finish(o, 'c-model-ani');
  }
  fs.rmSync(cDir, { recursive: true, force: true });
}

// ---- .ani animations ----
// the tool's numbers (6 significant digits) against the page's, relative to the window's size
function aniDiff(a, b, n, size) {
  let d = 0, strings = 0;
  a.forEach((p, i) => {
    p.v.forEach((col, k) => {
      const x = samples(col, n), y = samples(b[i].v[k], n);
      for (let q = 0; q < n; q++) {
        if (Number.isNaN(x[q]) && Number.isNaN(y[q])) continue;
        d = Math.max(d, Math.abs(x[q] - y[q]) / size);
      }
    });
    if (p.s !== undefined) {
      const x = typeof p.s === 'string' ? new Array(n).fill(p.s) : p.s, y = typeof b[i].s === 'string' ? new Array(n).fill(b[i].s) : b[i].s;
      for (let q = 0; q < n; q++) strings += x[q] !== y[q];
    }
  });
  return { d, strings };
}

const aniDir = fs.mkdtempSync(path.join(os.tmpdir(), 'dynkit-live-ani-'));
const hostileOde = path.join(aniDir, 'hostile.ode');
fs.copyFileSync(ex('examples/models/pendulum.ode'), hostileOde);
fs.writeFileSync(path.join(aniDir, 'hostile.ani'), fs.readFileSync(ex('examples/models/pendulum.ani'), 'utf8')
  .replace(/^end$/m, 'text .1;.1;</script><script>window.pwned=1</script><img src=x onerror=window.pwned=2>\nend'));
// (the double pendulum over 4 s: later its chaos makes the last bits of libm, the page's
// musl against the tool's glibc, visible in the picture)
const anis = [
  { name: 'pendulum-ani', file: ex('examples/models/pendulum.ode'), set: { l: 5 }, inPlace: 1000 },
  { name: 'double-pendulum-ani', file: ex('examples/models/double_pendulum.ode'), set: { l1: 1.6, m2: 3, t1: 4 } },
  { name: 'double-pendulum-mech-ani', file: ex('examples/mechanisms/double_pendulum.mech'), set: { l1: 1.6, m2: 3, t1: 4 } },
  { name: 'hostile-ani', file: hostileOde, set: { l: 5 }, hostile: true },
];
for (const p of anis) {
  checks.current = p.name;
  p.page = path.join(dir, p.name + '.html');
  const r = spawnSync(dynkit, ['animate', p.file, '--live', '-o', p.page], { encoding: 'utf8' });
  if (!check(r.status === 0 && !/not live/.test(r.stderr), `dynkit animate --live: exit ${r.status} ${r.stderr.trim()}`)) continue;
  const o = await open(p.page);
  if (!o) continue;
  const { page } = o;
  const written = pageData(p.page);
  check(!!written.ani && written.live.ani_outputs === true, 'the page carries its animation and the module writes its numbers');
  const aniCanvas = '#ani canvas.ani-canvas';
  const drawnBefore = await drawnAt(page, aniCanvas, 0.3, true);
  for (const [k, v] of Object.entries(p.set)) await page.evaluate(([k, v]) => window.dynkitLive.set(k, v), [k, v]);
  const out = await page.evaluate(async () => {
    await window.dynkitLive.run();
    return { cmd: window.dynkitLive.command(), ani: window.dynkitLive.ani(), note: document.getElementById('messages').textContent };
  });
  if (p.inPlace) {
    const drawnAfter = await drawnAt(page, aniCanvas, 0.3);
    const kept = drawnAfter && drawnAfter.kept;
    check(kept === 'the same canvas' && drawnBefore && drawnAfter.url !== drawnBefore.url,
      `the change redraws the animation in place: the same canvas (${kept || 'a new one'}), another frame drawn at t = ${drawnAfter && drawnAfter.t.toFixed(3)}`);
  }
  if (!check(out.ani && out.ani.length === written.ani.prims.length, `the live run has the animation's ${out.ani ? out.ani.length : 0} primitives`)) { await finish(o, p.name); continue; }
  check(!/animation shows the run the page was written with/.test(out.note), `the page does not say its animation is the original run's (${out.note || 'no note'})`);
  const w = written.ani.window, size = Math.max(w[2] - w[0], w[3] - w[1]);
  const ref = path.join(dir, p.name + '-tool.html');
  const line = shellLine(out.cmd).replace(/^('[^']*') run /, '$1 animate ').replace(/ -o run\.csv$/, ` -o '${ref}'`);
  let tool = null;
  try { execFileSync('sh', ['-c', line], { encoding: 'utf8' }); tool = pageData(ref); } catch (e) { check(false, `dynkit animate with the page's settings failed: ${e.message}`); }
  if (tool) {
    const n = tool.runs[0].data[0].length;
    const firstLen = out.ani.map(q => q.v.find(x => typeof x !== 'number')).find(x => x);
    check(firstLen && firstLen.length === n, `as many frames as the tool's page of the same run (${firstLen && firstLen.length}, ${n})`);
    const d = aniDiff(out.ani, tool.ani.runs[0], n, size);
    const okd = check(d.d <= 1e-5 && d.strings === 0, `the animation equals the tool's for the new settings (numbers within ${d.d.toExponential(2)} of the window's ${size}, ${d.strings} texts differ)`);
    const moved = aniDiff(out.ani, written.ani.runs[0], Math.min(n, written.runs[0].data[0].length), size);
    check(moved.d > 1e-3, `and differs from the run the page was written with (${moved.d.toExponential(2)} of the window)`);
    if (!okd) fs.writeFileSync(path.join(dir, p.name + '-ani.json'), JSON.stringify({ page: out.ani, tool: tool.ani.runs[0] }));
  }
  if (p.hostile) check(await page.evaluate(() => window.pwned === undefined), 'hostile text in the animation runs no script');
  if (p.inPlace) checkLongRun(await longRunInPlace(page, aniCanvas, p.inPlace, 'ani'));
  await finish(o, p.name);
}
fs.rmSync(aniDir, { recursive: true, force: true });

// ---- the report ----
checks.current = 'report';
{
  const file = path.join(dir, 'report.html');
  const r = spawnSync(dynkit, ['report', '--no-studies', '--html', file, '--live'], { encoding: 'utf8' });
  check(r.status === 0 && !/not live/.test(r.stderr), `dynkit report --html --live: exit ${r.status} ${r.stderr.trim()}`);
  const o = r.status === 0 ? await open(file) : null;
  if (o) {
    const { page } = o;
    const models = await page.evaluate(() => window.dynkitReportLive.models);
    check(JSON.stringify(models) === JSON.stringify(['pendulum', 'vanderpol', 'plane', 'cart']), `the live section offers the homework's models (${models.join(', ')})`);
    const changes = { pendulum: { l: 1.3 }, vanderpol: { mu: 1.7 }, plane: { k: 25 }, cart: { Fx: -40 } };
    for (const name of models) {
      const ready = await page.evaluate(async nm => { await window.dynkitReportLive.choose(nm); return document.body.dataset.live; }, name);
      check(ready === 'ready', `${name}: its module instance runs`);
      for (const [k, v] of Object.entries(changes[name] || {})) await page.evaluate(([k, v]) => window.dynkitLive.set(k, v), [k, v]);
      const out = await page.evaluate(async () => { const r = await window.dynkitLive.run(); return { r, cmd: window.dynkitLive.command(), title: document.getElementById('title').textContent }; });
      check(out.title.startsWith(name + ' '), `${name}: the section shows it (${out.title})`);
      let ref;
      try { ref = runCommand(out.cmd); } catch (e) { check(false, `${name}: dynkit run failed: ${e.message}`); }
      if (!ref) continue;
      const n = out.r.names.length, scale = new Array(n + 1).fill(0);
      ref.rows.forEach(row => row.forEach((v, c) => { scale[c] = Math.max(scale[c], Math.abs(v)); }));
      let worst = ref.rows.length === out.r.t.length ? 0 : Infinity;
      for (let k = 0; k < Math.min(ref.rows.length, out.r.t.length); k++) {
        const mine = [out.r.t[k], ...out.r.y[k]];
        for (let c = 0; c <= n; c++) if (!Object.is(mine[c], ref.rows[k][c])) worst = Math.max(worst, Math.abs(mine[c] - ref.rows[k][c]) / (scale[c] || 1));
      }
      check(worst <= 1e-12, `${name}: ${out.r.t.length} samples equal to dynkit run's with the page's command (${out.cmd}) within 1e-12 (largest ${worst.toExponential(2)})`);
    }
    // a model switched away from before its module ran leaves no worker behind: one
    // worker runs the model shown (the page's own thread runs no worker)
    const switched = await page.evaluate(async () => {
      const R = window.dynkitReportLive;
      const early = [R.choose('pendulum'), R.choose('plane')];
      await R.choose('vanderpol');
      await Promise.allSettled(early);
      await new Promise(r => setTimeout(r, 300));
      return document.getElementById('title').textContent;
    });
    // a model switched away from while its module starts or runs: its choose() settles too
    const settled = await page.evaluate(async () => {
      const R = window.dynkitReportLive, out = [];
      for (const ms of [0, 20, 50, 100, 200]) {
        const first = R.choose('pendulum');
        await new Promise(r => setTimeout(r, ms));
        const second = R.choose('cart');
        const timeout = new Promise(r => setTimeout(() => r('pending'), 20000));
        out.push(await Promise.race([first.then(() => 'settled', () => 'settled'), timeout]));
        await second;
      }
      await R.choose('vanderpol');
      return out;
    });
    check(settled.every(s => s === 'settled'), `choose() settles when another model is chosen 0 to 200 ms later (${settled.join(', ')})`);
    await page.waitForTimeout(300);
    const workers = page.workers().length;
    check(workers === 1 && switched.startsWith('vanderpol '), `after switching models before their modules ran, ${workers} worker runs (the model shown: ${switched})`);
    await finish(o, 'report');
  }
}

await context.close();
fs.rmSync(userDataDir, { recursive: true, force: true });
fs.rmSync(hostileDir, { recursive: true, force: true });
const failed = results.filter(r => !r.ok);
console.log(`\n${results.length - failed.length}/${results.length} checks passed`);
process.exit(failed.length ? 1 : 0);
