#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# bench/run.sh — every benchmark in one command: builds a Release tree (build-bench, or
# $DYNKIT_BENCH_BUILD) with the peers CMake finds (GSL, Boost.Odeint, SUNDIALS; installed by
# scripts/install-deps.sh), runs bench_suite (fixed steps, adaptive work-precision, calls
# over families of problems, stiff, `dynkit report`, then the table of targets), its
# fixed-step section again from a tree
# built at -O2 (build-bench-O2), bench_jit (models compiled at run time; not with --only),
# bench_mech and bench_mech_sympy.py (mechanisms, against sympy.physics.mechanics),
# bench_sweep, bench_band and bench_sparse (large stiff systems), bench_step (one step of the adaptive pairs)
# and bench_output (numbers as text, every
# sample written; none of them with --only) and, when hyperfine is installed, times
# `dynkit report` with it too. Arguments
# go to bench_suite, e.g.
#   bench/run.sh                      # everything (about a minute)
#   bench/run.sh --only fixed --reps 31
#   bench/run.sh --svg docs/img       # also write the work-precision diagrams
#   bench/run.sh --quick              # checks only, the times mean nothing
# Run it on a quiet machine; compare ratios within one run (see docs/performance.md).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${DYNKIT_BENCH_BUILD:-build-bench}"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DDYNKIT_BUILD_BENCH=ON \
  -DDYNKIT_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" -j"$(nproc)" --target bench_suite bench_fixed bench_sweep bench_band \
  bench_sparse bench_output bench_step dynkit_cli >/dev/null
cmake --build "$build" -j"$(nproc)" --target bench_jit bench_mech >/dev/null 2>&1 || true # needs src/jit
"$build/bench/bench_suite" "$@"

# the fixed-step section again from a tree built at -O2 (the default of most builds and
# distributions): the header-only driver must hold its ratio there too
fixed=1
for ((i = 1; i <= $#; i++)); do
  if [ "${!i}" = --only ]; then j=$((i + 1)); [[ "${!j:-}" == *fixed* ]] || fixed=0; fi
done
if [ "$fixed" -eq 1 ]; then
  cmake -S . -B "$build-O2" -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS_RELEASE="-O2 -DNDEBUG" \
    -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" -DDYNKIT_BUILD_BENCH=ON -DDYNKIT_BUILD_TESTS=OFF >/dev/null
  cmake --build "$build-O2" -j"$(nproc)" --target bench_suite >/dev/null
  echo
  echo "## The fixed-step section at -O2"
  args=()
  skip=0
  for a in "$@"; do # the same options, but only the fixed-step section
    if [ "$skip" -eq 1 ]; then skip=0; continue; fi
    case "$a" in --only|--svg|--csv) skip=1 ;; *) args+=("$a") ;; esac
  done
  "$build-O2/bench/bench_suite" "${args[@]}" --only fixed
fi

quick=0 report=1 only=0
for ((i = 1; i <= $#; i++)); do
  case "${!i}" in
    --quick) quick=1 ;;
    --only) only=1; j=$((i + 1)); [[ "${!j:-}" == *report* ]] || report=0 ;;
  esac
done
# compiled models (bench_jit): with every run that is not limited by --only
if [ "$only" -eq 0 ] && [ -x "$build/bench/bench_jit" ]; then
  echo
  if [ "$quick" -eq 1 ]; then "$build/bench/bench_jit" --quick; else "$build/bench/bench_jit"; fi
fi
# mechanisms (bench_mech, then against sympy.physics.mechanics): with every run that is not
# limited by --only
if [ "$only" -eq 0 ] && [ -x "$build/bench/bench_mech" ]; then
  echo
  if [ "$quick" -eq 1 ]; then
    "$build/bench/bench_mech" --quick
  else
    "$build/bench/bench_mech"
    echo
    rc=0
    /usr/bin/python3 bench/bench_mech_sympy.py "$build/bench/bench_mech" "$build/dynkit" || rc=$?
    if [ "$rc" -eq 77 ]; then echo "(SymPy, NumPy or SciPy is missing: no comparison with sympy.physics.mechanics)"
    elif [ "$rc" -ne 0 ]; then exit "$rc"; fi
  fi
fi
# sweeps (bench_sweep): with every run that is not limited by --only
if [ "$only" -eq 0 ]; then
  echo
  if [ "$quick" -eq 1 ]; then "$build/bench/bench_sweep" --quick; else "$build/bench/bench_sweep"; fi
fi
# large stiff systems (bench_band): with every run that is not limited by --only; the
# diagram of the growth with N goes where --svg DIR sends the others
if [ "$only" -eq 0 ]; then
  echo
  svg=()
  for ((i = 1; i <= $#; i++)); do
    if [ "${!i}" = "--svg" ]; then j=$((i + 1)); svg=(--svg "${!j}"); fi
  done
  if [ "$quick" -eq 1 ]; then "$build/bench/bench_band" --quick; else "$build/bench/bench_band" "${svg[@]}"; fi
  echo
  if [ "$quick" -eq 1 ]; then "$build/bench/bench_sparse" --quick; else "$build/bench/bench_sparse"; fi
fi
# writing numbers as text (bench_output): with every run that is not limited by --only
if [ "$only" -eq 0 ]; then
  echo
  if [ "$quick" -eq 1 ]; then "$build/bench/bench_output" --quick; else "$build/bench/bench_output"; fi
fi
# one attempted step of the adaptive pairs (bench_step): with every run not limited by --only
if [ "$only" -eq 0 ]; then
  echo
  if [ "$quick" -eq 1 ]; then "$build/bench/bench_step" --quick; else "$build/bench/bench_step"; fi
fi
if [ "$quick" -eq 0 ] && [ "$report" -eq 1 ]; then
  echo
  if command -v hyperfine >/dev/null 2>&1; then
    echo "### \`dynkit report\` by hyperfine"
    echo
    echo '```'
    hyperfine -N --warmup 3 --runs 30 --style basic "$build/dynkit report" 2>&1
    echo '```'
  else
    echo "(hyperfine is not installed: apt-get install hyperfine for a second timing of dynkit report)"
  fi
fi
