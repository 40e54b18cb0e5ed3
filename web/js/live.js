/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: live pages (`animate --live`) — the model compiled by the tool to
 * WebAssembly (data.live.module, a zlib stream in base64; its entry
 * backends/wasm/live_run.c) runs in the
 * page: a slider and a number box for every parameter and initial value, the method, step,
 * tolerances and span; every change reruns the main run, the --compare runs and the
 * trajectories started by a click in the phase plane, and redraws the animation page with
 * them; the command line that reproduces the run and a CSV download of its samples. A
 * long run runs in a worker (web/js/live_runner.js): the page stays responsive, the run is
 * drawn as it computes and a newer change cancels it; a short one on the page's thread.
 * The hook window.dynkitLive (set, get, run) serves scripts and the browser tests.
 * The module is compiled by the browser (the page's policy allows WebAssembly, no eval);
 * every name and unit reaches the page as text only. docs/web.md, "Live pages". */
'use strict';
(function (DK) {
  const MAX_ROWS = 2000;       /* samples a picture keeps (the tool's CLI_MAX_ROWS) */
  const RUN_ROWS = 5000000;    /* samples a run may have at most */
  const MAX_CLICKED = 6;       /* trajectories kept from clicks */
  /* settings of dk_live_run (live_run.c's SET_*) */
  const S = { t0: 0, t1: 1, step: 2, rtol: 3, atol: 4, end: 5, atSteps: 6, every: 7, maxRows: 8 };

  /* The range of a slider: the range the model file declares (declared: [lo, hi], lo < hi),
   * else around the value: [0, 2v] for a parameter v > 0 ([2v, 0] below 0), v +- max(|v|, 1)
   * for an initial value, [-1, 1] around 0; widened to take a typed value. */
  function rangeOf(v, isState, declared) {
    if (declared) return [Math.min(declared[0], v), Math.max(declared[1], v)];
    if (isState || v === 0) { const d = Math.max(Math.abs(v), 1); return [v - d, v + d]; }
    return v > 0 ? [0, 2 * v] : [2 * v, 0];
  }

  /* A shell word: kept as it is when plain, else in single quotes. */
  function shellWord(s) {
    return /^[A-Za-z0-9_.,:=+\-/@%]+$/.test(s) ? s : "'" + s.replace(/'/g, "'\\''") + "'";
  }

  const Runner = DK.LiveRunner;

  class Live {
    constructor(data) {
      this.localMs = undefined; /* the runner's default: how long a run on the page's thread may take */
      this.data = data;
      const L = this.L = data.live;
      this.model = data.model;
      this.params = L.params.map(p => ({ name: p.name, unit: p.unit, value: p.value, dflt: p.default }));
      this.states = L.states.map(s => ({ name: s.name, unit: s.unit, value: s.value, dflt: s.default, given: s.value !== s.default }));
      this.method = L.method;
      this.adaptive = {};
      this.methods = L.methods.map(m => m[0]);
      for (const m of L.methods) this.adaptive[m[0]] = m[1];
      this.t0 = L.t0; this.t1 = L.t1; this.step = L.step; this.rtol = L.rtol; this.atol = L.atol;
      this.atSteps = !!L.at_steps;
      this.clicked = [];
      this.timing = {};
      this.partialDraws = 0; /* drawings of a run being computed */
      this.template = document.getElementById('animate').cloneNode(true); /* the body's own markup */
      this.ready = this.instantiate();
    }

    async instantiate() {
      /* the module the tool links imports one function, dynkit.progress (live_run.c); a
       * module of every built-in model (report --html --live) runs the one of this page */
      const module = await DK.liveModule(this.L.module);
      if (this.stopped) throw Live.stopped; /* another model chosen meanwhile: no worker */
      this.runner = new Runner(module, this.data.choose);
      await this.runner.ready;
      this.cols = this.runner.cols;
    }

    /* One run's settings for the worker (live_run.c's buffers): the method, the step, the
     * span and tolerances, the parameters, the initial values and which are given. */
    job(method, step, inits) {
      const set = new Array(9).fill(0);
      set[S.t0] = this.t0; set[S.t1] = this.t1; set[S.step] = step;
      set[S.rtol] = this.rtol; set[S.atol] = this.atol; set[S.end] = this.L.end === 'grid' ? 1 : 0;
      set[S.atSteps] = this.atSteps && step === this.step ? 1 : 0; set[S.every] = this.L.every;
      set[S.maxRows] = RUN_ROWS;
      const params = this.params.length ? this.params.map(p => p.value) : [0];
      const iv = [], gv = [];
      this.states.forEach(s => {
        const own = inits && inits[s.name] !== undefined;
        iv.push(own ? inits[s.name] : s.value);
        gv.push(own || s.given ? 1 : 0);
      });
      return { method, step, settings: set, params, inits: iv, given: gv };
    }

    /* The samples a run of that step writes on the span (Infinity when it writes one at each
     * of its steps, which an adaptive method chooses). */
    expected(step, atSteps) {
      if (atSteps) return Infinity;
      return Math.floor(Math.abs(this.t1 - this.t0) / step / Math.max(1, this.L.every)) + 2;
    }

    /* A run as the page's data (cli_json_series): its columns thinned to MAX_ROWS samples. */
    asSeries(r, label, method, step) {
      const m = this.model, cols = this.cols, n = r.n;
      const names = ['t'].concat(m.states.map(s => s.name), m.outputs.map(s => s.name));
      const units = [m.time_unit || 's'].concat(m.states.map(s => s.unit), m.outputs.map(s => s.unit));
      const every = Math.max(1, Math.ceil(n / MAX_ROWS));
      const keep = [];
      for (let k = 0; k < n; k += every) keep.push(k);
      if (n > 0 && keep[keep.length - 1] !== n - 1) keep.push(n - 1);
      if (this.kept) this.kept.push({ rows: r.rows, keep }); /* for the scene, the .ani */
      const data = names.map((_, c) => keep.map(k => r.rows[k * cols + c]));
      return { label, method, method_title: '', map: false, step, samples: n, status: r.message ? 'stopped' : 'ok', message: r.message, columns: names, units, data };
    }

    label(method, step) {
      const unit = this.model.time_unit || 's';
      return this.adaptive[method] ? method + ', rtol ' + this.rtol + ', atol ' + this.atol : method + ', h = ' + step + ' ' + unit;
    }

    /* The main run, the --compare runs and the clicked trajectories, run by the worker; the
     * page drawn as a long run computes (once a frame at most) and at the end (draw false:
     * the first run, of the settings the tool's runs on the page were made with, which
     * keeps its pictures: a mechanism's scene, an .ani animation). A promise of the main
     * run; a newer rerun ends this one, whose promise then gives the newer one's. */
    rerun(draw = true) {
      const start = performance.now();
      const phase = this.phaseNames();
      const runs = [{ job: this.job(this.method, this.step), label: this.label(this.method, this.step), method: this.method, step: this.step }];
      for (const c of this.L.compare) {
        const step = c.step > 0 ? c.step : this.step;
        runs.push({ job: this.job(c.method, step), label: this.label(c.method, step), method: c.method, step });
      }
      for (const p of this.clicked)
        runs.push({ job: this.job(this.method, this.step, p), label: 'from ' + phase.map(nm => nm + ' = ' + DK.fmt(p[nm], 4)).join(', '), method: this.method, step: this.step });
      /* the runs as the page's data: those begun (2 samples at least) */
      const series = results => {
        this.kept = []; /* the rows of the runs drawn, for the scene, the .ani */
        return runs.map((r, i) => results[i] && results[i].n > 1 ? this.asSeries(results[i], r.label, r.method, r.step) : null).filter(Boolean);
      };
      let partial = null;
      const onRows = draw ? acc => {
        partial = acc;
        if (this.frame) return;
        this.frame = requestAnimationFrame(() => {
          this.frame = 0;
          if (this.current !== promise || !partial || !partial[0] || partial[0].n < 2) return;
          this.redraw(series(partial.map(a => a && { rows: a.rows, n: a.n, message: '' })), true);
          this.partialDraws++;
        });
      } : null;
      const samples = runs.reduce((a, r) => a + this.expected(r.step, r.job.settings[S.atSteps] && this.adaptive[r.method]), 0);
      const promise = this.current = this.runner.run(runs.map(r => r.job), onRows, { samples, localMs: this.localMs }).then(results => {
        const main = this.last = results[0];
        const t1 = performance.now();
        if (draw) this.redraw(series(results));
        const t2 = performance.now();
        this.timing = { run_ms: results.reduce((a, r) => a + r.ms, 0), draw_ms: t2 - t1, total_ms: t2 - start, samples: main.n, rhs_calls: main.rhsCalls, thread: this.runner.where };
        this.showStatus();
        this.showCommand();
        this.showStates();
        return main;
      }, e => {
        if (e === Runner.cancelled || e === Runner.stopped) return this.current;
        throw e;
      });
      return promise;
    }

    /* A rerun from a control or a click: an error shown in the panel. */
    rerunShown() {
      this.rerun().catch(e => {
        this.status.textContent = 'The run failed: ' + (e && e.message || e);
        console.error(e);
      });
    }

    /* The states of the phase plane, when both axes are states (else a click does nothing). */
    phaseNames() {
      const m = this.model, chosen = this.data.plot;
      const names = chosen ? (chosen.x !== 't' ? [chosen.x, chosen.y[0]] : null) : m.phase || (m.name === 'vanderpol' ? ['y1', 'y2'] : null);
      if (!names || !names.every(n => m.states.some(s => s.name === n))) return [];
      return names;
    }

    /* The page drawn with the new runs: in place (every view keeps its canvas and takes the
     * new samples, DK.updateAnimate; a mechanism's scene and an .ani animation with the
     * frames of the live runs when their module gives their numbers), else built again (a
     * scene or an animation that shows the tool's run, at the first rerun); a run being
     * computed (partial) is drawn only in place. */
    redraw(runs, partial) {
      if (this.stopped) return; /* replaced by another model's (report --live) */
      const old = this.player;
      /* a mechanism's scene from the runs' scene inputs (live_scene.js), an .ani animation
       * from its frames' numbers (live_ani.js); else they belong to the tool's run */
      const mech = this.sceneOf(runs), ani = this.aniOf(runs);
      const staleAni = !!this.data.ani && !ani, staleMech = !!this.data.mech && !mech, stale = staleMech || staleAni;
      /* (a scene or an animation of the tool's run keeps it in place: ani_stale, mech_stale) */
      const data = Object.assign({}, this.data, { runs, span: [this.t0, this.t1], ani, mech, ani_stale: staleAni, mech_stale: staleMech, shows: stale ? (staleAni ? 'The .ani animation shows' : 'The mechanism\u2019s scene shows') + ' the run the page was written with; the live runs are drawn in the plots.' : this.data.shows });
      if (DK.updateAnimate(old, data) || partial) return;
      const t = old ? old.t : null, playing = old ? old.playing : true;
      if (old) {
        old.pause();
        const i = DK.players.indexOf(old);
        if (i >= 0) DK.players.splice(i, 1);
      }
      document.getElementById('animate').replaceWith(this.template.cloneNode(true));
      DK.holdDraws();
      try {
        this.player = DK.buildAnimate(data);
        if (t !== null) {
          this.player.seek(Math.min(t, this.player.t1));
          if (!playing) { this.player.touched = true; this.player.pause(); }
        }
      } finally {
        DK.releaseDraws();
      }
      this.hookPhase();
    }

    /* The mechanism's scene of the runs (data.mech with their frames), or null when the
     * page has none or its module does not write the scene's inputs. */
    sceneOf(runs) {
      const plan = this.data.mech_plan, mech = this.data.mech;
      if (!mech || !plan || !this.L.scene_inputs || this.kept.length !== runs.length) return null;
      const base = 1 + this.model.states.length + this.model.outputs.length;
      if (base + plan.inputs > this.cols) return null;
      this.sceneRuns = this.kept.map(k => DK.liveMechRun(plan, mech.shapes, k.rows, this.cols, base, k.keep));
      return Object.assign({}, mech, { runs: this.sceneRuns });
    }

    /* The .ani animation of the runs (data.ani with their frames), or null when the page
     * has none or its module does not write the frames' numbers. */
    aniOf(runs) {
      const ani = this.data.ani;
      if (!ani || !this.L.ani_outputs || this.kept.length !== runs.length) return null;
      const counts = ani.runs[0].map(p => p.v.length), n = counts.reduce((a, b) => a + b, 0);
      /* after the model's outputs, and a mechanism's scene's inputs (dyn_mech_ani_to_c) */
      const scene = this.L.scene_inputs && this.data.mech_plan ? this.data.mech_plan.inputs : 0;
      const base = 1 + this.model.states.length + this.model.outputs.length + scene;
      if (base + n > this.cols) return null;
      this.aniRuns = this.kept.map(k => DK.liveAniRun(ani, counts, k.rows, this.cols, base, k.keep));
      return Object.assign({}, ani, { runs: this.aniRuns });
    }

    /* A click in the phase plane starts a trajectory there (XPPAUT's initial conditions,
     * mouse); the last MAX_CLICKED are kept. */
    hookPhase() {
      const names = this.phaseNames();
      const canvas = document.querySelector('#view canvas.plot-canvas');
      if (names.length !== 2 || !canvas || !canvas.dkPlot || canvas.dkLiveClicks) return;
      canvas.dkLiveClicks = true; /* a canvas redrawn in place keeps its listener */
      const plot = canvas.dkPlot;
      canvas.style.cursor = 'crosshair';
      canvas.title = 'click: a trajectory from there';
      canvas.addEventListener('click', e => {
        const r = canvas.getBoundingClientRect();
        const px = e.clientX - r.left, py = e.clientY - r.top;
        const pw = plot.w - plot.m.l - plot.m.r, ph = plot.h - plot.m.t - plot.m.b;
        if (px < plot.m.l || px > plot.w - plot.m.r || py < plot.m.t || py > plot.h - plot.m.b) return;
        const x = plot.xr[0] + (px - plot.m.l) / pw * (plot.xr[1] - plot.xr[0]);
        const y = plot.yr[1] - (py - plot.m.t) / ph * (plot.yr[1] - plot.yr[0]);
        this.clicked.push({ [names[0]]: x, [names[1]]: y });
        if (this.clicked.length > MAX_CLICKED) this.clicked.shift();
        this.clearButton.disabled = false;
        this.rerunShown();
      });
    }

    showStatus() {
      const tm = this.timing;
      this.status.textContent = 'live: ' + tm.samples + ' samples, ' + tm.rhs_calls + ' right-hand sides; run ' + tm.run_ms.toFixed(1) + ' ms, drawn in ' + tm.draw_ms.toFixed(1) + ' ms' + (this.last.message ? ' \u2014 ' + this.last.message : '');
    }

    /* The command line of the main run: the settings, the parameters that differ from the
     * model's and the initial values given (dynkit run writes the same samples). */
    command() {
      const L = this.L, w = ['dynkit', 'run', shellWord(L.spec), '--method', this.method];
      if (!(this.atSteps && this.step === L.step)) w.push('--step', String(this.step));
      w.push('--tspan', String(this.t0) + ':' + String(this.t1));
      if (this.adaptive[this.method]) w.push('--rtol', String(this.rtol), '--atol', String(this.atol));
      if (L.end === 'grid') w.push('--end', 'grid');
      if (L.every !== L.model_every) w.push('--every', String(L.every));
      for (const p of this.params) if (!Object.is(p.value, p.dflt)) w.push('--set', shellWord(p.name + '=' + String(p.value)));
      for (const s of this.states) if (s.given) w.push('--init', shellWord(s.name + '=' + String(s.value)));
      w.push('-o', 'run.csv');
      return w.join(' ');
    }

    showCommand() { this.commandText.textContent = this.command(); }

    csv() {
      const r = this.last, m = this.model, cols = 1 + m.states.length;
      const lines = [['t'].concat(m.states.map(s => s.name)).join(',')];
      for (let k = 0; k < r.n; k++) {
        const row = [];
        for (let c = 0; c < cols; c++) row.push(String(r.rows[k * this.cols + c]));
        lines.push(row.join(','));
      }
      return lines.join('\n') + '\n';
    }

    /* A change from a control: rerun once per frame at most. */
    changed() {
      if (this.pending) return;
      this.pending = true;
      requestAnimationFrame(() => { this.pending = false; this.rerunShown(); });
    }

    /* The range a model file declares for a slider: XPPAUT's window of the phase plane
     * (@ xlo, xhi, ylo, yhi) for the initial value of the state on its axis (@ xp, yp), where
     * a click starts a trajectory; else null (no model kind declares a parameter's range). */
    declaredRange(item, isState) {
      const m = this.model, axes = m.phase, w = m.phase_window;
      if (!isState || !axes || !w) return null;
      const a = axes.indexOf(item.name), r = a >= 0 ? w[a] : null;
      return r && r[0] < r[1] ? r : null;
    }

    /* One row: name [unit], a slider and a number box for a parameter or initial value. */
    valueRow(item, isState) {
      const E = DK.el, declared = this.declaredRange(item, isState);
      let [lo, hi] = rangeOf(item.value, isState, declared);
      const slider = E('input', { type: 'range', min: lo, max: hi, step: 'any', value: item.value, 'aria-label': item.name });
      const box = E('input', { type: 'number', step: 'any', value: String(item.value), 'aria-label': item.name + ' value' });
      const apply = (v, from) => {
        if (!isFinite(v)) return;
        item.value = v;
        if (isState) item.given = true;
        if (v < lo || v > hi) { [lo, hi] = declared ? [Math.min(lo, v), Math.max(hi, v)] : rangeOf(v, isState); slider.min = lo; slider.max = hi; }
        if (from !== slider) slider.value = v;
        if (from !== box) box.value = String(v);
        this.changed();
      };
      slider.addEventListener('input', () => apply(Number(Number(slider.value).toPrecision(6)), slider));
      box.addEventListener('change', () => apply(Number(box.value), box));
      item.show = v => { slider.value = v; box.value = String(v); };
      const label = E('span', { class: 'live-name', text: DK.label(item.name, item.unit === '1' ? '' : item.unit) });
      return E('div', { class: 'live-row' }, [label, slider, box]);
    }

    buildControls() {
      const E = DK.el;
      const panel = E('section', { class: 'live', 'aria-label': 'live controls' });
      panel.addEventListener('keydown', e => e.stopPropagation()); /* the player's keys stay outside */
      const head = E('h2', { text: 'Live run' });
      this.status = E('p', { class: 'muted live-status', text: 'live: starting\u2026' });
      const select = E('select', { 'aria-label': 'method' });
      for (const m of this.methods) select.appendChild(E('option', { value: m, text: m }));
      select.value = this.method;
      const num = (value, label, set) => {
        const box = E('input', { type: 'number', step: 'any', value: String(value), 'aria-label': label });
        box.addEventListener('change', () => { const v = Number(box.value); if (isFinite(v)) { set(v); this.changed(); } });
        return E('label', { class: 'live-setting' }, [label + ' ', box]);
      };
      const tolerances = E('span', { class: 'live-tols' }, [
        num(this.rtol, 'rtol', v => { this.rtol = v; }), num(this.atol, 'atol', v => { this.atol = v; })]);
      const showTols = () => { tolerances.hidden = !this.adaptive[this.method]; };
      select.addEventListener('change', () => { this.method = select.value; showTols(); this.changed(); });
      showTols();
      const settings = E('div', { class: 'live-settings' }, [
        E('label', { class: 'live-setting' }, ['method ', select]),
        num(this.step, 'step', v => { if (v > 0) this.step = v; }),
        tolerances,
        num(this.t0, 't0', v => { this.t0 = v; }),
        num(this.t1, 't1', v => { this.t1 = v; })]);
      const group = (title, items, isState) => E('div', { class: 'live-group' }, [E('h3', { text: title })].concat(items.map(it => this.valueRow(it, isState))));
      this.commandText = E('code', { class: 'live-command' });
      const copy = E('button', { type: 'button', text: 'copy', onclick: () => { if (navigator.clipboard) navigator.clipboard.writeText(this.command()).catch(() => {}); } });
      const download = E('button', { type: 'button', text: 'CSV', title: 'the samples of the run (t and the states, as dynkit run writes them)', onclick: () => {
        const url = URL.createObjectURL(new Blob([this.csv()], { type: 'text/csv' }));
        const a = E('a', { href: url, download: (this.model.name || 'run').replace(/[^A-Za-z0-9_-]/g, '_') + '.csv' });
        document.body.appendChild(a); a.click(); a.remove();
        setTimeout(() => URL.revokeObjectURL(url), 1000);
      } });
      this.clearButton = E('button', { type: 'button', text: 'clear trajectories', disabled: 'disabled', onclick: () => { this.clicked = []; this.clearButton.disabled = true; this.rerunShown(); } });
      const tools = E('div', { class: 'live-tools' }, [download].concat(this.phaseNames().length ? [this.clearButton] : []));
      panel.appendChild(head);
      panel.appendChild(this.status);
      panel.appendChild(settings);
      panel.appendChild(group('Parameters', this.params, false));
      panel.appendChild(group('Initial values', this.states, true));
      panel.appendChild(E('div', { class: 'live-cli' }, [this.commandText, copy]));
      panel.appendChild(tools);
      const main = document.getElementById('animate');
      main.parentNode.insertBefore(panel, main);
    }

    /* The states that follow the parameters show their values at t0 after a run. */
    showStates() {
      const r = this.last;
      if (!r || r.n < 1) return;
      this.states.forEach((s, i) => { if (!s.given && s.show) { s.value = r.rows[1 + i]; s.show(s.value); } });
    }
  }

  Live.stopped = { stopped: true }; /* the end of a page replaced before its module ran */

  DK.startLive = function (data) {
    const live = new Live(data);
    DK.lastLive = live;
    /* the tool's run until the module runs; the report's live part has none: the module's
     * first run is drawn */
    const fromTool = data.runs.length > 0;
    if (fromTool) live.player = DK.buildAnimate(data);
    live.buildControls();
    const find = name => live.params.find(p => p.name === name) || live.states.find(s => s.name === name);
    /* the module set up in its worker and its first run done */
    const started = live.ready.then(() => live.rerun(!fromTool)).then(() => {
      live.hookPhase();
      document.body.dataset.live = 'ready';
    });
    window.dynkitLive = {
      ready: started,
      /* a parameter or an initial value (as its slider does); else a setting: method, step,
       * t0, t1, rtol, atol */
      set(name, value) {
        const it = find(name);
        if (it) {
          it.value = Number(value);
          if (live.states.includes(it)) it.given = true;
          if (it.show) it.show(it.value);
        } else if (name === 'method') live.method = String(value);
        else if (['step', 't0', 't1', 'rtol', 'atol'].includes(name)) live[name] = Number(value);
        else if (name === 'local_ms') live.localMs = value === null || value === undefined ? undefined : Number(value); /* 0: every run in the worker; null: the default */
        else throw new Error('no parameter, initial value or setting ' + name);
      },
      get(name) { const it = find(name); return it ? it.value : live[name]; },
      /* rerun with the current settings and redraw: {names, t, y} of the main run (of a
       * newer run when a change comes before this one ends) */
      async run() {
        await live.ready;
        const r = await live.rerun();
        const names = live.model.states.map(s => s.name), n = names.length, t = [], y = [];
        for (let k = 0; k < r.n; k++) {
          t.push(r.rows[k * live.cols]);
          y.push(Array.from(r.rows.subarray(k * live.cols + 1, k * live.cols + 1 + n)));
        }
        return { names, t, y, message: r.message };
      },
      command: () => live.command(),
      csv: () => live.csv(),
      /* the last rerun's times, and how often a run was drawn as it computed and cancelled */
      timing: () => Object.assign({ partial_draws: live.partialDraws, cancelled: live.runner ? live.runner.cancels : 0 }, live.timing),
      clicked: () => live.clicked.map(p => Object.assign({}, p)),
      /* the mechanism's scene drawn for the main run: its times, each body's pose (x, then
       * R row-major, 12 arrays) and each shape's numbers, or null */
      scene: () => (live.sceneRuns ? { poses: live.sceneRuns[0].poses, values: live.sceneRuns[0].values } : null),
      /* the .ani animation's numbers drawn for the main run (data.ani.runs[0]), or null */
      ani: () => (live.aniRuns ? live.aniRuns[0] : null)
    };
    started.catch(e => {
      if (live.stopped) return; /* another model of the report chosen meanwhile */
      live.status.textContent = 'This page could not run the model: ' + e;
      live.status.className = 'error';
      document.body.dataset.live = 'failed';
      console.error(e);
    });
    return live.player;
  };
})(window.DK);
