/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: an XPPAUT animation (.ani) for the runs of a live page. The module (the .ode
 * file's C with the animation's formulas as outputs, dyn_ani_ode_to_c in dynkit/ani.h)
 * writes, after t, the states and the outputs of every sample, the numbers of that sample's
 * frame; here they become the page's data.ani.runs as cli/pages/ani_page.c writes them for
 * web/js/ani.js: per primitive its numbers over the samples drawn (a permanent primitive's
 * place is the first frame's, its colour every frame's), colours clamped to [0, 1] (XPPAUT's
 * eval_ani_color), and a vtext's string followed by its value as C's printf "%g" does
 * (dyn_ani_vtext). Only numbers are read. docs/web.md, "Live pages". */
'use strict';
(function (DK) {
  const strip = s => (s.indexOf('.') >= 0 ? s.replace(/0+$/, '').replace(/\.$/, '') : s);

  /* C's printf("%g", x): 6 significant digits, trailing zeros dropped, the exponent form
   * when the exponent is below -4 or at least 6 (two digits at least) */
  DK.printfG = function (x) {
    if (Number.isNaN(x)) return 'nan';
    if (!isFinite(x)) return x > 0 ? 'inf' : '-inf';
    if (x === 0) return Object.is(x, -0) ? '-0' : '0';
    const [mant, exp] = x.toExponential(5).split('e');
    const e = Number(exp);
    if (e < -4 || e >= 6) return strip(mant) + 'e' + (e < 0 ? '-' : '+') + String(Math.abs(e)).padStart(2, '0');
    return strip(x.toFixed(5 - e));
  };

  /* data.ani.runs[r] of one run: rows (cols numbers per sample, the frame's from column
   * base), the samples keep; counts[i]: how many numbers primitive i of ani.prims has */
  DK.liveAniRun = function (ani, counts, rows, cols, base, keep) {
    let offset = 0;
    return ani.prims.map((p, i) => {
      const n = counts[i], at = base + offset;
      offset += n;
      const colour = p.color === null ? n - 1 : -1;
      const column = k => keep.map(s => {
        const x = rows[s * cols + at + k];
        return k === colour ? (x > 1 ? 1 : x < 0 ? 0 : x) : x;
      });
      const v = [];
      for (let k = 0; k < n; k++) v.push(p.permanent && k !== colour ? column(k)[0] : column(k));
      const out = { v };
      if (p.kind === 'vtext') {
        const text = p.text || '', value = v[2];
        out.s = typeof value === 'number' ? text + DK.printfG(value) : value.map(x => text + DK.printfG(x));
      }
      return out;
    });
  };
})(window.DK);
