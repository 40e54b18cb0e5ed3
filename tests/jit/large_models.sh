#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# Large generated models through the bounds on compiling them (docs/model-files.md, "Large
# models"): the system compiler is stopped at its time limit (DYNKIT_CC_TIMEOUT, here made
# tiny, 0.01 s, so that the limit is reached on any machine) and libtcc compiles the model
# instead, said on stderr; with DYNKIT_JIT=cc the limit is an error naming the bound, and no
# compiler process is left running; a source above 1 MiB goes to libtcc at once. Each model
# has a known solution (bench/gen_large_ode.py): x(1) = exp(-1) through 5,000 or 20,000
# chained fixed quantities, x_2(1) = exp(-1) among 100,000 states.
#   large_models.sh DYNKIT GEN_LARGE_ODE_PY
set -u
DYNKIT=$1
GEN=$2
T=$(mktemp -d /tmp/dynkit-large.XXXXXX) || exit 1
trap 'rm -rf "$T"' EXIT
export DYNKIT_CACHE_DIR="$T/cache"
unset DYNKIT_JIT DYNKIT_CC CC DYNKIT_CFLAGS DYNKIT_CC_TIMEOUT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

python3 "$GEN" chain 3 >"$T/small.ode" || exit 1
if ! DYNKIT_JIT=tcc "$DYNKIT" run "$T/small.ode" --final >/dev/null 2>"$T/err"; then
    grep -q "without libtcc" "$T/err" && { echo "SKIP: this dynkit was built without libtcc"; exit 77; }
    fail "a small model with libtcc:"
    cat "$T/err"
fi
python3 "$GEN" chain 5000 >"$T/chain5k.ode" && python3 "$GEN" chain 20000 >"$T/chain.ode" &&
    python3 "$GEN" states 100000 >"$T/states.ode" || exit 1

# near NAME VALUE: VALUE is exp(-1) to 1e-6 (the runs' own error is about 1e-8)
near() {
    awk -v v="$2" 'BEGIN { e = exp(-1); d = v - e; if (d < 0) d = -d; exit !(d < 1e-6) }' ||
        fail "$1 = $2, not exp(-1) = 0.367879441171"
}

# 1. the time limit reached: libtcc instead, said on stderr, the right answer
DYNKIT_CC_TIMEOUT=0.01 "$DYNKIT" run "$T/chain5k.ode" --final >"$T/out" 2>"$T/err" ||
    { fail "5,000 fixed quantities with a limit of 0.01 s:"; cat "$T/err"; }
x=$(tail -1 "$T/out" | cut -d, -f2)
near "x(1) of 5,000 chained fixed quantities" "$x"
grep -qF "the C compiler 'cc' did not finish within 0.01 s (DYNKIT_CC_TIMEOUT=SECONDS allows more): compiled with libtcc instead" "$T/err" ||
    { fail "no note of the fallback:"; cat "$T/err"; }
echo "ok: 5,000 chained fixed quantities, cc stopped at 0.01 s, libtcc: x(1) = $x"

# 2. the compiler named: the limit is an error naming the bound, the compiler is gone
DYNKIT_JIT=cc DYNKIT_CC_TIMEOUT=0.01 "$DYNKIT" run "$T/chain.ode" --final >"$T/out" 2>"$T/err"
rc=$?
[ $rc = 2 ] || fail "DYNKIT_JIT=cc past the limit: exit $rc, not 2"
grep -qF "did not finish within 0.01 s and was stopped (the bound is DYNKIT_CC_TIMEOUT" "$T/err" ||
    { fail "no message naming the bound:"; cat "$T/err"; }
sleep 0.5
if pgrep -f "$T/cache" >/dev/null; then
    fail "a compiler process still runs on the stopped compilation:"
    pgrep -af "$T/cache"
fi
echo "ok: DYNKIT_JIT=cc past the limit: exit 2, $(grep -o 'did not finish[^(]*' "$T/err")"

# 3. sources above 1 MiB: libtcc at once
"$DYNKIT" run "$T/states.ode" --final >"$T/out" 2>"$T/err" ||
    { fail "100,000 states:"; cat "$T/err"; }
x2=$(tail -1 "$T/out" | cut -d, -f3)
near "x_2(1) of 100,000 states" "$x2"
grep -qF "MiB, more than the 1 MiB given to the system C compiler (DYNKIT_JIT=cc gives it anyway, at -O0): compiled with libtcc instead" "$T/err" ||
    { fail "no note of the size:"; cat "$T/err"; }
echo "ok: 100,000 states with libtcc at once: x_2(1) = $x2"
"$DYNKIT" run "$T/chain.ode" --final >"$T/out" 2>"$T/err" || { fail "20,000 fixed quantities:"; cat "$T/err"; }
x=$(tail -1 "$T/out" | cut -d, -f2)
near "x(1) of 20,000 chained fixed quantities" "$x"
grep -qF "more than the 1 MiB" "$T/err" || { fail "no note of the size:"; cat "$T/err"; }
echo "ok: 20,000 chained fixed quantities with libtcc at once: x(1) = $x"

# 4. a limit that is no number of seconds
DYNKIT_CC_TIMEOUT=soon "$DYNKIT" run "$T/small.ode" --final >/dev/null 2>"$T/err"
rc=$?
[ $rc = 2 ] && grep -qF "DYNKIT_CC_TIMEOUT=soon is not a number of seconds > 0" "$T/err" ||
    { fail "DYNKIT_CC_TIMEOUT=soon: exit $rc"; cat "$T/err"; }

if [ $failures -ne 0 ]; then
    echo "$failures failure(s)"
    exit 1
fi
echo "all large-model cases passed"
