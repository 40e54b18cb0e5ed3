/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: an XPPAUT animation (.ani) of a model file, drawn on a canvas in the file's
 * coordinates — [0,1]x[0,1] unless `dimension` says otherwise, y up, equal scales — at the
 * player's time. The numbers come from the tool (cli/pages/ani_page.c: every primitive evaluated
 * in C at every sample); here they are interpolated between samples, and drawn as XPPAUT's
 * animator draws them (its aniparse.c): primitives in the file's order, widths and comet
 * dots in pixels, rline from the end of the last line, text in the current colour (the last
 * settext's or the last primitive's), the symbol font as Greek letters, colours by name or
 * from XPPAUT's colour map (color.c), comets as the last n samples up to the time shown. */
'use strict';
(function (DK) {
  /* XPPAUT's named colours (color.c: MakeColormap); BLACK is its foreground colour, which
   * it also uses for $WHITE and for a primitive without a colour. */
  const NAMED = {
    BLACK: 'rgb(0,0,0)', RED: 'rgb(255,0,0)', REDORANGE: 'rgb(240,100,0)', ORANGE: 'rgb(255,165,0)',
    YELLOWORANGE: 'rgb(255,205,0)', YELLOW: 'rgb(200,200,0)', YELLOWGREEN: 'rgb(200,235,75)',
    GREEN: 'rgb(0,225,0)', BLUEGREEN: 'rgb(0,200,200)', BLUE: 'rgb(0,0,255)', PURPLE: 'rgb(160,32,240)'
  };

  /* A formula's colour z in [0, 1]: entry (int)(200 z) of XPPAUT's default colour map
   * (color.c: make_cmaps, C_NORM, 201 entries): 0 is dark blue, 0.5 cyan, 1 red. */
  DK.aniColor = function (z) {
    if (z === null || !isFinite(z)) return NAMED.BLACK;
    const k = Math.floor(200 * Math.min(1, Math.max(0, z)));
    const y = 1 - k / 201;
    const r = y > 0.33333333333 ? 0 : Math.floor(3 * 255 * Math.sqrt((0.333334 - y) * (y + 0.33334)));
    const g = y > 0.666666 ? 0 : Math.floor(3 * 255 * Math.sqrt((0.6666667 - y) * y));
    const b = y < 0.333334 ? 0 : Math.floor(2.79 * 255 * Math.sqrt((1.05 - y) * (y - 0.333333333)));
    const c = v => Math.min(255, Math.max(0, v || 0));
    return 'rgb(' + c(r) + ',' + c(g) + ',' + c(b) + ')';
  };

  /* XPPAUT's symbol font (Adobe Symbol): Latin letters shown as Greek ones. */
  const GREEK = { a: 'α', b: 'β', c: 'χ', d: 'δ', e: 'ε', f: 'φ', g: 'γ', h: 'η', i: 'ι', j: 'ϕ', k: 'κ', l: 'λ', m: 'μ', n: 'ν', o: 'ο', p: 'π', q: 'θ', r: 'ρ', s: 'σ', t: 'τ', u: 'υ', v: 'ϖ', w: 'ω', x: 'ξ', y: 'ψ', z: 'ζ', A: 'Α', B: 'Β', C: 'Χ', D: 'Δ', E: 'Ε', F: 'Φ', G: 'Γ', H: 'Η', I: 'Ι', J: 'ϑ', K: 'Κ', L: 'Λ', M: 'Μ', N: 'Ν', O: 'Ο', P: 'Π', Q: 'Θ', R: 'Ρ', S: 'Σ', T: 'Τ', U: 'Υ', V: 'ς', W: 'Ω', X: 'Ξ', Y: 'Ψ', Z: 'Ζ' };
  const greek = s => s.replace(/[A-Za-z]/g, ch => GREEK[ch] || ch);
  /* settext sizes 0..4 (XPPAUT's five fonts), in CSS pixels */
  const SIZES = [9, 12, 14, 18, 24];

  /* The animation of every run; the first is shown, a menu picks another. */
  DK.AniView = function (container, runs, ani, player, o) {
    o = o || {};
    const [xlo, ylo, xhi, yhi] = ani.window;
    const canvas = DK.el('canvas', { class: 'ani-canvas', 'aria-label': 'animation ' + ani.file });
    const wrap = DK.el('div', { class: 'dk-scene dk-ani' }, [canvas]);
    /* the menu of the runs, shown when there are several (kept choice while it exists) */
    const select = DK.el('select', { class: 'view-mode', 'aria-label': 'run' });
    const controls = DK.el('div', { class: 'view-controls' }, [DK.el('label', {}, ['run: ', select])]);
    const options = rs => {
      const was = select.value;
      select.replaceChildren(...rs.map((r, i) => DK.el('option', { value: String(i), text: r.label })));
      if (was && Number(was) < rs.length) select.value = was;
      controls.hidden = rs.length < 2;
    };
    options(runs);
    container.appendChild(controls);
    container.appendChild(wrap);
    container.appendChild(DK.el('p', { class: 'hint', text: 'XPPAUT animation ' + ani.file + ' (' + ani.prims.length + ' commands; window [' + DK.fmt(xlo) + ', ' + DK.fmt(xhi) + '] × [' + DK.fmt(ylo) + ', ' + DK.fmt(yhi) + '])' }));
    const state = { t: player.t };
    let w = 0, h = 0, dpr = 1;
    function size() {
      const avail = Math.max(200, Math.floor(wrap.clientWidth || 600));
      const ratio = (yhi - ylo) / (xhi - xlo);
      let cw = avail, ch = cw * ratio;
      const maxH = o.maxHeight || 560;
      if (ch > maxH) { ch = maxH; cw = ch / ratio; }
      cw = Math.max(60, Math.floor(cw)); ch = Math.max(60, Math.floor(ch));
      if (cw === w && ch === h) return;
      w = cw; h = ch; dpr = window.devicePixelRatio || 1;
      canvas.width = Math.round(w * dpr); canvas.height = Math.round(h * dpr);
      canvas.style.width = w + 'px'; canvas.style.height = h + 'px';
      canvas.style.margin = '0 auto';
    }
    function paint() {
      size();
      const ctx = canvas.getContext('2d');
      ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
      ctx.fillStyle = '#ffffff';
      ctx.fillRect(0, 0, w, h);
      const ri = parseInt(select.value, 10) || 0;
      const run = runs[ri], vals = ani.runs[ri];
      if (!run || !vals) return;
      const s = w / (xhi - xlo);
      const px = x => (x - xlo) * s, py = y => h - (y - ylo) * s;
      const pos = DK.locate(run.t, state.t);
      const near = pos.f < 0.5 ? pos.i : Math.min(pos.i + 1, run.t.length - 1);
      const val = v => (typeof v === 'number' ? v : v === null ? NaN : DK.at(v, pos));
      const valAt = (v, k) => (typeof v === 'number' ? v : v === null ? NaN : v[k]);
      const colorOf = (p, v, z) => (p.color !== null ? NAMED[p.color] || NAMED.BLACK : DK.aniColor(z !== undefined ? z : val(v[v.length - 1])));
      const ok = (...a) => a.every(x => x !== null && isFinite(x));
      /* the text state a frame starts with: where the last one ended (XPPAUT keeps its
       * drawing context from frame to frame) */
      const text = { size: 1, font: 'roman', color: NAMED.BLACK };
      ani.prims.forEach((p, i) => {
        if (p.kind === 'settext') Object.assign(text, { size: p.size, font: p.font, color: NAMED[p.color] || NAMED.BLACK });
        else if (p.kind !== 'text' && p.kind !== 'vtext') text.color = colorOf(p, vals[i].v);
      });
      let lastX = 0, lastY = 0;
      ctx.lineCap = 'butt'; ctx.lineJoin = 'round';
      ani.prims.forEach((p, i) => {
        const v = vals[i].v, c = v.map(val);
        if (p.kind === 'settext') {
          Object.assign(text, { size: p.size, font: p.font, color: NAMED[p.color] || NAMED.BLACK });
          return;
        }
        if (p.kind === 'text' || p.kind === 'vtext') {
          if (!ok(c[0], c[1])) return;
          let str = p.kind === 'text' ? p.text : (typeof vals[i].s === 'string' ? vals[i].s : vals[i].s[near]);
          if (text.font === 'symbol') str = greek(str);
          ctx.fillStyle = text.color;
          ctx.font = SIZES[text.size] + 'px "Times New Roman", Times, serif';
          ctx.textBaseline = 'alphabetic';
          ctx.textAlign = 'left';
          ctx.fillText(str, px(c[0]), py(c[1]));
          return;
        }
        const col = colorOf(p, v);
        text.color = col;
        ctx.strokeStyle = col; ctx.fillStyle = col;
        ctx.lineWidth = Math.max(1, p.thickness || 0);
        switch (p.kind) {
          case 'line':
            if (ok(...c.slice(0, 4))) {
              ctx.beginPath(); ctx.moveTo(px(c[0]), py(c[1])); ctx.lineTo(px(c[2]), py(c[3])); ctx.stroke();
              lastX = c[2]; lastY = c[3];
            }
            break;
          case 'rline':
            if (ok(c[0], c[1], lastX, lastY)) {
              ctx.beginPath(); ctx.moveTo(px(lastX), py(lastY));
              lastX += c[0]; lastY += c[1];
              ctx.lineTo(px(lastX), py(lastY)); ctx.stroke();
            }
            break;
          case 'rect': case 'frect':
            if (ok(...c.slice(0, 4))) {
              const x = Math.min(px(c[0]), px(c[2])), y = Math.min(py(c[1]), py(c[3]));
              const rw = Math.abs(px(c[2]) - px(c[0])), rh = Math.abs(py(c[3]) - py(c[1]));
              if (p.kind === 'frect') ctx.fillRect(x, y, rw, rh); else ctx.strokeRect(x, y, rw, rh);
            }
            break;
          case 'circle': case 'fcircle':
            if (ok(c[0], c[1], c[2])) {
              ctx.beginPath(); ctx.arc(px(c[0]), py(c[1]), Math.abs(c[2]) * s, 0, 2 * Math.PI);
              if (p.kind === 'fcircle') ctx.fill(); else ctx.stroke();
            }
            break;
          case 'ellipse': case 'fellipse':
            if (ok(...c.slice(0, 4))) {
              ctx.beginPath(); ctx.ellipse(px(c[0]), py(c[1]), Math.abs(c[2]) * s, Math.abs(c[3]) * s, 0, 0, 2 * Math.PI);
              if (p.kind === 'fellipse') ctx.fill(); else ctx.stroke();
            }
            break;
          case 'comet': {
            /* the last `length` points: samples up to the time shown, then the point now */
            const n = p.length, pts = [];
            const k1 = pos.f > 0 ? pos.i : pos.i - 1;
            for (let k = Math.max(0, k1 - (n - 2)); k <= k1; k++) {
              pts.push([valAt(v[0], k), valAt(v[1], k), p.color === null ? valAt(v[2], k) : undefined]);
            }
            pts.push([c[0], c[1], p.color === null ? c[2] : undefined]);
            while (pts.length > n) pts.shift();
            if (p.type < 0) {
              const rad = -p.type;
              for (const q of pts) {
                if (!ok(q[0], q[1])) continue;
                ctx.fillStyle = colorOf(p, v, q[2]);
                ctx.beginPath(); ctx.arc(px(q[0]), py(q[1]), rad, 0, 2 * Math.PI); ctx.fill();
              }
            } else if (pts.length > 2) {
              ctx.lineWidth = Math.max(1, p.type);
              for (let k = 1; k < pts.length; k++) {
                const a = pts[k - 1], b = pts[k];
                if (!ok(a[0], a[1], b[0], b[1])) continue;
                ctx.strokeStyle = colorOf(p, v, b[2]);
                ctx.beginPath(); ctx.moveTo(px(a[0]), py(a[1])); ctx.lineTo(px(b[0]), py(b[1])); ctx.stroke();
              }
            }
            break;
          }
        }
      });
    }
    /* drawn once at DK.releaseDraws when draws are held (a live page's rerun) */
    const held = { draw: () => paint() };
    function draw() { if (DK.heldDraws) DK.heldDraws.add(held); else paint(); }
    size();
    select.addEventListener('change', () => draw());
    if (window.ResizeObserver) new ResizeObserver(() => draw()).observe(wrap);
    player.onTime(t => { state.t = t; draw(); });
    /* new runs with their frames (a live page's rerun, data.ani of the same file): the
     * canvas and the run chosen kept; data.ani_stale: the animation keeps the runs it has
     * (the tool's: the page's module does not compute its frames) */
    const accepts = (rs, data) => !!data.ani_stale || (!!data.ani && data.ani.prims.length === ani.prims.length && data.ani.runs.length === rs.length);
    const update = (rs, data) => {
      if (!data.ani_stale) { runs = rs; ani = data.ani; options(rs); }
      draw();
    };
    return { canvas, draw, accepts, update };
  };
})(window.DK);
