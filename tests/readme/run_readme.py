#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Every command a document shows is run, and every output it shows is checked.

The README and each docs/*.md are read the same way, their fenced blocks in the order of
the text, all in one scratch directory per document (so a later command may read a file an
earlier one wrote), with the built dynkit first on PATH and `examples/`, `bench/` and
`tests/` of the project linked in:

- In ```sh blocks, each line that starts with `dynkit ` (continued by a trailing `\\`), or
  with `printf ` (a file the next commands read), is run by bash; it must exit with status
  0. Other lines are the set-up (install, build, test: what runs this test) and are not
  run. Lines with `...` (an elision for the reader) are skipped.
- In ```console blocks, each `$ COMMAND` (any command: `dynkit ...`, `cat FILE`, `wc -c
  FILE`) is run by bash, and its standard output (or its standard error followed by it, as
  a terminal shows a note or a trace) must be exactly the lines shown after it, up to the
  next `$`, where a line `...` stands for any number of lines. A block shown after the comment `<!-- doc-test: numbers within P% -->` (on
  the line before its fence) compares each number with that relative tolerance and the
  text between the numbers exactly: for sizes of pages that change with every edit of the
  page's scripts. A command that must fail for the reader to see its message is shown
  with `# exit N` after it (N its exit status).
- A command listed in SKIPPED below is not run; each entry gives the reason (a benchmark
  shown as a measurement, an interrupt by hand). A command of an optional backend's method
  (`--method cvode`) is skipped, saying so, when dynkit was built without it.

Usage: run_readme.py DYNKIT DOC.md [PROJECT_ROOT [SECTION]]
With SECTION, only the text under the headings that contain SECTION (each up to the next
heading of its level or above) is read.

Usage: run_readme.py DYNKIT --help PROJECT_ROOT
reads the help texts instead: 'dynkit --help' and 'dynkit help CMD' for each command it
lists (which must be 'dynkit CMD --help' too). Each line that starts with 'dynkit CMD'
(CMD a listed command; `mpirun ... dynkit CMD`, skipped without MPI), continued by a
trailing `\\`, is an example, unless it has a placeholder in capitals (MODEL, FILE.csv:
a synopsis); each runs by bash, in the order shown, and must exit with status 0 and
print no error message.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

# (document, text the command contains) -> why it is not run here
SKIPPED = {
    ("sweeps.md", "mu=0.5:3:400"): "shows a sweep interrupted by Ctrl-C and resumed; "
                                   "tests/test_sweep_cli.c sends the SIGINT and checks both",
    ("performance.md", "/usr/bin/time"): "a throughput measurement, timed by hand: its "
                                         "numbers depend on the machine and its load",
}


def skip_reason(doc, cmd, methods):
    for (name, text), why in SKIPPED.items():
        if doc == name and text in cmd:
            return why
    # an optional backend's method, when this dynkit was built without it
    if cmd.startswith("mpirun ") and not shutil.which("mpirun"):
        return "MPI is not installed (no mpirun)"
    m = re.search(r"--method (cvode)\b", cmd)
    if m and not re.search(r"^" + m.group(1) + r"\s", methods, re.M):
        return "dynkit was built without %s (dynkit methods)" % m.group(1)
    return None


def fenced_blocks(text):
    """(language, body, tolerance) of each fenced block in the order of the text; the
    tolerance is the relative one of a doc-test comment on the line before, else None."""
    out, lines, i = [], text.splitlines(), 0
    while i < len(lines):
        m = re.match(r"```(\w*)\s*$", lines[i])
        if not m:
            i += 1
            continue
        tol = None
        if i > 0:
            c = re.match(r"<!-- doc-test: numbers within ([0-9.]+)% -->", lines[i - 1].strip())
            if c:
                tol = float(c.group(1)) / 100
        j = i + 1
        while j < len(lines) and not lines[j].startswith("```"):
            j += 1
        out.append((m.group(1), "\n".join(lines[i + 1:j]) + "\n", tol))
        i = j + 1
    return out


def sh_commands(block):
    cmds, cur = [], ""
    for line in block.splitlines():
        line = line.rstrip()
        if cur:
            cur += " " + line.strip()
        elif line.startswith(("dynkit ", "printf ")):
            cur = line
        else:
            continue
        if cur.endswith("\\"):
            cur = cur[:-1].rstrip()
            continue
        cmds.append(cur)
        cur = ""
    return cmds


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


NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def matches(want, got, tol):
    """got is want, a line '...' of want standing for any lines (none too), numbers compared
    within the relative tolerance tol (None: exactly)."""
    def same(a, b):
        return a == b if tol is None else same_within(a, b, tol)
    segments, cur = [], []
    for line in want.split("\n"):
        if line == "...":
            segments.append(cur)
            cur = []
        else:
            cur.append(line)
    segments.append(cur)
    lines = got.split("\n")
    if len(segments) == 1:
        return len(lines) == len(cur) and same(want, got)
    first, last = segments[0], segments[-1]
    if len(first) + len(last) > len(lines):
        return False
    if not same("\n".join(first), "\n".join(lines[:len(first)])):
        return False
    if last and not same("\n".join(last), "\n".join(lines[len(lines) - len(last):])):
        return False
    pos, stop = len(first), len(lines) - len(last)
    for seg in segments[1:-1]:   # each in order, anywhere between
        while pos + len(seg) <= stop and not same("\n".join(seg),
                                                  "\n".join(lines[pos:pos + len(seg)])):
            pos += 1
        if pos + len(seg) > stop:
            return False
        pos += len(seg)
    return True


def same_within(want, got, tol):
    """want and got have the same text between their numbers, and each number of got is
    within the relative tolerance tol of want's."""
    if NUMBER.split(want) != NUMBER.split(got):
        return False
    a, b = NUMBER.findall(want), NUMBER.findall(got)
    return len(a) == len(b) and all(abs(float(x) - float(y)) <= tol * abs(float(x))
                                     for x, y in zip(a, b))


def expected_status(cmd):
    """The exit status a command is shown with ('# exit N' after it), else 0."""
    m = re.search(r"\s#\s*exit\s+(\d+)\s*$", cmd)
    return (int(m.group(1)), cmd[:m.start()]) if m else (0, cmd)


def run(cmd, work, env):
    start = time.monotonic()
    p = subprocess.run(["bash", "-c", cmd], cwd=work, env=env, capture_output=True, text=True,
                       timeout=600)
    return p, time.monotonic() - start


# an error message on standard error: dynkit's ("dynkit: error: ..."), a compiler's
ERROR_LINE = re.compile(r"(^|: )error\b", re.I | re.M)
# a synopsis, not an example: a placeholder in capitals (MODEL, FILE.csv, NAME=VALUE)
PLACEHOLDER = re.compile(r"(?<![\w=.:-])[A-Z][A-Z0-9_]{2,}(?![a-z])")


def help_text(dynkit, args, env):
    p = subprocess.run([dynkit] + args, capture_output=True, text=True, env=env)
    if p.returncode != 0:
        raise RuntimeError("dynkit %s: exit %d\n%s" % (" ".join(args), p.returncode, p.stderr))
    return p.stdout


def help_examples(dynkit, env):
    """(where, command) of every command line shown by 'dynkit --help' and by 'dynkit help
    CMD' for each command it lists (Examples: sections and any other line that starts with
    'dynkit ', continued by a trailing '\\'; synopses with placeholders are not examples),
    and the commands whose 'dynkit CMD --help' differs from 'dynkit help CMD'."""
    top = help_text(dynkit, ["--help"], env)
    listed = top.split("Commands:\n", 1)[1].split("\n\n", 1)[0]
    names = [n for n in re.findall(r"^  ([a-z]+)\b", listed, re.M) if n != "help"]
    texts, differ = [("dynkit --help", top)], []
    for name in names:
        text = help_text(dynkit, ["help", name], env)
        if help_text(dynkit, [name, "--help"], env) != text:
            differ.append(name)
        texts.append(("dynkit help " + name, text))
    out = []
    for where, text in texts:
        lines = text.splitlines()
        i = 0
        while i < len(lines):
            cmd = re.sub(r"^(Examples?:)?\s*", "", lines[i].strip())
            while cmd.endswith("\\") and i + 1 < len(lines):
                i += 1
                cmd = cmd[:-1].rstrip() + " " + lines[i].strip()
            i += 1
            # a command line: 'dynkit CMD ...' (or under mpirun), CMD one of those listed
            words = cmd.split()
            if words[:1] == ["mpirun"]:
                words = words[words.index("dynkit"):] if "dynkit" in words else []
            if len(words) > 1 and words[0] == "dynkit" and words[1] in names + ["help"] \
                    and not PLACEHOLDER.search(cmd):
                out.append((where, cmd))
    return names, out, differ


def run_help(dynkit, work, env, methods):
    """Each example of the --help texts is run; it must exit 0 and print no error."""
    names, examples, differ = help_examples(dynkit, env)
    failures = len(differ)
    for name in differ:
        print("FAIL: 'dynkit %s --help' is not 'dynkit help %s'" % (name, name))
    ran = skipped = 0
    for where, cmd in examples:
        why = skip_reason("--help", cmd, methods)
        if why:
            skipped += 1
            print("skip %s\n     (%s)" % (cmd, why))
            continue
        p, secs = run(cmd, work, env)
        ran += 1
        if p.returncode != 0 or ERROR_LINE.search(p.stderr):
            failures += 1
            print("FAIL (exit %d%s; %s): %s\n%s"
                  % (p.returncode, ", an error on stderr" if p.returncode == 0 else "", where,
                     cmd, p.stderr[-2000:]))
        else:
            print("ok   %5.1f s  %s" % (secs, cmd))
    print("%d examples of the --help of %d commands run, %d failed, %d skipped"
          % (ran, len(names), failures, skipped))
    return 1 if failures else 0


def run_doc(doc, text, work, env, methods):
    name = os.path.basename(doc)
    failures = ran = skipped = 0
    for lang, block, tol in fenced_blocks(text):
        if lang == "sh":
            for cmd in sh_commands(block):
                if "..." in cmd:
                    continue
                why = skip_reason(name, cmd, methods)
                if why:
                    skipped += 1
                    print("skip %s\n     (%s)" % (cmd, why))
                    continue
                p, secs = run(cmd, work, env)
                ran += 1
                if p.returncode != 0:
                    failures += 1
                    print("FAIL (exit %d): %s\n%s" % (p.returncode, cmd, p.stderr[-2000:]))
                else:
                    print("ok   %5.1f s  %s" % (secs, cmd))
        elif lang == "console":
            for step in console_steps(block):
                why = skip_reason(name, step["cmd"], methods)
                if why:
                    skipped += 1
                    print("skip $ %s\n     (%s)" % (step["cmd"], why))
                    continue
                status, cmd = expected_status(step["cmd"])
                p, secs = run(cmd, work, env)
                ran += 1
                want = "\n".join(step["out"]).rstrip("\n")
                got = p.stdout.rstrip("\n")
                # standard error before or after the output, as a terminal shows a
                # note, a trace or a last message
                shown = (got, (p.stderr + p.stdout).rstrip("\n"),
                         (p.stdout + p.stderr).rstrip("\n"))
                same = any(matches(want, g, tol) for g in shown)
                if p.returncode != status or not same:
                    failures += 1
                    print("FAIL: $ %s\n--- %s shows:\n%s\n--- it printed (exit %d, "
                          "shown %d):\n%s\n%s" % (step["cmd"], name, want, p.returncode,
                                                  status, got, p.stderr[-1000:]))
                else:
                    print("ok   %5.1f s  $ %s" % (secs, step["cmd"]))
    print("%d commands of %s run, %d failed, %d skipped (reasons above)"
          % (ran, name, failures, skipped))
    return 1 if failures else 0


def main():
    dynkit, doc = os.path.abspath(sys.argv[1]), sys.argv[2]
    # the project whose examples/ the commands read: the document's, or a third argument
    root = sys.argv[3] if len(sys.argv) > 3 else os.path.dirname(os.path.abspath(doc))
    text = None
    if doc != "--help":
        with open(doc) as f:
            text = f.read()
        if len(sys.argv) > 4:
            text = sections(text, sys.argv[4])
            if "```" not in text:
                print("no commands under a heading with '%s' in %s" % (sys.argv[4], doc))
                return 1
    name = "help" if text is None else os.path.basename(doc)
    with tempfile.TemporaryDirectory(prefix="doc-" + name + "-") as work:
        bindir = os.path.join(work, "bin")
        os.makedirs(bindir)
        os.symlink(dynkit, os.path.join(bindir, "dynkit"))
        for folder in ("examples", "bench", "tests"):
            os.symlink(os.path.join(root, folder), os.path.join(work, folder))
        env = dict(os.environ)
        env["PATH"] = bindir + os.pathsep + env.get("PATH", "")
        env["LC_ALL"] = "C"   # messages of other programs (a compiler's) in ASCII, as shown
        env.setdefault("DYNKIT_CACHE_DIR", os.path.join(work, "cache"))
        methods = subprocess.run([dynkit, "methods"], capture_output=True, text=True).stdout
        if text is None:
            return run_help(dynkit, work, env, methods)
        return run_doc(doc, text, work, env, methods)


if __name__ == "__main__":
    sys.exit(main())
