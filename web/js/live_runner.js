/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit page: the runs of a live page's module (web/js/live.js; its entry
 * backends/wasm/live_run.c): a run's settings written into the module's buffers, its rows
 * read back. A long run goes to a worker, so that the page stays responsive, draws the run as
 * it computes and can cancel it when a newer change comes; a short one (predicted from the
 * page's last runs to take at most LOCAL_MS, and of at most LOCAL_SAMPLES samples) runs on the
 * page's own thread, in an instance of the same compiled module, without the worker's two
 * messages. docs/web.md, "Live pages"; the times in docs/performance.md, section 20. */
'use strict';
(function (DK) {
  const CHUNK_MS = 40;          /* a long run's samples reach the page this often */
  /* a run runs on the page's thread when predicted to take at most LOCAL_MS (the worker's
   * round trip costs up to 40 ms on a loaded machine, a frame 16 ms) and has at most
   * LOCAL_SAMPLES samples */
  const LOCAL_MS = 8;
  const RATES = 5;              /* the runs whose median time per sample predicts the next */
  const LOCAL_SAMPLES = 50000;

  /* The runs of one instance of the module. Its text is also the worker's source: it uses
   * nothing from outside. send(rows, n): the rows [sent, n) of a run under way, at the
   * module's dynkit.progress every chunkMs at most (null: never). */
  function moduleRuns(chunkMs, send) {
    'use strict';
    let x = null, cols = 0, sent = 0, lastPost = 0;
    /* the rows [sent, n) copied out of the module's memory */
    const take = n => {
      const rows = new Float64Array(x.memory.buffer, x.dk_live_rows() + sent * cols * 8, (n - sent) * cols).slice();
      sent = n;
      lastPost = performance.now();
      return rows;
    };
    const progress = n => {
      if (!send || performance.now() - lastPost < chunkMs) return;
      send(take(n), n);
    };
    /* the instance, set up for the model (choose: the built-in model of a module of all) */
    const attach = async (module, choose) => {
      const instance = await WebAssembly.instantiate(module, { dynkit: { progress } });
      x = instance.exports;
      if (x._initialize) x._initialize();
      if (choose !== undefined && choose !== null && x.dk_live_choose) x.dk_live_choose(choose);
      if (!x.dk_live_setup()) throw new Error('the model could not be set up (out of memory)');
      cols = x.dk_live_cols();
      return cols;
    };
    /* one run of the settings j: {rows, n, ms, message, rhsCalls} */
    const run = j => {
      const mem = () => x.memory.buffer;
      new Float64Array(mem(), x.dk_live_settings(), j.settings.length).set(j.settings);
      const mbuf = new Uint8Array(mem(), x.dk_live_method(), 64);
      mbuf.fill(0); mbuf.set(new TextEncoder().encode(j.method).subarray(0, 63));
      new Float64Array(mem(), x.dk_live_params(), j.params.length).set(j.params);
      new Float64Array(mem(), x.dk_live_inits(), j.inits.length).set(j.inits);
      new Float64Array(mem(), x.dk_live_given(), j.given.length).set(j.given);
      sent = 0;
      lastPost = performance.now();
      const t0 = performance.now();
      const n = Math.max(x.dk_live_run(), 0);
      const ms = performance.now() - t0;
      const rows = take(n);
      const bytes = new Uint8Array(mem()), mp = x.dk_live_message();
      let e = mp; while (bytes[e]) e++;
      return { rows, n, ms, message: new TextDecoder().decode(bytes.subarray(mp, e)), rhsCalls: x.dk_live_rhs_calls() };
    };
    return { attach, run };
  }

  /* The worker's script: the module instantiated from the compiled module it is sent, then
   * batches of runs, each run's rows sent back as they come and at its end. */
  function liveWorker(chunkMs, runsOf) {
    'use strict';
    let batch = 0, job = 0;
    const runs = runsOf(chunkMs, (rows, n) => postMessage({ batch, job, rows, n }, [rows.buffer]));
    onmessage = async e => {
      const m = e.data;
      try {
        if (m.module) {
          postMessage({ cols: await runs.attach(m.module, m.choose) });
          return;
        }
        batch = m.batch;
        for (job = 0; job < m.jobs.length; job++) {
          const r = runs.run(m.jobs[job]);
          postMessage(Object.assign({ batch, job, done: true }, r), [r.rows.buffer]);
        }
      } catch (err) {
        postMessage({ batch, error: String(err && err.message || err) });
      }
    };
  }

  function decode64(text) {
    const bin = atob(text), out = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
    return out;
  }

  /* The module of a zlib stream (cli/pages/zlib_write.c) in base64 text: inflated by the
   * browser and compiled, once per text (the report's models share one). */
  let compiled = null;
  DK.liveModule = function (text) {
    if (!compiled || compiled.text !== text) {
      const inflated = new Blob([decode64(text)]).stream().pipeThrough(new DecompressionStream('deflate'));
      compiled = { text, module: new Response(inflated).arrayBuffer().then(bytes => WebAssembly.compile(bytes)) };
    }
    return compiled.module;
  };

  /* The module's runs. run(jobs, onRows, o) gives the runs' {rows, n, message, rhsCalls, ms}
   * once all are done: on the page's thread when short (o.samples, the samples expected in
   * all, and o.localMs, the longest predicted time run there), else in the worker, which
   * calls onRows([{rows, n}] of the runs begun) as a long one computes; a run asked for while
   * another is under way in the worker ends that one (the worker is stopped and another
   * started: its promise is rejected with Runner.cancelled). `where` says where the last
   * run ran: 'page' or 'worker'. */
  class Runner {
    constructor(module, choose) {
      this.module = module;
      this.choose = choose; /* a module of every built-in model: the one to run */
      this.url = URL.createObjectURL(new Blob(['(' + liveWorker.toString() + ')(' + CHUNK_MS + ', ' + moduleRuns.toString() + ');'], { type: 'text/javascript' }));
      this.batch = 0;
      this.cancels = 0;
      this.perSample = null; /* ms per sample predicted: the median of the last RATES runs' */
      this.rates = [];
      this.local = null;
      const local = moduleRuns(CHUNK_MS, null);
      this.localReady = local.attach(module, choose).then(() => { if (!this.closed) this.local = local; }, () => {});
      this.start();
    }

    start() {
      const w = this.worker = new Worker(this.url);
      this.ready = new Promise((resolve, reject) => {
        this.rejectReady = reject;
        w.onmessage = e => {
          if (e.data.error) reject(new Error(e.data.error));
          else { this.cols = e.data.cols; w.onmessage = m => this.received(m.data); resolve(); }
        };
        w.onerror = e => { e.preventDefault(); reject(new Error(e.message || 'the worker failed')); };
      });
      this.ready.catch(() => {}); /* reported by the run that awaits it */
      w.postMessage({ module: this.module, choose: this.choose });
    }

    /* A message of the batch under way: rows of a run, a run's end, or an error. */
    received(m) {
      const b = this.pending;
      if (!b || m.batch !== b.batch) return;
      if (m.error) { this.pending = null; this.restart(); b.reject(new Error(m.error)); return; }
      if (m.done && !b.acc[m.job]) b.acc[m.job] = { rows: m.rows, n: m.n }; /* a run in one piece */
      else this.append(b, m);
      if (!m.done) { if (b.onRows) b.onRows(b.acc); return; }
      const acc = b.acc[m.job];
      b.results[m.job] = { rows: acc.rows.subarray(0, acc.n * this.cols), n: acc.n, message: m.message, rhsCalls: m.rhsCalls, ms: m.ms };
      if (m.job === b.jobs.length - 1) { this.pending = null; this.learn(b.results); b.resolve(b.results); }
    }

    /* The rows of a message after those of its run received before (a buffer that grows). */
    append(b, m) {
      const acc = b.acc[m.job] || (b.acc[m.job] = { rows: new Float64Array(Math.max(m.n, 1024) * this.cols), n: 0 });
      const need = m.n * this.cols;
      if (need > acc.rows.length) {
        const grown = new Float64Array(Math.max(need, 2 * acc.rows.length));
        grown.set(acc.rows.subarray(0, acc.n * this.cols));
        acc.rows = grown;
      }
      acc.rows.set(m.rows, acc.n * this.cols);
      acc.n = m.n;
    }

    /* The time per sample of the runs just done (their clock has 0.1 ms steps at worst),
     * and the median of the last RATES (a run slowed by the machine's load does not send
     * the next ones to the worker). */
    learn(results) {
      const n = results.reduce((a, r) => a + r.n, 0), ms = results.reduce((a, r) => a + r.ms, 0);
      if (!(n > 0)) return;
      this.rates.push(Math.max(ms, 0.1) / n);
      if (this.rates.length > RATES) this.rates.shift();
      const sorted = this.rates.slice().sort((a, b) => a - b);
      this.perSample = sorted[Math.floor(sorted.length / 2)];
    }

    /* Whether runs of that many samples in all run on the page's thread. */
    short(samples, localMs) {
      return !!this.local && this.perSample !== null && samples <= LOCAL_SAMPLES && samples * this.perSample <= localMs;
    }

    restart() { this.worker.terminate(); this.start(); }

    /* The worker stopped for good (a page that shows another model's runs): the batch under
     * way and a start not yet done end with Runner.stopped. */
    close() {
      const b = this.pending;
      this.closed = true;
      this.pending = null;
      this.local = null;
      this.worker.terminate();
      this.rejectReady(Runner.stopped);
      if (b) b.reject(Runner.stopped);
    }

    async run(jobs, onRows, o) {
      if (this.closed) return new Promise(() => {}); /* the page shows another model */
      if (this.pending) { /* a newer change: the older run stops */
        const old = this.pending;
        this.pending = null;
        this.cancels++;
        this.restart();
        old.reject(Runner.cancelled);
      }
      const localMs = o && o.localMs !== undefined ? o.localMs : LOCAL_MS;
      if (o && this.short(o.samples, localMs)) {
        this.where = 'page';
        try {
          const results = jobs.map(j => this.local.run(j));
          this.learn(results);
          return results;
        } catch (e) {
          this.local = null; /* an instance that failed is not used again */
          throw e;
        }
      }
      this.where = 'worker';
      const b = { batch: ++this.batch, jobs, onRows, acc: [], results: [] };
      const done = new Promise((resolve, reject) => { b.resolve = resolve; b.reject = reject; });
      done.catch(() => {}); /* handled by whoever awaits it; none when cancelled early */
      this.pending = b;
      try {
        await this.ready;
      } catch (e) {
        if (this.pending === b) this.pending = null;
        throw e;
      }
      if (this.pending === b) this.worker.postMessage({ batch: b.batch, jobs });
      return done;
    }
  }
  Runner.cancelled = { cancelled: true };
  Runner.stopped = { stopped: true }; /* the page went on to another model (close) */
  Runner.LOCAL_MS = LOCAL_MS;
  DK.LiveRunner = Runner;
})(window.DK);
