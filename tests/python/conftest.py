# SPDX-License-Identifier: BSD-3-Clause
"""pytest set-up of the Python package's tests: the package from the build tree
(DYNKIT_PYTHON_DIR, else build/python), the tool beside it (DYNKIT_CLI), the repository."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))
PYDIR = os.environ.get("DYNKIT_PYTHON_DIR", os.path.join(SOURCE, "build", "python"))
sys.path.insert(0, PYDIR)
CLI = os.environ.get("DYNKIT_CLI", os.path.join(SOURCE, "build", "dynkit"))
