/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: 'dynkit animate' — the picture of the model (if it has one), a player, and a
 * time series plot of every state and extra output with all runs overlaid. */
'use strict';
(function (DK) {
  /* Runs of the data as the views take them: {label, color, t, cols, raw, map} (map: the
   * iterates of a discrete map, drawn as dots). */
  DK.prepareRuns = function (runs) {
    return runs.map((r, i) => {
      const cols = {};
      r.columns.forEach((name, j) => { cols[name] = r.data[j]; });
      return { label: r.label, color: DK.colors[i % DK.colors.length], t: r.data[0], cols, raw: r, map: !!r.map };
    });
  };

  /* Which picture a model gets: by name, or by its states for models alike. */
  function pictureOf(model, params) {
    const has = names => names.every(n => model.states.some(s => s.name === n));
    if (model.name.startsWith('plane') && has(['sX', 'sY', 'sZ']) && (has(['psi', 'theta', 'phi']) || has(['qw', 'qx', 'qy', 'qz'])) && params.length_plane) return 'plane';
    if (model.name === 'cart' && has(['sX', 'sY', 'theta'])) return 'cart';
    if (model.name === 'pendulum' && has(['phi']) && params.l) return 'pendulum';
    if (model.name === 'vanderpol' && has(['y1', 'y2'])) return 'phase';
    if (model.phase) return 'phase';
    return null;
  }

  /* The lines above the pictures: the runs and their sample counts, the notes, the runs'
   * messages (written again at a live page's rerun). */
  function describe(data, runs) {
    document.getElementById('subtitle').textContent = runs.map(r => r.label + ' (' + r.raw.samples + ' samples' + (r.raw.samples > r.t.length ? ', ' + r.t.length + ' shown' : '') + ')').join(' · ');
    const messages = document.getElementById('messages');
    messages.replaceChildren();
    if (data.shows) messages.appendChild(DK.el('p', { class: 'note', text: data.shows }));
    for (const r of data.runs) if (r.message) messages.appendChild(DK.el('p', { class: 'warning', text: r.message }));
  }

  /* The player's span: from the data's start to the end of the longest run; 1x plays one
   * second per second when that fits a watchable minute, else the whole run in 20 s (a
   * neuron's 400 ms, van der Pol's 1000 s), in the model's time unit. */
  function spanOf(data, runs) {
    const t0 = data.span[0];
    const t1 = Math.max(...runs.map(r => r.t[r.t.length - 1]));
    const unit = data.model.time_unit || 's';
    return { t0, t1, unit, rate: unit === 's' && t1 - t0 <= 60 ? 1 : (t1 - t0) / 20 };
  }

  DK.buildAnimate = function (data) {
    const model = data.model, params = model.params;
    const runs = DK.prepareRuns(data.runs);
    document.getElementById('title').textContent = model.name + ' — ' + model.title;
    describe(data, runs);
    const { t0, t1, unit, rate } = spanOf(data, runs);
    DK.timeUnit = unit;
    const player = new DK.Player(document.getElementById('player'), { t0, t1, times: runs[0].t, label: model.name, watch: document.querySelector('.stage'), unit, rate });
    const views = player.views = []; /* what DK.updateAnimate draws again */
    const view = document.getElementById('view');
    /* dynkit plot --live: the columns asked for, against t or in an x-y picture */
    const chosen = data.plot;
    const xy = chosen && chosen.x !== 't' ? [chosen.x, chosen.y[0]] : null;
    const kind = chosen ? (xy ? 'phase' : null) : data.mech ? 'mech' : pictureOf(model, params);
    /* an XPPAUT animation of the model file (NAME.ani): first, beside the model's other
     * picture on a wide screen, above it on a narrow one */
    const hasAni = !!(data.ani && data.ani.prims.length);
    if (hasAni) {
      const box = DK.el('div', { id: 'ani', class: 'view ani-view' });
      if (kind) {
        const both = DK.el('div', { class: 'pictures' });
        view.parentNode.insertBefore(both, view);
        both.appendChild(box);
        both.appendChild(view);
      } else {
        view.parentNode.insertBefore(box, view);
      }
      views.push(DK.AniView(box, runs, data.ani, player));
    }
    if (kind === 'mech') views.push(DK.MechView(view, runs, data.mech, player));
    else if (kind === 'plane') views.push(DK.PlaneView(view, runs, params, player));
    else if (kind === 'cart') views.push(DK.CartView(view, runs, params, player));
    else if (kind === 'pendulum') views.push(DK.PendulumView(view, runs, params.l, player));
    else if (kind === 'phase') {
      /* the model's own phase plane (a model file's @ xp=, yp=), or van der Pol's; equal
       * scales only when both axes are lengths in the same unit (a path in space) */
      const [xn, yn] = xy || model.phase || ['y1', 'y2'];
      const ux = DK.unit(runs[0].raw, xn);
      const same = ux === DK.unit(runs[0].raw, yn) && DK.isLength(ux) && xn !== 't' && yn !== 't';
      const o = same ? { equal: true } : {};
      const w = xy ? null : model.phase_window; /* XPPAUT's @ xlo, xhi, ylo, yhi */
      if (w && w[0]) o.xrange = w[0];
      if (w && w[1]) o.yrange = w[1];
      views.push(DK.PhaseView(view, runs, xn, yn, player, o));
    }
    else view.remove();
    document.body.classList.toggle('no-picture', !kind && !hasAni);
    document.getElementById('hint').textContent = 'keys: space play/pause · ←/→ one sample · shift+←/→ one second · ↑/↓ speed · home/end · click a plot to jump there';
    const plots = document.getElementById('plots');
    const names = chosen ? chosen.y : model.states.map(s => s.name).concat(model.outputs.map(s => s.name));
    for (const name of names) {
      const cell = DK.el('div', { class: 'plot-cell' });
      plots.appendChild(cell);
      views.push(DK.timePlot(cell, runs, name, player, { height: kind || hasAni ? 240 : 330 }));
    }
    player.activate();
    return player;
  };

  /* The page of buildAnimate drawn again with new runs of the same model and settings (a
   * live page's rerun): every view keeps its canvas and replaces its data, the player keeps
   * its time, speed and playing, and each canvas is drawn once. False, and nothing changed,
   * when a view of the page cannot take new runs (the page is then built again). */
  DK.updateAnimate = function (player, data) {
    const views = player && player.views;
    if (!views || !views.every(v => v && typeof v.update === 'function')) return false;
    const runs = DK.prepareRuns(data.runs);
    /* a mechanism's scene or an .ani animation takes the runs' own frames (data.mech,
     * data.ani), when there are some of the same kind */
    if (!views.every(v => !v.accepts || v.accepts(runs, data))) return false;
    DK.holdDraws();
    try {
      describe(data, runs);
      for (const v of views) v.update(runs, data);
      const s = spanOf(data, runs);
      player.setSpan(s.t0, s.t1, runs[0].t, s.rate);
    } finally {
      DK.releaseDraws();
    }
    return true;
  };
})(window.DK);
