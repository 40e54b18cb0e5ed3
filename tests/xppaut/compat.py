#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Compatibility of dynkit's .ode reader with XPPAUT itself.

For every .ode file given (by default the examples Debian's xppaut package ships and
dynkit's own examples/models), run the file's default run with `xppaut FILE -silent`
(which writes output.dat: t, the states in declaration order, then the aux values) and
with `dynkit run FILE --outputs` using the same method and step (XPPAUT's default method,
the classical Runge-Kutta method, unless the file sets @ meth), and compare the two
tables at the common sample times. XPPAUT writes 8 significant digits, so two runs of the
same method agree to about 1e-7 relative while the solution is not chaotic; a chaotic
run agrees up to a time and then separates: that time is reported.

XPPAUT 8 (Debian 12) is not deterministic on every file: parsing cuplamdif.ode it reads an
uninitialised stack buffer (valgrind: strtod on a stack allocation), and about 1 run in 70
integrates other numbers from the first step on. A file that does not agree is therefore run
by XPPAUT again (XPPAUT_RUNS times in all) and compared with the output most of the runs
gave; the result then says how many distinct outputs XPPAUT wrote.

Prints a summary (accepted, refused with the feature named, agreeing) and writes a JSON
report with --json FILE. Exit status 0 unless --require lists files that must agree, fewer
than --min-agree agree, or a document given with --doc states counts this run did not
measure (the README's sentence, docs/model-files.md's table). When
it fails, every file that did not agree keeps its inputs and both programs' outputs under
the artifacts directory (artifacts_dir below), in a directory of its own for this run.
"""
import argparse
import collections
import datetime
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np

DEBIAN_EXAMPLES = "/usr/share/doc/xppaut/examples/ode"
XPPAUT_RUNS = 5  # XPPAUT's runs of a file that does not agree at the first


def artifacts_dir(dynkit):
    """build/tests/artifacts beside the dynkit binary (build/dynkit), or
    $DYNKIT_TEST_ARTIFACTS."""
    env = os.environ.get("DYNKIT_TEST_ARTIFACTS")
    if env:
        return env
    return os.path.join(os.path.dirname(os.path.abspath(dynkit)), "tests", "artifacts")


def keep_artifacts(dynkit, label, paths, extra=None):
    """Copy paths (files or directories) into a new directory of this run under
    artifacts_dir/label (named by the UTC time and the process, so that a rerun does not
    overwrite it), with extra {name: text} files; returns the directory."""
    stamp = datetime.datetime.now(datetime.timezone.utc).strftime("%Y%m%dT%H%M%S.%fZ")
    dest = os.path.join(artifacts_dir(dynkit), label, "%s-%d" % (stamp, os.getpid()))
    os.makedirs(dest, exist_ok=True)
    for p in paths:
        if not p or not os.path.exists(p):
            continue
        target = os.path.join(dest, os.path.basename(os.path.normpath(p)))
        if os.path.isdir(p):  # compiled models left out
            shutil.copytree(p, target, dirs_exist_ok=True,
                            ignore=shutil.ignore_patterns("cache"))
        else:
            shutil.copy(p, target)
    for name, text in (extra or {}).items():
        with open(os.path.join(dest, name), "w") as f:
            f.write(text)
    return dest


def has_algebraic(text):
    """The file has algebraic equations (0=...)."""
    return any(re.match(r"\s*0\s*=", line) for line in text.splitlines())


def file_method(text):
    for line in text.splitlines():
        s = line.strip().lower()
        if s.startswith("@"):
            m = re.search(r"\bmeth(od)?\s*=\s*([a-z0-9]+)", s)
            if m:
                return m.group(2)
    return None


# XPPAUT's methods that choose their own steps (or are otherwise not dynkit's): such files
# are compared with the classical Runge-Kutta method at the file's dt in both programs, so
# that the comparison checks what the file means, not two different error controls.
FIXED_STEP = ("rungekutta", "runge", "r", "euler", "e", "modeuler", "m")


def is_map(text, meth):
    """A discrete map (x(t+1)=, or meth=discrete and its prefixes): both programs iterate
    it with their own (the only) method."""
    if meth is not None and "discrete".startswith(meth):
        return True
    return re.search(r"(?im)^\s*[a-z_][a-z0-9_]*\s*\(\s*t\s*\+\s*1\s*\)\s*=", text) is not None


def has_special(text):
    """A network sum (special): XPPAUT writes an aux output that reads one from the sum's
    last evaluation inside the step, not at the written state (nnet2.ode: by symmetry its
    k5 equals u5 at t = 0.05; XPPAUT writes 2.2146626e-06 beside u5 = 2.2141799e-06), so
    only the states of such files are compared."""
    return re.search(r"(?im)^\s*sp(ecial)?\s", text) is not None


def state_count(dynkit, path, method, timeout, env):
    """The number of states of a model file (columns of a run without --outputs, less t)."""
    cmd = [dynkit, "run", path, "--final", "--quiet"] + (["--method", method] if method else [])
    try:
        out = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        return None
    head = out.stdout.splitlines()[:1]
    return len(head[0].split(",")) - 1 if out.returncode == 0 and head else None


def rk4_everywhere(text):
    return re.sub(r"(?i)\b(meth(od)?\s*=\s*)[a-z0-9]+", r"\1rungekutta", text)


def run_xppaut(path, workdir, timeout, text=None):
    """output.dat of xppaut -silent as an array, or (None, reason)."""
    base = os.path.basename(path)
    # companion files (tables, .so) are looked up next to the .ode file
    src_dir = os.path.dirname(os.path.abspath(path))
    for name in os.listdir(src_dir):
        if name.endswith((".tab", ".dat")) and not os.path.exists(os.path.join(workdir, name)):
            shutil.copy(os.path.join(src_dir, name), workdir)
    if text is None:
        shutil.copy(path, os.path.join(workdir, base))
    else:
        with open(os.path.join(workdir, base), "w") as f:
            f.write(text)
    out = os.path.join(workdir, "output.dat")
    if os.path.exists(out):
        os.remove(out)
    try:
        subprocess.run(["xppaut", base, "-silent"], cwd=workdir, timeout=timeout,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        return None, "xppaut timed out"
    if not os.path.exists(out) or os.path.getsize(out) == 0:
        return None, "xppaut wrote no output"
    try:
        data = np.loadtxt(out, ndmin=2)
    except ValueError as e:
        return None, "xppaut output unreadable: %s" % e
    return data, None


def xppaut_majority(path, workdir, timeout, text, first):
    """XPPAUT's output that most of XPPAUT_RUNS runs give (first: the first run's), and how
    many distinct outputs the runs gave. The runs' output.dat files stay in workdir."""
    out = os.path.join(workdir, "output.dat")
    outputs = [first]
    digests = [hashlib.sha256(first.tobytes()).hexdigest()]
    shutil.copy(out, os.path.join(workdir, "output-run1.dat"))
    for k in range(2, XPPAUT_RUNS + 1):
        data, _ = run_xppaut(path, workdir, timeout, text)
        if data is None:
            continue
        shutil.copy(out, os.path.join(workdir, "output-run%d.dat" % k))
        outputs.append(data)
        digests.append(hashlib.sha256(data.tobytes()).hexdigest())
    counts = collections.Counter(digests)
    best, n_best = counts.most_common(1)[0]
    return outputs[digests.index(best)], len(counts), n_best, len(digests)


def run_dynkit(dynkit, path, method, timeout, env, keep=None):
    """dynkit's table of the file's default run; with keep (a directory), its command,
    standard output and error are written there."""
    cmd = [dynkit, "run", path, "--outputs", "--quiet"]
    if method:
        cmd += ["--method", method]
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        return None, "dynkit timed out", 124
    if keep:
        os.makedirs(keep, exist_ok=True)
        with open(os.path.join(keep, "dynkit.csv"), "w") as f:
            f.write(p.stdout)
        with open(os.path.join(keep, "dynkit.stderr"), "w") as f:
            f.write("$ %s\nexit status %d\n%s" % (" ".join(cmd), p.returncode, p.stderr))
    if p.returncode != 0 and not p.stdout.strip():
        return None, p.stderr.strip(), p.returncode
    rows = [r for r in p.stdout.splitlines()[1:] if r.strip()]
    if not rows:
        return None, p.stderr.strip() or "no samples", p.returncode
    data = np.array([[float(v) for v in r.split(",")] for r in rows])
    return data, (p.stderr.strip() if p.returncode else None), p.returncode


def refused_feature(message):
    """The feature a refusal names, from dynkit's message FILE:LINE:COL: error: ..."""
    first = message.splitlines()[0] if message else ""
    m = re.search(r"error: (.*)", first)
    text = m.group(1) if m else first
    text = re.sub(r"'[^']*'", "'...'", text)
    return text.strip()


def file_option(text, name, default):
    """The number of option `name` on the file's first @ line that gives it."""
    for line in text.splitlines():
        s = line.strip().lower()
        if s.startswith("@"):
            m = re.search(r"\b%s\s*=\s*([-+0-9.eE]+)" % name, s)
            if m:
                return float(m.group(1))
    return default


def file_t0(text):
    return file_option(text, "t0", 0.0)


def file_dt(text):
    return file_option(text, "dt", 0.05)


def is_old_format(text):
    """XPPAUT's first format: the first line is a positive number (its `v` lines declare
    the variables, not integral equations)."""
    m = re.match(r"[ \t]*\+?([0-9]+)", text)
    return m is not None and int(m.group(1)) > 0


def has_volterra(text):
    """Volterra integrals (int{...}, int[m]{...}) or integral equations (volt, x(t)=): XPPAUT
    runs them with its volterra method whatever meth says, and dynkit with the same one."""
    if is_old_format(text):
        return re.search(r"(?i)\bint\s*[\[{]", text) is not None
    return re.search(r"(?i)\bint\s*[\[{]|^\s*v(olt(erra)?)?\s+[a-z]", text, re.M) is not None


def has_global(text):
    """A global event: XPPAUT reads the statement by its first letter ("globa1 1 ...")."""
    return re.search(r"(?im)^\s*g[a-z0-9]*\s+[-+]?[01]\s", text) is not None


def has_noise(text):
    """wiener, normal(), ran(), Markov states or gill: the two runs draw other random
    numbers."""
    return re.search(r"(?im)^\s*(wiener|markov)\b|\b(ran|normal|gill)\s*\(", text) is not None


def compare(xpp, dyn, t0, rtol=2e-6, scaled=False):
    """(agreement, first time of disagreement or None, max relative difference); runs that
    share no sample after the start t0 (the initial state alone) are not compared."""
    if xpp.shape[1] != dyn.shape[1]:
        return "columns differ (xppaut %d, dynkit %d)" % (xpp.shape[1], dyn.shape[1]), None, None
    # common times (XPPAUT prints t in single precision)
    tx, td = xpp[:, 0], dyn[:, 0]
    idx = np.searchsorted(td, tx - 1e-6 * (1 + abs(tx)))
    ok = (idx < len(td))
    idx = np.minimum(idx, len(td) - 1)
    ok &= np.abs(td[idx] - tx) <= 1e-5 * (1 + np.abs(tx))
    if not np.any(ok & (tx > t0 + 1e-9 * (1 + abs(t0)))):
        # the initial state alone (XPPAUT stopped at once) agrees by construction
        return "no common sample time after t0 = %g" % t0, None, None
    x = xpp[ok][:, 1:]
    d = dyn[idx[ok]][:, 1:]
    t = tx[ok]
    scale = np.maximum(np.max(np.abs(x), axis=0), 1e-12)
    if scaled:  # a tolerance on the column's scale (after global events)
        err = np.abs(d - x) / (rtol * scale)
    else:
        err = np.abs(d - x) / (rtol * (np.abs(x) + 1e-3 * scale))
    bad = np.any(err > 1.0, axis=1)
    rel = float(np.max(np.abs(d - x) / (np.abs(x) + 1e-3 * scale)))
    if not bad.any():
        return "agree", None, rel
    first = float(t[np.argmax(bad)])
    return "separate", first, rel


def verdict_text(r):
    """One line for a result of check_file."""
    return (r.get("reason") or r.get("compare", "")
            + ("" if r.get("t_separate") is None
               else " at t=%g of %g" % (r["t_separate"], r["t_end"]))
            + ("" if r.get("xppaut_stops") is None
               else " (xppaut stops at t=%g)" % r["xppaut_stops"])
            + ("" if r.get("xppaut_runs") is None else " (%s)" % r["xppaut_runs"]))


def check_file(dynkit, path, timeout, env, work, xppaut_refused=False):
    """Run one file in both programs; a dict: status accepted/refused/failed, and for an
    accepted file the comparison (agree, separate with the time, or why not compared).
    With xppaut_refused, a file dynkit refuses is run by XPPAUT too ("xppaut": whether
    it integrates it)."""
    base = os.path.basename(path)
    with open(path, errors="replace") as f:
        text = f.read()
    meth = file_method(text)
    own_steps = meth is not None and meth not in FIXED_STEP and not is_map(text, meth)
    method = None if is_map(text, meth) else "rk4" if meth is None or own_steps else None
    if has_noise(text):  # the model's method for noise (euler, rkmil, a map)
        own_steps, method = False, None
    if has_volterra(text):  # the model's method, volterra, as XPPAUT's
        own_steps, method = False, None
    r = {"file": base}
    xdir = os.path.join(work, "x-" + base)
    r["work"] = xdir
    os.makedirs(xdir, exist_ok=True)
    dyn, msg, rc = run_dynkit(dynkit, path, method, timeout, env, keep=xdir)
    if dyn is None and rc == 2:
        r["status"] = "refused"
        r["reason"] = refused_feature(msg)
        if xppaut_refused:
            xpp, why = run_xppaut(path, xdir, timeout)
            r["xppaut"] = "integrates (%d rows)" % len(xpp) if xpp is not None else why
    elif dyn is None:
        r["status"] = "failed"
        r["reason"] = (msg or "").splitlines()[0] if msg else "no output"
    else:
        r["status"] = "accepted"
        if msg:
            r["note"] = msg.splitlines()[0]
        if own_steps:
            r["method"] = "rk4 in both (the file asks for meth=%s)" % meth
        xpp, why = run_xppaut(path, xdir, timeout,
                              rk4_everywhere(text) if own_steps else None)
        xpp_all = xpp
        if xpp is None:
            r["compare"] = why
        else:
            # XPPAUT places a global event by linear interpolation inside the
            # step (an error of order dt^2 in the event's time), dynkit on the
            # step's dense output: after an event the two differ by that much
            rtol, scaled = 2e-6, False
            if has_global(text):
                rtol, scaled = max(rtol, 10 * file_dt(text) ** 2), True
                r["tolerance"] = "10 dt^2 of the column's scale (global events)"
            if has_algebraic(text):
                # XPPAUT solves 0= equations to its Newton tolerance only: against
                # SciPy its values are off by up to 1e-3 (dae_check.py)
                rtol, scaled = max(rtol, 2e-3), True
                r["tolerance"] = "2e-3 of the column's scale (XPPAUT's algebraic " \
                                 "values are good to 1e-3: dae_check.py)"
            ns = state_count(dynkit, path, method, timeout, env) \
                if has_special(text) else None
            t0 = file_t0(text)

            def cut(x):
                """The columns and rows of XPPAUT's table that are compared."""
                if ns is not None:
                    x = x[:, :1 + ns]
                if has_volterra(text):
                    x = x[x[:, 0] > t0 + 1e-9 * (1 + abs(t0))]
                return x
            xpp = cut(xpp)
            if ns is not None:
                dyn = dyn[:, :1 + ns]
                r["columns"] = "states only (aux outputs of network sums differ by " \
                               "XPPAUT's evaluation inside the step)"
            if has_volterra(text):
                # XPPAUT writes the initial data of its integral equations at t0, not their
                # values there (lamvolt.ode: u = 0 where u(0) = u0 exp(0) = 1)
                r["rows"] = "after t0 (XPPAUT writes the integral equations' initial data there)"
            verdict, t_sep, rel = compare(xpp, dyn, file_t0(text), rtol, scaled)
            if verdict != "agree" and not has_noise(text):
                # XPPAUT may misread the file now and then: its usual output decides
                usual, distinct, n_usual, n_runs = xppaut_majority(
                    path, xdir, timeout, rk4_everywhere(text) if own_steps else None, xpp_all)
                if distinct > 1:
                    r["xppaut_runs"] = ("%d runs of xppaut wrote %d different outputs: compared "
                                        "with the one %d of them wrote"
                                        % (n_runs, distinct, n_usual))
                    xpp = cut(usual)
                    verdict, t_sep, rel = compare(xpp, dyn, file_t0(text), rtol, scaled)
            # XPPAUT may end a run early (its default bound 100): the runs are
            # compared as far as it goes, and the line says so
            t_xpp, t_dyn = float(xpp[-1, 0]), float(dyn[-1, 0])
            if t_xpp < t_dyn - 1e-5 * (1 + abs(t_dyn)):
                r["xppaut_stops"] = t_xpp
            if verdict == "separate" and has_noise(text):
                verdict = "noise: other random numbers than XPPAUT's"
            r["compare"] = verdict
            r["t_separate"] = t_sep
            r["max_rel_diff"] = rel
            r["t_end"] = float(xpp[-1, 0])
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dynkit", help="the dynkit binary")
    ap.add_argument("files", nargs="*", help=".ode files (default: Debian's xppaut examples)")
    ap.add_argument("--json", help="write the per-file results here")
    ap.add_argument("--timeout", type=float, default=60)
    ap.add_argument("--require", nargs="*", default=[],
                    help="base names of files that must be accepted and agree")
    ap.add_argument("--min-agree", type=int, default=0,
                    help="fail when fewer files agree over their whole run")
    ap.add_argument("--doc", action="append", default=[],
                    help="a document that states the counts of this run (the README's "
                         "'N of M are accepted, K agree over the whole run', the table of "
                         "docs/model-files.md): fail when a count differs")
    args = ap.parse_args()
    files = args.files or sorted(os.path.join(DEBIAN_EXAMPLES, f)
                                 for f in os.listdir(DEBIAN_EXAMPLES) if f.endswith(".ode"))
    env = dict(os.environ)
    results = []
    with tempfile.TemporaryDirectory() as work:
        env.setdefault("DYNKIT_CACHE_DIR", os.path.join(work, "cache"))
        for path in files:
            r = check_file(args.dynkit, path, args.timeout, env, work)
            r["path"] = os.path.abspath(path)
            results.append(r)
            print("%-22s %-9s %s" % (r["file"], r["status"], verdict_text(r)), flush=True)
        rc = verdict(args, results)
        if rc != 0:
            keep = [r for r in results if r.get("compare") != "agree"]
            for r in keep:  # the input beside both programs' outputs
                if not os.path.exists(os.path.join(r["work"], r["file"])):
                    shutil.copy(r["path"], r["work"])
            dest = keep_artifacts(args.dynkit, "xppaut-compat", [r["work"] for r in keep],
                                  {"results.json": json.dumps(results, indent=1)})
            print("the inputs and outputs of the %d files that did not agree are kept in %s"
                  % (len(keep), dest))
    return rc


def verdict(args, results):
    """Prints the summary, writes the JSON report; the exit status."""
    n = len(results)
    acc = [r for r in results if r["status"] == "accepted"]
    agree = [r for r in acc if r.get("compare") == "agree"]
    sep = [r for r in acc if r.get("compare") == "separate"]
    refused = [r for r in results if r["status"] == "refused"]
    print("\n%d files: %d accepted (%d agree over the whole run, %d agree and then separate), "
          "%d refused, %d failed" % (n, len(acc), len(agree), len(sep), len(refused),
                                    n - len(acc) - len(refused)))
    reasons = {}
    for r in refused:
        reasons[r["reason"]] = reasons.get(r["reason"], 0) + 1
    for reason, count in sorted(reasons.items(), key=lambda kv: -kv[1]):
        print("  refused %3d: %s" % (count, reason))
    if args.json:
        os.makedirs(os.path.dirname(os.path.abspath(args.json)), exist_ok=True)
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    missing = [b for b in args.require
               if not any(r["file"] == b and r.get("compare") == "agree" for r in results)]
    if missing:
        print("required to agree but did not: " + ", ".join(missing))
        return 1
    failed = [r["file"] for r in results if r["status"] == "failed"]
    if failed:
        print("failed (neither a result nor a usage error): " + ", ".join(failed))
        return 1
    if len(agree) < args.min_agree:
        print("%d files agree, fewer than the %d required" % (len(agree), args.min_agree))
        return 1
    measured = {"files": n, "accepted": len(acc), "agree": len(agree), "refused": len(refused)}
    stale = [m for doc in args.doc for m in doc_mismatches(doc, measured)]
    for m in stale:
        print(m)
    return 1 if stale else 0


# The counts as the documents state them: the README's sentence and the rows of the table
# in docs/model-files.md, "Compatibility with XPPAUT".
DOC_COUNTS = [
    (r"compares them: (?P<accepted>\d+) of (?P<files>\d+) are accepted, "
     r"(?P<agree>\d+) agree over the whole run", ("accepted", "files", "agree")),
    (r"\| Debian's (?P<files>\d+) example files \|", ("files",)),
    (r"\n\| accepted \| (?P<accepted>\d+) \|", ("accepted",)),
    (r"\n\| — agree with XPPAUT over the whole run [^\n]*\| (?P<agree>\d+) \|", ("agree",)),
    (r"\n\| refused, with the feature named \| (?P<refused>\d+) \|", ("refused",)),
]


def doc_mismatches(path, measured):
    """Messages for each count of the file at path that is not the one measured; a document
    that states none of them is a mismatch too (the sentence was reworded)."""
    with open(path, encoding="utf-8") as f:
        text = re.sub(r"\s*\n\s*", "\n", f.read())
    flat = text.replace("\n", " ")
    found, out = 0, []
    for pattern, keys in DOC_COUNTS:
        m = re.search(pattern, text if pattern.startswith(r"\n") else flat)
        if not m:
            continue
        found += 1
        for k in keys:
            if int(m.group(k)) != measured[k]:
                out.append("%s states %s %s, this run measured %d: update the document"
                           % (path, m.group(k), k, measured[k]))
    if not found:
        out.append("%s states none of the counts of this run (%s)"
                   % (path, ", ".join("%s %d" % kv for kv in measured.items())))
    return out


if __name__ == "__main__":
    sys.exit(main())
