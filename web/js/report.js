/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: 'dynkit report --html' — fills every number of the answers from the report's
 * JSON (the numbers of 'dynkit report --json') and builds the figures of each problem from
 * the recorded runs (report.h, dyn_homework_series), one player per problem, and the
 * figures of the three studies of many runs (report_studies.h): a curve, two histograms and
 * a heat map. */
'use strict';
(function (DK) {
  const C = { blue: '#1f77b4', red: '#d62728', green: '#2ca02c', orange: '#ff7f0e', purple: '#9467bd', grey: '#7f7f7f' };
  const DEG = 180 / Math.PI;

  function format(v, fmt) {
    if (typeof v === 'boolean' || typeof v === 'string') return String(v);
    if (v === null || v === undefined || !isFinite(v)) return '—';
    const m = /^(se|f|e|g|deg|pct)(\d+)$/.exec(fmt || '');
    if (!m) return String(Number(v.toPrecision(6)));
    const n = parseInt(m[2], 10);
    switch (m[1]) {
      case 'f': return v.toFixed(n);
      case 'e': return v.toExponential(n).replace('e+', 'e');
      case 'se': return (v >= 0 ? '+' : '') + v.toExponential(n).replace('e+', 'e');
      case 'g': return DK.fmt(v, n);
      case 'pct': return (100 * v).toFixed(n) + ' %';
      default: return (v * DEG).toFixed(n);
    }
  }

  function fillNumbers(data) {
    const r = data.report;
    for (const e of document.querySelectorAll('[data-key]')) {
      let v = r[e.dataset.key];
      if (v === undefined) { e.textContent = '?'; console.error('report has no key ' + e.dataset.key); continue; }
      if (e.dataset.index !== undefined) v = v[parseInt(e.dataset.index, 10)];
      let text = format(v, e.dataset.fmt);
      if (e.dataset.map) {
        for (const pair of e.dataset.map.split('|')) {
          const i = pair.indexOf(':');
          if (pair.slice(0, i) === String(v)) text = pair.slice(i + 1);
        }
      }
      e.textContent = text;
    }
    for (const e of document.querySelectorAll('[data-model]')) {
      const [model, name] = e.dataset.model.split('.');
      e.textContent = format(data.models[model].params[name], e.dataset.fmt);
    }
  }

  const text = (id, s) => { const e = document.getElementById(id); if (e) e.textContent = s; };

  /* A table of the series as a run for the views: {label, color, t, cols}. */
  function run(table, label, color, rename) {
    const cols = {};
    table.columns.forEach((name, j) => { cols[name] = table.data[j]; });
    for (const [to, from] of Object.entries(rename || {})) cols[to] = cols[from];
    return { label, color, t: table.data[0], cols, raw: table };
  }

  /* The figure slot called name: a <figure> with its caption. */
  function figure(name, caption) {
    const f = document.querySelector('[data-fig="' + name + '"]');
    if (caption) f.appendChild(DK.el('figcaption', { text: caption }));
    const body = DK.el('div', { class: 'fig-body' });
    f.insertBefore(body, f.firstChild);
    return body;
  }

  function player(name, runs, label) {
    const f = document.querySelector('[data-fig="' + name + '"]');
    const slot = DK.el('div', { class: 'player-slot' });
    f.parentNode.insertBefore(slot, f.nextSibling);
    const t1 = Math.max(...runs.map(r => r.t[r.t.length - 1]));
    /* the fragment names it by its problem (#p2&t=1.5); it starts when its animation shows */
    const section = f.closest('section');
    return new DK.Player(slot, { t0: runs[0].t[0], t1, times: runs[0].t, label, key: section && section.id, watch: f });
  }

  /* ---- problem 1 ---- */
  function pendulum(data) {
    const S = data.series, R = data.report, par = data.models.pendulum.params;
    const te = R['pendulum.te_s'];
    const nonlinear = run(S['pendulum.nonlinear'], 'nonlinear (RK4, h = ' + S['pendulum.nonlinear'].step + ' s)', C.blue);
    const small = run(S['pendulum.nonlinear'], 'small-angle solution', C.green, { phi: 'phi_small_angle' });
    const euler = run(S['pendulum.euler'], 'Euler, h = ' + S['pendulum.euler'].step + ' s', C.red);
    small.cols.height = small.cols.phi.map(p => par.l * (1 - Math.cos(p)));
    small.cols.energy = null;
    const runs = [nonlinear, small, euler];
    const p = player('pendulum-anim', runs, 'pendulum');
    DK.PendulumView(figure('pendulum-anim', 'The three answers in motion: the nonlinear solution, the small-angle solution and Euler\'s method with the step of question 1e.'), runs, par.l, p);
    DK.timePlot(figure('pendulum-phi', 'φ(t): at t = 0.2 s the three agree closely; over a swing of this amplitude the small-angle solution runs ahead and Euler\'s swing grows.'), runs, 'phi', p, { title: 'angle φ', unit: 'rad' });
    /* 1e, 1f: errors at te on a log scale */
    const st = S['pendulum.step'], tcol = st.data[0];
    const err = st.data[st.columns.indexOf('small_angle_error')];
    const dot = (label, err, color) => ({ label, color, x: [te], y: [Math.abs(err)], t: [te], markers: 5, width: 0 });
    const zoom = new DK.Plot(figure('pendulum-zoom', '1e and 1f: |error| against the nonlinear solution at tₑ = 0.2 s, on a log scale; the small-angle error grows from zero during the step.'), {
      title: '|error| at tₑ (1e, 1f)', xlabel: 't [s]', ylabel: '|φ − φ_nonlinear| [rad]', logy: true, cursor: 'none', legend: 'br', unitY: 'rad',
      xrange: [0, te * 1.08], yrange: [1e-9, 1e-2],
      series: [
        { label: 'small-angle', color: C.green, x: tcol, y: err.map(Math.abs), t: tcol },
        dot('one Euler step of 0.2 s', R['pendulum.error_euler_rad'], C.red),
        dot('10 Euler steps of 0.02 s', R['pendulum.euler_10_steps_error_rad'], C.orange),
        dot('one RK4 step of 0.2 s', R['pendulum.rk4_one_step_error_rad'], C.purple)
      ]
    });
    zoom.setTime(te);
    DK.timePlot(figure('pendulum-height', '1a: the height of the mass above its lowest point; energy conservation caps it at the dashed line.'), runs, 'height', p, {
      title: 'height above the bottom', unit: 'm', hlines: [{ v: R['pendulum.max_height_m'], label: '1a: h max = ' + R['pendulum.max_height_m'].toFixed(3) + ' m', color: C.blue }, { v: par.l, label: 'pivot', color: '#999', dash: [2, 3] }]
    });
    DK.timePlot(figure('pendulum-energy', 'Energy: constant for the nonlinear solution; Euler\'s method adds energy at every step.'), [nonlinear, euler], 'energy', p, { title: 'energy', unit: 'J' });
    const amplitude = Math.acos(1 - R['pendulum.max_height_m'] / par.l);
    text('p1-amplitude', amplitude.toFixed(2));
    text('p1-ratio', Math.round(Math.abs(R['pendulum.error_euler_rad'] / R['pendulum.error_small_angle_rad'])).toString());
    if (data.studies) {
      const a = R['studies.period.amplitude_rad'].map(v => v * DEG);
      new DK.Plot(figure('pendulum-period', 'Many runs: the period against the amplitude, one run of the sweep per amplitude (dots, dop853, stopped at the first bottom: a quarter period) on the exact 4K(k)/ω, k = sin(a/2) (line); the dashed line is the small-angle period 2π/ω.'), {
        title: 'period against amplitude', xlabel: 'amplitude a [deg]', ylabel: 'period T [s]', unitY: 's', cursor: 'none', legend: 'tl', legendValues: false,
        series: [{ label: 'exact 4K(k)/ω', color: C.blue, x: a, y: R['studies.period.exact_s'] },
          { label: 'sweep: 4 × first bottom', color: C.red, x: a, y: R['studies.period.period_s'], markers: 3, width: 0 }],
        hlines: [{ v: R['studies.period.small_angle_period_s'], label: '2π/ω', color: '#888', dash: [4, 3] }]
      });
    }
    text('p1-over', R['pendulum.goes_over_top'] ? '— more than 2 l: the mass goes over the top.' : '< 2 l: the mass turns back' + (R['pendulum.max_height_m'] > par.l ? ', above the pivot (the rigid rod holds it).' : '.'));
  }

  /* Least-squares slope of log(err) against log(step), over errors above rounding. */
  function slope(xs, ys) {
    const pts = xs.map((x, i) => [Math.log10(x), Math.log10(ys[i])]).filter(p => isFinite(p[1]) && p[1] > -11);
    if (pts.length < 2) return NaN;
    const mx = pts.reduce((a, p) => a + p[0], 0) / pts.length, my = pts.reduce((a, p) => a + p[1], 0) / pts.length;
    let sxy = 0, sxx = 0;
    for (const p of pts) { sxy += (p[0] - mx) * (p[1] - my); sxx += (p[0] - mx) * (p[0] - mx); }
    return sxy / sxx;
  }

  /* ---- problem 2 ---- */
  function vanderpol(data) {
    const S = data.series, R = data.report;
    const runs = [run(S['vanderpol.euler'], 'Euler', C.red), run(S['vanderpol.heun'], 'modified Euler', C.orange),
      run(S['vanderpol.midpoint'], 'RK2 (midpoint)', C.purple), run(S['vanderpol.rk4'], 'RK4', C.blue)];
    runs.forEach(r => { r.label += ', h = ' + r.raw.step + ' s'; });
    const p = player('vdp-phase', runs, 'van der Pol');
    DK.PhaseView(figure('vdp-phase', 'Phase portrait: y₀ = (2, 0) lies close to the limit cycle and every method follows it; the dots are the states at the current time (Euler\'s falls behind).'), runs, 'y1', 'y2', p, { title: 'phase plane (y₁, y₂)' });
    DK.timePlot(figure('vdp-time', 'y₁(t): Euler falls behind in phase; the others lie on top of each other.'), runs, 'y1', p, { title: 'y₁(t)', unit: '1' });
    const st = S['vanderpol.steps'], steps = st.data[0];
    const names = ['euler', 'heun', 'midpoint', 'rk4'], labels = ['Euler', 'modified Euler', 'RK2 (midpoint)', 'RK4'], colors = [C.red, C.orange, C.purple, C.blue];
    const series = names.map((n, i) => ({ label: labels[i], color: colors[i], x: steps, y: st.data[st.columns.indexOf(n)], markers: 3.5 }));
    new DK.Plot(figure('vdp-steps', 'Final-state error |y(15) − reference| against the step, each run from y₀ over 15 s: straight lines of slope 1, 2 and 4, the orders of the methods.'), {
      title: 'error against step size', xlabel: 'step h [s]', ylabel: '|y(15 s) − reference| [1]', logx: true, logy: true, cursor: 'none', legend: 'br', legendValues: false,
      series, vlines: [{ v: R['vanderpol.step_s'], label: 'h = ' + R['vanderpol.step_s'] + ' s', color: '#888' }]
    });
    text('p2-slopes', names.map((n, i) => labels[i] + ' ' + slope(steps, series[i].y).toFixed(2)).join(', '));
  }

  /* ---- problem 3 ---- */
  function plane(data) {
    const S = data.series, R = data.report;
    const euler = run(S['plane.euler'], 'Euler, h = ' + S['plane.euler'].step + ' s', C.red);
    const rk4 = run(S['plane.rk4'], 'RK4, h = ' + S['plane.rk4'].step + ' s', C.blue);
    const runs = [euler, rk4];
    for (const r of runs) r.cols.theta_margin_deg = r.cols.theta_margin.map(v => v * DEG);
    const p = player('plane-anim', runs, 'plane');
    DK.PlaneView(figure('plane-anim', 'The plane on its spring (A: the ceiling point, the spring ends at P). Euler and RK4 start together and part within the first second, as the motion nears θ = ±90°, where the Euler angles are singular.'), runs, data.models.plane.params, p);
    const cmp = run(S['plane.compare'], 'Euler against RK4', C.purple);
    DK.timePlot(figure('plane-distance', 'Distance between the two centres of mass; its final value is the answer.'), [cmp], 'distance', p, { title: 'distance |s_Euler − s_RK4|', ylabel: 'distance [m]', unit: 'm', legend: 'tl' });
    DK.timePlot(figure('plane-angle', 'Principal angle of the rotation between the two orientations; its final value is the answer.'), [cmp], 'principal_angle', p, { title: 'principal angle between the orientations', ylabel: 'angle [rad]', unit: 'rad', legend: 'tl' });
    DK.timePlot(figure('plane-theta', 'How close θ comes to ±90°, where the Euler angles are singular (log scale).'), runs, 'theta_margin_deg', p, { title: 'distance of θ to ±90°', ylabel: '90° − |θ| [deg]', unit: 'deg', logy: true, legend: 'br', hlines: [{ v: 5, label: 'warning: 5°', color: '#999' }] });
    if (data.studies) {
      const pct = R['studies.plane.percentiles'], n = R['studies.plane.runs'];
      const hist = (name, values, unit, mean, pcts, answer, caption, title, xlabel) => {
        const v = values.filter(x => x !== null && isFinite(x));
        const lo = Math.min(...v), hi = Math.max(...v), bins = 40, w = (hi - lo) / bins || 1;
        const count = new Array(bins).fill(0);
        for (const x of v) count[Math.min(bins - 1, Math.floor((x - lo) / w))]++;
        const X = [], Y = [];
        count.forEach((c, k) => { X.push(lo + k * w, lo + (k + 1) * w); Y.push(c, c); });
        X.unshift(lo); Y.unshift(0); X.push(hi); Y.push(0);
        const top = Math.max(...count) * 1.3, up = v => ({ x: [v, v], y: [0, top] });
        new DK.Plot(figure(name, caption), {
          title, xlabel, ylabel: 'runs [1]', cursor: 'none', legend: 'tr', legendValues: false, yrange: [0, top],
          series: [{ label: n + ' starts, bins of ' + DK.fmt(w, 2) + ' ' + unit, color: C.purple, x: X, y: Y },
            Object.assign({ label: 'mean ' + DK.fmt(mean, 4) + ' ' + unit, color: C.red, width: 2 }, up(mean)),
            Object.assign({ label: 'the answer ' + DK.fmt(answer, 4) + ' ' + unit, color: C.blue, width: 2 }, up(answer)),
            Object.assign({ label: pct[0] + '–' + pct[4] + ' % of the runs', color: '#777', dash: [4, 3] }, { x: [pcts[0], pcts[0], NaN, pcts[4], pcts[4]], y: [0, top, NaN, top, 0] })]
        });
      };
      const S2 = data.studies;
      hist('plane-hist-distance', S2.plane_distance_m, 'm', R['studies.plane.distance_mean_m'], R['studies.plane.distance_percentiles_m'], R['plane.distance_m'],
        'Many runs: the distance between the final centres of mass (Euler against RK4) from ' + n + ' starts, each non-zero initial state changed by a relative 1e−14 (normal, Philox4x32-10): the mean, the 5, 50 and 95 % percentiles and the answer above.',
        'distance |s_Euler − s_RK4| from ' + n + ' starts', 'distance [m]');
      hist('plane-hist-angle', S2.plane_angle_rad, 'rad', R['studies.plane.angle_mean_rad'], R['studies.plane.angle_percentiles_rad'], R['plane.principal_angle_rad'],
        'Many runs: the principal angle between the final orientations over the same starts.',
        'principal angle from ' + n + ' starts', 'angle [rad]');
    }
    DK.timePlot(figure('plane-energy', 'Energy: conserved by the exact motion; Euler\'s grows once it passes the singularity.'), runs, 'energy', p, { title: 'energy', unit: 'J', legend: 'tl' });
  }

  /* ---- problem 4 ---- */
  function cart(data) {
    const S = data.series, R = data.report;
    const fwd = run(S['cart.forward'], 'simulated (modified Euler)', C.blue);
    const pre = run(S['cart.prescribed'], 'prescribed motion', C.green);
    const runs = [fwd, pre];
    const p = player('cart-anim', runs, 'cart');
    DK.CartView(figure('cart-anim', 'Seen from above (the homework\'s cartanimation): the triangle body with the wheels at its corners and the tracks of the wheels (the front wheel\'s dashed). Choose "whole path" to see both paths at once.'), runs, data.models.cart.params, p);
    const path = new DK.Plot(figure('cart-path', 'Prescribed against simulated path of the centre of mass: the simulated cart leaves the path within a second.'), {
      title: 'path of the centre of mass', xlabel: 'sX [m]', ylabel: 'sY [m]', equal: true, cursor: 'points', legend: 'tr', legendValues: false, aspect: 0.7,
      series: runs.map(r => ({ label: r.label, color: r.color, x: r.cols.sX, y: r.cols.sY, t: r.t, trail: true }))
    });
    p.onTime(t => path.setTime(t));
    const forces = new DK.Plot(figure('cart-forces', '4b: the body-frame forces at the front wheel from the inverse dynamics, the table the forward run reads.'), {
      title: 'forces at C (inverse dynamics)', xlabel: 't [s]', ylabel: 'force [N]', unitY: 'N', legend: 'tr', onSeek: t => p.seek(t),
      series: [{ label: 'Fx', color: C.orange, x: pre.t, y: pre.cols.Fx }, { label: 'Fy', color: C.purple, x: pre.t, y: pre.cols.Fy }]
    });
    p.onTime(t => forces.setTime(t));
    const lim = R['cart.friction_limit_N'];
    const lambda = new DK.Plot(figure('cart-lambda', '4d: the lateral force on the rear axle against the friction limit of the two rear wheels (dashed): far beyond it, so the wheels would slip.'), {
      title: 'rear-axle constraint force λ', xlabel: 't [s]', ylabel: 'λ [N]', unitY: 'N', legend: 'tr', onSeek: t => p.seek(t),
      series: [{ label: 'simulated', color: C.blue, x: fwd.t, y: fwd.cols.lambda }, { label: 'prescribed', color: C.green, x: pre.t, y: pre.cols.lambda }],
      hlines: [{ v: lim, label: '+μ(2/3)mg = ' + lim.toFixed(2) + ' N', color: C.red }, { v: -lim, label: '−μ(2/3)mg', color: C.red }]
    });
    p.onTime(t => lambda.setTime(t));
    const Ts = R['cart.study_Ts_s'];
    new DK.Plot(figure('cart-study', '4c: the error in sX(tₑ) as the sampling time (table and step) is refined: no convergence — the instability amplifies every error.'), {
      title: 'forward error against sampling time', xlabel: 'Ts [s]', ylabel: '|sX(tₑ) + v₀ tₑ| [m]', logx: true, logy: true, cursor: 'none', legend: 'br', legendValues: false,
      series: [{ label: 'modified Euler, held', color: C.blue, x: Ts, y: R['cart.study_error_heun_hold_m'], markers: 3.5 },
        { label: 'RK4, held', color: C.orange, x: Ts, y: R['cart.study_error_rk4_hold_m'], markers: 3.5 },
        { label: 'RK4, linear', color: C.purple, x: Ts, y: R['cart.study_error_rk4_linear_m'], markers: 3.5 }]
    });
    if (data.studies) {
      const v0 = R['studies.cart.v0_mps'], f = R['studies.cart.f_Hz'], b = R['studies.cart.boundary_f_Hz'];
      const bx = [], by = [];
      v0.forEach((v, i) => { if (b[i] !== null && isFinite(b[i])) { bx.push(v); by.push(b[i]); } });
      const ratio = data.studies.cart_ratio;
      const top = Math.max(...ratio.filter(v => v !== null && isFinite(v)));
      DK.heatMap(figure('cart-slip-map', 'Many runs: max |λ| / μ(2/3)mg along the prescribed motion for every pair of speed v₀ and steering frequency f (' + ratio.length + ' runs of the sweep); the white line is the slip boundary, ratio = 1 (red on the colour bar): above it the rear wheels would slip. The red dot is the homework\'s v₀ = 20 m/s, f = 2 Hz.'), {
        title: 'max |λ| / friction limit over v₀ and f', xlabel: 'speed v₀ [m/s]', ylabel: 'steering frequency f [Hz]', zlabel: 'max |λ| / μ(2/3)mg (log scale)',
        x: v0, y: f, z: ratio, log: true, zrange: [0.01, top], marks: [{ v: 1, color: '#d62728' }],
        lines: [{ label: 'ratio = 1', color: '#ffffff', width: 2.5, x: bx, y: by },
          { label: 'homework', color: '#d62728', x: [20], y: [2], markers: 5, width: 0 }]
      });
    }
    text('p4-growth', Math.exp(R['cart.instability_rate_per_s'] * R['cart.te_s']).toExponential(1).replace('e+', 'e'));
    text('p4-ratio', (R['cart.max_constraint_force_N'] / lim).toFixed(2));
  }

  DK.buildReport = function (data) {
    /* without the studies of many runs (report --no-studies) their paragraphs and figures go */
    if (!data.studies) for (const e of document.querySelectorAll('.study')) e.remove();
    fillNumbers(data);
    document.getElementById('report-text').textContent = data.text;
    for (const build of [pendulum, vanderpol, plane, cart]) {
      try { build(data); } catch (e) { console.error(e); }
    }
    if (data.live_models && DK.startReportLive) DK.startReportLive(data); /* report --live */
    /* #p3&t=1.5: the browser knows no element "p3&t=1.5"; go to problem 3 */
    const f = DK.readFragment(), target = f.key && document.getElementById(f.key);
    if (target && (f.t !== undefined || f.speed !== undefined)) target.scrollIntoView();
  };
})(window.DK);
