#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# CTest's check of sweeps over MPI ranks: `mpirun -n 2 dynkit sweep ...` writes the same bytes
# as one process, for a Monte Carlo table, a grid with failed runs (status column) and a
# table written with --output; a bad option ends every rank with status 2 (no rank waits).
# Usage: sweep_mpi_test.sh DYNKIT MPIRUN WORKDIR
set -eu
dynkit=$1 mpirun=$2 dir=$3
mkdir -p "$dir"
cd "$dir"
# as root (CI containers) Open MPI needs to be told; --oversubscribe: more ranks than cores
flags="--oversubscribe"
[ "$(id -u)" -eq 0 ] && flags="$flags --allow-run-as-root"
# under AddressSanitizer (DYNKIT_SANITIZE): what the MPI library allocates for its life is not
# ours to free; leaks of dynkit itself are found by the one-process runs
ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
export ASAN_OPTIONS
check() { # name, sweep arguments...
  name=$1
  shift
  ASAN_OPTIONS=${ASAN_OPTIONS%detect_leaks=0} "$dynkit" sweep "$@" --threads 1 >"$name.one.csv"
  for t in 1 2; do
    $mpirun -n 2 $flags "$dynkit" sweep "$@" --threads $t >"$name.mpi$t.csv" 2>"$name.mpi$t.err"
    if ! cmp "$name.one.csv" "$name.mpi$t.csv"; then
      echo "FAIL: $name: mpirun -n 2 (threads $t) differs from one process"
      exit 1
    fi
  done
  echo "ok: $name ($(($(wc -l <"$name.one.csv") - 1)) runs, the same bytes with 2 ranks)"
}
check monte-carlo vanderpol --method dp45 --tspan 0:10 --sample 'mu=uniform(0.5,2)' \
  --sample 'y1=normal(2,0.1)' --runs 1001 --seed 7 --reduce final,max:y2,argmin:y1
check failures vanderpol --method rk4 --step 0.5 --tspan 0:20 --vary mu=0.5:1000:7 \
  --vary y1=1,2 --reduce final,mean:y1
grep -q nonfinite failures.one.csv || { echo "FAIL: failures: no failed run"; exit 1; }
check period pendulum --method dop853 --rtol 1e-12 --atol 1e-12 --tspan 0:5 \
  --vary dphi=0.1:1.9:50 --reduce event:turn
# --output: rank 0 writes the file
$mpirun -n 2 $flags "$dynkit" sweep pendulum --method rk4 --step 0.01 --tspan 0:2 \
  --vary l=1:3:5 --reduce final --output out.csv
"$dynkit" sweep pendulum --method rk4 --step 0.01 --tspan 0:2 --vary l=1:3:5 --reduce final \
  >out.one.csv
cmp out.csv out.one.csv || { echo "FAIL: --output under mpirun"; exit 1; }
echo "ok: --output"
# a bad option: every rank stops, status 2, one message
set +e
$mpirun -n 2 $flags "$dynkit" sweep pendulum --vary nothing=1,2 >bad.out 2>bad.err
rc=$?
set -e
if [ "$rc" -eq 0 ] || ! grep -q "neither a parameter nor a state" bad.err; then
  echo "FAIL: a bad option under mpirun: status $rc"
  cat bad.err
  exit 1
fi
echo "ok: a bad option ends every rank (status $rc)"
