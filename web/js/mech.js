/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: the picture of a mechanism file (docs/mechanisms.md, "Geometry to draw") from
 * the numbers the tool computed at every sample (data.mech: each body's mass centre x and
 * rotation R, N to B, and each shape's numbers in N): boxes, cylinders and disks turned with
 * their body (points at x + R' p), spheres, rods, springs, the axes of a body, the ground as
 * a grid, the paths of traced points, and the constraint forces as arrows (a multiplier
 * times its direction) scaled by a legend (a force below 1e-9 of the weight m g, or below
 * 1e-3 of the largest force, is not drawn), with every multiplier's value below the picture.
 * In 3D (DK.SceneView, the plane's view, with gravity pointing down) or, when everything
 * moves in one plane of N (every point keeps one coordinate and every rotation is about
 * that axis), in 2D on equal scales. */
'use strict';
(function (DK) {
  const val = (x, pos) => (x === null ? NaN : typeof x === 'number' ? x : DK.at(x, pos) ?? NaN);
  const vec = (xs, k, pos) => [val(xs[k], pos), val(xs[k + 1], pos), val(xs[k + 2], pos)];
  const add = (a, b, s) => [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const unit = a => { const n = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / n, a[1] / n, a[2] / n]; };

  /* Every sample of a value (a number: the same in all). */
  const samples = (x, n) => (typeof x === 'number' || x === null ? new Array(n).fill(x === null ? NaN : x) : x);

  /* The axis k of body frame B in N: row k of R (R maps N to B). */
  const axisN = (R, k) => [R[3 * k], R[3 * k + 1], R[3 * k + 2]];

  /* The N axis that every point keeps and every rotation turns about, or -1: a planar
   * mechanism (arrows across that axis, too). */
  function planarAxis(mech, runs) {
    const flat = k => mech.runs.every((mr, r) => {
      const n = runs[r].t.length, coords = mr.poses.map(p => p[k]);
      mech.shapes.forEach((s, i) => {
        const v = mr.values[i];
        if (s.kind !== 'ground') coords.push(v[k]);
        if (s.kind === 'rod' || s.kind === 'spring') coords.push(v[3 + k]);
      });
      let lo = Infinity, hi = -Infinity;
      for (const c of coords) for (const x of samples(c, n)) if (isFinite(x)) { lo = Math.min(lo, x); hi = Math.max(hi, x); }
      const across = mech.shapes.every((s, i) => s.kind !== 'arrow' || samples(mr.values[i][3 + k], n).every(x => !(Math.abs(x) > 1e-9)));
      /* rotations about axis k: R e_k = e_k */
      const about = mr.poses.every(p => samples(p[3 + 4 * k], n).every(x => Math.abs(x - 1) < 1e-9));
      return hi - lo <= 1e-9 * (1 + Math.abs(hi)) && across && about;
    });
    for (let k = 0; k < 3; k++) if (flat(k)) return k;
    return -1;
  }

  /* N to the display frame: z up against gravity (z of N when there is none). */
  function displayFrame(g) {
    const n = Math.hypot(g[0], g[1], g[2]);
    const up = n > 0 ? [-g[0] / n, -g[1] / n, -g[2] / n] : [0, 0, 1];
    let k = 0;
    for (let i = 1; i < 3; i++) if (Math.abs(up[i]) < Math.abs(up[k])) k = i;
    const e = [0, 0, 0]; e[k] = 1;
    const ex = unit(add(e, up, -up[k])), ey = cross(up, ex);
    return p => [ex[0] * p[0] + ex[1] * p[1] + ex[2] * p[2], ey[0] * p[0] + ey[1] * p[1] + ey[2] * p[2], up[0] * p[0] + up[1] * p[1] + up[2] * p[2]];
  }

  /* The pose of body b at pos: [x, R]. */
  function pose(mr, b, pos) {
    const p = mr.poses[b];
    return { x: vec(p, 0, pos), R: [3, 4, 5, 6, 7, 8, 9, 10, 11].map(k => val(p[k], pos)) };
  }

  /* Outline points in N of a solid shape (box corners, cylinder rims) and its faces. */
  function solid(s, v, R) {
    const c = [v[0], v[1], v[2]];
    const P = (a, b, d) => { let p = c; const l = [a, b, d]; for (let k = 0; k < 3; k++) p = add(p, axisN(R, k), l[k]); return p; };
    if (s.kind === 'box') {
      const [hx, hy, hz] = [v[3], v[4], v[5]];
      const q = [[-hx, -hy, -hz], [hx, -hy, -hz], [hx, hy, -hz], [-hx, hy, -hz], [-hx, -hy, hz], [hx, -hy, hz], [hx, hy, hz], [-hx, hy, hz]].map(a => P(a[0], a[1], a[2]));
      return { points: q, faces: [[0, 1, 2, 3], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]].map(f => f.map(i => q[i])) };
    }
    /* a cylinder: its unit axis in N (v[5..7]) and two directions across it */
    const ax = [v[5], v[6], v[7]], e = Math.abs(ax[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
    const u = unit(cross(ax, e)), w = cross(ax, u), r = v[3], hl = v[4], n = 20;
    const rim = z => Array.from({ length: n }, (_, m) => { const an = 2 * Math.PI * m / n; return add(add(add(c, u, r * Math.cos(an)), w, r * Math.sin(an)), ax, z); });
    const top = rim(hl), bot = rim(-hl);
    const faces = [top];
    if (hl > 0) { faces.push(bot); for (let m = 0; m < n; m++) faces.push([top[m], top[(m + 1) % n], bot[(m + 1) % n], bot[m]]); }
    return { points: top.concat(bot), faces };
  }

  /* What a scene's drawing needs from its runs: the mechanism's extent (lo, hi, its size L,
   * mid), whether the camera follows the first body (a disk rolling away), the arrows' scale
   * and legend, and the plane it moves in (axis, or -1 in 3D). */
  function measure(runs, mech, axis) {
    const n0 = runs[0].t.length;
    /* the size of the mechanism: the spread of every point over the first run */
    const pts = [];
    const mr0 = mech.runs[0];
    for (let k = 0; k < n0; k += Math.max(1, Math.floor(n0 / 80))) {
      const pos = { i: k, f: 0 };
      mr0.poses.forEach((_, b) => pts.push(pose(mr0, b, pos).x));
      mech.shapes.forEach((s, i) => {
        const v = mr0.values[i];
        if (s.kind === 'ground') return;
        pts.push(vec(v, 0, pos));
        if (s.kind === 'rod' || s.kind === 'spring') pts.push(vec(v, 3, pos));
      });
    }
    const good = pts.filter(p => p.every(isFinite));
    const lo = [0, 1, 2].map(i => Math.min(...good.map(p => p[i]))), hi = [0, 1, 2].map(i => Math.max(...good.map(p => p[i])));
    const L0 = Math.max(...[0, 1, 2].map(i => hi[i] - lo[i])) || 1;
    /* the mechanism's own size: the largest spread of its points at one time, and its
     * solids' sizes; a motion much larger than that (a disk rolling away) is followed */
    let S = 0;
    for (let k = 0; k < n0; k += Math.max(1, Math.floor(n0 / 20))) {
      const pos = { i: k, f: 0 }, at = [];
      mr0.poses.forEach((_, b) => at.push(pose(mr0, b, pos).x));
      mech.shapes.forEach((s, i) => {
        const v = mr0.values[i].map(x => val(x, pos));
        if (s.kind === 'ground' || s.kind === 'arrow') return;
        at.push(v.slice(0, 3));
        if (s.kind === 'rod' || s.kind === 'spring') at.push(v.slice(3, 6));
        if (s.kind === 'box') S = Math.max(S, Math.hypot(v[3], v[4], v[5]) || 0);
        if (s.kind === 'cylinder' || s.kind === 'sphere') S = Math.max(S, v[3] || 0);
      });
      const ok = at.filter(p => p.every(isFinite));
      for (let q = 0; q < 3; q++) S = Math.max(S, Math.max(...ok.map(p => p[q])) - Math.min(...ok.map(p => p[q])));
    }
    const follow = S > 0 && L0 > 6 * S && mech.bodies.length > 0;
    const L = follow ? 3 * S : L0;
    const mid = [0, 1, 2].map(i => (lo[i] + hi[i]) / 2);
    /* the arrows: |lambda| at most a quarter of the size, at a round scale. A force below
     * ARROW_WEIGHT of the weight m |g| (rounding left of a zero force) or below
     * ARROW_FRACTION of the largest force drawn (shorter than a pixel) is not drawn */
    const ARROW_WEIGHT = 1e-9, ARROW_FRACTION = 1e-3;
    const forces = [...new Set(mech.shapes.filter(s => s.kind === 'arrow').map(s => s.force))];
    let fmax = 0;
    for (const r of runs) for (const f of forces) for (const x of r.cols[f] || []) if (isFinite(x)) fmax = Math.max(fmax, Math.abs(x));
    const weight = (mech.mass || 0) * Math.hypot(...(mech.gravity || [0, 0, 0]));
    if (fmax < ARROW_WEIGHT * weight) fmax = 0;
    const fmin = Math.max(ARROW_FRACTION * fmax, ARROW_WEIGHT * weight); /* drawn from it on */
    const perM = fmax > 0 ? DK.niceStep(fmax / (0.25 * L), 1) : 1; /* force units per metre of arrow */
    const funit = forces.length ? DK.unit(runs[0].raw, forces[0]) : '';
    const fu = funit ? ' ' + funit : '';
    const legendText = !forces.length ? ''
      : fmax > 0 ? 'arrows: 1 m = ' + DK.fmt(perM, 3) + fu + (fmin > 0 ? ', none below ' + DK.fmt(fmin, 2) + fu : '')
      : 'arrows: none, all below ' + DK.fmt(fmin, 2) + fu + ' (1e-9 m g)';
    return { runs, mech, lo, hi, L, mid, follow, fmin, perM, legendText, axis: axis !== undefined ? axis : planarAxis(mech, runs),
      auto: { sphere: 0.04 * L, frame: 0.2 * L, ground: 0.7 * L } };
  }

  /* The view of a mechanism; update(runs, data) draws it again with new runs and their
   * scene (a live page's rerun: the canvas, the player's time and a moved camera kept),
   * accepts(runs, data) says whether it can (the scene moves in the same plane, or in 3D). */
  DK.MechView = function (container, runs, mech, player) {
    let o = measure(runs, mech); /* replaced at every update: the closures below read it */
    /* the followed point: the first body's mass centre in the first run */
    const centreAt = t => pose(o.mech.runs[0], 0, DK.locate(o.runs[0].t, t)).x;
    /* the readouts of the multipliers */
    const read = DK.el('div', { class: 'mech-readouts' });
    function readouts(t) {
      if (!mech.constraints.length) return;
      read.textContent = '';
      for (const r of o.runs) {
        const pos = DK.locate(r.t, t);
        const items = mech.constraints.map(c => c + ' = ' + DK.fmt(r.cols[c] ? DK.at(r.cols[c], pos) : NaN, 4) + (DK.unit(r.raw, c) ? ' ' + DK.unit(r.raw, c) : ''));
        read.appendChild(DK.el('p', { class: 'hint' }, [DK.el('i', { class: 'swatch', style: 'background:' + r.color }), (o.runs.length > 1 ? r.label + ': ' : 'constraint forces: ') + items.join(' · ')]));
      }
    }
    /* every shape of run i at time t as primitives in N: {poly}, {line}, {ball}, {arrow} */
    function prims(i, t, out) {
      const r = o.runs[i], mr = o.mech.runs[i], pos = DK.locate(r.t, t), color = r.color, auto = o.auto;
      mech.shapes.forEach((s, k) => {
        const xs = mr.values[k], v = xs.map(x => val(x, pos));
        const R = s.body >= 0 ? pose(mr, s.body, pos).R : [1, 0, 0, 0, 1, 0, 0, 0, 1];
        const fill = s.color || color;
        switch (s.kind) {
          case 'box': case 'cylinder': {
            if (!v.slice(0, s.kind === 'box' ? 6 : 8).every(isFinite)) break;
            const so = solid(s, v, R);
            out.push({ kind: 'solid', points: so.points, faces: so.faces, fill, edge: color });
            break;
          }
          case 'sphere': out.push({ kind: 'ball', p: v.slice(0, 3), r: isFinite(v[3]) ? v[3] : auto.sphere, fill, edge: color }); break;
          case 'rod': out.push({ kind: 'line', ps: [v.slice(0, 3), v.slice(3, 6)], color: s.color || color, width: 4 }); break;
          case 'spring': out.push({ kind: 'spring', a: v.slice(0, 3), b: v.slice(3, 6), color: '#555' }); break;
          case 'frame': {
            const c0 = v.slice(0, 3), len = isFinite(v[3]) ? v[3] : auto.frame;
            ['#c0392b', '#27ae60', '#2c6fbb'].forEach((c, a) => out.push({ kind: 'line', ps: [c0, add(c0, axisN(R, a), len)], color: c, width: 2 }));
            break;
          }
          case 'ground': {
            if (i > 0) break;
            const p = v.slice(0, 3), nrm = v.slice(3, 6), h = isFinite(v[6]) ? v[6] : auto.ground;
            let e = [1, 0, 0]; if (Math.abs(nrm[0]) > 0.9) e = [0, 1, 0];
            const u = unit(cross(nrm, e)), w = cross(nrm, u);
            /* centred on the mechanism's middle, within the plane */
            const m = o.follow ? centreAt(t).map(x => Math.round(x / (h / 4)) * (h / 4)) : o.mid;
            const d = [0, 1, 2].reduce((a, q) => a + (m[q] - p[q]) * nrm[q], 0), c = add(m, nrm, -d);
            out.push({ kind: 'ground', c, u, w, h, normal: nrm, color: s.color });
            break;
          }
          case 'trace': {
            const xs3 = [0, 1, 2].map(q => samples(xs[q], r.t.length));
            const path = [];
            for (let m = 0; m <= pos.i; m++) path.push([xs3[0][m], xs3[1][m], xs3[2][m]]);
            path.push(v.slice(0, 3));
            out.push({ kind: 'line', ps: path, color: s.color || color, width: 1.3, alpha: 0.7, trail: true });
            out.push({ kind: 'ball', p: v.slice(0, 3), r: 0.012 * o.L, fill: s.color || color, edge: '#fff' });
            break;
          }
          case 'arrow': {
            const f = r.cols[s.force] ? DK.at(r.cols[s.force], pos) : NaN;
            if (!isFinite(f) || f === 0 || Math.abs(f) < o.fmin) break;
            const a = v.slice(0, 3), b = add(a, v.slice(3, 6), f / o.perM);
            out.push({ kind: 'arrow', a, b, color: s.color || '#c2185b', label: s.force });
            break;
          }
        }
      });
    }
    const shown = () => {
      container.dataset.mechView = o.axis >= 0 ? '2d' : '3d';
      container.dataset.mechArrows = o.legendText;
    };
    const st = () => o;
    const view = o.axis >= 0 ? view2d(container, mech, player, o.axis, prims, st) : view3d(container, mech, player, prims, st, centreAt);
    container.appendChild(read);
    readouts(player.t);
    player.onTime(readouts);
    shown();
    let checked = null; /* the plane of the scene accepts saw last */
    /* data.mech_stale: the scene keeps the runs it has (the tool's: the page's module does
     * not compute its frames) */
    view.accepts = (rs, data) => {
      if (data.mech_stale) return true;
      if (!data.mech || data.mech.runs.length !== rs.length) return false;
      checked = { mech: data.mech, axis: planarAxis(data.mech, rs) };
      return checked.axis === o.axis;
    };
    view.update = (rs, data) => {
      if (data.mech_stale) { readouts(player.t); return; }
      o = measure(rs, data.mech, checked && checked.mech === data.mech ? checked.axis : undefined);
      view.refresh();
      readouts(player.t);
      shown();
    };
    return view;
  };

  /* The scene in 3D; st() gives the measures of the runs drawn (measure). */
  function view3d(container, mech, player, prims, st, centreAt) {
    const D = displayFrame(mech.gravity);
    const keysOf = o => {
      const keys = [D([0, 0, 0])];
      if (o.follow) { /* a box of the mechanism's size around where the run starts */
        const c = centreAt(o.runs[0].t[0]), h = o.L;
        keys.length = 0;
        for (const a of [-h, h]) for (const b of [-h, h]) for (const e of [-h, h]) keys.push(D([c[0] + a, c[1] + b, c[2] + e]));
      } else {
        for (const a of [o.lo[0], o.hi[0]]) for (const b of [o.lo[1], o.hi[1]]) for (const c of [o.lo[2], o.hi[2]]) keys.push(D([a, b, c]));
      }
      return keys;
    };
    let view = null;
    function world(scene, t) {
      const o = st();
      if (o.follow && view) { /* the camera keeps the first body in the middle */
        const c = D(centreAt(t));
        if (c.every(isFinite)) scene.target = c;
      }
      for (let i = 0; i < o.runs.length; i++) {
        const out = [];
        prims(i, t, out);
        for (const p of out) {
          if (p.kind === 'solid') for (const f of p.faces) scene.poly(f.map(D), { fill: p.fill, alpha: 0.55, color: p.edge, width: 0.8 });
          else if (p.kind === 'ball') scene.ball(D(p.p), p.r, { color: p.fill, ring: p.edge });
          else if (p.kind === 'line') scene.line(p.ps.map(D), { color: p.color, width: p.width, alpha: p.alpha }, p.trail ? 12 : 0);
          else if (p.kind === 'spring') scene.line(DK.helix(D(p.a), D(p.b), 10, 0.02 * o.L), { color: p.color, width: 1.3 }, 10);
          else if (p.kind === 'ground') {
            const h = p.h, c = p.c, corner = (a, b) => add(add(c, p.u, a), p.w, b);
            scene.poly([corner(-h, -h), corner(h, -h), corner(h, h), corner(-h, h)].map(D), { fill: p.color || '#d9dee6', alpha: 0.35, bias: 1e3 });
            const step = DK.niceStep(2 * h, 8);
            for (let a = -Math.floor(h / step) * step; a <= h + 1e-9; a += step) {
              scene.line([corner(a, -h), corner(a, h)].map(D), { color: '#b9c1cc', width: 0.8 }, 4);
              scene.line([corner(-h, a), corner(h, a)].map(D), { color: '#b9c1cc', width: 0.8 }, 4);
            }
          } else if (p.kind === 'arrow') {
            const a = D(p.a), b = D(p.b), d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]], len = Math.hypot(d[0], d[1], d[2]);
            const side = unit(cross(d, Math.abs(d[2]) < 0.9 * len ? [0, 0, 1] : [1, 0, 0]));
            const head = 0.25 * len, back = add(b, d, -0.25);
            scene.line([a, b], { color: p.color, width: 2.5 });
            scene.line([add(back, side, 0.4 * head), b, add(back, side, -0.4 * head)], { color: p.color, width: 2.5 });
          }
        }
      }
      DK.axesN(scene, D, 0.12 * o.L, 'Z');
    }
    const scaleAt = t => D(mech.bodies.length ? pose(st().mech.runs[0], 0, DK.locate(st().runs[0].t, t)).x : [0, 0, 0]);
    const afterScale = (ctx, s) => {
      const text = st().legendText;
      if (!text) return;
      ctx.fillStyle = '#c2185b'; ctx.textAlign = 'right'; ctx.textBaseline = 'alphabetic';
      ctx.fillText(text, s.w - 16, s.h - 34);
      ctx.textAlign = 'left';
    };
    view = DK.SceneView(container, st().runs, player, { keys: keysOf(st()), world, home: { azimuth: -1.05, elevation: 0.35 }, scaleNote: 'at ' + (mech.bodies[0] ? mech.bodies[0].name : 'the origin'), scaleAt, afterScale });
    view.refresh = () => view.refit(st().runs, keysOf(st()));
    return view;
  }

  /* convex hull of 2D points (monotone chain) */
  function hull(ps) {
    const p = ps.filter(q => isFinite(q[0]) && isFinite(q[1])).sort((a, b) => a[0] - b[0] || a[1] - b[1]);
    if (p.length < 3) return p;
    const x = (o, a, b) => (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    const lower = [], upper = [];
    for (const q of p) { while (lower.length >= 2 && x(lower[lower.length - 2], lower[lower.length - 1], q) <= 0) lower.pop(); lower.push(q); }
    for (const q of p.slice().reverse()) { while (upper.length >= 2 && x(upper[upper.length - 2], upper[upper.length - 1], q) <= 0) upper.pop(); upper.push(q); }
    return lower.slice(0, -1).concat(upper.slice(0, -1));
  }

  /* The scene in the plane across axis k of N, on equal scales; st() as view3d's. */
  function view2d(container, mech, player, k, prims, st) {
    /* the plane's two axes, the one against gravity vertical when there is one */
    let i = (k + 1) % 3, j = (k + 2) % 3;
    const g = mech.gravity;
    if (Math.abs(g[i]) > Math.abs(g[j])) [i, j] = [j, i];
    const names = ['X', 'Y', 'Z'];
    const P = p => [p[i], p[j]];
    /* a series per run spanning the mechanism's extent: the frame the plot fits */
    const seriesOf = o => {
      const pad = 0.12 * o.L;
      return o.runs.map(r => ({ label: r.label, color: r.color, t: r.t, x: [o.lo[i] - pad, o.hi[i] + pad], y: [o.lo[j] - pad, o.hi[j] + pad], width: 0 }));
    };
    const legendOf = o => (o.runs.length > 1 ? 'tr' : 'none');
    const plot = new DK.Plot(container, {
      title: 'the mechanism in its plane', xlabel: names[i] + ' [m]', ylabel: names[j] + ' [m]', equal: true, fitData: true, series: seriesOf(st()), cursor: 'none', legend: legendOf(st()), legendValues: false, aspect: 0.8,
      overlay: (ctx, p, t) => {
        const o = st();
        const px = q => [p.px(q[0]), p.py(q[1])];
        const scale = Math.abs(p.px(1) - p.px(0));
        for (let r = 0; r < o.runs.length; r++) {
          const out = [];
          prims(r, t, out);
          for (const q of out) {
            ctx.globalAlpha = 1;
            if (q.kind === 'solid') {
              const h = hull(q.points.map(P)).map(px);
              if (h.length < 2) continue;
              ctx.beginPath(); ctx.moveTo(h[0][0], h[0][1]);
              for (const a of h.slice(1)) ctx.lineTo(a[0], a[1]);
              ctx.closePath();
              ctx.globalAlpha = 0.45; ctx.fillStyle = q.fill; ctx.fill();
              ctx.globalAlpha = 1; ctx.strokeStyle = q.edge; ctx.lineWidth = 1.2; ctx.stroke();
            } else if (q.kind === 'ball') {
              const c = px(P(q.p));
              ctx.fillStyle = q.fill; ctx.beginPath(); ctx.arc(c[0], c[1], Math.max(2, q.r * scale), 0, 2 * Math.PI); ctx.fill();
              ctx.strokeStyle = q.edge; ctx.lineWidth = 1.2; ctx.stroke();
            } else if (q.kind === 'line' || q.kind === 'spring' || q.kind === 'arrow') {
              let ps = q.kind === 'line' ? q.ps : [q.a, q.b];
              if (q.kind === 'spring') {
                const a = P(q.a), b = P(q.b), d = [b[0] - a[0], b[1] - a[1]], n = [-d[1], d[0]], len = Math.hypot(d[0], d[1]) || 1, z = 0.02 * o.L;
                ps = []; ps.push(q.a);
                for (let m = 1; m < 24; m++) { const f = m / 24, s = (m % 2 ? 1 : -1) * (m > 1 && m < 23 ? z : 0); const q2 = [a[0] + f * d[0] + s * n[0] / len, a[1] + f * d[1] + s * n[1] / len]; const full = [0, 0, 0]; full[i] = q2[0]; full[j] = q2[1]; ps.push(full); }
                ps.push(q.b);
              }
              const xy = ps.map(a => px(P(a)));
              ctx.strokeStyle = q.color; ctx.lineWidth = q.width || (q.kind === 'arrow' ? 2.5 : 1.3); ctx.globalAlpha = q.alpha || 1; ctx.lineCap = 'round'; ctx.lineJoin = 'round';
              ctx.beginPath(); ctx.moveTo(xy[0][0], xy[0][1]);
              for (const a of xy.slice(1)) ctx.lineTo(a[0], a[1]);
              if (q.kind === 'arrow') {
                const a = xy[0], b = xy[1], an = Math.atan2(b[1] - a[1], b[0] - a[0]);
                for (const s of [-0.45, 0.45]) { ctx.moveTo(b[0], b[1]); ctx.lineTo(b[0] - 10 * Math.cos(an + s), b[1] - 10 * Math.sin(an + s)); }
              }
              ctx.stroke(); ctx.globalAlpha = 1;
            } else if (q.kind === 'ground') {
              /* the ground's trace in the plane: a line across, hatched below */
              const e = [0, 0, 0]; e[k] = 1;
              const along = unit(cross(q.normal, e));
              const a = px(P(add(q.c, along, -q.h))), b = px(P(add(q.c, along, q.h))), nn = P(q.normal);
              if (Math.hypot(nn[0], nn[1]) < 0.5) continue;
              ctx.strokeStyle = q.color || '#8a94a3'; ctx.lineWidth = 1.5;
              ctx.beginPath(); ctx.moveTo(a[0], a[1]); ctx.lineTo(b[0], b[1]);
              const len = Math.hypot(b[0] - a[0], b[1] - a[1]), nx = -nn[0] * 8, ny = nn[1] * 8;
              for (let s = 0; s <= len; s += 10) { const x = a[0] + (b[0] - a[0]) * s / len, y = a[1] + (b[1] - a[1]) * s / len; ctx.moveTo(x, y); ctx.lineTo(x + nx - 4, y + ny + 0); }
              ctx.stroke();
            }
          }
        }
        if (o.legendText) {
          ctx.fillStyle = '#c2185b'; ctx.font = '12px system-ui, sans-serif'; ctx.textAlign = 'left'; ctx.textBaseline = 'alphabetic';
          ctx.fillText(o.legendText, p.px(p.xr[0]) + 8, p.py(p.yr[0]) - 8);
        }
      }
    });
    player.onTime(t => plot.setTime(t));
    plot.refresh = () => plot.setSeries(seriesOf(st()), { legend: legendOf(st()) });
    return plot;
  }
})(window.DK);
