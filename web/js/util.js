/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: shared helpers — the namespace DK, DOM building, number formatting, nice
 * axis ticks, sample lookup and linear interpolation in time, the line colours. */
'use strict';
window.DK = window.DK || {};
(function (DK) {
  /* The line colours; cli/pages/svg_plot.c uses the same. */
  DK.colors = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2',
    '#17becf'];

  /* el('div', {class: 'x', text: 'hello', onclick: f}, [children]) */
  DK.el = function (tag, attrs, children) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (v === undefined || v === null) continue;
      if (k === 'text') e.textContent = v;
      else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
      else e.setAttribute(k, v);
    }
    for (const c of children || []) if (c) e.appendChild(typeof c === 'string' ? document.createTextNode(c) : c);
    return e;
  };

  /* A number for people: fixed or exponential, no trailing noise. */
  DK.fmt = function (v, digits) {
    if (v === null || v === undefined || !isFinite(v)) return '—';
    digits = digits || 4;
    const a = Math.abs(v);
    if (a !== 0 && (a < 1e-3 || a >= 1e6)) return v.toExponential(Math.max(digits - 1, 0)).replace('e+', 'e');
    return Number(v.toPrecision(digits)).toString();
  };

  /* A step of 1, 2 or 5 times a power of ten, about range / target. */
  DK.niceStep = function (range, target) {
    const raw = range / target, p = Math.pow(10, Math.floor(Math.log10(raw))), f = raw / p;
    return (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * p;
  };

  /* Tick values inside [lo, hi] and their labels. A tiny range on large values (a conserved
   * energy, 237.453059026 .. 237.453059031) is labelled relative to an offset, out.offset
   * (the ticks' common leading digits, as cli/pages/svg_axes.c does), which the plot shows. */
  DK.ticks = function (lo, hi, target) {
    const step = DK.niceStep(hi - lo, target), out = [];
    const digits = Math.max(0, Math.ceil(-Math.log10(step) - 1e-9));
    const k0 = Math.ceil(lo / step - 1e-9), k1 = Math.floor(hi / step + 1e-9);
    let offset = 0;
    if (Math.max(Math.abs(k0 * step), Math.abs(k1 * step)) >= 1e5 * step && k1 >= k0) {
      const span = Math.pow(10, Math.ceil(Math.log10((k1 - k0) * step + step)));
      offset = Math.floor(k0 * step / span) * span;
    }
    for (let k = k0; k <= k1; k++) {
      let v = k * step;
      if (Math.abs(v) < 1e-9 * step) v = 0;
      const d = offset ? (k - Math.round(offset / step)) * step : v;
      const mag = Math.max(Math.abs(d), step);
      const label = d === 0 ? '0' : mag >= 1e5 || mag < 1e-3 ? Number(d.toPrecision(3)).toExponential().replace('e+', 'e') : d.toFixed(digits);
      out.push({ v: v, label: offset && d > 0 ? '+' + label : label });
    }
    out.offset = offset;
    return out;
  };

  const SUP = { '-': '⁻', '0': '⁰', '1': '¹', '2': '²', '3': '³', '4': '⁴', '5': '⁵', '6': '⁶', '7': '⁷', '8': '⁸', '9': '⁹' };
  /* Ticks of a logarithmic axis in [lo, hi] (values > 0): the powers of ten, or 1, 2 and 5
   * times them (with plain numbers) when the range spans less than two decades. */
  DK.logTicks = function (lo, hi) {
    const out = [];
    const k0 = Math.floor(Math.log10(lo)), k1 = Math.ceil(Math.log10(hi));
    const inside = v => v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9);
    if (Math.log10(hi / lo) < 2) {
      for (let k = k0; k <= k1; k++) for (const m of [1, 2, 5]) {
        const v = m * Math.pow(10, k);
        if (inside(v)) out.push({ v, label: Math.abs(k) < 5 ? String(Number(v.toPrecision(1))) : m + '×10' + String(k).split('').map(c => SUP[c]).join('') });
      }
      return out;
    }
    const every = Math.max(1, Math.ceil((k1 - k0 + 1) / 8));
    for (let k = k0; k <= k1; k++) {
      const v = Math.pow(10, k);
      if ((k - k0) % every || !inside(v)) continue;
      out.push({ v, label: '10' + String(k).split('').map(c => SUP[c]).join('') });
    }
    return out;
  };

  /* Position of time t in the increasing array ts: {i, f} with t = ts[i] + f (ts[i+1] - ts[i]),
   * clamped to the ends. */
  DK.locate = function (ts, t) {
    const n = ts.length;
    if (n === 0) return { i: 0, f: 0 };
    if (!(t > ts[0])) return { i: 0, f: 0 };
    if (t >= ts[n - 1]) return { i: n - 1, f: 0 };
    let lo = 0, hi = n - 1;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (ts[mid] <= t) lo = mid; else hi = mid;
    }
    const d = ts[hi] - ts[lo];
    return { i: lo, f: d > 0 ? (t - ts[lo]) / d : 0 };
  };

  /* Value of the array at a position from DK.locate. */
  DK.at = function (arr, pos) {
    const a = arr[pos.i];
    if (pos.f === 0 || pos.i + 1 >= arr.length) return a;
    const b = arr[pos.i + 1];
    if (a === null || b === null) return a;
    return a + pos.f * (b - a);
  };

  /* A column of a recorded run {columns, units, data} by name, or null. */
  DK.column = function (run, name) {
    const j = run.columns.indexOf(name);
    return j < 0 ? null : run.data[j];
  };
  DK.unit = function (run, name) {
    const j = run.columns.indexOf(name);
    return j < 0 ? '' : run.units[j];
  };

  /* Smallest and largest finite value of arrays (null when none). */
  DK.extent = function (arrays) {
    let lo = Infinity, hi = -Infinity;
    for (const a of arrays) for (const v of a) if (v !== null && isFinite(v)) { if (v < lo) lo = v; if (v > hi) hi = v; }
    return lo <= hi ? [lo, hi] : null;
  };

  DK.clamp = (v, lo, hi) => Math.min(hi, Math.max(lo, v));
})(window.DK);
