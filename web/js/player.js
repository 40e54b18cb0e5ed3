/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: the player that drives the time of an animation and its plots — play/pause,
 * speed from 0.1x to 10x (real time by default), a time slider, the current time, and the
 * keyboard: space play/pause, left/right one sample, shift+left/right one second, up/down
 * speed, home/end. With several players on a page the keys go to the one used last.
 * A player starts playing once its pictures are on the screen, unless the reader asks for
 * reduced motion (prefers-reduced-motion); it plays once, loop off. The URL fragment keeps
 * the view: #t=2.5&speed=0.5 (on the report #p2&t=2.5&speed=0.5, the player of problem 2)
 * is read when the page opens and follows the player used last (history.replaceState). */
'use strict';
(function (DK) {
  const SPEED_MIN = 0.1, SPEED_MAX = 10;
  DK.players = [];
  let active = null;

  /* The fragment as {key, t, speed} (key: a bare word such as p2). */
  DK.readFragment = function (hash) {
    const out = {};
    let text = String(hash === undefined ? location.hash : hash).replace(/^#/, '');
    try { text = decodeURIComponent(text); } catch (e) { /* keep it as it is */ }
    for (const part of text.split('&')) {
      const i = part.indexOf('=');
      if (i < 0) { if (part) out.key = part; continue; }
      const v = parseFloat(part.slice(i + 1));
      if (isFinite(v)) out[part.slice(0, i)] = v;
    }
    return out;
  };
  DK.reducedMotion = () => !!(window.matchMedia && window.matchMedia('(prefers-reduced-motion: reduce)').matches);
  const short = v => String(Number(v.toPrecision(6)));

  class Player {
    /* opts: t0, t1, times (sample times for stepping), label, key (its name in the URL
     * fragment), watch (the element whose showing starts it; default the player),
     * autoplay (default true) */
    constructor(container, opts) {
      this.t0 = opts.t0;
      this.t1 = opts.t1 > opts.t0 ? opts.t1 : opts.t0 + 1;
      /* the unit of the time, and the model time that passes in a second at 1x */
      this.unit = opts.unit || 's';
      this.rate = opts.rate > 0 ? opts.rate : 1;
      this.times = opts.times || [];
      this.t = this.t0;
      this.speed = 1;
      this.playing = false;
      this.listeners = [];
      this.last = null;
      this.key = opts.key || null;
      this.touched = false;
      this.build(container, opts.label);
      DK.players.push(this);
      const f = DK.readFragment();
      if (this.fragmentIsMine(f)) {
        this.applyFragment(f);
        active = this;
      }
      this.update();
      if (opts.autoplay !== false) this.autoplay(opts.watch || this.root);
    }

    /* A fragment without a key is the first player's. */
    fragmentIsMine(f) {
      if (f.t === undefined && f.speed === undefined) return false;
      return f.key ? f.key === this.key : DK.players[0] === this;
    }

    applyFragment(f) {
      if (f.speed !== undefined && f.speed > 0) {
        this.speed = DK.clamp(f.speed, SPEED_MIN, SPEED_MAX);
        this.speedSlider.value = Math.log10(this.speed);
      }
      if (f.t !== undefined) this.t = DK.clamp(f.t, this.t0, this.t1);
    }

    /* Play once the pictures show (not with reduced motion, nor after the reader took over). */
    autoplay(watch) {
      if (DK.reducedMotion()) return;
      /* autoStart: the time it started from (read by the browser tests, which on a loaded
         machine may first look after a short run has played to its end) */
      const start = () => { if (!this.touched && !this.started) { this.started = true; this.autoStart = this.t; this.play(); } };
      if (!window.IntersectionObserver) { start(); return; }
      const io = new IntersectionObserver(es => {
        if (es.some(e => e.isIntersecting)) { io.disconnect(); start(); }
      });
      io.observe(watch);
    }

    /* The fragment of this player's view (written a little later, at most a few times a
     * second, for the player used last). */
    saveFragment() {
      if (active !== this || this.fragTimer) return;
      this.fragTimer = setTimeout(() => {
        this.fragTimer = null;
        if (active !== this) return;
        const h = '#' + (this.key ? this.key + '&' : '') + 't=' + short(this.t) + '&speed=' + short(this.speed);
        if (location.hash !== h) {
          try { history.replaceState(history.state, '', h); } catch (e) { /* a page that may not change its URL */ }
        }
      }, this.playing ? 300 : 80);
    }

    build(container, label) {
      const E = DK.el;
      this.playButton = E('button', { class: 'play', type: 'button', title: 'play / pause (space)', 'aria-label': 'play', onclick: () => { this.activate(); this.toggle(); } });
      this.slider = E('input', { class: 'time', type: 'range', min: this.t0, max: this.t1, step: 'any', value: this.t0, 'aria-label': 'time', title: 'time (left/right: one sample, shift: one second)' });
      this.slider.addEventListener('input', () => { this.activate(); this.seek(parseFloat(this.slider.value)); });
      this.timeText = E('output', { class: 'now', 'aria-live': 'off' });
      this.speedSlider = E('input', { class: 'speed', type: 'range', min: -1, max: 1, step: 0.01, value: 0, 'aria-label': 'speed', title: 'speed 0.1x to 10x (up/down; double-click: 1x)' });
      this.speedSlider.addEventListener('input', () => { this.activate(); this.setSpeed(Math.pow(10, parseFloat(this.speedSlider.value)), true); });
      this.speedSlider.addEventListener('dblclick', () => this.setSpeed(1));
      this.speedText = E('output', { class: 'speed-value' });
      this.loopBox = E('input', { type: 'checkbox', class: 'loop' });
      this.root = E('div', { class: 'player', tabindex: '0', role: 'group', 'aria-label': label || 'player' }, [
        this.playButton, this.slider, this.timeText,
        E('label', { class: 'speed-label' }, ['speed ', this.speedSlider, this.speedText]),
        E('label', { class: 'loop-label', title: 'start again at the end' }, [this.loopBox, ' loop'])
      ]);
      this.root.addEventListener('pointerdown', () => this.activate());
      this.root.addEventListener('focusin', () => this.activate());
      container.appendChild(this.root);
    }

    activate() {
      active = this;
      for (const p of DK.players) p.root.classList.toggle('active', p === this);
      this.saveFragment();
    }

    onTime(fn) { this.listeners.push(fn); fn(this.t); }

    update() {
      const span = this.t1 - this.t0;
      const digits = span < 1 ? 4 : span < 100 ? 3 : 1;
      this.timeText.textContent = 't = ' + this.t.toFixed(digits) + ' ' + this.unit + ' / ' + this.t1.toFixed(digits) + ' ' + this.unit;
      this.speedText.textContent = (this.speed < 1 ? this.speed.toFixed(2) : this.speed.toFixed(1)) + '×';
      /* 1x of a run that is not in seconds, or too long for real time: the model time per second */
      this.speedText.title = short(this.rate * this.speed) + ' ' + this.unit + ' per second' + (this.rate !== 1 ? ' (1× plays the whole run in 20 s)' : '');
      this.slider.value = this.t;
      this.playButton.textContent = this.playing ? '❚❚' : '▶';
      this.playButton.setAttribute('aria-label', this.playing ? 'pause' : 'play');
      this.root.dataset.time = this.t;
      this.root.dataset.speed = this.speed;
      this.root.dataset.rate = this.rate;
      this.root.dataset.playing = this.playing ? '1' : '0';
      for (const fn of this.listeners) fn(this.t);
      this.saveFragment();
    }

    /* A new span and samples (a live page's rerun): the time kept inside it, the speed and
     * the playing kept. */
    setSpan(t0, t1, times, rate) {
      this.t0 = t0;
      this.t1 = t1 > t0 ? t1 : t0 + 1;
      this.times = times || [];
      if (rate > 0) this.rate = rate;
      this.slider.min = this.t0;
      this.slider.max = this.t1;
      this.t = DK.clamp(this.t, this.t0, this.t1);
      this.update();
    }

    seek(t) { this.touched = true; this.t = DK.clamp(t, this.t0, this.t1); this.update(); }

    /* One sample forwards (+1) or backwards (-1). */
    step(dir) {
      this.touched = true;
      this.pause();
      const ts = this.times;
      if (!ts.length) { this.seek(this.t + dir * (this.t1 - this.t0) / 100); return; }
      const eps = 1e-9 * (this.t1 - this.t0);
      let i = DK.locate(ts, this.t).i;
      if (dir > 0) { while (i < ts.length - 1 && ts[i] <= this.t + eps) i++; }
      else { while (i > 0 && ts[i] >= this.t - eps) i--; }
      this.seek(ts[i]);
    }

    setSpeed(s, fromSlider) {
      this.touched = true;
      this.speed = DK.clamp(s, SPEED_MIN, SPEED_MAX);
      if (!fromSlider) this.speedSlider.value = Math.log10(this.speed);
      this.update();
    }

    play() {
      if (this.playing) return;
      if (this.t >= this.t1) this.t = this.t0;
      this.playing = true;
      this.last = null;
      this.update();
      requestAnimationFrame(now => this.frame(now));
    }

    pause() { if (this.playing) { this.playing = false; this.update(); } }

    toggle() { this.touched = true; if (this.playing) this.pause(); else this.play(); }

    frame(now) {
      if (!this.playing) return;
      if (this.last !== null) {
        let t = this.t + (now - this.last) / 1000 * this.speed * this.rate;
        if (t >= this.t1) {
          if (this.loopBox.checked) t = this.t0 + (t - this.t1) % (this.t1 - this.t0);
          else { t = this.t1; this.playing = false; }
        }
        this.t = t;
        this.update();
      }
      this.last = now;
      if (this.playing) requestAnimationFrame(n => this.frame(n));
    }
  }
  DK.Player = Player;

  /* A fragment typed into the address bar moves its player. */
  window.addEventListener('hashchange', () => {
    const f = DK.readFragment();
    const p = DK.players.find(q => q.fragmentIsMine(f));
    if (!p) return;
    p.applyFragment(f);
    p.activate();
    p.update();
  });

  /* The keys go to the player used last, else to the first one on the page. */
  document.addEventListener('keydown', e => {
    const tag = (e.target && e.target.tagName) || '';
    if (tag === 'SELECT' || tag === 'TEXTAREA' || (tag === 'INPUT' && e.target.type !== 'range' && e.target.type !== 'checkbox')) return;
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    /* a focused button or checkbox keeps its own space and enter */
    if ((tag === 'BUTTON' || (tag === 'INPUT' && e.target.type === 'checkbox')) && (e.key === ' ' || e.key === 'Enter')) return;
    const p = active || DK.players[0];
    if (!p) return;
    let handled = true;
    switch (e.key) {
      case ' ': case 'Spacebar': p.toggle(); break;
      case 'ArrowRight': if (e.shiftKey) p.seek(p.t + 1); else p.step(1); break;
      case 'ArrowLeft': if (e.shiftKey) p.seek(p.t - 1); else p.step(-1); break;
      case 'ArrowUp': p.setSpeed(p.speed * 2); break;
      case 'ArrowDown': p.setSpeed(p.speed / 2); break;
      case 'Home': p.pause(); p.seek(p.t0); break;
      case 'End': p.pause(); p.seek(p.t1); break;
      default: handled = false;
    }
    if (handled) e.preventDefault();
  });
})(window.DK);
