#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# The trust rules of the cache of compiled models (docs/model-files.md, "Who may write the
# cache"), tested with two users besides root: a victim who runs dynkit, and another user
# who owns what is planted. Every attack ends either in a refusal that names the file and
# the rule, or in the model that was asked for (Lorenz's numbers, as a fresh compilation in a
# cache of its own gives them, and never van der Pol's). Needs root to create the users and
# to plant files as the other user; skipped (exit 77) otherwise.
#   cache_trust.sh DYNKIT MODELS_DIR
set -u
DYNKIT=$1
MODELS=$2
VICTIM=dynkit-cache-victim
OTHER=dynkit-cache-other

if [ "$(id -u)" != 0 ]; then
    echo "SKIP: the second-user tests of the cache need root (to create the users $VICTIM and $OTHER)"
    exit 77
fi
for cmd in useradd setpriv; do
    command -v $cmd >/dev/null 2>&1 || { echo "SKIP: $cmd is missing (util-linux, passwd)"; exit 77; }
done
for u in $VICTIM $OTHER; do
    id -u $u >/dev/null 2>&1 || useradd --system --no-create-home --shell /usr/sbin/nologin $u ||
        { echo "FAIL: cannot create the user $u"; exit 1; }
done

T=$(mktemp -d /tmp/dynkit-cache-trust.XXXXXX) || exit 1
trap 'rm -rf "$T"' EXIT
chmod 755 "$T"
cp "$DYNKIT" "$T/dynkit" && cp "$MODELS/lorenz.ode" "$MODELS/vanderpol.ode" "$T/" || exit 1
chmod 755 "$T/dynkit" && chmod 644 "$T"/*.ode
mkdir "$T/home" && chown $VICTIM "$T/home" && chmod 700 "$T/home"
CACHE=$T/home/cache
failures=0

fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# as_victim CACHE_DIR ARGS...: dynkit as the victim; stdout to $T/out, stderr to $T/err
as_victim() {
    dir=$1
    shift
    (cd "$T" && setpriv --reuid=$VICTIM --regid=$(id -g $VICTIM) --clear-groups \
        env -i PATH=/usr/bin:/bin HOME="$T/home" DYNKIT_CACHE_DIR="$dir" ./dynkit "$@") \
        >"$T/out" 2>"$T/err"
}

# expect_refusal WHAT PATTERN...: the last run failed and its message holds each pattern
expect_refusal() {
    what=$1
    shift
    if [ -s "$T/out" ]; then fail "$what: the model ran ($(tail -1 "$T/out"))"; return; fi
    for p in "$@"; do
        grep -qF -- "$p" "$T/err" || { fail "$what: the message lacks '$p':"; cat "$T/err"; return; }
    done
    echo "ok: $what: $(head -c 300 "$T/err" | tr '\n' ' ')"
}

# expect_lorenz WHAT [NOTE]: the last run printed Lorenz's final state, with NOTE on stderr
expect_lorenz() {
    got=$(tail -1 "$T/out")
    if [ "$got" != "$LORENZ" ]; then fail "$what: '$got' instead of Lorenz's '$LORENZ'"; cat "$T/err"; return; fi
    if [ $# -gt 1 ] && ! grep -qF -- "$2" "$T/err"; then fail "$1: no note '$2':"; cat "$T/err"; return; fi
    echo "ok: $1: Lorenz's state${2:+, with the note '$2'}"
}

RUN="run lorenz.ode --tspan 0:1 --final"

# the reference: a fresh compilation in a cache of root's own
(cd "$T" && DYNKIT_CACHE_DIR="$T/root-cache" ./dynkit $RUN) >"$T/ref" || { fail "reference run"; exit 1; }
LORENZ=$(tail -1 "$T/ref")
VDP=$(cd "$T" && DYNKIT_CACHE_DIR="$T/root-cache" ./dynkit run vanderpol.ode --tspan 0:1 --final | tail -1)
[ "$LORENZ" != "$VDP" ] || { fail "Lorenz and van der Pol give the same line"; exit 1; }

# 0. the victim's own cache works, and is made for the victim alone
as_victim "$CACHE" $RUN
expect_lorenz "a new cache of the victim's"
[ "$(stat -c %a "$CACHE")" = 700 ] || fail "the new cache directory has mode $(stat -c %a "$CACHE"), not 700"
as_victim "$CACHE" run vanderpol.ode --tspan 0:1 --final
SO=$(ls "$CACHE"/lorenz-*.so) && VSO=$(ls "$CACHE"/vanderpol-*.so) || { fail "no cached objects"; exit 1; }

# 1. a cache directory owned by another user: refused, for the victim and for root
mkdir "$T/theirs" && chown $OTHER "$T/theirs" && chmod 755 "$T/theirs"
as_victim "$T/theirs" $RUN
expect_refusal "a cache directory of another user" "refusing the cache directory $T/theirs" \
    "belongs to user $OTHER" DYNKIT_CACHE_DIR
(cd "$T" && DYNKIT_CACHE_DIR="$CACHE" ./dynkit $RUN) >"$T/out" 2>"$T/err"
expect_refusal "root given the victim's cache" "refusing the cache directory $CACHE" \
    "belongs to user $VICTIM" "not to you (root)"

# 2. a cache directory writable by its group or by everyone; a parent writable by everyone
for mode in 777 770; do
    chmod $mode "$CACHE"
    as_victim "$CACHE" $RUN
    expect_refusal "a cache directory of mode $mode" "refusing the cache directory $CACHE" \
        "(mode 0$mode)" "chmod go-w"
done
chmod 700 "$CACHE"
mkdir -p "$T/open/cache" && chmod 777 "$T/open" && chown $VICTIM "$T/open/cache" && chmod 700 "$T/open/cache"
as_victim "$T/open/cache" $RUN
expect_refusal "a parent writable by everyone" "the directory $T/open above it" "no sticky bit"

# 3. the object of Lorenz a symbolic link to van der Pol's: another user's is refused,
#    the victim's own is compiled again; van der Pol never runs
ln -sf "$VSO" "$SO.new" && chown -h $OTHER "$SO.new" && mv -f "$SO.new" "$SO"
as_victim "$CACHE" $RUN
expect_refusal "another user's link to van der Pol" "refusing $SO" "belongs to user $OTHER" "rm -rf"
chown -h $VICTIM "$SO"
as_victim "$CACHE" $RUN
expect_lorenz "the victim's own link to van der Pol" "is a symbolic link"
[ -f "$SO" ] && [ ! -L "$SO" ] || fail "the link was not replaced by an object"

# 4. another user's object under Lorenz's name: refused
cp "$VSO" "$SO" && chown $OTHER "$SO"
as_victim "$CACHE" $RUN
expect_refusal "another user's object" "refusing $SO" "belongs to user $OTHER"
rm -f "$SO"
as_victim "$CACHE" $RUN

# 5. a truncated object: compiled again, and Lorenz runs
truncate -s 1000 "$SO"
as_victim "$CACHE" $RUN
expect_lorenz "a truncated object" "does not match the SHA-256"
as_victim "$CACHE" $RUN
expect_lorenz "the object compiled again, from the cache"
[ ! -s "$T/err" ] || { fail "a note on the next run:"; cat "$T/err"; }

# 6. content that does not match the hash: van der Pol's whole object (its own valid trailer)
#    copied under Lorenz's name, and one byte changed inside Lorenz's
cp "$VSO" "$SO"
as_victim "$CACHE" $RUN
expect_lorenz "van der Pol's object under Lorenz's name" "does not match the SHA-256"
printf 'X' | dd of="$SO" bs=1 seek=2000 conv=notrunc 2>/dev/null
as_victim "$CACHE" $RUN
expect_lorenz "one byte changed" "does not match the SHA-256"

# 7. a header planted into the headers directory (math.h comes before the system's through
#    -I): another user's is refused, the victim's own makes the directory be written anew
INC=$(ls -d "$CACHE"/include-*)
printf '#error planted\n' >"$INC/math.h" && chown $OTHER "$INC/math.h"
sed 's/^# Lorenz/# Lorenz again/' "$T/lorenz.ode" >"$T/lorenz2.ode"
as_victim "$CACHE" run lorenz2.ode --tspan 0:1 --final
expect_refusal "another user's math.h in the headers" "refusing $INC/math.h" "belongs to user $OTHER"
chown $VICTIM "$INC/math.h"
as_victim "$CACHE" run lorenz2.ode --tspan 0:1 --final
expect_lorenz "the victim's own math.h in the headers" "is not a file dynkit writes there"
[ ! -e "$INC/math.h" ] || fail "math.h is still in the headers directory"
# a changed model.h (the victim's own file): written anew
echo '#define y0 planted' >>"$INC/dynkit/model.h"
sed 's/^# Lorenz/# Lorenz once more/' "$T/lorenz.ode" >"$T/lorenz3.ode"
as_victim "$CACHE" run lorenz3.ode --tspan 0:1 --final
expect_lorenz "a changed model.h" "differs from the header this dynkit holds"

if [ $failures -ne 0 ]; then
    echo "$failures failure(s)"
    exit 1
fi
echo "all cache trust cases passed"
