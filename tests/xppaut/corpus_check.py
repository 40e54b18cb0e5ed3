#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Published .ode files from public repositories against XPPAUT (tests/xppaut/corpus/).

The files are not part of dynkit: tests/xppaut/corpus/manifest.tsv names each one (the
repository, the path and the commit it was taken from, its SHA-256 and size, the features
it uses, and the outcome measured). Given a directory holding them as
DIR/OWNER/REPO/PATH (by default $DYNKIT_ODE_CORPUS), every file is checked against its
SHA-256, run by `xppaut FILE -silent` and by `dynkit run FILE` with the same method and
step (compat.py's rules: the classical Runge-Kutta method where the file asks for a method
that chooses its own steps; a tolerance of the column's scale after global events), and
compared at XPPAUT's output times. A chaotic run agrees up to a time and then separates:
the time is printed. A file dynkit refuses is run by XPPAUT too, to say whether XPPAUT
integrates it. A file with `set` lines, for which `xppaut -silent` writes each set's run
into SET.dat and no output.dat, is compared set by set with `dynkit run --set ...`.

Prints a table (one line a file) and a summary. Exit status: 77 (skipped) without the
directory, 1 when a file is missing or differs from its SHA-256 or when an outcome is
not the manifest's `expect` (agree, separate, noise: other random numbers, and each
column's time mean over the second half of XPPAUT's run within 4 standard deviations of
dynkit's runs with 8 seeds (noise-differs when not);
refused while XPPAUT integrates the file; xppaut-fails: both refuse or XPPAUT writes
nothing; not-compared: dynkit runs it, XPPAUT's run shares no sample after the start), else 0.
"""
import argparse
import hashlib
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compat  # noqa: E402  (same directory)

MANIFEST = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus", "manifest.tsv")
COLUMNS = ("repo", "path", "commit", "sha256", "size", "features", "expect")

# what a file uses, by the statements and functions XPPAUT reads (the manifest's column)
FEATURES = (
    ("global", r"(?im)^\s*g[a-z0-9]*\s+[-+]?[01]\s"),
    ("aux", r"(?im)^\s*aux\s"),
    ("fun", r"(?im)^\s*[a-z_][a-z0-9_]*\s*\([a-z_][a-z0-9_,\s]*\)\s*=(?!=)"),
    ("fixed", r"(?im)^\s*[a-z_][a-z0-9_]*\s*=(?!=)"),
    ("table", r"(?im)^\s*tab(le)?\s"),
    ("array", r"\[[0-9]+\s*\.\.\s*[0-9]+\]"),
    ("noise", r"(?im)^\s*wiener\b|\b(ran|normal)\s*\("),
    ("delay", r"(?i)\bdelay\s*\("),
    ("markov", r"(?im)^\s*markov\b"),
    ("volterra", r"(?i)\bint\s*(\[[^\]]*\])?\s*\{"),
    ("special", r"(?im)^\s*sp(ecial)?\s"),
    ("dae", r"(?im)^\s*0\s*="),
    ("map", r"(?im)^\s*[a-z_][a-z0-9_]*\s*\(\s*t\s*\+\s*1\s*\)\s*="),
    ("heav", r"(?i)\bheav\s*\("),
    ("numbered-par", r"(?im)^\s*par(am)?[0-9]+-[0-9]+\s"),
    ("set", r"(?im)^\s*set\s"),
    ("old-format", r"\A\s*[0-9]+\s*\n"),
)


def features(text):
    """The manifest's feature list of a file: the method it asks for, then FEATURES."""
    text = "\n".join(l for l in text.splitlines() if not l.lstrip().startswith("#"))
    out = []
    meth = compat.file_method(text)
    if meth:
        out.append("meth=" + meth)
    out += [name for name, rx in FEATURES if re.search(rx, text)]
    return ",".join(out) or "-"


SET_LINE = re.compile(r"(?im)^\s*set\s+([a-z_][a-z0-9_]*)\s*\{([^}]*)\}")


def check_sets(dynkit, path, work, timeout, env):
    """A file with `set` lines: `xppaut -silent` runs each set into SET.dat instead of the
    default run into output.dat. Each set's table against `dynkit run --set NAME=VALUE ...`
    with the set's values (the classical Runge-Kutta method at dt, XPPAUT's default): the
    worst verdict, or None when the file has no sets or XPPAUT wrote no set's table."""
    with open(path, errors="replace") as f:
        text = f.read()
    sets = SET_LINE.findall(text)
    if not sets or compat.file_method(text) is not None:
        return None
    xdir = os.path.join(work, "sets")
    os.makedirs(xdir, exist_ok=True)
    compat.run_xppaut(path, xdir, timeout)
    verdicts = []
    for name, body in sets:
        table = os.path.join(xdir, name + ".dat")
        if not os.path.exists(table):
            return None
        xpp = compat.np.loadtxt(table, ndmin=2)
        cmd = [dynkit, "run", path, "--outputs", "--quiet", "--method", "rk4"]
        for a in body.split(","):
            cmd += ["--set", a.strip()]
        p = compat.subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
        rows = [r for r in p.stdout.splitlines()[1:] if r.strip()]
        if p.returncode or not rows:
            return "set %s: dynkit: %s" % (name, p.stderr.strip().splitlines()[:1])
        dyn = compat.np.array([[float(v) for v in r.split(",")] for r in rows])
        verdict, t_sep, _ = compat.compare(xpp, dyn, compat.file_t0(text))
        verdicts.append((verdict, t_sep, name))
    bad = [v for v in verdicts if v[0] != "agree"]
    if not bad:
        return "agree"
    v = bad[0]
    return "%s (set %s%s)" % (v[0], v[2], "" if v[1] is None else " at t=%g" % v[1])


SEEDS = 8


def noise_statistics(dynkit, path, work, timeout, env):
    """A file with noise (the two programs draw other random numbers) compared by
    statistics: each column's time mean over the second half of XPPAUT's run, against the
    same mean in dynkit's runs with seeds 1..SEEDS. XPPAUT's must lie within 4 standard
    deviations of dynkit's runs (sd sqrt(1 + 1/SEEDS), a prediction interval; at least
    1e-6 of the column's scale). Returns (agrees, text)."""
    xdir = os.path.join(work, "stats")
    os.makedirs(xdir, exist_ok=True)
    xpp, why = compat.run_xppaut(path, xdir, timeout)
    if xpp is None:
        return False, why
    t_end = float(xpp[-1, 0])
    t_lo = float(xpp[0, 0]) + 0.5 * (t_end - float(xpp[0, 0]))
    xsel = xpp[:, 0] >= t_lo
    means = []
    for seed in range(1, SEEDS + 1):
        p = subprocess.run([dynkit, "run", path, "--outputs", "--quiet", "--seed", str(seed)],
                           capture_output=True, text=True, timeout=timeout, env=env)
        rows = [r for r in p.stdout.splitlines()[1:] if r.strip()]
        d = np.array([[float(v) for v in r.split(",")] for r in rows])
        if d.shape[1] != xpp.shape[1]:
            return False, "columns differ (xppaut %d, dynkit %d)" % (xpp.shape[1], d.shape[1])
        sel = (d[:, 0] >= t_lo - 1e-9) & (d[:, 0] <= t_end + 1e-9)
        means.append(d[sel, 1:].mean(axis=0))
    means = np.array(means)
    mu, sd = means.mean(axis=0), means.std(axis=0, ddof=1)
    scale = np.maximum(np.max(np.abs(xpp[:, 1:]), axis=0), 1e-12)
    bound = 4 * np.maximum(sd * np.sqrt(1 + 1.0 / SEEDS), 1e-6 * scale)
    z = np.abs(xpp[xsel, 1:].mean(axis=0) - mu) / bound
    worst = int(np.argmax(z))
    return bool(np.all(z <= 1)), (
        "time means over t in [%g, %g] within 4 sd of %d seeds' (largest |difference| / "
        "bound %.2f, column %d)" % (t_lo, t_end, SEEDS, z[worst], worst + 1))


def read_manifest(path):
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            cells = line.rstrip("\n").split("\t")
            if cells[0] == "repo":
                continue
            rows.append(dict(zip(COLUMNS, cells)))
    return rows


def outcome(r):
    """The measured outcome in the manifest's words."""
    if r["status"] == "refused":
        return "refused" if r.get("xppaut", "").startswith("integrates") else "xppaut-fails"
    if r["status"] != "accepted":
        return "failed"
    c = r.get("compare", "")
    if c == "agree":
        return "agree"
    if c == "separate":
        return "separate"
    if c.startswith("noise"):
        return "noise"
    if c.startswith("xppaut"):  # wrote no output, timed out
        return "xppaut-fails"
    return "not-compared"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dynkit", help="the dynkit binary")
    ap.add_argument("--dir", default=os.environ.get("DYNKIT_ODE_CORPUS"),
                    help="the directory of the files (default: $DYNKIT_ODE_CORPUS)")
    ap.add_argument("--manifest", default=MANIFEST)
    ap.add_argument("--timeout", type=float, default=60)
    args = ap.parse_args()
    if not args.dir or not os.path.isdir(args.dir):
        print("SKIP: DYNKIT_ODE_CORPUS is not a directory; fetch the files named in %s "
              "(repository, path, commit) into DIR/OWNER/REPO/PATH and set "
              "DYNKIT_ODE_CORPUS=DIR" % os.path.relpath(args.manifest))
        return 77
    rows = read_manifest(args.manifest)
    env = dict(os.environ)
    bad, counts, kept = [], {}, []
    with tempfile.TemporaryDirectory() as work:
        env.setdefault("DYNKIT_CACHE_DIR", os.path.join(work, "cache"))
        for i, row in enumerate(rows):
            name = "%s/%s" % (row["repo"], row["path"])
            path = os.path.join(args.dir, row["repo"], row["path"])
            if not os.path.isfile(path):
                print("%-58s missing" % name)
                bad.append(name)
                continue
            with open(path, "rb") as f:
                if hashlib.sha256(f.read()).hexdigest() != row["sha256"]:
                    print("%-58s differs from its sha256" % name)
                    bad.append(name)
                    continue
            # each file in its own directory: XPPAUT reads companion files beside it
            wdir = os.path.join(work, "f%d" % i)
            os.makedirs(wdir)
            r = compat.check_file(args.dynkit, path, args.timeout, env, wdir,
                                  xppaut_refused=True)
            if r.get("compare") == "xppaut wrote no output":
                sets = check_sets(args.dynkit, path, wdir, args.timeout, env)
                if sets is not None:
                    r["compare"] = sets.split(" (")[0]
                    r["sets"] = sets
            got = outcome(r)
            if got == "noise":
                agrees, stats = noise_statistics(args.dynkit, path, wdir, args.timeout, env)
                r["compare"] = "noise: " + stats
                r["t_separate"] = None
                if not agrees:
                    got = "noise-differs"
            counts[got] = counts.get(got, 0) + 1
            mark = "" if got == row["expect"] else "  (expected %s)" % row["expect"]
            if mark:
                bad.append(name)
                shutil.copy(path, wdir)  # the input beside both programs' outputs
                kept.append(wdir)
            text = compat.verdict_text(r)
            if r.get("sets"):
                text = "each set's SET.dat (xppaut -silent runs the sets): " + r["sets"]
            if r["status"] == "refused":
                text += "; xppaut: " + r.get("xppaut", "")
            print("%-58s %-12s %s%s" % (name, got, text, mark), flush=True)
        if kept:
            print("inputs and outputs kept in %s" % compat.keep_artifacts(
                args.dynkit, "xppaut-corpus", kept))
    print("\n%d files from %d repositories: %s" % (
        len(rows), len({r["repo"] for r in rows}),
        ", ".join("%d %s" % (n, k) for k, n in sorted(counts.items(), key=lambda kv: -kv[1]))))
    if bad:
        print("not as the manifest says: " + ", ".join(bad))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
