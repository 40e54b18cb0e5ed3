/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: start — read the data the tool wrote into the page and build the report,
 * the animation, a sweep's table, a phase plane or a bifurcation diagram; a failure is
 * shown on the page as well as in the console. */
'use strict';
(function (DK) {
  function start() {
    try {
      const data = JSON.parse(document.getElementById('dynkit-data').textContent);
      if (data.kind === 'report') DK.buildReport(data);
      else if (data.kind === 'sweep') DK.buildSweep(data);
      else if (data.kind === 'phase') DK.buildPhase(data);
      else if (data.kind === 'diagram') DK.buildDiagram(data);
      else if (data.live) DK.startLive(data);
      else DK.buildAnimate(data);
      document.body.dataset.ready = '1';
    } catch (e) {
      document.body.insertBefore(DK.el('p', { class: 'error', text: 'This page could not be built: ' + e }), document.body.firstChild);
      throw e;
    }
  }
  if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', start);
  else start();
})(window.DK);
