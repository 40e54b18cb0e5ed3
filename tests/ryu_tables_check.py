#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Ryu's tables and constants in src/io against exact integers, checked independently of
tools/ryu_tables.py's formulas:
- each POW5[i] has 125 bits and brackets 5^i: POW5[i] 2^s <= 5^i < (POW5[i] + 1) 2^s
  (s = the bit length of 5^i, counted from its binary digits, minus 125), i.e. it is 5^i
  truncated to its 125 leading bits;
- each POW5_INV[q] - 1 is floor(2^k / 5^q): (POW5_INV[q] - 1) 5^q <= 2^k < POW5_INV[q] 5^q,
  k = bit length of 5^q - 1 + 125;
- the tables cover every index the conversion uses for every binary exponent of a double;
- the integer approximations of shortest_double.c (log10 2^e, log10 5^e, bit length of 5^e)
  equal the exact values (decimal digits counted from str(), bits from bin()) over their
  ranges;
- the header is what tools/ryu_tables.py prints (the file is up to date).
Run: ryu_tables_check.py SOURCE_DIR
"""
import re
import subprocess
import sys


def read_table(text, name):
    body = re.search(r"%s\[(\d+)\]\[2\] = \{(.*?)\};" % name, text, re.S)
    pairs = re.findall(r"\{0x([0-9a-f]+)u, 0x([0-9a-f]+)u\}", body.group(2))
    assert len(pairs) == int(body.group(1))
    return [int(lo, 16) + (int(hi, 16) << 64) for lo, hi in pairs]


def bits(n):
    return len(bin(n)) - 2


def main():
    src = sys.argv[1]
    path = src + "/src/io/ryu_tables.h"
    text = open(path).read()
    pow5, inv = read_table(text, "RYU_POW5"), read_table(text, "RYU_POW5_INV")
    for i, v in enumerate(pow5):
        p = 5**i
        s = bits(p) - 125
        assert 1 << 124 <= v < 1 << 125, i
        if s >= 0:
            assert v << s <= p < (v + 1) << s, i
        else:
            assert v == p << -s, i
    for q, v in enumerate(inv):
        p = 5**q
        k = bits(p) - 1 + 125
        assert (v - 1) * p <= 1 << k < v * p, q
    # exact log10 and bit lengths against the integer formulas of shortest_double.c
    for e in range(0, 1651):
        assert (e * 78913) >> 18 == len(str(2**e)) - 1, e
    for e in range(0, 2621):
        assert (e * 732923) >> 20 == len(str(5**e)) - 1, e
    for e in range(0, 3529):
        assert ((e * 1217359) >> 19) + 1 == max(bits(5**e), 1), e
    # every index used: e2 = biased exponent - 1023 - 52 - 2 (1 for subnormals)
    need_inv = need_pow5 = 0
    for biased in range(0, 2047):
        e2 = (max(biased, 1)) - 1023 - 52 - 2
        if e2 >= 0:
            q = len(str(2**e2)) - 1 - (e2 > 3)
            need_inv = max(need_inv, q)
        else:
            q = len(str(5 ** (-e2))) - 1 - (-e2 > 1)
            need_pow5 = max(need_pow5, -e2 - q)
    assert need_inv < len(inv) and need_pow5 < len(pow5), (need_inv, need_pow5)
    generated = subprocess.run([sys.executable, src + "/tools/ryu_tables.py"],
                               capture_output=True, text=True, check=True).stdout
    assert generated == text, "src/io/ryu_tables.h differs from tools/ryu_tables.py's output"
    print("POW5[0..%d], POW5_INV[0..%d] exact; indices used up to %d and %d"
          % (len(pow5) - 1, len(inv) - 1, need_pow5, need_inv))


if __name__ == "__main__":
    main()
