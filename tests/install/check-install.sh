#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Checks an installed dynkit (prefix as $1): the CLI runs, its manual page and bash completion
# are there, a CMake project finds the package with find_package(dynkit) and builds on
# dynkit::dynkit, dynkit::sweep, dynkit::lang and dynkit::jit, and pkg-config compiles and
# links the same programs with dynkit.pc and the component's dynkit-NAME.pc; so for each
# backend installed (lapack, sweep-mpi, cvode). The programs print known numbers: the
# pendulum's first turn (docs/sweeps.md, also on 2 MPI ranks), the closed-form solution of
# a damped linear oscillator loaded from an .ode file (ode_user.c) and its eigenvalues
# (lapack_user.c). The installed Python package runs the installed tool for Model.sweep.
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
# the model-file API: oscillator.ode translated, compiled (the system compiler, into a cache
# of this check) and run; ode_user exits 1 unless x(5) is the closed form's to 1e-9 m
export DYNKIT_CACHE_DIR="$work/cache"
LD_LIBRARY_PATH="$prefix/lib:$prefix/lib64:${LD_LIBRARY_PATH:-}" "$work/cmake/user_ode" \
  "$here/oscillator.ode"
libdir=$(ls -d "$prefix"/lib*/pkgconfig | head -n1)
# a .pc file per component; the sweep and the model file built with theirs
for pc in dynkit dynkit-sweep dynkit-lang dynkit-jit; do
  [ -f "$libdir/$pc.pc" ] || { echo "$pc.pc not installed"; exit 1; }
done
cc -std=c11 "$here/sweep_user.c" -o "$work/pc_sweep" \
  $(PKG_CONFIG_PATH="$libdir" pkg-config --cflags --libs dynkit-sweep)
turn=$(OMP_NUM_THREADS=2 "$work/pc_sweep")
[ "$turn" = "2.59001123087446" ] || { echo "dynkit-sweep.pc's sweep printed '$turn'"; exit 1; }
cc -std=c11 "$here/ode_user.c" -o "$work/pc_ode" \
  $(PKG_CONFIG_PATH="$libdir" pkg-config --cflags --libs dynkit-jit dynkit-lang)
env -u LD_LIBRARY_PATH "$work/pc_ode" "$here/oscillator.ode"
PKG_CONFIG_PATH="$libdir" cc -std=c11 "$here/../../examples/vanderpol.c" -o "$work/pc_example" \
  $(PKG_CONFIG_PATH="$libdir" pkg-config --cflags --libs --static dynkit)
LD_LIBRARY_PATH="$prefix/lib:$prefix/lib64:${LD_LIBRARY_PATH:-}" "$work/pc_example"
# the README's command: linked to the shared library, which the program finds without
# LD_LIBRARY_PATH (the .pc file's flags give it an RPATH)
cc -std=c11 "$here/../../examples/vanderpol.c" -o "$work/pc_shared" \
  $(PKG_CONFIG_PATH="$libdir" pkg-config --cflags --libs dynkit)
env -u LD_LIBRARY_PATH "$work/pc_shared" >/dev/null ||
  { echo "a program built with pkg-config's flags does not find libdynkit.so"; exit 1; }
# the optional LAPACK backend: the oscillator's eigenvalues by dgeev against the closed form
if [ -f "$libdir/dynkit-lapack.pc" ]; then
  [ -x "$work/cmake/user_lapack" ] || { echo "dynkit::lapack not found by find_package"; exit 1; }
  "$work/cmake/user_lapack"
  cc -std=c11 "$here/lapack_user.c" -o "$work/pc_lapack" \
    $(PKG_CONFIG_PATH="$libdir" pkg-config --cflags --libs dynkit-lapack)
  "$work/pc_lapack"
  echo "install check: dynkit::lapack and dynkit-lapack.pc work"
fi
# sweeps over MPI ranks: the sweep example on 2 ranks, the same turn as in one process
if [ -f "$libdir/dynkit-sweep-mpi.pc" ]; then
  [ -x "$work/cmake/user_sweep_mpi" ] || { echo "dynkit::sweep_mpi not found by find_package"; exit 1; }
  cc -std=c11 -DSWEEP_USER_MPI "$here/sweep_user.c" -o "$work/pc_sweep_mpi" \
    $(PKG_CONFIG_PATH="$libdir" pkg-config --cflags --libs dynkit-sweep-mpi)
  if command -v mpirun >/dev/null; then
    mpi_flags="--oversubscribe"
    [ "$(id -u)" -eq 0 ] && mpi_flags="$mpi_flags --allow-run-as-root"
    for program in "$work/cmake/user_sweep_mpi" "$work/pc_sweep_mpi"; do
      turn=$(OMP_NUM_THREADS=1 mpirun -n 2 $mpi_flags "$program")
      [ "$turn" = "2.59001123087446" ] || { echo "$program on 2 ranks printed '$turn'"; exit 1; }
    done
    echo "install check: dynkit::sweep_mpi and dynkit-sweep-mpi.pc work (2 ranks)"
  else
    echo "install check: dynkit::sweep_mpi and dynkit-sweep-mpi.pc build; not run (no mpirun:" \
      "openmpi-bin)"
  fi
fi
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
# the installed Python package finds the installed tool for its commands (Model.sweep),
# with neither DYNKIT_CLI nor the build on the PATH
pkg=$(ls -d "$prefix"/lib/python3*/site-packages/dynkit 2>/dev/null | head -n1 || true)
if [ -n "$pkg" ] && [ -x /usr/bin/python3 ]; then
  found=$(cd "$work" && env -u DYNKIT_CLI PATH=/usr/bin:/bin PYTHONPATH="$(dirname "$pkg")" \
    /usr/bin/python3 -c "import dynkit, dynkit._cli as c
t = dynkit.Model('pendulum').sweep(vary={'dphi': [1.0]}, tspan=(0, 1))
print(c.tool(), t.columns[-1], len(t))")
  [ "$found" = "$prefix/bin/dynkit final_dphi 1" ] || {
    echo "the installed Python package's sweep: '$found'"; exit 1; }
  echo "install check: the Python package runs the installed tool ($found)"
fi
# live pages: the WebAssembly library installed beside the tool makes the page live (its
# module a zlib stream, its first byte 78 in base64: "e")
for wasm in "$prefix"/lib*/dynkit/wasm32 "$prefix"/lib/*/dynkit/wasm32; do
  [ -f "$wasm/libdynkit.a" ] || continue
  (cd "$work" && "$prefix/bin/dynkit" animate vanderpol --live -o live.html 2>"$work/live.err")
  if grep -q "not live" "$work/live.err" || ! grep -q '"module":"e' "$work/live.html"; then
    echo "the installed dynkit wrote no live page: $(cat "$work/live.err")"; exit 1
  fi
  echo "install check: dynkit animate --live finds $wasm"
  break
done
echo "install check: find_package (dynkit::dynkit, dynkit::sweep, dynkit::lang, dynkit::jit)" \
  "and pkg-config (dynkit, dynkit-sweep, dynkit-lang, dynkit-jit) work"
