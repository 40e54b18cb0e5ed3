#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Every command the README shows is run, and every output it shows is checked.

- In ```sh blocks, each line that starts with `dynkit ` (continued by a trailing `\\`) is
  run in order, in one scratch directory (so a later line may read a file an earlier one
  wrote), with the built dynkit first on PATH and `examples/` linked in; a comment after
  `#` is dropped. It must exit with status 0. Lines with `...` (an elision for the reader)
  are skipped, and so are the set-up commands (they are what runs this test).
- In ```console blocks, each `$ dynkit ...` command's standard output (or its standard
  error followed by it, as a terminal shows a trace) must be exactly the lines shown after
  it (up to the next `$`), and a `$ cat FILE` shows a file written by the command before.

Usage: run_readme.py DYNKIT README.md [PROJECT_ROOT [SECTION]]
With SECTION, only the text under the headings that contain SECTION (each up to the next
heading of its level or above) is read.
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile


def blocks(text, lang):
    return re.findall(r"```" + lang + r"\n(.*?)```", text, re.S)


def sh_commands(block):
    cmds, cur = [], ""
    for line in block.splitlines():
        line = line.rstrip()
        if cur:
            cur += " " + line.strip()
        elif line.startswith("dynkit "):
            cur = line
        else:
            continue
        if cur.endswith("\\"):
            cur = cur[:-1].rstrip()
            continue
        cmds.append(cur)
        cur = ""
    return cmds


def strip_comment(cmd):
    # a '#' that starts a word begins a comment (which may hold an apostrophe)
    return shlex.split(re.sub(r"(^|\s)#.*$", "", cmd))


def console_steps(block):
    steps, cur = [], None
    lines = block.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("$ "):
            cmd = line[2:]
            while cmd.endswith("\\"):
                i += 1
                cmd = cmd[:-1].rstrip() + " " + lines[i].strip()
            cur = {"cmd": cmd, "out": []}
            steps.append(cur)
        elif cur is not None:
            cur["out"].append(line)
        i += 1
    return steps


def sections(text, title):
    """The text under the headings that contain title, each to the next heading of its level
    or above (fenced blocks are not headings)."""
    out, level, fence = [], 0, False
    for line in text.splitlines(keepends=True):
        if line.startswith("```"):
            fence = not fence
        m = None if fence else re.match(r"(#+) ", line)
        if m:
            if level and len(m.group(1)) <= level:
                level = 0
            if not level and title in line:
                level = len(m.group(1))
        if level:
            out.append(line)
    return "".join(out)


def main():
    dynkit, readme = os.path.abspath(sys.argv[1]), sys.argv[2]
    # the folder whose examples/ the commands read: the README's, or a third argument
    root = sys.argv[3] if len(sys.argv) > 3 else os.path.dirname(os.path.abspath(readme))
    with open(readme) as f:
        text = f.read()
    if len(sys.argv) > 4:
        text = sections(text, sys.argv[4])
        if "```" not in text:
            print("no commands under a heading with '%s' in %s" % (sys.argv[4], readme))
            return 1
    failures = 0
    with tempfile.TemporaryDirectory() as work:
        bindir = os.path.join(work, "bin")
        os.makedirs(bindir)
        os.symlink(dynkit, os.path.join(bindir, "dynkit"))
        os.symlink(os.path.join(root, "examples"), os.path.join(work, "examples"))
        env = dict(os.environ)
        env["PATH"] = bindir + os.pathsep + env.get("PATH", "")
        env.setdefault("DYNKIT_CACHE_DIR", os.path.join(work, "cache"))
        ran = 0
        for block in blocks(text, "sh"):
            for cmd in sh_commands(block):
                if "..." in cmd:
                    continue
                argv = strip_comment(cmd)
                p = subprocess.run(argv, cwd=work, env=env, capture_output=True, text=True,
                                   timeout=600)
                ran += 1
                if p.returncode != 0:
                    failures += 1
                    print("FAIL (exit %d): %s\n%s" % (p.returncode, cmd, p.stderr[-2000:]))
                else:
                    print("ok   %s" % cmd)
        for block in blocks(text, "console"):
            for step in console_steps(block):
                argv = shlex.split(step["cmd"])
                p = subprocess.run(argv, cwd=work, env=env, capture_output=True, text=True,
                                   timeout=600)
                ran += 1
                want = "\n".join(step["out"]).rstrip("\n")
                got = p.stdout.rstrip("\n")
                # a block may show standard error (a trace, a note) before the output, as a
                # terminal does
                both = (p.stderr + p.stdout).rstrip("\n")
                if p.returncode != 0 or want not in (got, both):
                    failures += 1
                    print("FAIL: $ %s\n--- the README shows:\n%s\n--- dynkit printed (exit %d):\n%s\n%s"
                          % (step["cmd"], want, p.returncode, got, p.stderr[-1000:]))
                else:
                    print("ok   $ %s" % step["cmd"])
    print("%d commands of the README run, %d failed" % (ran, failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
