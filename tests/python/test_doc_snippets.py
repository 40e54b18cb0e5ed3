# SPDX-License-Identifier: BSD-3-Clause
"""The Python snippets of docs/python.md and the README run without an error (in a scratch
directory with examples/ linked), and the shell lines of docs/python.md's set-up that use
the build tree import the package."""
import os
import re
import subprocess
import sys

import pytest

from conftest import PYDIR, SOURCE


def snippets(path):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    return re.findall(r"```python\n(.*?)```", text, re.S)


DOCS = [os.path.join(SOURCE, "docs", "python.md"), os.path.join(SOURCE, "README.md")]
CASES = [(os.path.basename(d), i, s) for d in DOCS for i, s in enumerate(snippets(d))]


@pytest.mark.parametrize("doc,index,code", CASES, ids=[f"{d}-{i}" for d, i, _ in CASES])
def test_snippet_runs(doc, index, code, tmp_path, monkeypatch):
    os.symlink(os.path.join(SOURCE, "examples"), tmp_path / "examples")
    monkeypatch.chdir(tmp_path)
    exec(compile(code, f"{doc} snippet {index}", "exec"), {"__name__": "__main__"})


def test_import_from_the_build_tree():
    env = dict(os.environ, PYTHONPATH=PYDIR)
    out = subprocess.run([sys.executable, "-c", "import dynkit; print(dynkit.models())"],
                         env=env, capture_output=True, text=True, check=True).stdout
    assert "pendulum" in out and "vanderpol" in out
