/* SPDX-License-Identifier: BSD-3-Clause */
// Checks of dynkit's live pages (`dynkit animate MODEL --live`) in headless Chromium, driven
// by playwright-core as tests/browser/run.mjs, with the network off (every request but the
// page's file is aborted and counted):
// - the numbers: for the homework's van der Pol, pendulum, plane and cart, an .ode file
//   (examples/models/lorenz.ode, tests/browser/morris_lecar.ode) and a .mech file
//   (examples/mechanisms/double_pendulum.mech), with a parameter or an initial value changed
//   through window.dynkitLive, the samples of dynkitLive.run() against those `dynkit run`
//   writes when given the command line the page shows: bit for bit where the model calls no
//   function of libm (van der Pol, Lorenz: the same operations in IEEE double), else within
//   1e-12 of each state's largest magnitude (the page's libm is wasi-libc's, musl's, whose
//   sin, cos, exp may differ from glibc's in the last bit);
// - moving a slider (keyboard on the range input) changes the plotted curve and the command;
// - `dynkit plot vanderpol --x y1 --y y2 --live`: the same, on the page of a plot;
// - a click in the phase plane adds a trajectory that starts there;
// - a long run is drawn as it computes, and a newer change cancels it;
// - the sliders of the initial values on a model file's phase-plane axes span its window;
// - at 390 px wide nothing scrolls sideways; no console error; hostile text in a model file
//   (title, units) stays text;
// - without the WebAssembly library the page is static and the tool names the packages.
// The times of a rerun (run and redraw) and of a right-hand side are printed and written to
// ARTIFACTS/live-timings.json, never asserted (the machine may be loaded).
//
// Usage: node live.mjs DYNKIT_BINARY SOURCE_DIR [ARTIFACTS_DIR]; exit 0, 1 (a check failed),
// 77 (skipped: no Chromium, no node_modules, or dynkit without the WebAssembly library).
import { execFileSync, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import zlib from 'node:zlib';
import { check, checks, loadChromium, skip } from './harness.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const dynkit = process.argv[2] && path.resolve(process.argv[2]);
const source = path.resolve(process.argv[3] || path.join(here, '..', '..'));
const artifacts = path.resolve(process.argv[4] || path.join(source, 'build', 'tests', 'artifacts'));

if (!dynkit || !fs.existsSync(dynkit)) {
  console.error(`usage: node live.mjs DYNKIT_BINARY SOURCE_DIR [ARTIFACTS_DIR] (got '${dynkit}')`);
  process.exit(2);
}
const { chromium, chromiumPath } = await loadChromium(here);
const dir = path.join(artifacts, 'live');
fs.mkdirSync(dir, { recursive: true });

const results = checks.results;

function pageData(file) {
  const html = fs.readFileSync(file, 'utf8');
  const m = /<script[^>]*id="dynkit-data"[^>]*>([\s\S]*?)<\/script>/.exec(html);
  return JSON.parse(m[1]);
}

// ---- the fallback: no library, a static page and the packages named ----
checks.current = 'fallback';
{
  const file = path.join(dir, 'fallback.html');
  const r = spawnSync(dynkit, ['animate', 'vanderpol', '--live', '-o', file],
    { env: Object.assign({}, process.env, { DYNKIT_WASM_DIR: path.join(dir, 'no-such-dir') }), encoding: 'utf8' });
  check(r.status === 0, `exit status 0 (got ${r.status})`);
  check(/not live/.test(r.stderr) && /wasi-libc/.test(r.stderr), `the warning names the packages: ${r.stderr.trim()}`);
  const html = fs.existsSync(file) ? fs.readFileSync(file, 'utf8') : '';
  check(html.includes('"runs"') && !html.includes('"live":{') && !html.includes("'wasm-unsafe-eval'"), 'a static page, without a module and without WebAssembly in its policy');
}

// ---- the pages ----
const hostileDir = fs.mkdtempSync(path.join(os.tmpdir(), 'dynkit-live-'));
const hostile = path.join(hostileDir, 'hostile.ode');
fs.writeFileSync(hostile, [
  '#: title </script><script>window.pwned=1</script><img src=x onerror="window.pwned=2">',
  "#: x [<b onmouseover=window.pwned=3>m</b>] position'\"",
  '#: k [</script>] stiffness',
  'par k=2', 'init x=1, v=0', "x'=v", "v'=-k*x", '@ total=5, dt=0.01', 'done', ''].join('\n'));

const ex = p => path.join(source, p);
// set: what dynkitLive.set changes before the compared run; exact: bit for bit required
const pages = [
  { name: 'vanderpol', args: ['vanderpol'], set: { mu: 1.7 }, exact: true, phase: true, slider: 'mu', timing: true, progressive: true },
  { name: 'pendulum', args: ['pendulum'], set: { l: 1.3, phi: 0.9 }, timing: true },
  { name: 'plane', args: ['plane'], set: { k: 25, dsX: 1.5 }, timing: true },
  { name: 'cart', args: ['cart'], set: { Fx: -40 }, timing: true },
  { name: 'lorenz', args: [ex('examples/models/lorenz.ode')], set: { rho: 24, x: 2 }, exact: true, phase: true },
  // ranges: the sliders' [min, max]: the file's phase window (@ xp=v, yp=w, xlo..yhi) for
  // the initial values on its axes, the rule around the default for a parameter (i = 100)
  { name: 'morris-lecar', args: [ex('tests/browser/morris_lecar.ode')], set: {}, ranges: { v: [-75, 45], w: [0, 0.6], i: [0, 200] } },
  { name: 'double-pendulum-mech', args: [ex('examples/mechanisms/double_pendulum.mech')], set: { m2: 1.5 } },
  { name: 'hostile', args: [hostile], set: { k: 3 }, hostile: true },
  { name: 'plot-vanderpol', command: 'plot', args: ['vanderpol'], extra: ['--x', 'y1', '--y', 'y2'], set: { mu: 0.5, y1: 1 }, exact: true, phase: true, slider: 'mu' },
];
for (const p of pages) {
  p.file = path.join(dir, p.name + '.html');
  const r = spawnSync(dynkit, [p.command || 'animate', ...p.args, ...(p.extra || []), '--live', '-o', p.file], { encoding: 'utf8' });
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

// `dynkit run` with the page's command line (the tool's path for 'dynkit', its CSV to stdout)
function runCommand(cmd) {
  const line = cmd.replace(/^dynkit /, "'" + dynkit.replace(/'/g, "'\\''") + "' ").replace(/ -o run\.csv$/, ' -o -');
  const text = execFileSync('sh', ['-c', line], { encoding: 'utf8', maxBuffer: 1 << 28 });
  const rows = text.trim().split('\n');
  const names = rows[0].split(',');
  return { names, rows: rows.slice(1).map(l => l.split(',').map(Number)) };
}

function canvasInk() {
  return [...document.querySelectorAll('#view canvas, #plots canvas')].map(c => {
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let h = 0;
    for (let i = 0; i < d.length; i += 16) h = (h * 31 + d[i] + 3 * d[i + 1] + 7 * d[i + 2]) | 0;
    return h;
  }).join(',');
}

const timings = {};
for (const p of pages.filter(q => !q.failed)) {
  checks.current = p.name;
  const page = await context.newPage();
  const errors = [], requests = [];
  const url = pathToFileURL(p.file).href;
  page.on('console', m => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', e => errors.push(String(e)));
  await page.route('**/*', route => {
    if (route.request().url() === url) return route.continue();
    requests.push(route.request().url());
    return route.abort();
  });
  await page.goto(url, { waitUntil: 'load' });
  await page.waitForSelector('body[data-live]', { timeout: 20000 }).catch(() => {});
  const state = await page.evaluate(() => document.body.dataset.live);
  const size = fs.statSync(p.file).size;
  if (!check(state === 'ready', `the module runs in the page (${(size / 1024).toFixed(0)} KiB)`)) {
    console.log(errors.join('\n'));
    await page.close();
    continue;
  }
  timings[p.name] = { page_bytes: size };
  // the module needs nothing from the page but the function it tells its progress to (no
  // system interface)
  // (the page carries the module as a zlib stream in base64: node's zlib inflates it here
  // and checks its Adler-32, as the browser's DecompressionStream does in the page)
  const imports = (() => {
    const text = pageData(p.file).live.module, packed = Buffer.from(text, 'base64');
    const bytes = zlib.inflateSync(packed), m = new WebAssembly.Module(bytes);
    return { imports: WebAssembly.Module.imports(m).map(i => i.module + '.' + i.name), bytes: bytes.length, packed: packed.length, text: text.length };
  })();
  timings[p.name].module_bytes = imports.bytes;
  timings[p.name].module_zlib_bytes = imports.packed;
  check(imports.imports.join() === 'dynkit.progress', `the module (${(imports.bytes / 1024).toFixed(0)} KiB, ${(imports.packed / 1024).toFixed(0)} KiB as a zlib stream, ${(imports.text / 1024).toFixed(0)} KiB in base64) imports dynkit.progress only (${imports.imports.join(', ')})`);
  check(size < 1e6, `the page is under 1 MB (${size} bytes)`);

  // a click in the phase plane (the page as it opened): a trajectory that starts there
  if (p.phase) {
    const box = await page.evaluate(() => {
      const c = document.querySelector('#view canvas.plot-canvas'), r = c.getBoundingClientRect(), P = c.dkPlot;
      return { x: r.left, y: r.top, l: P.m.l, t: P.m.t, w: P.w - P.m.l - P.m.r, h: P.h - P.m.t - P.m.b };
    });
    const cx = box.x + box.l + 0.3 * box.w, cy = box.y + box.t + 0.7 * box.h;
    const nBefore = await page.evaluate(() => document.querySelector('#view canvas.plot-canvas').dkPlot.o.series.length);
    await page.mouse.click(cx, cy);
    await page.waitForFunction(n => document.querySelector('#view canvas.plot-canvas').dkPlot.o.series.length !== n, nBefore, { timeout: 20000 }).catch(() => {});
    const after = await page.evaluate(() => {
      const c = document.querySelector('#view canvas.plot-canvas'), P = c.dkPlot, r = c.getBoundingClientRect();
      const s = P.o.series[P.o.series.length - 1];
      return { n: P.o.series.length, x0: r.left + P.px(s.x[0]), y0: r.top + P.py(s.y[0]), label: s.label, clicked: window.dynkitLive.clicked() };
    });
    check(after.n === nBefore + 1 && after.clicked.length === 1, `a click adds a trajectory (${nBefore} -> ${after.n} series: ${after.label})`);
    check(Math.abs(after.x0 - cx) <= 1.5 && Math.abs(after.y0 - cy) <= 1.5, `it starts where the click was (${after.x0.toFixed(1)}, ${after.y0.toFixed(1)} against ${cx.toFixed(1)}, ${cy.toFixed(1)})`);
    await page.getByRole('button', { name: 'clear trajectories' }).click();
    await page.waitForFunction(n => document.querySelector('#view canvas.plot-canvas').dkPlot.o.series.length === n, nBefore, { timeout: 20000 }).catch(() => {});
    check(await page.evaluate(() => document.querySelector('#view canvas.plot-canvas').dkPlot.o.series.length) === nBefore, 'clear removes it');
  }

  // the numbers against dynkit run, with the page's own command line
  for (const [k, v] of Object.entries(p.set)) await page.evaluate(([k, v]) => window.dynkitLive.set(k, v), [k, v]);
  const out = await page.evaluate(async () => { const r = await window.dynkitLive.run(); return { r, cmd: window.dynkitLive.command() }; });
  for (const [k, v] of Object.entries(p.set))
    check(out.cmd.includes(`${k}=${v}`), `the command line carries ${k}=${v}: ${out.cmd}`);
  let ref;
  try { ref = runCommand(out.cmd); } catch (e) { check(false, `dynkit run failed: ${e.message}`); }
  if (ref) {
    const n = out.r.names.length;
    check(JSON.stringify(ref.names) === JSON.stringify(['t', ...out.r.names]), `the columns are dynkit run's: ${ref.names.join(',')}`);
    check(ref.rows.length === out.r.t.length, `as many samples as dynkit run (${out.r.t.length}, ${ref.rows.length})`);
    let same = 0, total = 0, worst = 0;
    const scale = new Array(n + 1).fill(0);
    ref.rows.forEach(row => row.forEach((v, c) => { scale[c] = Math.max(scale[c], Math.abs(v)); }));
    for (let k = 0; k < Math.min(ref.rows.length, out.r.t.length); k++) {
      const mine = [out.r.t[k], ...out.r.y[k]];
      for (let c = 0; c <= n; c++) {
        total++;
        if (Object.is(mine[c], ref.rows[k][c])) same++;
        else worst = Math.max(worst, Math.abs(mine[c] - ref.rows[k][c]) / (scale[c] || 1));
      }
    }
    timings[p.name].bit_equal = `${same}/${total}`;
    timings[p.name].max_rel_diff = worst;
    if (p.exact) check(same === total && total > 0, `bit for bit equal to dynkit run (${same}/${total} numbers)`);
    else check(total > 0 && worst <= 1e-12, `equal to dynkit run within 1e-12 of each column's magnitude (${same}/${total} bit for bit, largest difference ${worst.toExponential(2)})`);
    fs.writeFileSync(path.join(dir, p.name + '-page.json'), JSON.stringify(out));
  }

  // the times of a rerun, each after a frame (as a slider's changes come): the module's
  // run, the page redrawn, and with the browser's own share (style, layout, and the canvases
  // rasterized, which reading a pixel of each forces): the least and the median of 15, the
  // least being the cost of the work itself on a machine other builds share
  if (p.timing) {
    // the same reruns with every run in the worker (local_ms 0) and as the page chooses (a
    // short run on its own thread), one after the other in this run
    const rerunTimes = localMs => page.evaluate(async localMs => {
      window.dynkitLive.set('local_ms', localMs);
      const all = [];
      for (let i = 0; i < 16; i++) {
        await new Promise(r => requestAnimationFrame(() => setTimeout(r, 0)));
        await window.dynkitLive.run();
        const tm = window.dynkitLive.timing(), t0 = performance.now();
        document.body.getBoundingClientRect();
        for (const c of document.querySelectorAll('canvas')) if (c.width && c.height) c.getContext('2d').getImageData(0, 0, 1, 1);
        tm.flushed_ms = tm.total_ms + performance.now() - t0;
        all.push(tm);
      }
      all.shift();
      const sorted = key => all.map(a => a[key]).sort((a, b) => a - b);
      const out = { samples: all[0].samples, rhs_calls: all[0].rhs_calls, thread: [...new Set(all.map(a => a.thread))].join(',') };
      for (const key of ['run_ms', 'draw_ms', 'total_ms', 'flushed_ms']) out[key] = { least: sorted(key)[0], median: sorted(key)[7] };
      return out;
    }, localMs);
    const f = x => `${x.least.toFixed(1)} (median ${x.median.toFixed(1)})`;
    const inWorker = await rerunTimes(0);
    const t = await rerunTimes(null);
    await page.evaluate(() => window.dynkitLive.set('local_ms', undefined));
    Object.assign(timings[p.name], t, { in_worker: inWorker });
    for (const [how, x] of [['every run in the worker', inWorker], ['as the page chooses', t]])
      console.log(`     ${p.name} (${how}: ${x.thread}): rerun ${f(x.total_ms)} ms, with the browser's share ${f(x.flushed_ms)} ms (run ${f(x.run_ms)}, drawn ${f(x.draw_ms)}), ${x.samples} samples, ${x.rhs_calls} right-hand sides`);
    // a right-hand side in the page against the native tool: a span 50 times as long, the
    // best of 3 runs in each (the tool's less its start-up, `dynkit info` of the model), each
    // divided by its own count of calls (the plane's long run nears the singularity of its
    // Euler angles, where the last bits of libm change the steps taken)
    const long = await page.evaluate(async () => {
      const L = window.dynkitLive, t0 = L.get('t0'), t1 = L.get('t1');
      L.set('t1', t0 + 50 * (t1 - t0));
      let best = null;
      for (let i = 0; i < 3; i++) { await L.run(); const tm = L.timing(); if (!best || tm.run_ms < best.run_ms) best = tm; }
      const cmd = L.command();
      L.set('t1', t1);
      await L.run();
      return { best, cmd };
    });
    const line = long.cmd.replace(/^dynkit /, "'" + dynkit.replace(/'/g, "'\\''") + "' ").replace(/ -o run\.csv$/, ' --final --stats');
    const wall = (args, shell) => {
      let best = Infinity, err = '';
      for (let i = 0; i < 3; i++) {
        const t0 = process.hrtime.bigint();
        const r = shell ? spawnSync('sh', ['-c', args], { encoding: 'utf8' }) : spawnSync(dynkit, args, { encoding: 'utf8' });
        best = Math.min(best, Number(process.hrtime.bigint() - t0) / 1e6);
        err = r.stderr;
      }
      return { ms: best, err };
    };
    const nat = wall(line, true), base = wall(['info', ...p.args], false);
    const m = /rhs=(\d+)/.exec(nat.err);
    const nativeRhs = m ? Number(m[1]) : NaN;
    timings[p.name].rhs_us_page = 1000 * long.best.run_ms / long.best.rhs_calls;
    timings[p.name].rhs_us_native = 1000 * Math.max(nat.ms - base.ms, 0) / nativeRhs;
    timings[p.name].rhs_calls_long = [long.best.rhs_calls, nativeRhs];
    console.log(`     ${p.name}: a right-hand side (with its share of the step) ${timings[p.name].rhs_us_page.toFixed(3)} us in the page, ${timings[p.name].rhs_us_native.toFixed(3)} us in the tool`);
  }

  // a long run (a span 2000 times the default, 3 million samples) is drawn as it computes,
  // and a newer change ends it: the page then shows the newer run, which run() gives to
  // both callers, and equals a run of its own
  if (p.progressive) {
    const r = await page.evaluate(async () => {
      const L = window.dynkitLive, t0 = L.get('t0'), t1 = L.get('t1'), before = L.timing();
      const plot = () => document.querySelector('#plots canvas.plot-canvas').dkPlot;
      L.set('t1', t0 + 2000 * (t1 - t0));
      const first = L.run();
      let ended = false;
      first.then(() => { ended = true; });
      while (!ended && L.timing().partial_draws === before.partial_draws) await new Promise(res => requestAnimationFrame(res));
      const drawnT = plot().o.series[0].x, drawnEnd = drawnT[drawnT.length - 1];
      L.set('t1', t1);
      L.set('mu', 1.25);
      const second = await L.run(), firstGave = await first;
      const after = L.timing(), shown = plot().o.series[0].x;
      const alone = await L.run();
      return {
        partial: after.partial_draws - before.partial_draws, cancelled: after.cancelled - before.cancelled,
        drawnEnd, longEnd: t0 + 2000 * (t1 - t0), t1, shownEnd: shown[shown.length - 1],
        same: JSON.stringify(second) === JSON.stringify(firstGave), alone: JSON.stringify(second) === JSON.stringify(alone), n: second.t.length
      };
    });
    check(r.partial >= 1 && r.drawnEnd > r.t1 && r.drawnEnd < r.longEnd, `a long run is drawn as it computes (${r.partial} drawings before the change, one up to t = ${r.drawnEnd.toFixed(1)} of ${r.longEnd})`);
    check(r.cancelled === 1, `a newer change cancels it (${r.cancelled} run cancelled)`);
    check(r.same && r.alone && r.shownEnd === r.t1, `the page shows the newer run (to t = ${r.shownEnd}, ${r.n} samples), given to both callers, equal to a run of its own`);
    await page.evaluate(() => { window.dynkitLive.set('mu', 1.7); return window.dynkitLive.run(); });
  }

  if (p.ranges) {
    for (const [name, want] of Object.entries(p.ranges)) {
      const got = await page.evaluate(n => {
        const s = [...document.querySelectorAll('.live input[type=range]')].find(e => e.getAttribute('aria-label') === n);
        return s ? [Number(s.min), Number(s.max)] : null;
      }, name);
      check(got && got[0] === want[0] && got[1] === want[1], `the slider of ${name} spans [${want}] (${got})`);
    }
  }

  // a slider moved with the keyboard changes the curve and the command line
  if (p.slider) {
    const inkBefore = await page.evaluate(canvasInk);
    const cmdBefore = await page.evaluate(() => window.dynkitLive.command());
    const slider = page.getByRole('slider', { name: p.slider, exact: true });
    await slider.focus();
    for (let i = 0; i < 5; i++) await page.keyboard.press('ArrowRight');
    await page.waitForFunction(c => window.dynkitLive.command() !== c, cmdBefore, { timeout: 5000 }).catch(() => {});
    await page.waitForTimeout(100);
    const inkAfter = await page.evaluate(canvasInk);
    const cmdAfter = await page.evaluate(() => window.dynkitLive.command());
    check(cmdAfter !== cmdBefore && new RegExp(`--set ${p.slider}=`).test(cmdAfter), `moving the ${p.slider} slider changes the command line: ${cmdAfter}`);
    check(inkAfter !== inkBefore, 'moving the slider changes the plotted curves');
  }

  if (p.hostile) {
    check(await page.evaluate(() => window.pwned === undefined), 'hostile text in the model file runs no script');
    check(await page.evaluate(() => document.body.textContent.includes('<b onmouseover=window.pwned=3>m</b>')), 'the hostile unit is shown as text');
  }

  // a phone: the controls fit without sideways scrolling
  await page.setViewportSize({ width: 390, height: 844 });
  await page.evaluate(() => window.dynkitLive.run());
  await page.waitForTimeout(150);
  const fit = await page.evaluate(() => ({ sw: document.documentElement.scrollWidth, w: innerWidth }));
  check(fit.sw <= fit.w, `at 390 px wide nothing scrolls sideways (${fit.sw} <= ${fit.w})`);
  await page.screenshot({ path: path.join(dir, p.name + '-390.png'), fullPage: true });
  await page.setViewportSize({ width: 1280, height: 900 });
  await page.screenshot({ path: path.join(dir, p.name + '.png'), fullPage: true });
  check(requests.length === 0, `no request but the page itself (${requests.length}: ${requests.slice(0, 3).join(' ')})`);
  check(errors.length === 0, `no console error${errors.length ? ': ' + errors.slice(0, 3).join(' | ') : ''}`);
  await page.close();
}
await context.close();
fs.rmSync(userDataDir, { recursive: true, force: true });
fs.rmSync(hostileDir, { recursive: true, force: true });

timings.load_average = os.loadavg();
fs.writeFileSync(path.join(artifacts, 'live-timings.json'), JSON.stringify(timings, null, 1));

const failed = results.filter(r => !r.ok);
console.log(`\n${results.length - failed.length}/${results.length} checks passed`);
process.exit(failed.length ? 1 : 0);
