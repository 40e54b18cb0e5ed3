/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: the pictures of the models, each following a player's time —
 * the pendulum (rod and mass), the phase plane (van der Pol), the plane on its spring in 3D
 * (body, wings and fin from the homework's animation data; the spring from the ceiling
 * point A to P; the ceiling), the cart from above (the homework's cartanimation: triangle
 * body, wheels at its corners, the track they leave), and a time series plot per quantity.
 * A run is {label, color, t, cols: {name: samples}}; several runs are drawn together. */
'use strict';
(function (DK) {
  /* ---- rotations (Greenwood's conventions, as dynkit/mech.h): R maps N to B ---- */

  /* R = R_phi R_theta R_psi of type I Euler angles, row-major. */
  DK.eulerToMatrix = function (psi, theta, phi) {
    const cps = Math.cos(psi), sps = Math.sin(psi), cth = Math.cos(theta), sth = Math.sin(theta);
    const cph = Math.cos(phi), sph = Math.sin(phi);
    return [cth * cps, cth * sps, -sth,
      sph * sth * cps - cph * sps, sph * sth * sps + cph * cps, sph * cth,
      cph * sth * cps + sph * sps, cph * sth * sps - sph * cps, cph * cth];
  };

  /* R(q) of a quaternion (w, x, y, z), need not be unit (dyn_quat_to_mat). */
  DK.quatToMatrix = function (w, x, y, z) {
    const n2 = w * w + x * x + y * y + z * z, s = n2 > 0 ? 2 / n2 : 0;
    const xx = s * x * x, yy = s * y * y, zz = s * z * z, xy = s * x * y, xz = s * x * z, yz = s * y * z;
    const wx = s * w * x, wy = s * w * y, wz = s * w * z;
    return [1 - (yy + zz), xy + wz, xz - wy, xy - wz, 1 - (xx + zz), yz + wx, xz + wy, yz - wx, 1 - (xx + yy)];
  };

  /* A body point rB to N: s + R^T rB. */
  DK.bodyToN = function (R, s, rB) {
    return [s[0] + R[0] * rB[0] + R[3] * rB[1] + R[6] * rB[2],
      s[1] + R[1] * rB[0] + R[4] * rB[1] + R[7] * rB[2],
      s[2] + R[2] * rB[0] + R[5] * rB[1] + R[8] * rB[2]];
  };

  /* "v [mV]", or "w" for a quantity without a unit (never "w []") */
  DK.label = function (name, unit) { return unit ? name + ' [' + unit + ']' : name; };
  /* units of length: a phase plane of two of them (the same) is a path, drawn to scale */
  DK.isLength = function (unit) { return ['m', 'km', 'cm', 'mm', 'um', 'µm', 'nm', 'ft', 'in'].includes(unit); };

  /* ---- time series: one plot per quantity, every run overlaid ---- */

  /* Every view returns an object with update(runs): the same view drawn with new runs of
   * the same model (a live page's rerun), its canvas and settings kept. */
  DK.timePlot = function (container, runs, name, player, o) {
    const unit = o && o.unit !== undefined ? o.unit : DK.unit(runs[0].raw || runs[0], name);
    const seriesOf = rs => rs.filter(r => r.cols[name]).map(r => Object.assign({ label: r.label, x: r.t, y: r.cols[name], color: r.color, dash: r.dash, unit: o && o.unit !== undefined ? o.unit : DK.unit(r.raw || r, name) }, r.map ? { width: 0, markers: 1.8 } : {}));
    const series = seriesOf(runs);
    const legend = n => (o && o.legend) || (n > 1 ? 'tr' : 'none');
    const plot = new DK.Plot(container, Object.assign({
      title: (o && o.title) || name, xlabel: 't [' + (DK.timeUnit || 's') + ']', ylabel: DK.label(name, unit), unitY: unit === '1' ? '' : unit,
      series, onSeek: t => player.seek(t)
    }, o || {}, { legend: legend(series.length) }));
    player.onTime(t => plot.setTime(t));
    plot.update = rs => { const ss = seriesOf(rs); plot.setSeries(ss, { legend: legend(ss.length) }); };
    return plot;
  };

  /* ---- pendulum: pivot at the origin, phi from the downward vertical ---- */

  DK.PendulumView = function (container, runs, l, player, o) {
    /* the paths of the masses, and a view that fits what is drawn: the pivot and the paths,
     * with room for the mass (drawn 10 px) and the pivot's hatching; at least a quarter of l
     * either side */
    const paths = rs => {
      const series = rs.map(r => {
        const phi = r.cols.phi, n = phi.length, x = new Array(n), y = new Array(n);
        for (let k = 0; k < n; k++) { x[k] = l * Math.sin(phi[k]); y[k] = -l * Math.cos(phi[k]); }
        return { label: r.label, color: r.color, t: r.t, x, y, trail: true, width: 1.2 };
      });
      let ax = 0, ylo = 0, yhi = 0;
      for (const s of series) for (let k = 0; k < s.x.length; k++) if (isFinite(s.x[k]) && isFinite(s.y[k])) {
        ax = Math.max(ax, Math.abs(s.x[k])); ylo = Math.min(ylo, s.y[k]); yhi = Math.max(yhi, s.y[k]);
      }
      const m = 0.15 * l, half = Math.max(0.25 * l, ax) + m;
      return { series, xrange: [-half, half], yrange: [ylo - m, yhi + 0.1 * l] };
    };
    const first = paths(runs);
    const plot = new DK.Plot(container, Object.assign({
      title: 'pendulum', xlabel: 'x [m]', ylabel: 'y [m]', equal: true, fitData: true, xrange: first.xrange, yrange: first.yrange,
      series: first.series, cursor: 'none', legend: 'tr', legendValues: false, aspect: 0.8, keepClear: [[0, 0]],
      overlay: (ctx, p, t) => {
        const ox = p.px(0), oy = p.py(0);
        ctx.strokeStyle = '#555'; ctx.lineWidth = 1;
        for (let k = -3; k <= 3; k++) { ctx.beginPath(); ctx.moveTo(ox + k * 6, oy); ctx.lineTo(ox + k * 6 + 5, oy - 6); ctx.stroke(); }
        ctx.beginPath(); ctx.moveTo(ox - 22, oy); ctx.lineTo(ox + 22, oy); ctx.stroke();
        for (const s of p.o.series) {
          const v = p.valueAt(s, t) || { x: s.x[s.x.length - 1], y: s.y[s.y.length - 1] };
          if (!isFinite(v.x) || !isFinite(v.y)) continue;
          ctx.strokeStyle = s.color; ctx.lineWidth = 3;
          ctx.beginPath(); ctx.moveTo(ox, oy); ctx.lineTo(p.px(v.x), p.py(v.y)); ctx.stroke();
          ctx.fillStyle = s.color; ctx.strokeStyle = '#fff'; ctx.lineWidth = 2;
          ctx.beginPath(); ctx.arc(p.px(v.x), p.py(v.y), 10, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
        }
        ctx.fillStyle = '#222'; ctx.beginPath(); ctx.arc(ox, oy, 4, 0, 2 * Math.PI); ctx.fill();
      }
    }, o || {}));
    player.onTime(t => plot.setTime(t));
    plot.update = rs => { const p = paths(rs); plot.setSeries(p.series, { xrange: p.xrange, yrange: p.yrange }); };
    return plot;
  };

  /* ---- phase plane: x against y of every run, drawn up to the current time ---- */

  DK.PhaseView = function (container, runs, xname, yname, player, o) {
    const seriesOf = rs => rs.map(r => Object.assign({ label: r.label, color: r.color, t: r.t, x: r.cols[xname], y: r.cols[yname], trail: true, width: 1.5 }, r.map ? { width: 0, markers: 1.8 } : {}));
    const series = seriesOf(runs);
    const ux = DK.unit(runs[0].raw || runs[0], xname), uy = DK.unit(runs[0].raw || runs[0], yname);
    const plot = new DK.Plot(container, Object.assign({
      title: 'phase plane', xlabel: DK.label(xname, ux), ylabel: DK.label(yname, uy),
      series, cursor: 'points', legend: 'tr', legendValues: false, aspect: 0.8
    }, o || {}));
    player.onTime(t => plot.setTime(t));
    plot.update = rs => plot.setSeries(seriesOf(rs));
    return plot;
  };

  /* ---- the plane on its spring, in 3D ---- */

  /* Shape of the plane in its body frame B (x forward, z down) from the homework's
   * animation data: fuselage of length_plane, wings of wingspan about r_wingcenter, a fin of
   * height_fin at the tail (up, i.e. -z). The chords are not in the data: a fifth and a
   * tenth of the length. */
  function planeShape(par) {
    const L = par.length_plane, b = par.wingspan, hf = par.height_fin;
    const w = [par.wing_x, par.wing_y, par.wing_z];
    const cr = 0.22 * L, ct = 0.12 * L, sweep = 0.06 * L;
    const wing = [[w[0] + cr / 2, w[1], w[2]], [w[0] + ct / 2 - sweep, w[1] + b / 2, w[2]], [w[0] - ct / 2 - sweep, w[1] + b / 2, w[2]],
      [w[0] - cr / 2, w[1], w[2]], [w[0] - ct / 2 - sweep, w[1] - b / 2, w[2]], [w[0] + ct / 2 - sweep, w[1] - b / 2, w[2]]];
    const fin = [[-L / 2, 0, 0], [-L / 2 + 0.18 * L, 0, 0], [-L / 2 + 0.02 * L, 0, -hf], [-L / 2 - 0.03 * L, 0, -hf]];
    const r = 0.035 * L; /* fuselage: a slim diamond section */
    const body = [[L / 2, 0, 0], [0.2 * L, r, 0], [-L / 2, 0, -r * 0.4], [0.2 * L, -r, 0]];
    const bodyV = [[L / 2, 0, 0], [0.2 * L, 0, -r], [-L / 2, 0, -r * 0.4], [0.2 * L, 0, r]];
    return { wing, fin, body, bodyV, nose: [L / 2, 0, 0], tail: [-L / 2, 0, 0], P: [par.px, par.py, par.pz] };
  }

  /* The state of a plane run at time t: position s and matrix R. */
  function planeAt(run, t) {
    const pos = DK.locate(run.t, t), c = run.cols;
    const s = [DK.at(c.sX, pos), DK.at(c.sY, pos), DK.at(c.sZ, pos)];
    let R;
    if (c.qw) R = DK.quatToMatrix(DK.at(c.qw, pos), DK.at(c.qx, pos), DK.at(c.qy, pos), DK.at(c.qz, pos));
    else R = DK.eulerToMatrix(DK.at(c.psi, pos), DK.at(c.theta, pos), DK.at(c.phi, pos));
    return { s, R, pos };
  }

  /* N (Z down) to the display frame (z up): a half turn about X. */
  const D = p => [p[0], -p[1], -p[2]];

  DK.helix = function (a, b, turns, radius) {
    const d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]], len = Math.hypot(d[0], d[1], d[2]) || 1;
    const e = d.map(v => v / len);
    const other = Math.abs(e[2]) < 0.9 ? [0, 0, 1] : [1, 0, 0];
    let u = [e[1] * other[2] - e[2] * other[1], e[2] * other[0] - e[0] * other[2], e[0] * other[1] - e[1] * other[0]];
    const un = Math.hypot(u[0], u[1], u[2]); u = u.map(v => v / un);
    const v = [e[1] * u[2] - e[2] * u[1], e[2] * u[0] - e[0] * u[2], e[0] * u[1] - e[1] * u[0]];
    const pts = [], n = turns * 16, lead = 0.06;
    for (let k = 0; k <= n; k++) {
      const f = k / n, along = lead + f * (1 - 2 * lead), ang = 2 * Math.PI * turns * f;
      const rad = k === 0 || k === n ? 0 : radius;
      pts.push([0, 1, 2].map(i => a[i] + d[i] * along + rad * (Math.cos(ang) * u[i] + Math.sin(ang) * v[i])));
    }
    return [a].concat(pts, [b]);
  };

  DK.PlaneView = function (container, runs, par, player, o) {
    o = o || {};
    const shape = planeShape(par);
    /* what must be seen: A and the centre of mass with the plane's reach around it */
    const reach = 0.5 * Math.max(par.wingspan, par.length_plane);
    let mean, keys, trails;
    const measure = rs => {
      mean = ['sX', 'sY', 'sZ'].map(k => rs[0].cols[k].reduce((a, v) => a + v, 0) / rs[0].cols[k].length);
      keys = [[0, 0, 0]];
      for (const r of rs) for (let k = 0; k < r.t.length; k += Math.max(1, Math.floor(r.t.length / 60))) {
        const c = [r.cols.sX[k], r.cols.sY[k], r.cols.sZ[k]];
        if (!c.every(isFinite)) continue;
        for (let i = 0; i < 3; i++) for (const sgn of [-1, 1]) { const p = c.slice(); p[i] += sgn * reach; keys.push(D(p)); }
      }
      trails = rs.map(r => r.t.map((_, k) => D([r.cols.sX[k], r.cols.sY[k], r.cols.sZ[k]])));
    };
    measure(runs);
    function world(scene, t) {
      /* the ceiling (Z = 0) around A, and the axes of N at A */
      const C = Math.max(1, Math.ceil(2 * (Math.hypot(mean[0], mean[1]) + 0.4 * par.wingspan)) / 2);
      scene.poly([[-C, -C, 0], [C, -C, 0], [C, C, 0], [-C, C, 0]].map(p => D(p)), { fill: '#d9dee6', alpha: 0.35, bias: 1e3 });
      for (let k = -C; k <= C + 1e-9; k += 0.5) {
        scene.line([D([k, -C, 0]), D([k, C, 0])], { color: '#b9c1cc', width: 0.8 }, 4);
        scene.line([D([-C, k, 0]), D([C, k, 0])], { color: '#b9c1cc', width: 0.8 }, 4);
      }
      DK.axesN(scene, D, 0.4, 'Z (down)');
      scene.text(D([0, 0, -0.08]), 'A', { color: '#222', font: '600 13px system-ui, sans-serif' });
      runs.forEach((r, i) => {
        const st = planeAt(r, t);
        const B = p => D(DK.bodyToN(st.R, st.s, p));
        /* the path of the centre of mass so far */
        const upto = trails[i].slice(0, st.pos.i + 1).concat([D(st.s)]);
        if (upto.length > 1) scene.line(upto, { color: r.color, width: 1.3, alpha: 0.55 }, 12);
        const P = B(shape.P);
        scene.line(DK.helix([0, 0, 0], P, 14, 0.035), { color: '#555', width: 1.3 }, 10);
        scene.point(P, { color: '#111', radius: 2.5 });
        scene.poly(shape.wing.map(B), { fill: r.color, alpha: 0.55, color: r.color, width: 1.2 });
        scene.poly(shape.fin.map(B), { fill: r.color, alpha: 0.75, color: r.color, width: 1.2 });
        scene.poly(shape.body.map(B), { fill: '#333', alpha: 0.8, color: r.color, width: 1 });
        scene.poly(shape.bodyV.map(B), { fill: '#444', alpha: 0.8, color: r.color, width: 1 });
        scene.line([B(shape.nose), B(shape.tail)], { color: r.color, width: 3 });
        scene.point(D(st.s), { color: r.color, radius: 3, ring: '#fff' });
      });
    }
    const view = DK.SceneView(container, runs, player, { keys, world, home: { azimuth: -1.05, elevation: 0.32 }, height: o.height, scaleNote: 'at the plane', scaleAt: t => D(planeAt(runs[0], t).s) });
    view.update = rs => { runs = rs; measure(rs); view.refit(rs, keys); };
    return view;
  };

  /* The axes of N at the origin (display frame by D), X, Y, Z labelled; zlabel for Z. */
  DK.axesN = function (scene, D, ax, zlabel) {
    scene.line([D([0, 0, 0]), D([ax, 0, 0])], { color: '#c0392b', width: 2 });
    scene.line([D([0, 0, 0]), D([0, ax, 0])], { color: '#27ae60', width: 2 });
    scene.line([D([0, 0, 0]), D([0, 0, ax])], { color: '#2c6fbb', width: 2 });
    scene.text(D([ax, 0, 0]), 'X', { color: '#c0392b' });
    scene.text(D([0, ax, 0]), 'Y', { color: '#27ae60' });
    scene.text(D([0, 0, ax]), zlabel || 'Z', { color: '#2c6fbb' });
    scene.point(D([0, 0, 0]), { color: '#222', radius: 4 });
  };

  /* ---- the cart from above (the homework's cartanimation) ---- */

  DK.CartView = function (container, runs, par, player, o) {
    o = o || {};
    const l = par.length_cart, d = par.width_cart;
    /* body points in B: rear corners (wheels A, B), the front wheel C, back to the start */
    const bodyB = [[-l / 2, -d / 2], [-l / 2, d / 2], [l / 2, 0], [-l / 2, -d / 2]];
    const toN = (sX, sY, th, p) => [sX + Math.cos(th) * p[0] - Math.sin(th) * p[1], sY + Math.sin(th) * p[0] + Math.cos(th) * p[1]];
    /* the paths of the wheels A, B (rear) and C (front) of every run */
    const paths = rs => {
      const series = [];
      for (const r of rs) {
        const c = r.cols, n = r.t.length, w = [0, 1, 2].map(() => ({ x: new Array(n), y: new Array(n) }));
        for (let k = 0; k < n; k++) {
          const sX = c.sX[k], sY = c.sY[k], co = Math.cos(c.theta[k]), si = Math.sin(c.theta[k]);
          for (let j = 0; j < 3; j++) {
            const p = bodyB[j];
            w[j].x[k] = sX + co * p[0] - si * p[1];
            w[j].y[k] = sY + si * p[0] + co * p[1];
          }
        }
        series.push({ label: r.label, color: r.color, t: r.t, x: w[0].x, y: w[0].y, trail: true, width: 1.4 });
        series.push({ label: r.label + ' B', noLegend: true, color: r.color, t: r.t, x: w[1].x, y: w[1].y, trail: true, width: 1.4 });
        series.push({ label: r.label + ' C', noLegend: true, color: r.color, t: r.t, x: w[2].x, y: w[2].y, trail: true, width: 1, dash: [3, 3] });
      }
      return series;
    };
    const series = paths(runs);
    const ext = [DK.extent(series.map(s => s.x)), DK.extent(series.map(s => s.y))];
    const big = Math.max(ext[0][1] - ext[0][0], ext[1][1] - ext[1][0]) > (o.followAbove || 30);
    const select = DK.el('select', { class: 'view-mode', 'aria-label': 'view' });
    /* the views: the whole path, or following a run (kept at a rerun while that run is there) */
    const options = rs => {
      const was = select.value;
      select.replaceChildren(DK.el('option', { value: '-1', text: 'whole path' }));
      rs.forEach((r, i) => select.appendChild(DK.el('option', { value: String(i), text: 'follow ' + r.label })));
      if (was && Number(was) < rs.length) select.value = was;
    };
    options(runs);
    select.value = big ? String(o.follow || 0) : '-1';
    container.appendChild(DK.el('div', { class: 'view-controls' }, [DK.el('label', {}, ['view: ', select])]));
    const win = o.window || 16;
    const plot = new DK.Plot(container, Object.assign({
      title: 'cart, seen from above', xlabel: 'X [m]', ylabel: 'Y [m]', equal: true, fitData: true, series, cursor: 'none', legend: 'tr', legendValues: false, aspect: 0.7,
      viewport: t => {
        const i = parseInt(select.value, 10);
        if (i < 0) return null;
        const r = runs[i], p = DK.locate(r.t, t), x = DK.at(r.cols.sX, p), y = DK.at(r.cols.sY, p);
        return [[x - win / 2, x + win / 2], [y - win / 2, y + win / 2]];
      },
      overlay: (ctx, p, t) => {
        const ox = p.px(0), oy = p.py(0);
        ctx.strokeStyle = '#1f4e9c'; ctx.lineWidth = 1.5;
        ctx.beginPath(); ctx.moveTo(ox - 5, oy - 5); ctx.lineTo(ox + 5, oy + 5); ctx.moveTo(ox - 5, oy + 5); ctx.lineTo(ox + 5, oy - 5); ctx.stroke();
        for (const r of runs) {
          const pos = DK.locate(r.t, t), c = r.cols;
          const sX = DK.at(c.sX, pos), sY = DK.at(c.sY, pos), th = DK.at(c.theta, pos);
          if (!isFinite(sX) || !isFinite(sY) || !isFinite(th)) continue;
          const pts = bodyB.map(q => toN(sX, sY, th, q)).map(q => [p.px(q[0]), p.py(q[1])]);
          ctx.beginPath(); ctx.moveTo(pts[0][0], pts[0][1]);
          for (let k = 1; k < pts.length; k++) ctx.lineTo(pts[k][0], pts[k][1]);
          ctx.globalAlpha = 0.18; ctx.fillStyle = r.color; ctx.fill(); ctx.globalAlpha = 1;
          ctx.strokeStyle = r.color; ctx.lineWidth = 4; ctx.lineJoin = 'round'; ctx.stroke();
          /* the wheels: red stars at the corners, as in the homework's animation */
          ctx.strokeStyle = '#e01b1b'; ctx.lineWidth = 2;
          for (let k = 0; k < 3; k++) {
            const [x, y] = pts[k];
            ctx.beginPath();
            for (let a = 0; a < 3; a++) { const an = a * Math.PI / 3; ctx.moveTo(x - 6 * Math.cos(an), y - 6 * Math.sin(an)); ctx.lineTo(x + 6 * Math.cos(an), y + 6 * Math.sin(an)); }
            ctx.stroke();
          }
          ctx.fillStyle = '#111'; ctx.beginPath(); ctx.arc(p.px(sX), p.py(sY), 2.5, 0, 2 * Math.PI); ctx.fill();
        }
      }
    }, o.plot || {}));
    select.addEventListener('change', () => plot.draw());
    player.onTime(t => plot.setTime(t));
    plot.update = rs => { runs = rs; options(rs); plot.setSeries(paths(rs)); };
    return plot;
  };
})(window.DK);
