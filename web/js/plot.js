/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: line plots on a canvas — axes with ticks and numbers (linear or logarithmic),
 * axis labels with units (one unit per axis), a title, a legend with the values at the
 * current time that never covers the data (in a corner of the frame where nothing is drawn,
 * else above the frame), a cursor
 * that follows the player (a vertical line on time axes, dots on the curves otherwise),
 * curves drawn up to the current time ("trails"), equal axis scales for pictures of space,
 * a moving viewport, and click-to-seek on time axes. The static part is cached. */
'use strict';
(function (DK) {
  const FONT = '12px system-ui, -apple-system, "Segoe UI", sans-serif';
  const FONT_BOLD = '600 13px system-ui, -apple-system, "Segoe UI", sans-serif';

  class Plot {
    /* o: title, xlabel, ylabel, logx, logy, equal, height, aspect, series [{label, x, y, t,
     * color, width (0: markers only), dash, markers, trail, faint, noLegend}], hlines/vlines [{v, label,
     * color, dash}], cursor ('line' | 'points' | 'none'), xrange, yrange, viewport(t),
     * overlay(ctx, plot, t), underlay(ctx, plot) (drawn once under the series, e.g. the
     * cells of a heat map), onSeek(t), legend ('tr' | 'tl' | 'br' | 'bl' | 'none': the
     * corner tried first), legendValues, unitY (shown with values), keepClear [[x, y]...]
     * (points of an overlay the legend must not cover). A series may give its unit; a plot
     * of series in different units is an error (one y axis per unit: separate plots). */
    constructor(container, o) {
      this.o = Object.assign({ cursor: 'line', legend: 'tr', legendValues: true }, o);
      for (const s of this.o.series) { if (!s.t) s.t = s.x; }
      this.t = null;
      this.canvas = DK.el('canvas', { class: 'plot-canvas' });
      this.wrap = DK.el('div', { class: 'dk-plot' }, [this.canvas]);
      container.appendChild(this.wrap);
      this.canvas.dkPlot = this; /* for the browser tests: see debug() */
      const unitOf = label => { const m = /\[([^\]]*)\]\s*$/.exec(label || ''); return m ? m[1] : ''; };
      this.xunit = unitOf(this.o.xlabel);
      this.yunit = unitOf(this.o.ylabel);
      const units = this.units = [...new Set(this.o.series.map(s => s.unit).filter(u => u !== undefined))];
      if (units.length > 1 || (units.length === 1 && this.yunit && units[0] !== this.yunit))
        console.error('plot "' + (this.o.title || '') + '": one y axis per unit, not ' + units.concat(this.yunit || []).join(' and '));
      this.canvas.dataset.xunit = this.xunit;
      this.canvas.dataset.yunit = this.yunit;
      this.cache = document.createElement('canvas');
      this.cacheKey = null;
      this.dataRange();
      this.layout();
      if (this.o.onSeek && this.o.cursor === 'line') this.enableSeek();
      if (window.ResizeObserver) {
        this.observer = new ResizeObserver(() => { if (this.layout()) this.draw(); });
        this.observer.observe(this.wrap);
      }
      this.draw();
    }

    /* The ranges of the data (or the fixed ranges). */
    dataRange() {
      const o = this.o;
      const finite = (v, log) => v !== null && isFinite(v) && (!log || v > 0);
      const ext = (key, log, extra) => {
        let lo = Infinity, hi = -Infinity;
        for (const s of o.series) {
          const a = s[key];
          for (let k = 0; k < a.length; k++) {
            const v = a[k];
            if (finite(v, log) && finite(key === 'x' ? s.y[k] : s.x[k], key === 'x' ? o.logy : o.logx)) { if (v < lo) lo = v; if (v > hi) hi = v; }
          }
        }
        for (const l of extra || []) if (finite(l.v, log)) { lo = Math.min(lo, l.v); hi = Math.max(hi, l.v); }
        if (!(lo <= hi)) { lo = log ? 1 : 0; hi = log ? 10 : 1; }
        /* a flat series (a conserved energy) at an end of the range: a wider margin there, so
         * that it is not drawn along the frame */
        const near = (a, b) => Math.abs(a - b) <= 0.01 * (hi - lo); /* a pixel or two */
        const flat = { lo: false, hi: false };
        if (key === 'y' && !log && hi > lo) for (const s of o.series) {
          const e = DK.extent([s.y]);
          if (!e || !near(e[0], e[1])) continue;
          if (near(e[0], lo)) flat.lo = true;
          if (near(e[1], hi)) flat.hi = true;
        }
        const r = pad(lo, hi, log);
        if (flat.lo) r[0] = lo - 0.12 * (hi - lo);
        if (flat.hi) r[1] = hi + 0.12 * (hi - lo);
        return r;
      };
      const pad = (lo, hi, log) => {
        if (log) {
          let a = Math.log10(lo), b = Math.log10(hi);
          if (b - a < 1e-9) { a -= 0.5; b += 0.5; }
          const p = 0.04 * (b - a);
          return [Math.pow(10, a - p), Math.pow(10, b + p)];
        }
        if (hi - lo <= 1e-12 * Math.max(Math.abs(lo), Math.abs(hi))) {
          const d = lo !== 0 ? 0.1 * Math.abs(lo) : 1;
          lo -= d; hi += d;
        }
        const p = 0.04 * (hi - lo);
        return [lo - p, hi + p];
      };
      this.xr = o.xrange ? o.xrange.slice() : ext('x', o.logx, o.vlines);
      this.yr = o.yrange ? o.yrange.slice() : ext('y', o.logy, o.hlines);
      if (o.xrange === undefined && o.cursor === 'line' && !o.logx) {
        /* a time axis starts and ends at the data */
        const e = DK.extent(o.series.map(s => s.x));
        if (e && e[1] > e[0]) this.xr = [e[0], e[1]];
      }
      this.baseX = this.xr.slice();
      this.baseY = this.yr.slice();
    }

    /* Size the canvas to its box; true when the size changed. */
    layout() { return this.fit(Math.max(200, Math.floor(this.wrap.clientWidth || 480)), false); }

    /* Size the canvas for a box boxW CSS pixels wide and place the legend (again when force:
     * new data); true when something changed. The canvas is reallocated only when its size
     * changes. */
    fit(boxW, force) {
      this.boxW = boxW;
      let w = boxW;
      const aspect = this.o.aspect || 0.58;
      let h = Math.floor(this.o.height || DK.clamp(w * (w < 480 ? Math.max(aspect, 0.8) : aspect), 180, 560)); /* taller on a phone */
      if (this.o.equal && this.o.fitData) {
        /* equal scales: the frame takes the data's shape (within 180..560 px high), and is
         * narrower than its box rather than showing metres of nothing beside the path */
        const a = (this.baseY[1] - this.baseY[0]) / (this.baseX[1] - this.baseX[0]);
        if (a > 0 && isFinite(a)) {
          h = Math.floor(DK.clamp((w - 78) * a + 72, 180, 560));
          w = Math.min(w, Math.max(200, Math.floor((h - 72) / a + 78)));
        }
      }
      if (!force && w === this.w && h === this.h0) return false;
      this.w = w; this.h = this.h0 = h;
      this.m0 = { l: 64, r: 14, t: this.o.title ? 28 : 12, b: 44 };
      this.placeLegend(this.baseX, this.baseY);
      this.dpr = window.devicePixelRatio || 1;
      const cw = Math.round(w * this.dpr), ch = Math.round(this.h * this.dpr);
      if (this.canvas.width !== cw || this.canvas.height !== ch) {
        for (const c of [this.canvas, this.cache]) { c.width = cw; c.height = ch; }
        this.canvas.style.width = w + 'px';
        this.canvas.style.height = this.h + 'px';
      }
      this.cacheKey = null;
      return true;
    }

    /* New data for the same plot (a live page's rerun): the series (and the options given,
     * e.g. fixed ranges) replaced, the ranges and the legend's place found again for the box
     * the plot has, and the plot drawn; its canvas, cursor and time stay. */
    setSeries(series, o) {
      Object.assign(this.o, o || {}, { series });
      for (const s of series) { if (!s.t) s.t = s.x; }
      this.dataRange();
      this.fit(this.boxW, true);
      this.draw();
    }

    /* Fit the ranges to the plot area's shape for equal scales on both axes. */
    equalize(xr, yr) {
      const pw = this.w - this.m.l - this.m.r, ph = this.h - this.m.t - this.m.b;
      const ux = (xr[1] - xr[0]) / pw, uy = (yr[1] - yr[0]) / ph;
      if (ux > uy) { const c = (yr[0] + yr[1]) / 2, d = ux * ph / 2; return [xr, [c - d, c + d]]; }
      const c = (xr[0] + xr[1]) / 2, d = uy * pw / 2;
      return [[c - d, c + d], yr];
    }

    setRanges(xr, yr) {
      if (this.o.equal) [xr, yr] = this.equalize(xr, yr);
      this.xr = xr; this.yr = yr;
      const X = v => this.o.logx ? Math.log10(v) : v, Y = v => this.o.logy ? Math.log10(v) : v;
      const x0 = X(xr[0]), x1 = X(xr[1]), y0 = Y(yr[0]), y1 = Y(yr[1]);
      const pw = this.w - this.m.l - this.m.r, ph = this.h - this.m.t - this.m.b;
      this.px = v => this.m.l + (X(v) - x0) / (x1 - x0) * pw;
      this.py = v => this.m.t + ph - (Y(v) - y0) / (y1 - y0) * ph;
      this.scale = pw / (x1 - x0); /* pixels per x unit (linear axes) */
      this.xOf = px => { const u = x0 + (px - this.m.l) / pw * (x1 - x0); return this.o.logx ? Math.pow(10, u) : u; };
    }

    enableSeek() {
      const seek = e => {
        const r = this.canvas.getBoundingClientRect();
        const x = e.clientX - r.left;
        if (x < this.m.l - 4 || x > this.w - this.m.r + 4) return;
        this.o.onSeek(DK.clamp(this.xOf(x), this.xr[0], this.xr[1]));
      };
      this.canvas.style.cursor = 'crosshair';
      this.canvas.addEventListener('pointerdown', e => { this.seeking = true; this.canvas.setPointerCapture(e.pointerId); seek(e); });
      this.canvas.addEventListener('pointermove', e => { if (this.seeking) seek(e); });
      this.canvas.addEventListener('pointerup', () => { this.seeking = false; });
    }

    setTime(t) { this.t = t; this.draw(); }

    clipArea(ctx) {
      ctx.beginPath();
      ctx.rect(this.m.l, this.m.t, this.w - this.m.l - this.m.r, this.h - this.m.t - this.m.b);
      ctx.clip();
    }

    /* The parts that do not move: axes, grid, labels, reference lines and whole curves. */
    drawStatic(ctx) {
      const o = this.o, m = this.m, w = this.w, h = this.h;
      ctx.setTransform(this.dpr, 0, 0, this.dpr, 0, 0);
      ctx.fillStyle = '#fff';
      ctx.fillRect(0, 0, w, h);
      ctx.font = FONT;
      const xt = o.logx ? DK.logTicks(this.xr[0], this.xr[1]) : DK.ticks(this.xr[0], this.xr[1], Math.max(3, Math.round((w - m.l - m.r) / 90)));
      const yt = o.logy ? DK.logTicks(this.yr[0], this.yr[1]) : DK.ticks(this.yr[0], this.yr[1], Math.max(3, Math.round((h - m.t - m.b) / 50)));
      ctx.strokeStyle = '#e6e6e6';
      ctx.lineWidth = 1;
      ctx.beginPath();
      for (const k of xt) { const x = Math.round(this.px(k.v)) + 0.5; ctx.moveTo(x, m.t); ctx.lineTo(x, h - m.b); }
      for (const k of yt) { const y = Math.round(this.py(k.v)) + 0.5; ctx.moveTo(m.l, y); ctx.lineTo(w - m.r, y); }
      ctx.stroke();
      ctx.strokeStyle = '#444';
      ctx.strokeRect(m.l + 0.5, m.t + 0.5, w - m.l - m.r - 1, h - m.t - m.b - 1);
      ctx.fillStyle = '#333';
      ctx.textAlign = 'center';
      ctx.textBaseline = 'top';
      ctx.beginPath();
      for (const k of xt) {
        const x = Math.round(this.px(k.v)) + 0.5;
        ctx.moveTo(x, h - m.b); ctx.lineTo(x, h - m.b + 4);
        ctx.fillText(k.label, x, h - m.b + 6);
      }
      ctx.textAlign = 'right';
      ctx.textBaseline = 'middle';
      for (const k of yt) {
        const y = Math.round(this.py(k.v)) + 0.5;
        ctx.moveTo(m.l - 4, y); ctx.lineTo(m.l, y);
        ctx.fillText(k.label, m.l - 6, y);
      }
      ctx.stroke();
      /* the offset of tick labels relative to it (DK.ticks): above the y axis, right of x */
      ctx.textBaseline = 'alphabetic';
      if (yt.offset) { ctx.textAlign = 'left'; ctx.fillText(DK.fmt(yt.offset, 12), m.l + 4, m.t + 12); }
      if (xt.offset) { ctx.textAlign = 'right'; ctx.fillText(DK.fmt(xt.offset, 12), w - m.r, h - 8); }
      ctx.textAlign = 'center';
      if (o.xlabel) ctx.fillText(o.xlabel, m.l + (w - m.l - m.r) / 2, h - 8);
      if (o.ylabel) {
        ctx.save();
        ctx.translate(14, m.t + (h - m.t - m.b) / 2);
        ctx.rotate(-Math.PI / 2);
        ctx.textBaseline = 'middle';
        ctx.fillText(o.ylabel, 0, 0);
        ctx.restore();
      }
      if (o.title) {
        ctx.font = FONT_BOLD;
        ctx.textAlign = 'left';
        /* over the frame, or further left when it is long (a phone), cut to the canvas */
        let title = o.title;
        while (title.length > 4 && ctx.measureText(title).width > w - 16) title = title.slice(0, -2) + '…';
        ctx.fillText(title, Math.max(8, Math.min(m.l, w - 8 - ctx.measureText(title).width)), 18);
      }
      ctx.save();
      this.clipArea(ctx);
      if (o.underlay) o.underlay(ctx, this);
      for (const l of o.hlines || []) this.refLine(ctx, l, true);
      for (const l of o.vlines || []) this.refLine(ctx, l, false);
      for (const s of o.series) {
        if (s.trail) this.curve(ctx, s, s.x.length - 1, null, 0.22);
        else this.curve(ctx, s, s.x.length - 1, null, s.faint ? 0.35 : 1);
      }
      ctx.restore();
    }

    refLine(ctx, l, horizontal) {
      ctx.strokeStyle = l.color || '#777';
      ctx.lineWidth = 1.2;
      ctx.setLineDash(l.dash || [6, 4]);
      ctx.beginPath();
      if (horizontal) { const y = this.py(l.v); ctx.moveTo(this.m.l, y); ctx.lineTo(this.w - this.m.r, y); }
      else { const x = this.px(l.v); ctx.moveTo(x, this.m.t); ctx.lineTo(x, this.h - this.m.b); }
      ctx.stroke();
      ctx.setLineDash([]);
      if (l.label) {
        ctx.fillStyle = l.color || '#555';
        ctx.font = FONT;
        ctx.textAlign = 'left';
        if (horizontal) ctx.fillText(l.label, this.m.l + 6, this.py(l.v) - 4);
        else ctx.fillText(l.label, this.px(l.v) + 4, this.m.t + 14);
      }
    }

    /* A curve up to sample last (and an interpolated end point), split at gaps. */
    curve(ctx, s, last, end, alpha) {
      const X = s.x, Y = s.y, logx = this.o.logx, logy = this.o.logy;
      ctx.globalAlpha = alpha;
      ctx.strokeStyle = s.color;
      ctx.fillStyle = s.color;
      ctx.lineWidth = s.width || 1.6;
      ctx.setLineDash(s.dash || []);
      ctx.lineJoin = 'round';
      ctx.beginPath();
      let pen = false;
      for (let k = 0; k <= last && k < X.length; k++) {
        const x = X[k], y = Y[k];
        if (x === null || y === null || !isFinite(x) || !isFinite(y) || (logx && x <= 0) || (logy && y <= 0)) { pen = false; continue; }
        const px = this.px(x), py = this.py(y);
        if (pen) ctx.lineTo(px, py); else ctx.moveTo(px, py);
        pen = true;
      }
      if (end && pen) ctx.lineTo(this.px(end[0]), this.py(end[1]));
      if (s.width !== 0) ctx.stroke(); /* width 0: markers only */
      ctx.setLineDash([]);
      if (s.markers) {
        for (let k = 0; k <= last && k < X.length; k++) {
          if (X[k] === null || Y[k] === null || !isFinite(Y[k])) continue;
          ctx.beginPath();
          ctx.arc(this.px(X[k]), this.py(Y[k]), s.markers === true ? 3.2 : s.markers, 0, 2 * Math.PI);
          ctx.fill();
        }
      }
      ctx.globalAlpha = 1;
    }

    /* The value of a series at the current time: {x, y} or null. */
    valueAt(s, t) {
      if (t === null || !s.t || !s.t.length) return null;
      if (t < s.t[0] - 1e-12 || t > s.t[s.t.length - 1] + 1e-9 * Math.max(1, Math.abs(t))) return null;
      const p = DK.locate(s.t, t);
      return { x: DK.at(s.x, p), y: DK.at(s.y, p), pos: p };
    }

    draw() {
      if (!this.w) return;
      if (DK.heldDraws) { DK.heldDraws.add(this); return; } /* drawn once at DK.releaseDraws */
      const o = this.o;
      let xr = this.baseX, yr = this.baseY;
      if (o.viewport && this.t !== null) { const v = o.viewport(this.t); if (v) { xr = v[0]; yr = v[1]; } }
      const key = xr.join() + '|' + yr.join() + '|' + this.w + 'x' + this.h;
      if (key !== this.cacheKey) {
        this.setRanges(xr.slice(), yr.slice());
        this.drawStatic(this.cache.getContext('2d'));
        this.cacheKey = key;
      }
      const ctx = this.canvas.getContext('2d');
      ctx.setTransform(1, 0, 0, 1, 0, 0);
      ctx.drawImage(this.cache, 0, 0);
      ctx.setTransform(this.dpr, 0, 0, this.dpr, 0, 0);
      const t = this.t;
      ctx.save();
      this.clipArea(ctx);
      for (const s of o.series) {
        if (!s.trail || t === null) continue;
        const v = this.valueAt(s, t);
        if (v) this.curve(ctx, s, v.pos.i, [v.x, v.y], 1);
        else if (t >= s.t[s.t.length - 1]) this.curve(ctx, s, s.x.length - 1, null, 1);
      }
      if (o.overlay && t !== null) o.overlay(ctx, this, t);
      if (t !== null && o.cursor === 'line') {
        const x = this.px(t);
        ctx.strokeStyle = 'rgba(40,40,40,0.55)';
        ctx.lineWidth = 1;
        ctx.beginPath(); ctx.moveTo(x, this.m.t); ctx.lineTo(x, this.h - this.m.b); ctx.stroke();
      }
      if (t !== null && o.cursor !== 'none') {
        /* the first series' dots are drawn largest, so dots on top of each other all show */
        const n = o.series.length;
        o.series.forEach((s, i) => {
          if (s.noCursor) return;
          const v = this.valueAt(s, t);
          if (!v || v.y === null || !isFinite(v.y) || !isFinite(v.x)) return;
          ctx.fillStyle = s.color;
          ctx.strokeStyle = '#fff';
          ctx.lineWidth = 1.5;
          ctx.beginPath();
          ctx.arc(this.px(v.x), this.py(v.y), (o.cursor === 'points' ? 4.5 : 3.5) + 1.5 * Math.min(n - 1 - i, 3), 0, 2 * Math.PI);
          ctx.fill(); ctx.stroke();
        });
      }
      ctx.restore();
      this.drawLegend(ctx, t);
    }

    /* The legend's items and texts at time t (or as wide as any value: sample). */
    legendTexts(t, sample) {
      const o = this.o;
      const items = o.series.filter(s => s.label && !s.noLegend);
      const unit = o.unitY ? ' ' + o.unitY : '';
      const texts = items.map(s => {
        let text = s.label;
        /* "rk4: 0.25" after a label with its own "=" (rk4, h = 0.01 s), never "= ... = ..." */
        const sep = s.label.includes('=') ? ': ' : ' = ';
        if (o.legendValues && sample) text += sep + '−8.888e−88' + unit;
        else if (o.legendValues && t !== null) {
          const v = this.valueAt(s, t);
          if (v && v.y !== null) text += sep + DK.fmt(v.y, 4) + unit;
        }
        return text;
      });
      return { items, texts };
    }

    /* Where the legend goes, and the frame's margins (at a layout, for the whole data): the
     * first corner of the frame (o.legend first, then counter-clockwise from the top right)
     * where the box covers nothing drawn, else above the frame in rows, the canvas made
     * taller by as much (always so when the view moves, that it does not jump). Its box is
     * wide enough for any value, so that it does not change as the time runs. */
    placeLegend(xr, yr) {
      const o = this.o;
      this.m = Object.assign({}, this.m0);
      this.legendBox = null;
      this.noValues = false;
      this.setRanges(xr.slice(), yr.slice());
      const { items, texts } = this.legendTexts(null, true);
      if (o.legend === 'none' || !items.length) return;
      const ctx = this.cache.getContext('2d');
      ctx.font = FONT;
      const widths = texts.map(x => ctx.measureText(x).width);
      const width = Math.max(...widths) + 44, height = 8 + 17 * items.length;
      if (!o.viewport) {
        const corners = [o.legend, 'tr', 'tl', 'bl', 'br'].filter((c, i, a) => /^[tb][lr]$/.test(c) && a.indexOf(c) === i);
        for (const c of corners) {
          const right = c[1] === 'r', bottom = c[0] === 'b';
          const box = {
            x: right ? this.w - this.m.r - width - 6 : this.m.l + 6,
            y: bottom ? this.h - this.m.b - height - 6 : this.m.t + 6, w: width, h: height
          };
          if (box.x < this.m.l || box.y < this.m.t || box.h > this.h - this.m.t - this.m.b - 12) break;
          if (!this.covers(box, 6)) { this.legendBox = Object.assign(box, { corner: c, rows: items.map((_, i) => [36, 12 + 17 * i]) }); return; }
        }
      }
      /* above the frame: items in rows across the canvas (without values if one is too wide) */
      const avail = this.w - 16;
      let ws = widths;
      if (Math.max(...ws) + 44 > avail) { this.noValues = true; ws = items.map(s => ctx.measureText(s.label).width); }
      /* in columns of the widest item, so that plots of the same runs line up */
      const top = this.o.title ? 26 : 6;
      const iw = Math.min(Math.max(...ws) + 44, avail), cols = Math.max(1, Math.floor(avail / iw));
      const rows = ws.map((_, i) => [(i % cols) * iw + 36, 10 + 17 * Math.floor(i / cols)]);
      const h = 4 + 17 * Math.ceil(ws.length / cols);
      this.legendBox = { x: 8, y: top, w: avail, h, corner: 'above', rows };
      this.m.t = top + h + 6;
      this.h += this.m.t - this.m0.t;
      this.setRanges(xr.slice(), yr.slice());
    }

    /* True when a box (CSS pixels, widened by pad) covers something drawn: a curve, a marker,
     * a reference line or its label, or a point to keep clear. */
    covers(b, pad) {
      const x0 = b.x - pad, x1 = b.x + b.w + pad, y0 = b.y - pad, y1 = b.y + b.h + pad;
      const o = this.o, logx = o.logx, logy = o.logy;
      const ok = (x, y) => x !== null && y !== null && isFinite(x) && isFinite(y) && (!logx || x > 0) && (!logy || y > 0);
      const inside = (x, y, r) => x >= x0 - r && x <= x1 + r && y >= y0 - r && y <= y1 + r;
      for (const s of o.series) {
        const r = s.markers ? (s.markers === true ? 3.2 : s.markers) : 0;
        let ax = null, ay = null;
        for (let k = 0; k < s.x.length; k++) {
          if (!ok(s.x[k], s.y[k])) { ax = null; continue; }
          const bx = this.px(s.x[k]), by = this.py(s.y[k]);
          if (inside(bx, by, r)) return true;
          if (ax !== null && segmentHits(ax, ay, bx, by, x0, y0, x1, y1)) return true;
          ax = bx; ay = by;
        }
      }
      const ctx = this.cache.getContext('2d');
      ctx.font = FONT;
      for (const l of o.hlines || []) {
        if (!ok(this.xr[0], l.v)) continue;
        const y = this.py(l.v);
        if (y >= y0 && y <= y1) return true;
        if (l.label && segmentHits(this.m.l + 6, y - 10, this.m.l + 6 + ctx.measureText(l.label).width, y - 10, x0, y0 - 6, x1, y1 + 6)) return true;
      }
      for (const l of o.vlines || []) {
        if (!ok(l.v, this.yr[0])) continue;
        const x = this.px(l.v);
        if (x >= x0 && x <= x1) return true;
        if (l.label && segmentHits(x + 4, this.m.t + 10, x + 4 + ctx.measureText(l.label).width, this.m.t + 10, x0, y0 - 6, x1, y1 + 6)) return true;
      }
      for (const p of o.keepClear || []) if (ok(p[0], p[1]) && inside(this.px(p[0]), this.py(p[1]), 12)) return true;
      return false;
    }

    drawLegend(ctx, t) {
      const b = this.legendBox;
      if (!b) return;
      ctx.font = FONT;
      const { items, texts } = this.legendTexts(this.noValues ? null : t, false);
      if (this.noValues) items.forEach((s, i) => { texts[i] = s.label; });
      ctx.fillStyle = 'rgba(255,255,255,0.88)';
      ctx.strokeStyle = '#c8c8c8';
      ctx.lineWidth = 1;
      if (b.corner !== 'above') {
        ctx.fillRect(b.x, b.y, b.w, b.h);
        ctx.strokeRect(b.x + 0.5, b.y + 0.5, b.w - 1, b.h - 1);
      }
      ctx.textAlign = 'left';
      ctx.textBaseline = 'middle';
      items.forEach((s, i) => {
        const lx = b.x + b.rows[i][0], ly = b.y + b.rows[i][1];
        ctx.strokeStyle = s.color;
        ctx.lineWidth = 2.2;
        ctx.setLineDash(s.dash || []);
        ctx.beginPath(); ctx.moveTo(lx - 28, ly); ctx.lineTo(lx - 6, ly); ctx.stroke();
        ctx.setLineDash([]);
        ctx.fillStyle = '#222';
        ctx.fillText(texts[i], lx, ly);
      });
      ctx.textBaseline = 'alphabetic';
    }

    /* For the browser tests: the legend's box, the frame and every drawn point of every
     * series in CSS pixels of the canvas (null at gaps), the axes' units and scales. */
    debug() {
      const pts = this.o.series.map(s => s.x.map((x, k) => {
        const y = s.y[k];
        if (x === null || y === null || !isFinite(x) || !isFinite(y) || (this.o.logx && x <= 0) || (this.o.logy && y <= 0)) return null;
        return [this.px(x), this.py(y)];
      }));
      return {
        legend: this.legendBox ? { x: this.legendBox.x, y: this.legendBox.y, w: this.legendBox.w, h: this.legendBox.h, corner: this.legendBox.corner } : null,
        frame: { l: this.m.l, t: this.m.t, r: this.w - this.m.r, b: this.h - this.m.b },
        markers: this.o.series.map(s => (s.markers ? (s.markers === true ? 3.2 : s.markers) : 0)),
        points: pts, units: this.units, xunit: this.xunit, yunit: this.yunit, logx: !!this.o.logx, logy: !!this.o.logy,
        equal: !!this.o.equal, sx: this.scale, sy: (this.py(this.yr[0]) - this.py(this.yr[1])) / (this.yr[1] - this.yr[0])
      };
    }
  }

  /* Does the segment a-b meet the rectangle [x0, x1] x [y0, y1]? (Liang-Barsky) */
  function segmentHits(ax, ay, bx, by, x0, y0, x1, y1) {
    if (Math.max(ax, bx) < x0 || Math.min(ax, bx) > x1 || Math.max(ay, by) < y0 || Math.min(ay, by) > y1) return false;
    const dx = bx - ax, dy = by - ay, p = [-dx, dx, -dy, dy], q = [ax - x0, x1 - ax, ay - y0, y1 - ay];
    let u0 = 0, u1 = 1;
    for (let i = 0; i < 4; i++) {
      if (p[i] === 0) { if (q[i] < 0) return false; continue; }
      const r = q[i] / p[i];
      if (p[i] < 0) { if (r > u1) return false; if (r > u0) u0 = r; } else { if (r < u0) return false; if (r < u1) u1 = r; }
    }
    return true;
  }
  DK.Plot = Plot;

  /* Pages built again at once (a live page's rerun): each plot drawn once at the end, not at
   * each step of its construction. */
  DK.holdDraws = function () { DK.heldDraws = DK.heldDraws || new Set(); };
  DK.releaseDraws = function () {
    const held = DK.heldDraws;
    DK.heldDraws = null;
    if (held) for (const p of held) p.draw();
  };
})(window.DK);
