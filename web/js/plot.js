/* dynkit page: line plots on a canvas — axes with ticks and numbers (linear or logarithmic),
 * axis labels with units, a title, a legend with the values at the current time, a cursor
 * that follows the player (a vertical line on time axes, dots on the curves otherwise),
 * curves drawn up to the current time ("trails"), equal axis scales for pictures of space,
 * a moving viewport, and click-to-seek on time axes. The static part is cached. */
'use strict';
(function (DK) {
  const FONT = '12px system-ui, -apple-system, "Segoe UI", sans-serif';
  const FONT_BOLD = '600 13px system-ui, -apple-system, "Segoe UI", sans-serif';

  class Plot {
    /* o: title, xlabel, ylabel, logx, logy, equal, height, aspect, series [{label, x, y, t,
     * color, width, dash, markers, trail, faint, noLegend}], hlines/vlines [{v, label,
     * color, dash}], cursor ('line' | 'points' | 'none'), xrange, yrange, viewport(t),
     * overlay(ctx, plot, t), onSeek(t), legend ('tr' | 'tl' | 'br' | 'bl' | 'none'),
     * legendValues, unitY (shown with values) */
    constructor(container, o) {
      this.o = Object.assign({ cursor: 'line', legend: 'tr', legendValues: true }, o);
      for (const s of this.o.series) { if (!s.t) s.t = s.x; }
      this.t = null;
      this.canvas = DK.el('canvas', { class: 'plot-canvas' });
      this.wrap = DK.el('div', { class: 'dk-plot' }, [this.canvas]);
      container.appendChild(this.wrap);
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
        return pad(lo, hi, log);
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
    layout() {
      const w = Math.max(200, Math.floor(this.wrap.clientWidth || 480));
      const h = Math.floor(this.o.height || DK.clamp(w * (this.o.aspect || 0.58), 180, 560));
      if (w === this.w && h === this.h) return false;
      this.w = w; this.h = h;
      this.dpr = window.devicePixelRatio || 1;
      for (const c of [this.canvas, this.cache]) {
        c.width = Math.round(w * this.dpr);
        c.height = Math.round(h * this.dpr);
      }
      this.canvas.style.width = w + 'px';
      this.canvas.style.height = h + 'px';
      this.m = { l: 64, r: 14, t: this.o.title ? 28 : 12, b: 44 };
      this.cacheKey = null;
      return true;
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
      ctx.textAlign = 'center';
      ctx.textBaseline = 'alphabetic';
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
        ctx.fillText(o.title, m.l, 18);
      }
      ctx.save();
      this.clipArea(ctx);
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
      ctx.stroke();
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

    drawLegend(ctx, t) {
      const o = this.o;
      const items = o.series.filter(s => s.label && !s.noLegend);
      if (o.legend === 'none' || !items.length) return;
      ctx.font = FONT;
      const texts = items.map(s => {
        let text = s.label;
        if (o.legendValues && t !== null) {
          const v = this.valueAt(s, t);
          if (v && v.y !== null) text += ' = ' + DK.fmt(v.y, 4) + (o.unitY ? ' ' + o.unitY : '');
        }
        return text;
      });
      const width = Math.max(...texts.map(x => ctx.measureText(x).width)) + 40;
      const height = 8 + 17 * items.length;
      const right = o.legend.includes('r'), bottom = o.legend.includes('b');
      const x = right ? this.w - this.m.r - width - 6 : this.m.l + 6;
      const y = bottom ? this.h - this.m.b - height - 6 : this.m.t + 6;
      ctx.fillStyle = 'rgba(255,255,255,0.88)';
      ctx.strokeStyle = '#c8c8c8';
      ctx.lineWidth = 1;
      ctx.fillRect(x, y, width, height);
      ctx.strokeRect(x + 0.5, y + 0.5, width - 1, height - 1);
      ctx.textAlign = 'left';
      ctx.textBaseline = 'middle';
      items.forEach((s, i) => {
        const ly = y + 12 + 17 * i;
        ctx.strokeStyle = s.color;
        ctx.lineWidth = 2.2;
        ctx.setLineDash(s.dash || []);
        ctx.beginPath(); ctx.moveTo(x + 8, ly); ctx.lineTo(x + 30, ly); ctx.stroke();
        ctx.setLineDash([]);
        ctx.fillStyle = '#222';
        ctx.fillText(texts[i], x + 36, ly);
      });
      ctx.textBaseline = 'alphabetic';
    }
  }
  DK.Plot = Plot;
})(window.DK);
