/* SPDX-License-Identifier: BSD-3-Clause */
// Checks of dynkit's HTML pages in a real browser (headless Chromium, driven by
// playwright-core): the report page (`dynkit report --html`) and an animation of every
// model of the homework (`dynkit animate`), plus models the page knows no picture for.
// For each page: no console errors, no request but the file itself, every canvas draws
// something, the picture changes as time runs, and the controls work as a person uses them
// (play/pause button, time slider, speed slider, space and arrow keys; real time at 1x).
// Each page is checked at 1280x900 and at a phone's 390x844 against the pages' conventions:
// it plays when opened (and stays paused with prefers-reduced-motion), loop off; nothing
// wider than the screen; no legend box over a drawn point or line; one unit per y axis;
// equal scales for x-y pictures in metres; a scale bar in the 3D view; the URL fragment
// (#t=..&speed=..) opens the page there and follows the player. On the report also: the
// figures of the three studies of many runs are drawn and fit the width (the period curve,
// the two histograms, the slip map with its cells, colour bar and boundary). And a sweep's
// table as a page (`dynkit plot TABLE.json --html`): a heat map and lines. A bifurcation
// diagram's page (`dynkit continue --output FILE.html`): clicking a dot of its periodic
// branch shows that orbit, whose period is the one `continue --json` gives, and which
// `dynkit run` from its first point over one period brings back to that point.
// Screenshots go to the artifacts directory (at 390 px wide with the suffix -390).
//
// Usage: node run.mjs DYNKIT_BINARY [ARTIFACTS_DIR]
// Exit status: 0 all passed, 1 a check failed, 77 skipped (no Chromium or no node_modules;
// CTest reports it as skipped). Environment: DYNKIT_CHROMIUM, the browser (default
// /usr/bin/chromium); DYNKIT_REQUIRE_BROWSER=1 fails instead of skipping.
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { check, checks, loadChromium } from './harness.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const dynkit = process.argv[2];
const artifacts = path.resolve(process.argv[3] || path.join(here, '..', '..', 'build', 'tests', 'artifacts'));

if (!dynkit || !fs.existsSync(dynkit)) {
  console.error(`usage: node run.mjs DYNKIT_BINARY [ARTIFACTS_DIR] (got '${dynkit}')`);
  process.exit(2);
}
const { chromium, chromiumPath } = await loadChromium(here);

fs.mkdirSync(artifacts, { recursive: true });
const results = checks.results;
const sleep = ms => new Promise(r => setTimeout(r, ms));

// ---- the pages ----
function run(args) {
  execFileSync(dynkit, args, { stdio: ['ignore', 'ignore', 'pipe'] });
}
const pages = [
  { name: 'report', args: ['report', '--html'], players: 4 },
  { name: 'pendulum', args: ['animate', 'pendulum', '--method', 'rk4', '--step', '0.01', '--tspan', '0:10', '--compare', 'euler:0.05'] },
  { name: 'pendulum-default', args: ['animate', 'pendulum'] },
  { name: 'vanderpol', args: ['animate', 'vanderpol', '--compare', 'euler', '--compare', 'heun:0.05', '--compare', 'dp45'] },
  { name: 'plane', args: ['animate', 'plane', '--compare', 'euler'], scene: true },
  { name: 'plane-quat', args: ['animate', 'plane-quat', '--compare', 'rk4:0.02'], scene: true },
  { name: 'cart', args: ['animate', 'cart'] },
  { name: 'long-run', args: ['animate', 'vanderpol', '--step', '0.001', '--tspan', '0:200'] },
  { name: 'robertson', args: ['animate', 'robertson'], generic: true },
  // a model file: its @ xp=, yp= phase plane (the lower mass's path) beside the time series
  // ... and its XPPAUT animation double_pendulum.ani (read beside the .ode), above them
  { name: 'double-pendulum-file', args: ['animate', path.join(here, '..', '..', 'examples', 'models', 'double_pendulum.ode')], ani: { ratio: 1, comet: true } },
  { name: 'double-pendulum-no-ani', args: ['animate', path.join(here, '..', '..', 'examples', 'models', 'double_pendulum.ode'), '--no-ani'], ani: false },
  { name: 'pendulum-file-ani', args: ['animate', path.join(here, '..', '..', 'examples', 'models', 'pendulum.ode'), '--compare', 'euler:0.05'], ani: { ratio: 1 } },
  // mechanism files drawn from their geometry: the top in 3D (the scale bar, the orbit), the
  // four-bar in its plane on equal scales, with its constraint forces as arrows
  { name: 'mech-top', args: ['animate', path.join(here, '..', '..', 'examples', 'mechanisms', 'top.mech')], scene: true, mech: '3d' },
  { name: 'mech-fourbar', args: ['animate', path.join(here, '..', '..', 'examples', 'mechanisms', 'fourbar.mech')], mech: '2d', read: /loop_x = -?[0-9]/, arrows: /^arrows: 1 m = [0-9.]+ N, none below [0-9.e+-]+ N$/ },
  // a bead on a rail along gravity: the rail's force is rounding (1e-10 N), not drawn
  { name: 'mech-rail', args: ['animate', path.join(here, 'rail.mech')], mech: '2d', read: /rail = -?[0-9]/, arrows: /^arrows: none, all below 9\.8e-9 N \(1e-9 m g\)$/ },
  // a model in milliseconds with an XPPAUT window, mV against a unitless gate
  { name: 'morris-lecar', args: ['animate', path.join(here, 'morris_lecar.ode')] },
];
// XPPAUT's own pend2.ani (text, settext, the symbol font, a colour formula), when Debian's
// xppaut examples are installed
const xppExamples = '/usr/share/doc/xppaut/examples/ode';
if (fs.existsSync(path.join(xppExamples, 'pend2.ani')))
  pages.push({ name: 'xppaut-pend2', args: ['animate', path.join(xppExamples, 'pend.ode'), '--ani', path.join(xppExamples, 'pend2.ani')], ani: { ratio: 1 } });
// DYNKIT_BROWSER_ONLY=NAME,NAME: only these pages (while working on them)
if (process.env.DYNKIT_BROWSER_ONLY) {
  const only = process.env.DYNKIT_BROWSER_ONLY.split(',');
  pages.splice(0, pages.length, ...pages.filter(p => only.includes(p.name)));
}
for (const p of pages) {
  p.file = path.join(artifacts, `${p.name}.html`);
  const args = p.args.slice();
  if (args[0] === 'report') args.push(p.file); else args.push('--output', p.file);
  run(args);
}
// a model without a picture: the van der Pol page with the model renamed
if (pages.some(p => p.name === 'vanderpol')) {
  const text = fs.readFileSync(path.join(artifacts, 'vanderpol.html'), 'utf8');
  const file = path.join(artifacts, 'generic.html');
  fs.writeFileSync(file, text.replace('"name":"vanderpol"', '"name":"my-oscillator"'));
  pages.push({ name: 'generic', file, generic: true });
}

// a sweep's table as a page (dynkit plot TABLE.json --html, axes with units): a heat map and lines
const sweepPages = [];
if (!process.env.DYNKIT_BROWSER_ONLY || process.env.DYNKIT_BROWSER_ONLY.split(',').includes('sweep')) {
  const grid = path.join(artifacts, 'sweep-grid.json');
  run(['sweep', 'pendulum', '--method', 'rk4', '--step', '0.01', '--tspan', '0:10', '--vary', 'l=1:10:10',
    '--vary', 'dphi=0.5:2.5:12', '--reduce', 'max:height,count:bottom', '--output', grid]);
  sweepPages.push({ name: 'sweep-heat', runs: 120, heat: true, args: ['plot', grid, '--y', 'max_height', '--html'] },
    { name: 'sweep-lines', runs: 120, lines: 10, args: ['plot', grid, '--x', 'dphi', '--y', 'count_bottom', '--html'] });
  for (const p of sweepPages) {
    p.file = path.join(artifacts, `${p.name}.html`);
    run(p.args.concat(p.file));
  }
}

// the phase plane as a page (dynkit plot MODEL --phase-plane --html): van der Pol's, with its
// one equilibrium, an unstable focus, in the table
const phasePages = [];
if (!process.env.DYNKIT_BROWSER_ONLY || process.env.DYNKIT_BROWSER_ONLY.split(',').includes('phase')) {
  const p = { name: 'phase-vanderpol', file: path.join(artifacts, 'phase-vanderpol.html') };
  run(['plot', 'vanderpol', '--phase-plane', '--html', p.file]);
  phasePages.push(p);
}

// the bifurcation diagram as a page (dynkit continue MODEL --par NAME --output FILE.html): the
// Brusselator's Hopf point at b = 2 and its branch of periodic orbits, with --json beside it
const diagramPages = [];
if (!process.env.DYNKIT_BROWSER_ONLY || process.env.DYNKIT_BROWSER_ONLY.split(',').includes('diagram')) {
  const model = path.join(here, '..', '..', 'examples', 'models', 'brusselator.ode');
  const p = { name: 'diagram-brusselator', model, par: 'b', file: path.join(artifacts, 'diagram-brusselator.html') };
  run(['continue', model, '--par', 'b', '--output', p.file]);
  p.json = JSON.parse(execFileSync(dynkit, ['continue', model, '--par', 'b', '--json'], { encoding: 'utf8' }));
  diagramPages.push(p);
}

// ---- the browser ----
const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'dynkit-chromium-'));
const context = await chromium.launchPersistentContext(userDataDir, {
  executablePath: chromiumPath,
  headless: true,
  viewport: { width: 1280, height: 900 },
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});

// In the page: a fingerprint of each canvas (how many pixels are not the background, and a
// hash of the pixels), so that "draws something" and "changes" can be checked.
function canvasPrints() {
  return [...document.querySelectorAll('canvas')].map(c => {
    const ctx = c.getContext('2d');
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    let ink = 0, hash = 0;
    for (let i = 0; i < d.length; i += 4) {
      const lum = d[i] + d[i + 1] + d[i + 2];
      if (lum < 720) ink++;
      hash = (hash * 31 + d[i] * 3 + d[i + 1] * 5 + d[i + 2] * 7) | 0;
    }
    return { ink, hash, w: c.width, h: c.height, pixels: d.length / 4 };
  });
}
const playerState = (page, i = 0) => page.evaluate(i => {
  const p = document.querySelectorAll('.player')[i], q = window.DK && DK.players ? DK.players[i] : null;
  return { t: parseFloat(p.dataset.time), speed: parseFloat(p.dataset.speed), rate: parseFloat(p.dataset.rate || '1'), playing: p.dataset.playing === '1',
    autoStart: q && q.started ? q.autoStart : null, end: q ? q.t1 : NaN };
}, i);

// The two screens every page is checked on: a desktop's and a phone's (full: every control).
const viewports = [
  { width: 1280, height: 900, suffix: '', full: true },
  { width: 390, height: 844, suffix: '-390', full: false },
];

// In the page: every plot's legend box against every drawn point and line of its series
// (from plot.js's debug hook), its units and scales; the 3D view's legend and scale bar.
function pictureFacts() {
  const hits = (ax, ay, bx, by, b) => {
    if (Math.max(ax, bx) < b.x || Math.min(ax, bx) > b.x + b.w || Math.max(ay, by) < b.y || Math.min(ay, by) > b.y + b.h) return false;
    // sample the segment finely enough (half a pixel)
    const n = Math.max(1, Math.ceil(2 * Math.hypot(bx - ax, by - ay)));
    for (let k = 0; k <= n; k++) {
      const x = ax + (bx - ax) * k / n, y = ay + (by - ay) * k / n;
      if (x >= b.x && x <= b.x + b.w && y >= b.y && y <= b.y + b.h) return true;
    }
    return false;
  };
  const plots = [...document.querySelectorAll('canvas.plot-canvas')].map(c => {
    const d = c.dkPlot.debug(), title = c.dkPlot.o.title || '?';
    let covered = 0, inCanvas = true;
    const b = d.legend;
    if (b) {
      inCanvas = b.x >= 0 && b.y >= 0 && b.x + b.w <= c.clientWidth + 0.5 && b.y + b.h <= c.clientHeight + 0.5;
      d.points.forEach((pts, i) => {
        const r = d.markers[i];
        for (let k = 0; k < pts.length; k++) {
          const p = pts[k], q = k > 0 ? pts[k - 1] : null;
          if (!p) continue;
          if (p[0] >= b.x - r && p[0] <= b.x + b.w + r && p[1] >= b.y - r && p[1] <= b.y + b.h + r) covered++;
          else if (q && hits(q[0], q[1], p[0], p[1], b)) covered++;
        }
      });
    }
    return { title, legend: b ? b.corner : 'none', covered, inCanvas, units: d.units, xunit: d.xunit, yunit: d.yunit, log: d.logx || d.logy, equal: d.equal, sx: d.sx, sy: d.sy };
  });
  const scene = document.querySelector('.dk-scene canvas.scene-canvas');
  let scale = null, legendOnScene = false;
  if (scene) {
    scale = { label: scene.dataset.scaleLabel || '', m: parseFloat(scene.dataset.scaleM), px: parseFloat(scene.dataset.scalePx) };
    const r = scene.getBoundingClientRect();
    for (const l of document.querySelectorAll('.dk-legend')) {
      const q = l.getBoundingClientRect();
      if (q.right > r.left && q.left < r.right && q.bottom > r.top && q.top < r.bottom) legendOnScene = true;
    }
  }
  return { plots, scale, legendOnScene };
}
const overflow = page => page.evaluate(() => ({ sw: document.documentElement.scrollWidth, iw: innerWidth }));

// The conventions of the pages (see the top of the file); s: the player's span [t0, t1].
async function checkConventions(page, spec, vp, url, span) {
  const f = await page.evaluate(pictureFacts);
  const covering = f.plots.filter(p => p.covered > 0 || !p.inCanvas);
  check(covering.length === 0, `no legend covers data (${f.plots.length} plots; legends ${f.plots.map(p => p.legend).join(',')})${covering.map(p => ` | "${p.title}" ${p.legend}: ${p.covered} points`).join('')}`);
  const mixed = f.plots.filter(p => p.units.length > 1 || (p.units.length === 1 && p.units[0] !== p.yunit));
  check(mixed.length === 0, `one unit per y axis${mixed.map(p => ` | "${p.title}": ${p.units.join(', ')} on [${p.yunit}]`).join('')}`);
  const paths = f.plots.filter(p => p.xunit === 'm' && p.yunit === 'm' && !p.log);
  const unequal = paths.filter(p => !p.equal || Math.abs(p.sx - p.sy) > 1e-6 * p.sx);
  check(unequal.length === 0, `equal scales on the ${paths.length} x-y pictures in metres${unequal.map(p => ` | "${p.title}": ${p.sx} px/m across, ${p.sy} up`).join('')}`);
  if (spec.scene) {
    check(f.scale && /^[0-9.e-]+ m$/.test(f.scale.label) && f.scale.px >= 40 && f.scale.px <= 200, `the 3D view has a scale bar (${f.scale && f.scale.label}, ${f.scale && f.scale.px.toFixed(0)} px)`);
    check(!f.legendOnScene, 'the 3D view\'s legend is beside the picture, not on it');
  }
  const o = await overflow(page);
  check(o.sw <= o.iw, `no sideways scrolling (${o.sw} px wide in ${o.iw})`);

  // the fragment: open the page at a time and speed, with reduced motion (paused there)
  const i = spec.players ? 2 : 0; // on the report: problem 3's player
  const key = spec.players ? 'p3&' : '';
  const tA = Number((span[0] + 0.37 * (span[1] - span[0])).toPrecision(5));
  const calm = await context.newPage();
  await calm.setViewportSize({ width: vp.width, height: vp.height });
  await calm.emulateMedia({ reducedMotion: 'reduce' });
  await calm.goto(`${url}#${key}t=${tA}&speed=0.5`);
  await calm.waitForSelector('body[data-ready="1"]', { timeout: 10000 }).catch(() => {});
  await sleep(400);
  const c = await playerState(calm, i);
  const span2 = await calm.evaluate(i => { const p = DK.players[i]; return [p.t0, p.t1]; }, i);
  const tA2 = Math.min(Math.max(tA, span2[0]), span2[1]);
  check(!c.playing && Math.abs(c.t - tA2) < 1e-9 * Math.max(1, Math.abs(tA2)) && c.speed === 0.5, `#${key}t=${tA}&speed=0.5 with reduced motion: paused there at 0.5x (t = ${c.t}, speed ${c.speed}, ${c.playing ? 'playing' : 'paused'})`);
  check(!(await calm.evaluate(i => document.querySelectorAll('.player input.loop')[i].checked, i)), 'loop is off');
  // the fragment follows the player: a second on, by the keys
  const pl = calm.locator('.player').nth(i);
  await pl.scrollIntoViewIfNeeded();
  await pl.focus();
  await calm.keyboard.press('Shift+ArrowRight');
  await sleep(300);
  const moved = await playerState(calm, i);
  const hash = await calm.evaluate(() => location.hash);
  const want = '#' + key + 't=' + Number(moved.t.toPrecision(6)) + '&speed=0.5';
  check(hash === want, `the fragment follows the player (${hash}, want ${want})`);
  const shared = await calm.evaluate(() => location.href);
  await calm.close();
  // opening the shared address (motion allowed) starts there and plays
  const again = await context.newPage();
  await again.setViewportSize({ width: vp.width, height: vp.height });
  await again.goto(shared);
  await again.waitForSelector('body[data-ready="1"]', { timeout: 10000 }).catch(() => {});
  const a = await playerState(again, i);
  const tB = Number(moved.t.toPrecision(6));
  /* where it started playing (on a loaded machine it may have played to the end before
     this read) */
  const from = a.autoStart === null ? a.t : a.autoStart;
  check(Math.abs(from - tB) <= 1e-9 * Math.max(1, tB) && a.t >= from && a.speed === 0.5, `the shared address opens at t = ${tB}, 0.5x (started at ${from}, now t = ${a.t}, speed ${a.speed})`);
  await again.close();
}

async function checkPage(spec, vp) {
  checks.current = `${spec.name} @${vp.width}`;
  const shot = name => path.join(artifacts, `${spec.name}${vp.suffix}-${name}.png`);
  const page = await context.newPage();
  await page.setViewportSize({ width: vp.width, height: vp.height });
  const errors = [], requests = [];
  const url = pathToFileURL(spec.file).href;
  page.on('console', m => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', e => errors.push(String(e)));
  await page.route('**/*', route => {
    const u = route.request().url();
    if (u === url) return route.continue();
    requests.push(u);
    return route.abort();
  });
  const t0 = Date.now();
  await page.goto(url, { waitUntil: 'load' });
  await page.waitForSelector('body[data-ready="1"]', { timeout: 10000 }).catch(() => {});
  const openMs = Date.now() - t0;
  const size = fs.statSync(spec.file).size;
  check(await page.evaluate(() => document.body.dataset.ready === '1'), `the page builds (${(size / 1024).toFixed(0)} KiB, open in ${openMs} ms)`);
  // a bound that catches a page gone slow (seconds of script), not the machine's load:
  // headless Chromium opens the report in about 0.3 s on an idle machine
  check(openMs < 8000, `opens in a few seconds at most (${openMs} ms)`);
  const html = fs.readFileSync(spec.file, 'utf8');
  check(!/https?:\/\//.test(html), 'no http(s):// reference in the file');

  // it plays when opened (once its picture shows), without a click
  await page.locator('canvas').first().scrollIntoViewIfNeeded();
  const auto0 = await playerState(page);
  await sleep(700);
  const auto1 = await playerState(page);
  /* playing and moving, or (a short run on a loaded machine) started by itself and
     played to its end before the first look */
  const ended = auto1.autoStart !== null && !auto1.playing && auto1.t >= auto1.end && auto1.autoStart < auto1.end;
  check(((auto1.playing && auto1.t > auto0.t) || ended) && auto1.speed === 1, `plays when opened, at 1x (t ${auto0.t.toFixed(3)} -> ${auto1.t.toFixed(3)}${ended ? `, played from ${auto1.autoStart} to its end` : ''})`);
  // paused from the page: a click can take longer than a short run has left (the button is
  // checked below)
  // and put at their start, so that the seek below always lands on another time (paused late
  // on a loaded machine, a player could stop near 60% of its span)
  await page.evaluate(() => DK.players.forEach(p => { p.pause(); p.seek(p.t0); }));

  if (spec.name === 'cart') {
    // the whole path at equal scales: the frame takes the path's shape, so that neither axis
    // spans more than 1.6 times the path's extent on it (not 24 m beside a 4 m path)
    const v = await page.evaluate(() => {
      const c = [...document.querySelectorAll('canvas.plot-canvas')].find(c => c.dkPlot.o.title === 'cart, seen from above');
      const sel = document.querySelector('select.view-mode'); sel.value = '-1'; c.dkPlot.draw();
      const p = c.dkPlot, e = [DK.extent(p.o.series.map(s => s.x)), DK.extent(p.o.series.map(s => s.y))];
      return { xr: p.xr, yr: p.yr, e };
    });
    const fx = (v.xr[1] - v.xr[0]) / (v.e[0][1] - v.e[0][0]), fy = (v.yr[1] - v.yr[0]) / (v.e[1][1] - v.e[1][0]);
    check(Math.min(fx, fy) < 1.6, `the whole path fills its frame (X ${(v.xr[1] - v.xr[0]).toFixed(1)} m for ${(v.e[0][1] - v.e[0][0]).toFixed(1)} m, Y ${(v.yr[1] - v.yr[0]).toFixed(1)} m for ${(v.e[1][1] - v.e[1][0]).toFixed(1)} m)`);
  }
  if (spec.name === 'morris-lecar') {
    // mV against a unitless gate: no equal scales, XPPAUT's window @ xlo..yhi
    const v = await page.evaluate(() => { const c = [...document.querySelectorAll('canvas.plot-canvas')].find(c => c.dkPlot.o.title === 'phase plane'); return { xr: c.dkPlot.xr, yr: c.dkPlot.yr, eq: !!c.dkPlot.o.equal }; });
    check(!v.eq && Math.abs(v.xr[0] + 75) < 1e-9 && Math.abs(v.xr[1] - 45) < 1e-9 && Math.abs(v.yr[1] - 0.6) < 1e-9, `the phase plane is XPPAUT's window, not equal scales (x ${v.xr}, y ${v.yr})`);
    const t = await page.evaluate(() => document.querySelector('.player output.now, .player output').textContent);
    check(/ms/.test(t), `the player counts in ms (${t})`);
  }

  // every canvas draws something
  const prints0 = await page.evaluate(canvasPrints);
  check(prints0.length > 0, `${prints0.length} canvases`);
  const blank = prints0.filter(p => p.ink < 0.002 * p.pixels);
  check(blank.length === 0, `every canvas draws something (${blank.length} blank)`);

  if (spec.ani !== undefined) {
    // the XPPAUT animation: one canvas above the other pictures, with the window's aspect,
    // changing with the time (and a comet's tail growing from nothing at the start)
    const n = await page.locator('canvas.ani-canvas').count();
    check(n === (spec.ani ? 1 : 0), spec.ani ? 'the .ani animation is shown' : '--no-ani: no animation');
    if (spec.ani) {
      const first = await page.evaluate(() => document.querySelector('canvas') === document.querySelector('canvas.ani-canvas'));
      check(first, 'the animation comes first, above the other pictures');
      const dims = await page.evaluate(() => { const c = document.querySelector('canvas.ani-canvas'); return [c.clientWidth, c.clientHeight]; });
      check(Math.abs(dims[0] / dims[1] - spec.ani.ratio) < 0.02, `equal scales: the canvas has the window's aspect (${dims[0]} x ${dims[1]})`);
      const aniPrint = () => page.evaluate(() => {
        const c = document.querySelector('canvas.ani-canvas'), d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        let ink = 0, hash = 0;
        for (let i = 0; i < d.length; i += 4) { if (d[i] + d[i + 1] + d[i + 2] < 720) ink++; hash = (hash * 31 + d[i] * 3 + d[i + 1] * 5 + d[i + 2] * 7) | 0; }
        return { ink, hash };
      });
      const seek = f => page.evaluate(f => { const p = DK.players[0]; p.seek(p.t0 + f * (p.t1 - p.t0)); }, f);
      await seek(0);
      const a0 = await aniPrint();
      await seek(0.3);
      const a1 = await aniPrint();
      await seek(0.31);
      const a2 = await aniPrint();
      check(a0.hash !== a1.hash && a1.hash !== a2.hash, 'the animation changes as the time runs');
      if (spec.ani.comet) check(a1.ink > a0.ink * 1.2, `the comet's tail grows (ink ${a0.ink} at the start, ${a1.ink} later)`);
      await page.locator('canvas.ani-canvas').screenshot({ path: shot('ani') });
      await seek(0);
    }
  }

  if (spec.generic) {
    check(await page.evaluate(() => document.body.classList.contains('no-picture')), 'a model without a picture gets the time series only');
  }
  if (spec.mech) {
    const m = await page.evaluate(() => { const v = document.getElementById('view'); return { view: v && v.dataset.mechView, arrows: v && v.dataset.mechArrows, read: (document.querySelector('.mech-readouts') || {}).textContent || '' }; });
    check(m.view === spec.mech, `the mechanism is drawn in ${spec.mech} (${m.view})`);
    if (spec.arrows) check(spec.arrows.test(m.arrows || ''), `the arrows' legend says which forces are drawn ('${m.arrows}')`);
    if (spec.read) check(spec.read.test(m.read) && / N/.test(m.read), `the constraint forces are read out with their unit ('${m.read}')`);
  }

  // controls of the first player: button, slider, keys, speed
  const player = page.locator('.player').first();
  const play = player.locator('button.play');
  const slider = player.locator('input.time');
  await page.screenshot({ path: shot('start') });
  if (!vp.full) await page.screenshot({ path: shot('page'), fullPage: !spec.players });

  let s = await playerState(page);
  await slider.scrollIntoViewIfNeeded();
  // the slider moves the time
  const box = await slider.boundingBox();
  await page.mouse.click(box.x + box.width * 0.6, box.y + box.height / 2);
  s = await playerState(page);
  const span = await page.evaluate(() => { const i = document.querySelector('.player input.time'); return [parseFloat(i.min), parseFloat(i.max)]; });
  const frac = (s.t - span[0]) / (span[1] - span[0]);
  check(frac > 0.45 && frac < 0.75, `clicking the time slider at 60% seeks there (t = ${s.t.toFixed(3)}, ${(frac * 100).toFixed(0)}%)`);
  const prints1 = await page.evaluate(canvasPrints);
  const changed = prints1.filter((p, i) => p.hash !== prints0[i].hash).length;
  check(changed >= 1, `the picture changes with the time (${changed} of ${prints1.length} canvases)`);
  // play in real time
  await page.mouse.click(box.x + 2, box.y + box.height / 2); // back to the start
  await play.click();
  // the rate by the page's own frame clock (the time stamp of the frame that set the time):
  // a loaded machine delays the click and these reads, not the player's clock
  const frameMark = () => page.evaluate(() => { const p = DK.players[0]; return { t: p.t, at: p.last }; });
  await sleep(100);
  const m0 = await frameMark();
  await sleep(vp.full ? 1200 : 400);
  const m1 = await frameMark();
  s = await playerState(page);
  check(s.playing || s.t >= span[1], 'the play button starts playing');
  const wall = (m1.at - m0.at) / 1000;
  const rate = (m1.t - m0.t) / wall;
  // 1x: one second per second, or the page's own rate (a run too long or not in seconds
  // plays in 20 s: data-rate model time per second)
  const expectRate = Math.min(s.rate, (span[1] - m0.t) / wall);
  if (vp.full) check(Math.abs(rate - expectRate) < 0.35 * Math.max(expectRate, 0.05 * s.rate) + 0.05 * s.rate, `plays at its rate at 1x (${rate.toFixed(2)} per s, 1x = ${s.rate} per s)`);
  const prints2 = await page.evaluate(canvasPrints);
  check(prints2.some((p, i) => p.hash !== prints1[i].hash), 'the picture moves while playing');
  await page.screenshot({ path: shot('playing'), fullPage: false });
  if (s.playing) {
    /* a click that comes just after the run reached its end starts it again from the
       start: then a second click pauses */
    for (let k = 0; k < 2; k++) {
      await play.click();
      s = await playerState(page);
      if (!s.playing) break;
    }
    check(!s.playing, 'the button pauses');
  } else {
    check(s.t >= span[1] - 1e-9, `the run ended and stopped there (t = ${s.t})`);
  }
  // keys: space, arrows (slowly, so that a short run does not end meanwhile); on the
  // desktop's screen only: they do not depend on its size
  if (vp.full) {
  await player.focus();
  await page.keyboard.press('Home');
  for (let k = 0; k < 4; k++) await page.keyboard.press('ArrowDown');
  check(Math.abs((await playerState(page)).speed - 0.1) < 1e-9, 'down arrows slow down to 0.1x, no further');
  const tPaused = (await playerState(page)).t;
  await page.keyboard.press('Space');
  check((await playerState(page)).playing, 'space plays');
  await sleep(200);
  await page.keyboard.press('Space');
  s = await playerState(page);
  check(!s.playing && s.t > tPaused, `space pauses again (t = ${s.t.toFixed(4)})`);
  await page.keyboard.press('Home');
  s = await playerState(page);
  check(Math.abs(s.t - span[0]) < 1e-9, 'home goes to the start');
  await page.keyboard.press('ArrowRight');
  const s1 = await playerState(page);
  check(s1.t > s.t, `right arrow steps one sample (${s.t} -> ${s1.t})`);
  await page.keyboard.press('ArrowLeft');
  check(Math.abs((await playerState(page)).t - s.t) < 1e-12, 'left arrow steps back');
  await page.keyboard.press('ArrowRight');
  await page.keyboard.press('ArrowRight');
  const s2 = await playerState(page);
  check(s2.t > s1.t || s2.t >= span[1] - 1e-12, `right arrow again steps on (${s1.t} -> ${s2.t})`);
  for (let k = 0; k < 4; k++) await page.keyboard.press('ArrowUp');
  check(Math.abs((await playerState(page)).speed - 1.6) < 1e-9, 'up arrows double the speed');
  await page.keyboard.press('ArrowDown');
  await page.keyboard.press('ArrowDown');
  check(Math.abs((await playerState(page)).speed - 0.4) < 1e-9, 'down arrows halve it');
  await page.keyboard.press('Shift+ArrowRight');
  s = await playerState(page);
  check(Math.abs(s.t - Math.min(s2.t + 1, span[1])) < 1e-9, `shift+right seeks one second (t = ${s.t})`);
  // the speed slider: its ends are 0.1x and 10x
  const speed = player.locator('input.speed');
  const sb = await speed.boundingBox();
  await page.mouse.click(sb.x + sb.width - 1, sb.y + sb.height / 2);
  const fast = (await playerState(page)).speed;
  await page.mouse.click(sb.x + 1, sb.y + sb.height / 2);
  const slow = (await playerState(page)).speed;
  check(fast > 8 && fast <= 10 && slow >= 0.1 && slow < 0.13, `the speed slider spans 0.1x to 10x (${slow.toFixed(3)} .. ${fast.toFixed(2)})`);
  await page.keyboard.press('Home');
  await page.mouse.click(sb.x + sb.width - 1, sb.y + sb.height / 2);
  await play.click();
  const w0 = Date.now();
  const a = (await playerState(page)).t;
  await sleep(500);
  const b = await playerState(page);
  await page.keyboard.press('Home'); /* pauses (a click could restart a run that just ended) */
  const fastRate = (b.t - a) / ((Date.now() - w0) / 1000);
  check(fastRate > 3 * b.rate || b.t >= span[1] - 1e-9, `at 10x the time runs faster (${fastRate.toFixed(2)} s per s)`);
  }

  if (spec.scene) {
    // the 3D view turns with the mouse and zooms with the wheel
    const canvas = page.locator('.dk-scene canvas');
    const cb = await canvas.boundingBox();
    const before = (await page.evaluate(canvasPrints))[0].hash;
    await page.mouse.move(cb.x + cb.width / 2, cb.y + cb.height / 2);
    await page.mouse.down();
    await page.mouse.move(cb.x + cb.width / 2 + 120, cb.y + cb.height / 2 + 30, { steps: 6 });
    await page.mouse.up();
    const turned = (await page.evaluate(canvasPrints))[0].hash;
    check(turned !== before, 'dragging turns the 3D view');
    const bar0 = await page.evaluate(() => parseFloat(document.querySelector('.dk-scene canvas').dataset.scalePx) / parseFloat(document.querySelector('.dk-scene canvas').dataset.scaleM));
    await page.mouse.wheel(0, -400);
    await sleep(100);
    const zoomed = (await page.evaluate(canvasPrints))[0].hash;
    check(zoomed !== turned, 'the wheel zooms the 3D view');
    const bar1 = await page.evaluate(() => parseFloat(document.querySelector('.dk-scene canvas').dataset.scalePx) / parseFloat(document.querySelector('.dk-scene canvas').dataset.scaleM));
    check(bar1 > bar0 * 1.1, `the scale bar follows the zoom (${bar0.toFixed(1)} -> ${bar1.toFixed(1)} px per m)`);
    await page.screenshot({ path: shot('turned') });
  }
  if (spec.players) {
    const n = await page.locator('.player').count();
    check(n === spec.players, `${n} players (one per problem)`);
    for (let i = 1; i < n; i++) {
      const p = page.locator('.player').nth(i);
      await p.scrollIntoViewIfNeeded();
      const before = await page.evaluate(canvasPrints);
      const tb = await p.locator('input.time').boundingBox();
      await page.mouse.click(tb.x + tb.width * 0.5, tb.y + tb.height / 2);
      const st = await playerState(page, i);
      const after = await page.evaluate(canvasPrints);
      check(st.t > 0 && after.some((q, k) => q.hash !== before[k].hash), `player ${i + 1} moves its pictures (t = ${st.t.toFixed(2)})`);
      // (it may be playing already: it starts when its animation shows)
      const was = (await playerState(page, i)).playing;
      await page.keyboard.press('Space');
      await sleep(300);
      check((await playerState(page, i)).playing !== was, `space plays or pauses player ${i + 1}, the one used last`);
      await page.keyboard.press('Space');
    }
    // the numbers of the answers are those of `dynkit report --json`
    const json = JSON.parse(execFileSync(dynkit, ['report', '--json']).toString());
    const shown = await page.evaluate(() => JSON.parse(document.getElementById('dynkit-data').textContent).report);
    const keys = ['pendulum.max_height_m', 'vanderpol.rk4', 'plane.distance_m', 'plane.principal_angle_rad', 'cart.max_constraint_force_N',
      'studies.period.max_difference_s', 'studies.plane.distance_percentiles_m', 'studies.cart.boundary_f_Hz'];
    check(keys.every(k => JSON.stringify(shown[k]) === JSON.stringify(json[k])), 'the page carries the numbers of report --json');
    const text = await page.evaluate(() => document.querySelector('#p3 .answer').textContent);
    check(text.includes(json['plane.distance_m'].toFixed(6)), `the plane's distance is shown (${text})`);
    const missing = await page.evaluate(() => [...document.querySelectorAll('[data-key]')].filter(e => !e.textContent || e.textContent === '?').length);
    check(missing === 0, `every answer is filled in (${missing} empty)`);
    // the three studies of many runs: their figures exist, draw and fit the width (a phone's too)
    const studies = await page.evaluate(() => ['pendulum-period', 'plane-hist-distance', 'plane-hist-angle', 'cart-slip-map'].map(name => {
      const f = document.querySelector(`[data-fig="${name}"]`), c = f && f.querySelector('canvas.plot-canvas');
      const r = f && f.getBoundingClientRect(), p = c && c.dkPlot.debug();
      return { name, ok: !!c, right: r ? r.right : Infinity, left: r ? r.left : -1, width: c ? c.clientWidth : 0,
        points: p ? p.points.map(s => s.filter(q => q).length) : [], cells: c ? Number(c.dataset.heatCells || 0) : 0,
        bar: !!(f && f.querySelector('canvas.dk-colorbar')) };
    }));
    for (const f of studies)
      check(f.ok && f.left >= 0 && f.right <= vp.width && f.width >= 200, `study figure ${f.name} is drawn and fits (${f.left.toFixed(0)}..${f.right.toFixed(0)} px of ${vp.width})`);
    const period = studies[0], map = studies[3];
    check(period.points[0] === json['studies.period.runs'] && period.points[1] === json['studies.period.runs'], `the period curve: exact and swept, ${period.points.join(' and ')} points`);
    check(map.cells === json['studies.cart.runs'] && map.bar, `the slip map: ${map.cells} cells and a colour bar`);
    check(map.points[0] >= 2, `the slip boundary (ratio = 1) is drawn (${map.points[0]} points)`);
    // the pendulum's conserved energy is drawn clear of the frame, not along its bottom
    const gap = await page.evaluate(() => {
      const c = [...document.querySelectorAll('#p1 canvas.plot-canvas')].find(c => c.dkPlot.o.title === 'energy');
      const p = c.dkPlot, e = DK.extent([p.o.series[0].y]);
      return Math.min(e[0] - p.yr[0], p.yr[1] - e[1]) / (p.yr[1] - p.yr[0]);
    });
    check(gap > 0.08, `the constant energy lies clear of the frame (${(100 * gap).toFixed(1)} % of the height)`);
    // the section links: each on one line (none broken at 390 px); the text report wraps
    // rather than scrolling sideways
    const toc = await page.evaluate(() => [...document.querySelectorAll('.toc a')].filter(a => a.getClientRects().length !== 1 || a.getBoundingClientRect().height > 30).map(a => a.textContent));
    check(toc.length === 0, `every section link is on one line (broken: ${toc.join(', ') || 'none'})`);
    const pre = await page.evaluate(() => { const d = document.querySelector('#report-text').closest('details'); d.open = true; const e = document.getElementById('report-text'); return [e.scrollWidth, e.clientWidth]; });
    if (!vp.full) check(pre[0] <= pre[1] + 1, `the text report does not scroll sideways (${pre[0]} of ${pre[1]} px)`);
    for (const id of ['p1', 'p2', 'p3', 'p4']) {
      await page.locator('#' + id).screenshot({ path: path.join(artifacts, `report${vp.suffix}-${id}.png`) });
    }
  }
  await page.keyboard.press('Home');
  await checkConventions(page, spec, vp, url, span);
  check(errors.length === 0, `no console errors${errors.length ? ': ' + errors.join(' | ') : ''}`);
  check(requests.length === 0, `no network requests${requests.length ? ': ' + requests.join(', ') : ''}`);
  await page.close();
}

// A page of the simpler kinds (a sweep's table, a phase plane, a bifurcation diagram) opened
// for its checks: console errors and requests recorded (every request but the file itself
// aborted), and built (body[data-ready]).
async function openPage(spec, vp) {
  checks.current = `${spec.name} @${vp.width}`;
  const page = await context.newPage();
  await page.setViewportSize({ width: vp.width, height: vp.height });
  const errors = [], requests = [], url = pathToFileURL(spec.file).href;
  page.on('console', m => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', e => errors.push(String(e)));
  await page.route('**/*', route => { if (route.request().url() === url) return route.continue(); requests.push(route.request().url()); return route.abort(); });
  await page.goto(url, { waitUntil: 'load' });
  await page.waitForSelector('body[data-ready="1"]', { timeout: 10000 }).catch(() => {});
  check(await page.evaluate(() => document.body.dataset.ready === '1'), 'the page builds');
  return { page, errors, requests };
}

// ... and closed: no sideways scrolling, a screenshot (of the whole page with fullPage), no
// console error and no request.
async function closePage(spec, vp, { page, errors, requests }, fullPage) {
  const o = await overflow(page);
  check(o.sw <= o.iw, `no sideways scrolling (${o.sw} px wide in ${o.iw})`);
  await page.screenshot({ path: path.join(artifacts, `${spec.name}${vp.suffix}.png`), fullPage });
  check(errors.length === 0, `no console errors${errors.length ? ': ' + errors.join(' | ') : ''}`);
  check(requests.length === 0, `no network requests${requests.length ? ': ' + requests.join(', ') : ''}`);
  await page.close();
}

// A sweep's page: it builds without errors or requests, its canvases draw, it fits the
// screen, and the heat map has a cell per run (the lines a line per value of the other name).
async function checkSweepPage(spec, vp) {
  const opened = await openPage(spec, vp), page = opened.page;
  const prints = await page.evaluate(canvasPrints);
  check(prints.length >= 1 && prints.every(p => p.ink > 0.002 * p.pixels), `every canvas draws something (${prints.length})`);
  const f = await page.evaluate(() => {
    const c = document.querySelector('canvas.plot-canvas'), r = c.getBoundingClientRect(), d = c.dkPlot.debug();
    return { left: r.left, right: r.right, cells: Number(c.dataset.heatCells || 0), bar: !!document.querySelector('canvas.dk-colorbar'), lines: d.points.length };
  });
  check(f.left >= 0 && f.right <= vp.width, `the picture fits (${f.left.toFixed(0)}..${f.right.toFixed(0)} px of ${vp.width})`);
  if (spec.heat) check(f.cells === spec.runs && f.bar, `a heat map of ${f.cells} cells with a colour bar`);
  if (spec.lines) check(f.lines === spec.lines, `${f.lines} lines, one per value of the other name`);
  await closePage(spec, vp, opened, false);
}

// A phase plane's page: it builds without errors or requests, its SVG is drawn within the
// screen's width (nullclines, field, trajectories), the table lists the equilibrium.
async function checkPhasePage(spec, vp) {
  const opened = await openPage(spec, vp), page = opened.page;
  const f = await page.evaluate(() => {
    const svg = document.querySelector('[data-fig="phase"] svg'), r = svg ? svg.getBoundingClientRect() : null;
    const rows = [...document.querySelectorAll('#equilibria tr')].map(tr => tr.textContent);
    return { svg: !!svg, left: r ? r.left : -1, right: r ? r.right : 1e9, height: r ? r.height : 0,
      lines: svg ? svg.querySelectorAll('polyline').length : 0, rows };
  });
  check(f.svg && f.left >= 0 && f.right <= vp.width && f.height > 100,
    `the picture fits (${f.left.toFixed(0)}..${f.right.toFixed(0)} px of ${vp.width}, ${f.height.toFixed(0)} px high)`);
  check(f.lines > 100, `nullclines, field and trajectories drawn (${f.lines} polylines)`);
  check(f.rows.length === 2 && f.rows[1].includes('unstable focus'), `the equilibria's table: ${f.rows.join(' | ')}`);
  await closePage(spec, vp, opened, true);
}

// A bifurcation diagram's page: it builds without errors or requests, its SVG fits the
// screen, and clicking near a dot of the periodic branch shows that orbit: the period in
// the panel and the end of its time axis are the period continue --json gives for that
// point, and `dynkit run` from the orbit's first node over one period comes back to it.
async function checkDiagramPage(spec, vp) {
  const opened = await openPage(spec, vp), page = opened.page;
  const f = await page.evaluate(() => {
    const svg = document.querySelector('[data-fig="diagram"] svg'), r = svg ? svg.getBoundingClientRect() : null;
    return { svg: !!svg, left: r ? r.left : -1, right: r ? r.right : 1e9, height: r ? r.height : 0,
      dashed: svg ? svg.querySelectorAll('line[stroke-dasharray]').length : 0,
      labels: svg ? [...svg.querySelectorAll('text')].map(t => t.textContent) : [],
      dots: svg ? svg.querySelectorAll('circle.dk-orbit').length : 0,
      dotPx: svg ? Math.min(...[...svg.querySelectorAll('circle.dk-orbit')].map(c => c.getBoundingClientRect().width)) : 0,
      panel: document.getElementById('orbit').hidden };
  });
  check(f.svg && f.left >= 0 && f.right <= vp.width && f.height > 100,
    `the picture fits (${f.left.toFixed(0)}..${f.right.toFixed(0)} px of ${vp.width}, ${f.height.toFixed(0)} px high)`);
  check(f.dashed > 0 && f.labels.includes('HB') && f.labels.includes('b [1]') && f.labels.includes('x [1]'),
    `unstable parts dashed (${f.dashed} segments), HB labelled, axes named with units`);
  const periodic = spec.json.branches.filter(b => b.kind === 'periodic');
  const computed = periodic.reduce((n, b) => n + b.points.length, 0);
  check(f.dots > 0 && f.panel, `${f.dots} dots on the periodic branch (${computed} orbits computed), no orbit shown before a click`);
  check(f.dotPx >= 6.9, `each dot at least 7 px across on the screen (${f.dotPx.toFixed(1)} px)`);
  /* a click a few pixels beside a dot in the middle of the branch */
  const dot = await page.evaluate(() => {
    const d = [...document.querySelectorAll('circle.dk-orbit')], c = d[Math.floor(d.length / 2)];
    c.scrollIntoView({ block: 'center' });
    const r = c.getBoundingClientRect();
    return { x: r.left + r.width / 2, y: r.top + r.height / 2, k: Number(c.dataset.orbit) };
  });
  const click = { x: dot.x + 3, y: dot.y + 2 };
  await page.mouse.click(click.x, click.y);
  await sleep(200);
  /* the dot nearest the click on the screen (on a phone a neighbour may be nearer) */
  dot.k = await page.evaluate(c => {
    let best = -1, dist = Infinity;
    for (const d of document.querySelectorAll('circle.dk-orbit')) {
      const r = d.getBoundingClientRect(), e = Math.hypot(r.left + r.width / 2 - c.x, r.top + r.height / 2 - c.y);
      if (e < dist) { dist = e; best = Number(d.dataset.orbit); }
    }
    return best;
  }, click);
  const o = await page.evaluate(() => {
    const info = document.getElementById('orbit-info'), k = Number(info.dataset.orbit);
    const data = JSON.parse(document.getElementById('dynkit-data').textContent), orbit = data.orbits[k];
    const plots = [...document.querySelectorAll('#orbit-plots canvas.plot-canvas')].map(c => c.dkPlot);
    const prof = plots.find(p => /over one period/.test(p.o.title));
    return { shown: !document.getElementById('orbit').hidden, k, period: Number(info.dataset.period), text: info.textContent,
      branch: orbit.branch, point: orbit.point, par: orbit.par, start: orbit.u.map(u => u[0]),
      amp: Math.max(...orbit.u.map(u => Math.max(...u) - Math.min(...u))),
      tEnd: prof ? prof.o.series[0].x[prof.o.series[0].x.length - 1] : NaN, plots: plots.length,
      selected: document.querySelectorAll('circle.dk-orbit.selected').length };
  });
  check(o.shown && o.k === dot.k && o.selected >= 1, `the click shows the orbit of the dot nearest to it (orbit ${o.k}, ${o.plots} plots): ${o.text}`);
  const ref = spec.json.branches.find(b => b.branch === o.branch).points[o.point - 1];
  check(Math.abs(o.period - ref.period) <= 1e-12 * ref.period && Math.abs(o.par - ref[spec.par]) <= 1e-12 * Math.abs(ref[spec.par]),
    `its period ${o.period} at ${spec.par} = ${o.par} is that of branch ${o.branch} point ${o.point} in --json (${ref.period})`);
  check(Math.abs(o.tEnd - o.period) <= 1e-9 * o.period, `the profile's time axis ends at the period (${o.tEnd})`);
  /* the orbit is periodic: a run from its first node over one period ends where it began */
  const names = spec.json.branches[0].points[0].state ? Object.keys(spec.json.branches[0].points[0].state) : [];
  const args = ['run', spec.model, '--set', `${spec.par}=${o.par}`, '--tspan', `0:${o.period}`, '--rtol', '1e-10', '--atol', '1e-12', '--final'];
  names.forEach((n, i) => args.push('--init', `${n}=${o.start[i]}`));
  const last = execFileSync(dynkit, args, { encoding: 'utf8' }).trim().split('\n').pop().split(',').map(Number).slice(1);
  const gap = Math.max(...last.map((v, i) => Math.abs(v - o.start[i])));
  check(names.length > 0 && gap <= 1e-3 * o.amp, `dynkit run over one period from the orbit's start returns within ${gap.toExponential(2)} (allowed 1e-3 of its size ${o.amp.toFixed(3)})`);
  await closePage(spec, vp, opened, true);
}

try {
  for (const vp of viewports) {
    for (const spec of diagramPages) {
      try {
        await checkDiagramPage(spec, vp);
      } catch (e) {
        check(false, `exception: ${e.stack || e}`);
      }
    }
    for (const spec of phasePages) {
      try {
        await checkPhasePage(spec, vp);
      } catch (e) {
        check(false, `exception: ${e.stack || e}`);
      }
    }
    for (const spec of sweepPages) {
      try {
        await checkSweepPage(spec, vp);
      } catch (e) {
        check(false, `exception: ${e.stack || e}`);
      }
    }
    for (const spec of pages) {
      try {
        await checkPage(spec, vp);
      } catch (e) {
        check(false, `exception: ${e.stack || e}`);
      }
    }
  }
} finally {
  await context.close();
  fs.rmSync(userDataDir, { recursive: true, force: true });
}
const failed = results.filter(r => !r.ok).length;
console.log(`\nscreenshots in ${artifacts}`);
console.log(`${results.length - failed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
