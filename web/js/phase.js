/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: 'dynkit plot MODEL --phase-plane --html' — the phase plane the tool drew
 * (cli/pages/phase_plot.c: nullclines, direction field, trajectories, equilibria by type)
 * as the same SVG, scaled to the page's width, and the table of the equilibria with their
 * eigenvalues and type. */
'use strict';
(function (DK) {
  DK.buildPhase = function (data) {
    document.getElementById('title').textContent = data.title;
    document.getElementById('subtitle').textContent = 'phase plane ' + data.x + ', ' + data.y +
      ' over ' + DK.fmt(data.window[0], 4) + ' \u2013 ' + DK.fmt(data.window[1], 4) + ', ' +
      DK.fmt(data.window[2], 4) + ' \u2013 ' + DK.fmt(data.window[3], 4) + ' \u00b7 ' +
      data.equilibria.length + ' equilibri' + (data.equilibria.length === 1 ? 'um' : 'a');
    const doc = new DOMParser().parseFromString(data.svg, 'image/svg+xml');
    const svg = document.importNode(doc.documentElement, true);
    svg.removeAttribute('width');
    svg.removeAttribute('height');
    svg.setAttribute('style', 'width:100%;height:auto;display:block');
    const fig = document.querySelector('[data-fig="phase"]');
    fig.appendChild(svg);
    const table = document.getElementById('equilibria');
    const row = (cells, tag) => {
      const tr = DK.el('tr');
      cells.forEach(c => tr.appendChild(DK.el(tag, { text: c })));
      table.appendChild(tr);
    };
    if (!data.equilibria.length) {
      row(['no equilibrium in the window'], 'td');
      return;
    }
    row([data.x, data.y, 'eigenvalues', 'type'], 'th');
    const ev = e => DK.fmt(e[0], 6) + (e[1] ? (e[1] > 0 ? ' + ' : ' \u2212 ') + DK.fmt(Math.abs(e[1]), 6) + 'i' : '');
    data.equilibria.forEach(p => row([DK.fmt(p.state[data.x], 8), DK.fmt(p.state[data.y], 8),
      p.eigenvalues.map(ev).join(', '), p.type], 'td'));
  };
})(window.DK);
