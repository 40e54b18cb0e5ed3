#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Checks an installed dynkit (prefix as $1): the CLI runs, its manual page and bash completion
# are there, a CMake project finds the package with find_package(dynkit) and builds on
# dynkit::dynkit and dynkit::sweep, and pkg-config
# compiles and links the example.
set -euo pipefail
prefix="$1"
here="$(cd "$(dirname "$0")" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$prefix/bin/dynkit" methods >/dev/null
# the manual page and the bash completion
[ -f "$prefix/share/man/man1/dynkit.1" ] || { echo "share/man/man1/dynkit.1 not installed"; exit 1; }
completion="$prefix/share/bash-completion/completions/dynkit"
[ -f "$completion" ] || { echo "the bash completion was not installed"; exit 1; }
completed=$(PATH="$prefix/bin:$PATH" bash --norc --noprofile -c \
  "source '$completion'; COMP_WORDS=(dynkit ru); COMP_CWORD=1; _dynkit; echo \${COMPREPLY[*]}")
[ "$completed" = run ] || { echo "the installed completion of 'dynkit ru': '$completed'"; exit 1; }
cmake -S "$here" -B "$work/cmake" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/cmake" >/dev/null
LD_LIBRARY_PATH="$prefix/lib:$prefix/lib64:${LD_LIBRARY_PATH:-}" "$work/cmake/user_example"
# dynkit::sweep: docs/sweeps.md's example, the pendulum's first turn of run 49 on 2 threads
turn=$(OMP_NUM_THREADS=2 "$work/cmake/user_sweep")
[ "$turn" = "2.59001123087446" ] || { echo "dynkit::sweep's example printed '$turn'"; exit 1; }
libdir=$(ls -d "$prefix"/lib*/pkgconfig | head -n1)
PKG_CONFIG_PATH="$libdir" cc -std=c11 "$here/../../examples/vanderpol.c" -o "$work/pc_example" \
  $(PKG_CONFIG_PATH="$libdir" pkg-config --cflags --libs --static dynkit)
LD_LIBRARY_PATH="$prefix/lib:$prefix/lib64:${LD_LIBRARY_PATH:-}" "$work/pc_example"
# the README's command: linked to the shared library, which the program finds without
# LD_LIBRARY_PATH (the .pc file's flags give it an RPATH)
cc -std=c11 "$here/../../examples/vanderpol.c" -o "$work/pc_shared" \
  $(PKG_CONFIG_PATH="$libdir" pkg-config --cflags --libs dynkit)
env -u LD_LIBRARY_PATH "$work/pc_shared" >/dev/null ||
  { echo "a program built with pkg-config's flags does not find libdynkit.so"; exit 1; }
# the optional CVODE backend, when it was built and installed
if [ -f "$libdir/dynkit-cvode.pc" ]; then
  [ -x "$work/cmake/user_cvode" ] || { echo "dynkit::cvode not found by find_package"; exit 1; }
  LD_LIBRARY_PATH="$prefix/lib:$prefix/lib64:${LD_LIBRARY_PATH:-}" "$work/cmake/user_cvode"
  cc -std=c11 "$here/cvode_user.c" -o "$work/pc_cvode" \
    $(PKG_CONFIG_PATH="$libdir" pkg-config --cflags --libs dynkit-cvode) -lm
  LD_LIBRARY_PATH="$prefix/lib:$prefix/lib64:${LD_LIBRARY_PATH:-}" "$work/pc_cvode"
  methods=$("$prefix/bin/dynkit" methods)
  grep -q '^cvode ' <<<"$methods" || { echo "dynkit methods lacks cvode"; exit 1; }
  echo "install check: dynkit::cvode and dynkit-cvode.pc work"
fi
echo "install check: find_package (dynkit::dynkit, dynkit::sweep) and pkg-config work"
