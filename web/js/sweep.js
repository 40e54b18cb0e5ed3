/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: 'dynkit plot TABLE.csv|TABLE.json --html' — a sweep's table (dynkit sweep) as the picture
 * the SVG of cli/pages/sweep_plot.c draws: lines of the reduced columns against the varied name
 * (one line per value of a second varied name, with --x), or a heat map of one reduced
 * column over the grid of two varied names (web/js/heatmap.js), or a point per run when
 * their values were sampled rather than a grid, failed runs in grey. */
'use strict';
(function (DK) {
  const sorted = v => [...new Set(v.filter(x => x !== null && isFinite(x)))].sort((a, b) => a - b);

  /* x and y of the rows where keep(r), ordered by x. */
  function line(xs, ys, keep) {
    const idx = xs.map((_, r) => r).filter(r => keep(r) && xs[r] !== null).sort((a, b) => xs[a] - xs[b]);
    return { x: idx.map(r => xs[r]), y: idx.map(r => ys[r]) };
  }

  DK.buildSweep = function (data) {
    const C = data.columns, fig = document.querySelector('[data-fig="sweep"]');
    /* a column's axis label: its name, with its unit when the table carries units */
    const L = name => (data.labels && data.labels[name]) || name;
    document.getElementById('title').textContent = data.title;
    document.getElementById('subtitle').textContent = data.rows + ' runs · ' +
      (data.picture === 'heat' ? data.y[0] + ' over ' + data.x + ' and ' + data.other : data.y.join(', ') + ' against ' + data.x);
    const body = DK.el('div', { class: 'fig-body' });
    fig.appendChild(body);
    if (data.picture === 'heat' && sorted(C[data.x]).length * sorted(C[data.other]).length > 2 * data.rows) {
      /* values sampled at random (--sample), not a grid: a point per run, its colour the
       * reduced value's eighth of the range (the SVG of cli/pages/sweep_plot.c colours them
       * continuously, with a colour bar) */
      const z = C[data.y[0]], zs = z.filter(v => v !== null && isFinite(v));
      const lo = zs.reduce((a, b) => Math.min(a, b), Infinity), hi = zs.reduce((a, b) => Math.max(a, b), -Infinity);
      const bins = 8, w = (hi - lo) / bins || 1;
      const bin = v => Math.min(bins - 1, Math.floor((v - lo) / w));
      const series = [];
      for (let k = 0; k < bins; k++) {
        const pts = line(C[data.x], C[data.other], r => z[r] !== null && isFinite(z[r]) && bin(z[r]) === k);
        if (pts.x.length) series.push(Object.assign({ label: data.y[0] + ' ' + DK.fmt(lo + k * w, 4) + ' \u2013 ' + DK.fmt(lo + (k + 1) * w, 4), color: DK.viridis((k + 0.5) / bins), width: 0, markers: 3 }, pts));
      }
      const failed = line(C[data.x], C[data.other], r => z[r] === null || !isFinite(z[r]));
      if (failed.x.length) series.push(Object.assign({ label: 'failed or nan', color: '#bbbbbb', width: 0, markers: 3 }, failed));
      new DK.Plot(body, { title: data.y[0], xlabel: L(data.x), ylabel: L(data.other), cursor: 'none', legend: 'tr', legendValues: false, series });
      fig.appendChild(DK.el('figcaption', { text: 'A point per run (the values were sampled, not a grid), coloured by ' + data.y[0] + ' in eighths of its range; grey: a failed run or nan.' }));
      return;
    }
    if (data.picture === 'heat') {
      const xv = sorted(C[data.x]), yv = sorted(C[data.other]), z = new Array(xv.length * yv.length).fill(null);
      C[data.x].forEach((x, r) => {
        const i = xv.indexOf(x), j = yv.indexOf(C[data.other][r]);
        if (i >= 0 && j >= 0) z[i * yv.length + j] = C[data.y[0]][r];
      });
      DK.heatMap(body, { title: data.y[0], xlabel: L(data.x), ylabel: L(data.other), zlabel: L(data.y[0]), x: xv, y: yv, z, lines: [] });
      fig.appendChild(DK.el('figcaption', { text: 'A cell per run (edges halfway between neighbouring values), viridis colours; grey: a failed run or nan.' }));
      return;
    }
    let series;
    if (data.other) {
      const ov = sorted(C[data.other]), col = C[data.y[0]];
      series = ov.slice(0, 20).map((v, k) => Object.assign({ label: data.other + ' = ' + DK.fmt(v, 6), color: DK.colors[k % DK.colors.length], markers: 2.5 },
        line(C[data.x], col, r => C[data.other][r] === v)));
    } else {
      series = data.y.map((name, k) => Object.assign({ label: name, color: DK.colors[k % DK.colors.length], markers: 2.5 }, line(C[data.x], C[name], () => true)));
    }
    new DK.Plot(body, {
      title: data.title, xlabel: L(data.x), ylabel: data.y.length === 1 || data.other ? L(data.y[0]) : '', cursor: 'none', legend: 'tr', legendValues: false, series
    });
    fig.appendChild(DK.el('figcaption', { text: 'A point per run; gaps: failed runs or nan.' }));
  };
})(window.DK);
