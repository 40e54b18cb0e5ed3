#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""compat.py's handling of an XPPAUT that misreads a file now and then (Debian's XPPAUT 8
does on cuplamdif.ode, about 1 run in 70: compat.py's docstring), with a stand-in for
xppaut on PATH so that the verdict does not depend on chance:

1. a stand-in whose first run writes wrong numbers and whose later runs write the right
   ones (the classical Runge-Kutta method's iterates of x' = -x, computed here): the file
   agrees, and the result says that the runs of xppaut wrote 2 different outputs;
2. a stand-in that is always wrong: the file separates, compat.py fails (--require), and
   the input and both programs' outputs are kept under the artifacts directory; a second
   run keeps its own copy beside the first one's.

Exit status 0 when all hold, 1 when not.
"""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
MODEL = "x'=-x\ninit x=1\n@ total=1, dt=0.05\ndone\n"

FAKE = r'''#!/usr/bin/env python3
import os, sys
count = os.path.join(os.environ["FAKE_XPPAUT_DIR"], "runs")
n = int(open(count).read()) if os.path.exists(count) else 0
open(count, "w").write(str(n + 1))
wrong = os.environ["FAKE_XPPAUT_MODE"] == "always" or n == 0
x, h, rows = 1.0, 0.05, []
for k in range(21):
    rows.append("%.8g %.8g" % (k * h, x * (1.1 if wrong and k > 0 else 1.0)))
    x *= 1 - h + h * h / 2 - h ** 3 / 6 + h ** 4 / 24
open("output.dat", "w").write("\n".join(rows) + "\n")
'''


def run(dynkit, tmp, mode, arts, failures, expect_rc, label):
    bindir = os.path.join(tmp, "bin-" + label)
    os.makedirs(bindir)
    with open(os.path.join(bindir, "xppaut"), "w") as f:
        f.write(FAKE)
    os.chmod(os.path.join(bindir, "xppaut"), 0o755)
    model = os.path.join(tmp, "decay.ode")
    with open(model, "w") as f:
        f.write(MODEL)
    report = os.path.join(tmp, label + ".json")
    env = dict(os.environ, PATH=bindir + os.pathsep + os.environ["PATH"],
               FAKE_XPPAUT_DIR=bindir, FAKE_XPPAUT_MODE=mode, DYNKIT_TEST_ARTIFACTS=arts)
    p = subprocess.run([sys.executable, os.path.join(HERE, "compat.py"), dynkit, model,
                        "--require", "decay.ode", "--json", report],
                       capture_output=True, text=True, env=env)
    print(p.stdout.strip())
    if p.returncode != expect_rc:
        failures.append("%s: exit status %d, expected %d (%s)" % (label, p.returncode,
                                                                  expect_rc, p.stderr))
    with open(report) as f:
        return json.load(f)[0]


def main():
    dynkit = sys.argv[1]
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        arts = os.path.join(tmp, "artifacts")
        r = run(dynkit, tmp, "first", arts, failures, 0, "first")
        if r.get("compare") != "agree" or "2 different outputs" not in r.get("xppaut_runs", ""):
            failures.append("a misreading first run of xppaut: %s" % r)
        if os.path.exists(arts):
            failures.append("artifacts kept though the file agreed")
        for k in (1, 2):
            r = run(dynkit, tmp, "always", arts, failures, 1, "always%d" % k)
            if r.get("compare") != "separate":
                failures.append("an xppaut that is always wrong: %s" % r)
        runs = sorted(os.listdir(os.path.join(arts, "xppaut-compat"))) \
            if os.path.isdir(os.path.join(arts, "xppaut-compat")) else []
        print("artifacts of the failing runs: %s" % ", ".join(runs))
        if len(runs) != 2:
            failures.append("each failing run keeps its own artifacts: found %d" % len(runs))
        for d in runs:
            kept = os.path.join(arts, "xppaut-compat", d, "x-decay.ode")
            have = sorted(os.listdir(kept)) if os.path.isdir(kept) else []
            for name in ("decay.ode", "dynkit.csv", "dynkit.stderr", "output-run1.dat"):
                if name not in have:
                    failures.append("%s is not kept in %s (%s)" % (name, kept, have))
    for f in failures:
        print("FAILED: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
