#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Start-up time of the tool: the wall time of `BINARY --version` (loading its shared
libraries, nothing else), for each binary given, the runs alternating between them so that a
busy machine slows all alike, and /bin/true as the reference of the same run (the cost of
starting any process here). Prints the median and the minimum of each, in ms, and the ratio
of the medians to /bin/true's.

    python3 bench/bench_start.py build/dynkit [other/dynkit ...] [--runs 31]
"""
import argparse
import statistics
import subprocess
import time


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binaries", nargs="+")
    ap.add_argument("--runs", type=int, default=31)
    args = ap.parse_args()
    cmds = [["/bin/true"]] + [[b, "--version"] for b in args.binaries]
    times = {i: [] for i in range(len(cmds))}
    for _ in range(args.runs):
        for i, cmd in enumerate(cmds):
            t0 = time.perf_counter()
            subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
            times[i].append(time.perf_counter() - t0)
    ref = statistics.median(times[0])
    print("| command | median [ms] | minimum [ms] | x /bin/true |")
    print("|---|---:|---:|---:|")
    for i, cmd in enumerate(cmds):
        med = statistics.median(times[i])
        print("| `%s` | %.1f | %.1f | %.1f |" % (" ".join(cmd), med * 1e3, min(times[i]) * 1e3,
                                                med / ref))


if __name__ == "__main__":
    main()
