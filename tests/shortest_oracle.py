#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""dyn_format_double against an independent oracle: Python's repr(float), the shortest
string that reads back, correctly rounded (David Gay's dtoa, mode 0). For 300,000 doubles
(random bit patterns, random decimals of 1 to 17 digits over the whole exponent range, the
neighbours of powers of two and ten, subnormals, integers, the special values) the string
of tests/shortest_print must have repr's digits and exponent, in dynkit's layout
(docs/data-files.md): plain decimal when the exponent X of the first digit is -4 <= X < 16
(integers without a point), else d.ddde[-]X; "-0", "inf", "-inf".
Run: shortest_oracle.py PATH/TO/shortest_print
"""
import math
import random
import struct
import subprocess
import sys
from decimal import Decimal


def bits_of(x):
    return struct.unpack("<Q", struct.pack("<d", x))[0]


def expected(x):
    """dynkit's layout of repr(x)'s digits and exponent."""
    if math.isinf(x):
        return "-inf" if x < 0 else "inf"
    sign = "-" if math.copysign(1.0, x) < 0 else ""
    if x == 0:
        return sign + "0"
    _, digits, exp = Decimal(repr(abs(x))).normalize().as_tuple()
    d = "".join(map(str, digits))
    x10 = exp + len(d) - 1
    if -4 <= x10 < 16:
        if exp >= 0:
            body = d + "0" * exp
        elif x10 >= 0:
            body = d[: x10 + 1] + "." + d[x10 + 1 :]
        else:
            body = "0." + "0" * (-x10 - 1) + d
    else:
        body = d[0] + ("." + d[1:] if len(d) > 1 else "") + "e" + str(x10)
    return sign + body


def values(rng):
    out = []
    while len(out) < 100000:  # random bit patterns: every exponent, both signs
        x = struct.unpack("<d", struct.pack("<Q", rng.getrandbits(64)))[0]
        if not math.isnan(x):
            out.append(x)
    for _ in range(100000):  # decimals of 1..17 digits: the shortest is often short
        n = rng.randint(1, 17)
        mant = str(rng.randrange(10 ** (n - 1), 10**n))
        x = float(mant[0] + "." + mant[1:] + "e" + str(rng.randint(-325, 308)))
        out.append(-x if rng.random() < 0.5 else x)
    for e in range(-1074, 1024):  # powers of two and their neighbours
        p = math.ldexp(1.0, e)
        out += [p, math.nextafter(p, 0.0), math.nextafter(p, math.inf)]
    for e in range(-323, 309):  # powers of ten and their neighbours
        p = float("1e%d" % e)
        out += [p, math.nextafter(p, 0.0), math.nextafter(p, math.inf)]
    for _ in range(30000):  # subnormals
        out.append(struct.unpack("<d", struct.pack("<Q", rng.randrange(1, 1 << 52)))[0])
    for _ in range(30000):  # integers up to 2^53 and beyond
        out.append(float(rng.randrange(0, 1 << rng.randint(1, 64))))
    out += [0.0, -0.0, math.inf, -math.inf, 5e-324, 2.2250738585072014e-308,
            1.7976931348623157e308, 0.1, 0.01, 1e-5, 1e16, 9007199254740993.0]
    while len(out) < 300000:
        out.append(rng.uniform(-1e3, 1e3))
    return out


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: shortest_oracle.py PATH/TO/shortest_print")
    xs = values(random.Random(20181207))
    feed = "".join("%016x\n" % bits_of(x) for x in xs)
    got = subprocess.run([sys.argv[1]], input=feed, capture_output=True, text=True, check=True)
    lines = got.stdout.split("\n")[:-1]
    if len(lines) != len(xs):
        sys.exit("FAIL: %d values, %d lines" % (len(xs), len(lines)))
    bad = 0
    for x, s in zip(xs, lines):
        want = expected(x)
        back = float(s)
        if s != want or bits_of(back) != bits_of(x):
            bad += 1
            if bad <= 10:
                print("MISMATCH %r (%s): dynkit %s, expected %s" % (x, x.hex(), s, want))
    print("%d values compared with repr: %d differ" % (len(xs), bad))
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
