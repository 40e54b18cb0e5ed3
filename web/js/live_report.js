/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: the live part of `dynkit report --html --live` — a section after the answers
 * where the homework's models run in the page: one module holds every built-in model
 * (data.live_module; an instance runs the one chosen, live_page.c), and the model chosen
 * gets the live page of `dynkit animate MODEL --live` (its controls, picture, time series,
 * command line and CSV; web/js/live.js) in the section, from its default run (the settings
 * in data.live_models, the run computed by the module). Choosing another model replaces it. window.dynkitReportLive.choose
 * serves scripts and the browser tests. docs/web.md, "Live pages". */
'use strict';
(function (DK) {
  /* The markup of the animate page's body (web/animate.html), which live.js fills. */
  function animateBody() {
    const E = DK.el;
    return [
      E('header', { class: 'top' }, [E('h1', { id: 'title', text: '' }), E('p', { id: 'subtitle', class: 'muted' })]),
      E('main', { id: 'animate', class: 'animate' }, [
        E('section', { class: 'stage' }, [
          E('div', { id: 'view', class: 'view' }), E('div', { id: 'player', class: 'player-slot' }),
          E('p', { class: 'hint', id: 'hint' }), E('div', { id: 'messages' })]),
        E('section', { class: 'series' }, [E('h2', { text: 'Time series' }), E('div', { id: 'plots', class: 'plot-grid' })])])];
  }

  DK.startReportLive = function (data) {
    const E = DK.el, names = Object.keys(data.live_models);
    const select = E('select', { 'aria-label': 'live model' });
    for (const n of names) select.appendChild(E('option', { value: n, text: n }));
    const slot = E('div', { class: 'live-report-slot' });
    const section = E('section', { class: 'problem live-report', id: 'live' }, [
      E('h2', { text: 'Live runs' }),
      E('p', { class: 'muted', text: 'The homework\u2019s models, compiled to WebAssembly, run in this page: choose one, move its sliders and it runs again at once, from its default run (the inputs of the cart held at Fx, Fy). The command line below the controls reproduces the run with dynkit run.' }),
      E('label', { class: 'live-setting' }, ['model ', select]),
      slot]);
    const main = document.querySelector('main.report');
    main.appendChild(section);
    document.querySelector('nav.toc').appendChild(E('a', { href: '#live', text: 'Live runs' }));
    function stop() {
      const live = DK.lastLive;
      if (!live) return;
      if (live.player) {
        live.player.pause();
        const i = DK.players.indexOf(live.player);
        if (i >= 0) DK.players.splice(i, 1);
      }
      live.stopped = true;
      if (live.runner) live.runner.close();
      DK.lastLive = null;
    }
    function choose(name) {
      if (!data.live_models[name]) throw new Error('no live model ' + name + ' (' + names.join(', ') + ')');
      stop();
      slot.textContent = '';
      document.body.removeAttribute('data-live');
      for (const e of animateBody()) slot.appendChild(e);
      const m = data.live_models[name];
      select.value = name;
      DK.startLive(Object.assign({}, m, { live: Object.assign({}, m.live, { module: data.live_module }) }));
      return window.dynkitLive.ready;
    }
    select.addEventListener('change', () => { choose(select.value); });
    /* choose(NAME): resolved once its model ran its first run, or once another model chosen
     * before that replaced it */
    const replaced = e => e && e.stopped === true;
    window.dynkitReportLive = { models: names.slice(), choose: async name => { await choose(name).catch(e => { if (!replaced(e)) throw e; }); } };
    choose(names[0]);
  };
})(window.DK);
