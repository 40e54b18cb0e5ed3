/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: a mechanism's scene for the runs of a live page. The module (the model's C
 * with DYN_MECH_SCENE_INPUTS) writes, after t, the states and the outputs of every sample,
 * the numbers the frames are computed from (the file's formulas at that sample: the scene's
 * inputs); here the steps of dyn_mech_scene_eval (src/mbs/mbs_scene.c: body_pose, point_of,
 * axis_n, contact, shape_values) turn them, with the plan the tool wrote (data.mech_plan:
 * which input is which body's angle, offset, size...; dynkit/mbs.h, dyn_mech_*_plan), into
 * each body's pose and each shape's numbers in N, the format of data.mech.runs that
 * web/js/mech.js draws. Only numbers are read: no text of the model reaches this code.
 * docs/web.md, "Live pages". */
'use strict';
(function (DK) {
  const N_VALUES = { box: 6, cylinder: 8, sphere: 4, rod: 6, spring: 6, frame: 4, ground: 7, trace: 3, arrow: 6 };

  /* One frame: fix (the inputs) into pose (12 per body) and values (the shapes' numbers). */
  function frame(plan, shapes, fix) {
    const inp = (k, none) => (k >= 0 ? fix[k] : none);
    const pose = new Array(12 * plan.bodies.length).fill(0);
    const g = plan.gravity.map(k => inp(k, 0));
    const unitAxis = b => {
      const n = b.axisv.map(k => inp(k, 0));
      const len = Math.sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      return n.map(x => x / len);
    };
    /* R = E R for the passive rotation by a about axis 0..2, or 3 (the joint's axis) */
    const turn = (b, R, axis, a) => {
      const co = Math.cos(a), si = Math.sin(a), E = new Array(9).fill(0);
      let n = [0, 0, 0];
      if (axis < 3) n[axis] = 1; else n = unitAxis(b);
      for (let r = 0; r < 3; r++) for (let k = 0; k < 3; k++) {
        E[3 * r + k] = (1 - co) * n[r] * n[k] + (r === k ? co : 0);
        if (r !== k) E[3 * r + k] += ((k - r + 3) % 3 === 1 ? si : -si) * n[3 - r - k];
      }
      const T = new Array(9);
      for (let r = 0; r < 3; r++) for (let k = 0; k < 3; k++) T[3 * r + k] = E[3 * r] * R[k] + E[3 * r + 1] * R[3 + k] + E[3 * r + 2] * R[6 + k];
      for (let k = 0; k < 9; k++) R[k] = T[k];
    };
    plan.bodies.forEach((b, bi) => {
      const o = 12 * bi, R = [1, 0, 0, 0, 1, 0, 0, 0, 1];
      if (b.frame && b.quat[0] >= 0) {
        const w = inp(b.quat[0], 1), v = [inp(b.quat[1], 0), inp(b.quat[2], 0), inp(b.quat[3], 0)];
        const vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2], n2 = w * w + vv;
        const sk = [0, -v[2], v[1], v[2], 0, -v[0], -v[1], v[0], 0];
        for (let r = 0; r < 3; r++) for (let c = 0; c < 3; c++) R[3 * r + c] = ((r === c ? w * w - vv : 0) + 2 * v[r] * v[c] - 2 * w * sk[3 * r + c]) / n2;
      } else if (b.frame) {
        for (let k = 0; k < b.axis.length; k++) turn(b, R, b.axis[k], inp(b.angle[k], 0));
      }
      for (let k = 0; k < 9; k++) pose[o + 3 + k] = R[k];
      if (!b.joint) {
        for (let k = 0; k < 3; k++) pose[o + k] = inp(b.at[k], 0);
        return;
      }
      const p = b.parent >= 0 ? plan.bodies[b.parent] : null, op = 12 * b.parent;
      let n = [0, 0, 0];
      if (b.slide >= 0 && b.slide_axis === 3) n = unitAxis(b); else if (b.slide >= 0) n[b.slide_axis] = 1;
      const slide = inp(b.slide, 0), a = [], pv = [];
      for (let k = 0; k < 3; k++) { a.push(inp(b.jp[k], 0) + inp(b.shift[k], 0) + n[k] * slide); pv.push(inp(b.pivot[k], 0)); }
      let r = a.slice();
      if (p && p.frame) {
        const Rp = pose.slice(op + 3, op + 12), Rj = R.slice();
        for (let i = 0; i < 3; i++) for (let j = 0; j < 3; j++) R[3 * i + j] = Rj[3 * i] * Rp[j] + Rj[3 * i + 1] * Rp[3 + j] + Rj[3 * i + 2] * Rp[6 + j];
        for (let k = 0; k < 9; k++) pose[o + 3 + k] = R[k];
        r = [0, 1, 2].map(k => Rp[k] * a[0] + Rp[3 + k] * a[1] + Rp[6 + k] * a[2]);
      }
      for (let k = 0; k < 3; k++) {
        const off = b.frame ? R[k] * pv[0] + R[3 + k] * pv[1] + R[6 + k] * pv[2] : pv[k];
        pose[o + k] = (p ? pose[op + k] : 0) + r[k] - off;
      }
    });
    const pointOf = (body, pt) => {
      const q = pt.map(k => inp(k, 0));
      if (body < 0) return q;
      const o = 12 * body;
      return [0, 1, 2].map(k => pose[o + k] + pose[o + 3 + k] * q[0] + pose[o + 6 + k] * q[1] + pose[o + 9 + k] * q[2]);
    };
    const axisN = (s, body) => {
      let a = [0, 0, 0];
      if (s.avec[0] >= 0) a = s.avec.map(k => inp(k, 0)); else a[s.axis] = 1;
      const o = 12 * body;
      const out = [0, 1, 2].map(k => (body >= 0 ? pose[o + 3 + k] * a[0] + pose[o + 6 + k] * a[1] + pose[o + 9 + k] * a[2] : a[k]));
      const len = Math.sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
      return out.map(x => (len > 0 ? x / len : NaN));
    };
    const values = [];
    shapes.forEach((sh, i) => {
      const s = plan.shapes[i], v = new Array(N_VALUES[sh.kind] || 0).fill(NaN);
      const put = (at, xs) => xs.forEach((x, k) => { v[at + k] = x; });
      switch (sh.kind) {
        case 'box': put(0, pointOf(s.body, s.p)); for (let k = 0; k < 3; k++) v[3 + k] = 0.5 * Math.abs(inp(s.v[k], NaN)); break;
        case 'cylinder': put(0, pointOf(s.body, s.p)); v[3] = inp(s.v[0], NaN); v[4] = 0.5 * inp(s.v[1], 0); put(5, axisN(s, s.body)); break;
        case 'sphere': put(0, pointOf(s.body, s.p)); v[3] = inp(s.v[0], NaN); break;
        case 'frame': put(0, pointOf(s.body, s.p)); v[3] = inp(s.size, NaN); break;
        case 'rod': case 'spring': put(0, pointOf(s.body, s.p)); put(3, pointOf(s.body_b, s.p_b)); break;
        case 'ground': {
          put(0, pointOf(s.body, s.p));
          const hasG = g[0] !== 0 || g[1] !== 0 || g[2] !== 0;
          const n = [0, 1, 2].map(k => (s.v[0] >= 0 ? inp(s.v[k], 0) : hasG ? -g[k] : (k === 2 ? 1 : 0)));
          const len = Math.sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
          put(3, n.map(x => (len > 0 ? x / len : NaN)));
          v[6] = 0.5 * inp(s.size, NaN);
          break;
        }
        case 'trace': put(0, pointOf(s.body, s.p)); break;
        case 'arrow': {
          if (s.wheel >= 0) { /* at the wheel's contact C - r k, along x or y of N */
            const wh = plan.wheels[s.wheel], c = pointOf(wh.body, wh.at);
            const a = axisN({ avec: wh.axis, axis: 0 }, wh.body), r = inp(wh.radius, 0);
            const k = [-a[2] * a[0], -a[2] * a[1], 1 - a[2] * a[2]], n = Math.sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]);
            put(0, [0, 1, 2].map(j => c[j] - (n > 0 ? r * k[j] / n : NaN)));
            put(3, [0, 1, 2].map(j => (j === s.axis ? 1 : 0)));
            break;
          }
          put(0, pointOf(s.body, s.p));
          let d = s.v.map(k => inp(k, 0));
          if (s.in_body && s.body >= 0) {
            const o = 12 * s.body, b = d;
            d = [0, 1, 2].map(k => pose[o + 3 + k] * b[0] + pose[o + 6 + k] * b[1] + pose[o + 9 + k] * b[2]);
          }
          const len = Math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
          put(3, d.map(x => (len > 0 ? x / len : 0)));
          break;
        }
      }
      values.push(v);
    });
    return { pose, values };
  }

  /* The scene of one run: rows (cols numbers per sample, the scene's inputs from column
   * base), the samples keep; {poses: [body][12 arrays], values: [shape][arrays]}. */
  DK.liveMechRun = function (plan, shapes, rows, cols, base, keep) {
    const nb = plan.bodies.length;
    const poses = Array.from({ length: nb }, () => Array.from({ length: 12 }, () => []));
    const values = shapes.map(s => Array.from({ length: N_VALUES[s.kind] || 0 }, () => []));
    for (const k of keep) {
      const f = frame(plan, shapes, rows.subarray(k * cols + base, k * cols + base + plan.inputs));
      for (let b = 0; b < nb; b++) for (let q = 0; q < 12; q++) poses[b][q].push(f.pose[12 * b + q]);
      f.values.forEach((v, i) => v.forEach((x, q) => values[i][q].push(x)));
    }
    return { poses, values };
  };
})(window.DK);
