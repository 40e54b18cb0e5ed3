/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: a small 3D renderer on a 2D canvas — an orbiting perspective camera (drag to
 * rotate, wheel to zoom, double-click to reset), lines, filled polygons, points and labels
 * in world coordinates with z up, drawn back to front (painter's algorithm). */
'use strict';
(function (DK) {
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const norm = a => { const n = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / n, a[1] / n, a[2] / n]; };

  class Scene3D {
    /* view: target [x,y,z], distance, azimuth, elevation (rad), fov (rad) */
    constructor(canvas, view, onChange) {
      this.canvas = canvas;
      this.home = Object.assign({ target: [0, 0, 0], distance: 6, azimuth: -0.9, elevation: 0.35, fov: 0.7 }, view);
      this.reset();
      this.onChange = onChange || (() => {});
      this.items = [];
      this.controls();
    }

    reset() { Object.assign(this, JSON.parse(JSON.stringify(this.home))); }

    controls() {
      const c = this.canvas;
      let drag = null;
      c.style.touchAction = 'none';
      c.style.cursor = 'grab';
      c.addEventListener('pointerdown', e => { drag = { x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button === 2 }; c.setPointerCapture(e.pointerId); c.style.cursor = 'grabbing'; });
      c.addEventListener('pointermove', e => {
        if (!drag) return;
        const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
        drag.x = e.clientX; drag.y = e.clientY;
        if (drag.pan) {
          const b = this.basis(), s = this.distance * 0.0016;
          for (let i = 0; i < 3; i++) this.target[i] += -dx * s * b.r[i] + dy * s * b.u[i];
        } else {
          this.azimuth -= dx * 0.008;
          this.elevation = DK.clamp(this.elevation + dy * 0.008, -1.55, 1.55);
        }
        this.onChange();
      });
      const end = () => { drag = null; c.style.cursor = 'grab'; };
      c.addEventListener('pointerup', end);
      c.addEventListener('pointercancel', end);
      c.addEventListener('contextmenu', e => e.preventDefault());
      c.addEventListener('wheel', e => {
        e.preventDefault();
        this.distance = DK.clamp(this.distance * Math.exp(e.deltaY * 0.0012), 0.2, 500);
        this.onChange();
      }, { passive: false });
      c.addEventListener('dblclick', () => { this.reset(); this.onChange(); });
    }

    basis() {
      const ce = Math.cos(this.elevation), se = Math.sin(this.elevation);
      const eye = [this.target[0] + this.distance * ce * Math.cos(this.azimuth),
        this.target[1] + this.distance * ce * Math.sin(this.azimuth),
        this.target[2] + this.distance * se];
      const f = norm(sub(this.target, eye));
      const r = norm(cross(f, [0, 0, 1]));
      const u = cross(r, f);
      return { eye, f, r, u };
    }

    /* Start a frame of w x h CSS pixels. */
    begin(w, h) {
      this.w = w; this.h = h;
      this.b = this.basis();
      this.focal = (h / 2) / Math.tan(this.fov / 2);
      this.items = [];
    }

    /* World point to [x, y, depth] on the screen (depth <= near: behind the camera). */
    project(p) {
      const d = sub(p, this.b.eye);
      const z = dot(d, this.b.f);
      const s = this.focal / Math.max(z, 1e-3);
      return [this.w / 2 + dot(d, this.b.r) * s, this.h / 2 - dot(d, this.b.u) * s, z];
    }

    visible(ps) { return ps.every(p => p[2] > 0.05); }

    /* A polyline; style: color, width, dash, alpha. Long lines are cut into pieces so
     * they sort well against the other items. */
    line(points, style, piece) {
      const ps = points.map(p => this.project(p));
      const n = piece || ps.length;
      for (let i = 0; i + 1 < ps.length; i += n - 1 || 1) {
        const part = ps.slice(i, Math.min(ps.length, i + n));
        if (part.length < 2 || !this.visible(part)) continue;
        this.items.push({ kind: 'line', ps: part, depth: part.reduce((a, p) => a + p[2], 0) / part.length, style });
      }
    }

    poly(points, style) {
      const ps = points.map(p => this.project(p));
      if (!this.visible(ps)) return;
      this.items.push({ kind: 'poly', ps, depth: ps.reduce((a, p) => a + p[2], 0) / ps.length + (style.bias || 0), style });
    }

    point(p, style) {
      const q = this.project(p);
      if (q[2] > 0.05) this.items.push({ kind: 'point', ps: [q], depth: q[2] + (style.bias || 0), style });
    }

    /* A ball of radius r (world units) at p, drawn as a disc of its projected size. */
    ball(p, r, style) {
      const q = this.project(p);
      if (q[2] > 0.05) this.items.push({ kind: 'point', ps: [q], depth: q[2] + (style.bias || 0), style: Object.assign({}, style, { radius: Math.max(1.5, r * this.focal / q[2]) }) });
    }

    text(p, text, style) {
      const q = this.project(p);
      if (q[2] > 0.05) this.items.push({ kind: 'text', ps: [q], depth: -1e9, text, style });
    }

    /* Draw every item, the farthest first. */
    flush(ctx) {
      this.items.sort((a, b) => b.depth - a.depth);
      for (const it of this.items) {
        const s = it.style, ps = it.ps;
        ctx.globalAlpha = s.alpha === undefined ? 1 : s.alpha;
        if (it.kind === 'line') {
          ctx.strokeStyle = s.color; ctx.lineWidth = s.width || 1; ctx.setLineDash(s.dash || []);
          ctx.lineJoin = 'round'; ctx.lineCap = 'round';
          ctx.beginPath(); ctx.moveTo(ps[0][0], ps[0][1]);
          for (let i = 1; i < ps.length; i++) ctx.lineTo(ps[i][0], ps[i][1]);
          ctx.stroke(); ctx.setLineDash([]);
        } else if (it.kind === 'poly') {
          ctx.beginPath(); ctx.moveTo(ps[0][0], ps[0][1]);
          for (let i = 1; i < ps.length; i++) ctx.lineTo(ps[i][0], ps[i][1]);
          ctx.closePath();
          ctx.fillStyle = s.fill; ctx.fill();
          if (s.color) { ctx.globalAlpha = 1; ctx.strokeStyle = s.color; ctx.lineWidth = s.width || 1; ctx.stroke(); }
        } else if (it.kind === 'point') {
          ctx.fillStyle = s.color; ctx.beginPath();
          ctx.arc(ps[0][0], ps[0][1], s.radius || 3, 0, 2 * Math.PI); ctx.fill();
          if (s.ring) { ctx.strokeStyle = s.ring; ctx.lineWidth = 1.2; ctx.stroke(); }
        } else {
          ctx.fillStyle = s.color || '#333'; ctx.font = s.font || '12px system-ui, sans-serif';
          ctx.textAlign = 'left'; ctx.textBaseline = 'middle';
          ctx.fillText(it.text, ps[0][0] + 4, ps[0][1]);
        }
      }
      ctx.globalAlpha = 1;
    }
  }
  DK.Scene3D = Scene3D;

  /* A 3D view of runs that follows a player: the legend of the runs above it, a canvas with
   * an orbiting camera (drag to turn, wheel to zoom, shift+drag to move, double-click to
   * reset) that first shows every key point (o.keys, display coordinates with z up), the
   * time at the bottom left and a scale bar at the bottom right: a round length (1, 2 or 5
   * times a power of ten metres, about 100 px) as long as it looks at the depth of
   * o.scaleAt(t), across the line of sight, following the zoom. o.world(scene, t) adds what
   * the runs show at time t; o.home: the camera's azimuth and elevation. */
  DK.SceneView = function (container, runs, player, o) {
    const canvas = DK.el('canvas', { class: 'scene-canvas' });
    const wrap = DK.el('div', { class: 'dk-scene' }, [canvas]);
    const legendOf = rs => rs.map(r => DK.el('span', {}, [DK.el('i', { style: 'background:' + r.color }), r.label]));
    const legend = DK.el('div', { class: 'dk-legend' }, legendOf(runs));
    container.appendChild(legend);
    container.appendChild(wrap);
    container.appendChild(DK.el('p', { class: 'hint', text: 'drag: rotate · wheel: zoom · shift+drag: move · double-click: reset view' }));
    let keys = o.keys;
    const centreOf = ks => {
      const lo = [0, 1, 2].map(i => Math.min(...ks.map(p => p[i]))), hi = [0, 1, 2].map(i => Math.max(...ks.map(p => p[i])));
      return [0, 1, 2].map(i => (lo[i] + hi[i]) / 2);
    };
    const centre = centreOf(keys);
    const state = { t: player.t };
    const scene = new Scene3D(canvas, Object.assign({ target: centre, distance: 10 }, o.home), () => draw());
    let w = 0, h = 0, dpr = 1;
    /* the camera's distance: the nearest at which every key point is inside the picture */
    function fit() {
      const inside = d => {
        scene.distance = d;
        scene.begin(w, h);
        return keys.every(p => { const q = scene.project(p); return q[2] > 0.1 && q[0] > 0.04 * w && q[0] < 0.96 * w && q[1] > 0.06 * h && q[1] < 0.94 * h; });
      };
      let a = 0.2, b = 400;
      for (let i = 0; i < 40; i++) { const m = Math.sqrt(a * b); if (inside(m)) b = m; else a = m; }
      scene.home.distance = b;
      scene.reset();
    }
    function size() {
      const nw = Math.max(240, Math.floor(wrap.clientWidth || 600));
      const nh = Math.floor(o.height || DK.clamp(nw * (nw < 600 ? 0.9 : 0.62), 280, 640)); /* taller on a phone */
      if (nw === w && nh === h) return;
      w = nw; h = nh; dpr = window.devicePixelRatio || 1;
      canvas.width = Math.round(w * dpr); canvas.height = Math.round(h * dpr);
      canvas.style.width = w + 'px'; canvas.style.height = h + 'px';
    }
    function scaleBar(ctx, s) {
      const q = scene.project(s);
      if (!(q[2] > 0.05) || !s.every(isFinite)) return;
      const ppm = scene.focal / q[2], L = DK.niceStep(100 / ppm, 1), len = L * ppm;
      const x1 = w - 16, x0 = x1 - len, y = h - 14;
      ctx.strokeStyle = '#222'; ctx.lineWidth = 2; ctx.lineCap = 'butt';
      ctx.beginPath();
      ctx.moveTo(x0, y - 5); ctx.lineTo(x0, y); ctx.lineTo(x1, y); ctx.lineTo(x1, y - 5);
      ctx.moveTo((x0 + x1) / 2, y); ctx.lineTo((x0 + x1) / 2, y - 3);
      ctx.stroke();
      ctx.fillStyle = '#222'; ctx.textAlign = 'center'; ctx.textBaseline = 'alphabetic';
      const label = DK.fmt(L, 3) + ' m';
      ctx.fillText(label, (x0 + x1) / 2, y - 8);
      ctx.fillStyle = '#666'; ctx.textAlign = 'right';
      ctx.fillText(o.scaleNote || '', x0 - 8, y + 1);
      ctx.textAlign = 'left';
      canvas.dataset.scaleLabel = label;
      canvas.dataset.scaleM = L;
      canvas.dataset.scalePx = len;
      if (o.afterScale) o.afterScale(ctx, { ppm, L, w, h });
    }
    /* drawn once at DK.releaseDraws when draws are held (a live page's rerun) */
    const held = { draw: () => paint() };
    function draw() { if (DK.heldDraws) DK.heldDraws.add(held); else paint(); }
    function paint() {
      size();
      const ctx = canvas.getContext('2d'), t = state.t;
      ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
      const g = ctx.createLinearGradient(0, 0, 0, h);
      g.addColorStop(0, '#f4f7fb'); g.addColorStop(1, '#ffffff');
      ctx.fillStyle = g; ctx.fillRect(0, 0, w, h);
      scene.begin(w, h);
      o.world(scene, t);
      scene.flush(ctx);
      ctx.font = '12px system-ui, sans-serif';
      ctx.textBaseline = 'middle';
      ctx.textAlign = 'left';
      ctx.fillStyle = '#555';
      ctx.fillText('t = ' + t.toFixed(3) + ' s', 10, h - 14);
      scaleBar(ctx, o.scaleAt(t));
    }
    size();
    fit();
    if (window.ResizeObserver) new ResizeObserver(() => draw()).observe(wrap);
    player.onTime(t => { state.t = t; draw(); });
    /* new runs (a live page's rerun): the legend, and the camera fitted to the new key
     * points when the reader has not moved it */
    const camera = () => JSON.stringify([scene.target, scene.distance, scene.azimuth, scene.elevation]);
    const refit = (rs, ks) => {
      legend.replaceChildren(...legendOf(rs));
      keys = ks;
      const untouched = camera() === JSON.stringify([scene.home.target, scene.home.distance, scene.home.azimuth, scene.home.elevation]);
      const kept = JSON.parse(camera());
      scene.home.target = centreOf(keys);
      fit();
      if (!untouched) [scene.target, scene.distance, scene.azimuth, scene.elevation] = kept;
      draw();
    };
    return { canvas, scene, draw, refit };
  };
})(window.DK);
