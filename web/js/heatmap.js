/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: a heat map of a value over a grid of two parameters (a sweep's runs), on the
 * axes of DK.Plot: a cell per grid point whose edges lie halfway between neighbouring
 * values (uneven grids drawn true), matplotlib's viridis colours (van der Walt and Smith,
 * 2015; the nine stops of cli/pages/sweep_plot.c), linear or logarithmic, NaN in grey, lines on
 * top (e.g. a boundary), and a colour bar with ticks under the picture. */
'use strict';
(function (DK) {
  const VIRIDIS = [[68, 1, 84], [71, 44, 122], [59, 81, 139], [44, 113, 142], [33, 144, 141],
    [39, 173, 129], [92, 200, 99], [170, 220, 50], [253, 231, 37]];

  /* The colour of f in [0, 1] (grey when not finite). */
  DK.viridis = function (f) {
    if (f === null || !isFinite(f)) return '#bbbbbb';
    const u8 = DK.clamp(f, 0, 1) * 8, k = Math.min(7, Math.floor(u8)), u = u8 - k;
    const c = VIRIDIS[k].map((a, i) => Math.round((1 - u) * a + u * VIRIDIS[k + 1][i]));
    return 'rgb(' + c.join(',') + ')';
  };

  /* Edges halfway between neighbouring values, the ends as far out as the first half-step. */
  function edges(v) {
    const e = [];
    if (v.length === 1) return [v[0] - 0.5, v[0] + 0.5];
    e.push(v[0] - (v[1] - v[0]) / 2);
    for (let i = 1; i < v.length; i++) e.push((v[i - 1] + v[i]) / 2);
    e.push(v[v.length - 1] + (v[v.length - 1] - v[v.length - 2]) / 2);
    return e;
  }

  /* o: x (nx), y (ny), z (nx * ny, z[i * ny + j] at x[i], y[j]), title, xlabel, ylabel,
   * zlabel, log (colours by log10 z), zrange [lo, hi] (default: the finite values; with log
   * the positive ones), lines [series of DK.Plot], caption-free. Returns the DK.Plot. */
  DK.heatMap = function (container, o) {
    const ex = edges(o.x), ey = edges(o.y);
    const finite = o.z.filter(v => v !== null && isFinite(v) && (!o.log || v > 0));
    let lo = o.zrange ? o.zrange[0] : finite.reduce((a, b) => Math.min(a, b), Infinity);
    let hi = o.zrange ? o.zrange[1] : finite.reduce((a, b) => Math.max(a, b), -Infinity);
    if (!(hi > lo)) hi = lo + 1;
    const T = v => (o.log ? Math.log10(v) : v);
    const frac = v => (v === null || !isFinite(v) ? NaN : o.log && v <= 0 ? 0 : (T(DK.clamp(v, lo, hi)) - T(lo)) / (T(hi) - T(lo)));
    const plot = new DK.Plot(container, {
      title: o.title, xlabel: o.xlabel, ylabel: o.ylabel, cursor: 'none', legend: 'none', legendValues: false,
      xrange: [ex[0], ex[ex.length - 1]], yrange: [ey[0], ey[ey.length - 1]],
      series: o.lines || [],
      underlay: (ctx, p) => {
        for (let i = 0; i < o.x.length; i++) {
          const x0 = p.px(ex[i]), x1 = p.px(ex[i + 1]);
          for (let j = 0; j < o.y.length; j++) {
            const y0 = p.py(ey[j]), y1 = p.py(ey[j + 1]);
            ctx.fillStyle = DK.viridis(frac(o.z[i * o.y.length + j]));
            /* a little overlap, so no seams show between the cells */
            ctx.fillRect(Math.min(x0, x1) - 0.3, Math.min(y0, y1) - 0.3, Math.abs(x1 - x0) + 0.6, Math.abs(y1 - y0) + 0.6);
          }
        }
      }
    });
    plot.canvas.dataset.heatCells = String(o.x.length * o.y.length);
    DK.colorBar(container, { lo, hi, log: !!o.log, label: o.zlabel, marks: o.marks || [] });
    return plot;
  };

  /* A horizontal colour bar as wide as its container: lo..hi (log10 or linear) with ticks,
   * the label under it, and marks [{v, label}] (e.g. a level drawn on the map). */
  DK.colorBar = function (container, o) {
    const canvas = DK.el('canvas', { class: 'dk-colorbar' });
    container.appendChild(canvas);
    const draw = () => {
      const w = Math.max(200, Math.floor(container.clientWidth || 480)), h = 52, dpr = window.devicePixelRatio || 1;
      canvas.width = Math.round(w * dpr); canvas.height = Math.round(h * dpr);
      canvas.style.width = w + 'px'; canvas.style.height = h + 'px';
      const ctx = canvas.getContext('2d');
      ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
      ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, w, h);
      const l = 64, r = w - 14, top = 4, bh = 12;
      const T = v => (o.log ? Math.log10(v) : v);
      const X = v => l + (T(v) - T(o.lo)) / (T(o.hi) - T(o.lo)) * (r - l);
      for (let x = l; x < r; x++) { ctx.fillStyle = DK.viridis((x - l) / (r - l)); ctx.fillRect(x, top, 1.5, bh); }
      ctx.strokeStyle = '#444'; ctx.strokeRect(l + 0.5, top + 0.5, r - l - 1, bh);
      ctx.font = '12px system-ui, -apple-system, "Segoe UI", sans-serif';
      ctx.fillStyle = '#333'; ctx.textAlign = 'center'; ctx.textBaseline = 'top';
      const ticks = o.log ? DK.logTicks(o.lo, o.hi) : DK.ticks(o.lo, o.hi, Math.max(3, Math.round((r - l) / 90)));
      ctx.beginPath();
      for (const k of ticks) {
        if (k.v < o.lo || k.v > o.hi) continue;
        const x = Math.round(X(k.v)) + 0.5;
        ctx.moveTo(x, top + bh); ctx.lineTo(x, top + bh + 4);
        if (k.label) ctx.fillText(k.label, x, top + bh + 5);
      }
      ctx.strokeStyle = '#444'; ctx.stroke();
      for (const m of o.marks) {
        const x = X(m.v);
        ctx.strokeStyle = m.color || '#d62728'; ctx.lineWidth = 2;
        ctx.beginPath(); ctx.moveTo(x, top - 2); ctx.lineTo(x, top + bh + 2); ctx.stroke();
        ctx.lineWidth = 1;
      }
      if (o.label) { ctx.textAlign = 'left'; ctx.fillText(o.label, l, top + bh + 22); }
    };
    draw();
    if (window.ResizeObserver) new ResizeObserver(draw).observe(container);
    canvas.dkColorBar = o; /* for the browser tests */
    return canvas;
  };
})(window.DK);
