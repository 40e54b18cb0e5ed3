/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: 'dynkit continue MODEL --par NAME --html' — the bifurcation diagram the tool
 * drew (cli/commands/cont_svg.c: stable solid, unstable dashed, periodic branches by their
 * maximum and minimum, the special points labelled), scaled to the page's width, with a dot
 * on each periodic point whose orbit the page holds. Clicking (or tapping) near a dot shows
 * that orbit: its states over one period, t = s T from the collocation nodes s in [0, 1]
 * (one plot per unit), and its path in the plane of the diagram's state and the next one. */
'use strict';
(function (DK) {
  const label = (name, unit) => unit ? name + ' [' + unit + ']' : name;
  const after = unit => unit && unit !== '1' ? ' ' + unit : ''; /* a value's unit, none for 1 */
  const TOUCH = 18; /* px: how far from a dot a click or tap still picks it */

  DK.buildDiagram = function (data) {
    const P = data.parameter, orbits = data.orbits;
    document.getElementById('title').textContent = data.title;
    document.getElementById('subtitle').textContent = (data.model_title && data.model_title !== data.model ? data.model_title + ' \u00b7 ' : '') +
      data.branches.length + ' branch' +
      (data.branches.length === 1 ? '' : 'es') + ' \u00b7 ' + data.orbits_computed + ' periodic orbit' +
      (data.orbits_computed === 1 ? '' : 's') + ' computed, ' + orbits.length + ' on this page';
    const doc = new DOMParser().parseFromString(data.svg, 'image/svg+xml');
    const svg = document.importNode(doc.documentElement, true);
    svg.removeAttribute('width');
    svg.removeAttribute('height');
    svg.setAttribute('style', 'width:100%;height:auto;display:block');
    document.querySelector('[data-fig="diagram"]').appendChild(svg);
    const dots = [...svg.querySelectorAll('circle.dk-orbit')];
    /* dots at least DOT px across on the screen, however narrow the page (a phone's
       390 px shows the drawing at about half its size) */
    const DOT = 3.5;
    function sizeDots() {
      const box = svg.viewBox.baseVal, scale = box && box.width > 0 ? svg.getBoundingClientRect().width / box.width : 0;
      if (!(scale > 0)) return;
      for (const d of dots) d.setAttribute('r', Math.max(2.2, DOT / scale).toFixed(2));
    }
    if (window.ResizeObserver) new ResizeObserver(sizeDots).observe(svg);
    else window.addEventListener('resize', sizeDots);
    document.getElementById('diagram-hint').textContent = orbits.length
      ? 'Click or tap a dot of a periodic branch (drawn by its maximum and minimum) to see that orbit below.'
      : 'No periodic orbit in this diagram: it has no Hopf point, or its periodic branches were not computed.';
    const section = document.getElementById('orbit');
    section.hidden = true;

    /* the dot nearest the pointer, within TOUCH px on the screen, or null */
    function nearest(e) {
      const ctm = svg.getScreenCTM();
      if (!ctm) return null;
      const p = new DOMPoint(e.clientX, e.clientY).matrixTransform(ctm.inverse());
      const scale = Math.hypot(ctm.a, ctm.b);
      let best = null, dist = TOUCH / scale;
      for (const d of dots) {
        const r = Math.hypot(Number(d.getAttribute('cx')) - p.x, Number(d.getAttribute('cy')) - p.y);
        if (r <= dist) { dist = r; best = d; }
      }
      return best;
    }
    svg.addEventListener('click', e => {
      const d = nearest(e);
      if (d) show(Number(d.dataset.orbit));
    });
    svg.addEventListener('pointermove', e => { svg.style.cursor = nearest(e) ? 'pointer' : ''; });

    function show(k) {
      const o = orbits[k];
      for (const d of dots) d.classList.toggle('selected', Number(d.dataset.orbit) === k);
      section.hidden = false;
      const tu = data.time_unit;
      const t = o.s.map(s => s * o.period);
      const mult = o.multipliers.map(m => DK.fmt(Math.hypot(m[0], m[1]), 5)).join(', ');
      document.getElementById('orbit-title').textContent = 'Orbit of branch ' + o.branch + ', point ' + o.point + (o.label ? ' (' + o.label + ')' : '');
      const info = document.getElementById('orbit-info');
      info.textContent = P.name + ' = ' + DK.fmt(o.par, 8) + after(P.unit) + ' \u00b7 period T = ' +
        DK.fmt(o.period, 8) + after(tu) + ' \u00b7 ' + (o.stable === null ? 'stability not known' : o.stable ? 'stable' : 'unstable') +
        (mult ? ' \u00b7 |Floquet multipliers| ' + mult : '');
      info.dataset.orbit = String(k);
      info.dataset.period = String(o.period);
      info.dataset.par = String(o.par);
      const box = document.getElementById('orbit-plots');
      box.replaceChildren();
      /* the states over one period, one plot per unit */
      const units = [...new Set(data.states.map(s => s.unit))];
      for (const u of units) {
        const series = [];
        data.states.forEach((s, i) => {
          if (s.unit === u) series.push({ label: s.name, x: t, y: o.u[i], color: DK.colors[i % DK.colors.length], unit: u });
        });
        const div = DK.el('div');
        box.appendChild(div);
        new DK.Plot(div, { title: 'over one period', xlabel: label('t', tu), ylabel: series.length === 1 ? label(series[0].label, u) : (u ? '[' + u + ']' : ''),
          cursor: 'none', legendValues: false, series });
      }
      /* the path in the plane of the diagram's state and the next one */
      const ix = data.states.findIndex(s => s.name === data.y);
      if (data.states.length >= 2 && ix >= 0) {
        const iy = (ix + 1) % data.states.length, X = data.states[ix], Y = data.states[iy];
        const div = DK.el('div');
        box.appendChild(div);
        new DK.Plot(div, { title: 'in the plane ' + X.name + ', ' + Y.name, xlabel: label(X.name, X.unit), ylabel: label(Y.name, Y.unit),
          cursor: 'none', legend: 'none', legendValues: false, equal: X.unit === Y.unit && X.unit === 'm',
          series: [{ label: 'orbit', x: o.u[ix], y: o.u[iy], color: DK.colors[0], unit: Y.unit }] });
      }
    }
    DK.diagramShow = show; /* for the browser tests */
  };
})(window.DK);
