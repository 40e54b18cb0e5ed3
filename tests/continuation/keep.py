# SPDX-License-Identifier: BSD-3-Clause
"""The end of one case of the AUTO-07p checks: on failure its work directory is kept under
the artifacts directory and each problem says where; else a line says it agreed."""
import os
import shutil


def settle(work, artifacts, keep_as, label, problems, agreed=None):
    """problems prefixed with label and the kept copy of work (artifacts/keep_as), or the
    line agreed printed (when given) when there are none; work removed either way."""
    if problems:
        dest = os.path.join(artifacts, keep_as)
        shutil.rmtree(dest, ignore_errors=True)
        os.makedirs(artifacts, exist_ok=True)
        shutil.copytree(work, dest)
        problems = [f"{label}: {p} (kept in {dest})" for p in problems]
    elif agreed is not None:
        print(agreed)
    shutil.rmtree(work, ignore_errors=True)
    return problems
