# SPDX-License-Identifier: BSD-3-Clause
"""What the checks of dynkit equilibria, lyapunov and steady share: running a command
with the expected exit status, recording a check's verdict, and running every example a
command's --help shows (its lines after "Examples:", a trailing backslash continuing a
line) in a scratch directory with examples/ linked in; and keeping what failed (the
output of a command, a check's detail) under an artifacts directory."""
import os
import shlex
import shutil
import subprocess
import tempfile


class Checks:
    def __init__(self, dynkit, command):
        self.dynkit, self.command, self.failed = dynkit, command, []
        self.kept = {}

    def run(self, *args, status=0):
        p = subprocess.run([self.dynkit, self.command, *args], capture_output=True, text=True)
        if p.returncode != status:
            self.failed.append(f"{self.command} {' '.join(args)}: exit {p.returncode}, "
                               f"expected {status}: {p.stderr.strip()}")
            self.kept[f"{self.command} {' '.join(args)}"] = (p.stdout + "\n--- stderr ---\n"
                                                              + p.stderr)
        return p

    def check(self, cond, what, detail=""):
        print(("ok    " if cond else "FAIL  ") + what)
        if not cond:
            self.failed.append(what)
            if detail:
                self.kept[what] = detail

    def keep(self, artifacts, label):
        """what failed into ARTIFACTS/LABEL/failed-K.txt (the directory emptied first)"""
        if not (self.failed and self.kept and artifacts):
            return
        d = os.path.join(artifacts, label)
        shutil.rmtree(d, ignore_errors=True)
        os.makedirs(d)
        for k, (what, text) in enumerate(self.kept.items()):
            with open(os.path.join(d, f"failed-{k}.txt"), "w") as f:
                f.write(what + "\n" + text)
        print(f"kept in {d}")

    def help_examples(self, source):
        text = self.run("--help").stdout.split("Examples:")[1]
        lines, cur = [], ""
        for line in text.splitlines():
            cur = (cur + " " + line.strip()) if cur else line.strip()
            if cur.endswith("\\"):
                cur = cur[:-1].rstrip()
                continue
            if cur:
                lines.append(cur.split("#")[0].strip())
            cur = ""
        self.check(len(lines) >= 2, f"{self.command} --help shows {len(lines)} examples")
        with tempfile.TemporaryDirectory() as tmp:
            os.symlink(os.path.join(os.path.abspath(source), "examples"),
                       os.path.join(tmp, "examples"))
            for line in lines:
                args = shlex.split(line)[1:]
                p = subprocess.run([os.path.abspath(self.dynkit), *args], capture_output=True,
                                   text=True, cwd=tmp)
                self.check(p.returncode == 0, f"shown: {line} ({p.stderr.strip()[:60]})")

    def finish(self):
        for f in self.failed:
            print("FAILED:", f)
        return 1 if self.failed else 0
