#!/usr/bin/env python3
"""Chooses Lucerna's initial Sobol' direction numbers (src/lucerna/sampling/sequences.h).

Dimension d >= 2 with primitive polynomial p of degree s takes m_i = 2 (SplitMix64(key) mod 2^(i-1)) + 1
for i = 1..s, key = d << 16 | c << 8 | i, with the smallest candidate c = 0, 1, ... for which the pair
(d-1, d) (what Get2D pairs) puts between 1/4 and 7/4 of the expected count into every cell of an 8x8
grid over the first 4096 points and of a 16x16 grid over the first 16384. Prints the c of every
dimension 2..1023 as the C++ initializer kSobolInitCandidate."""
import subprocess, sys, os

MASK = (1 << 64) - 1

def splitmix(v):
    v = (v + 0x9e3779b97f4a7c15) & MASK
    v = ((v ^ (v >> 30)) * 0xbf58476d1ce4e5b9) & MASK
    v = ((v ^ (v >> 27)) * 0x94d049bb133111eb) & MASK
    return v ^ (v >> 31)

def polys():
    here = os.path.dirname(os.path.abspath(__file__))
    out = subprocess.run([sys.executable, os.path.join(here, "gen_primitive_polys.py")], capture_output=True, text=True).stdout
    return [int(t) for t in out.replace(",", " ").split()]

NCOL = 14   # 16384 points need 14 columns

def columns(p, d, c):
    s = p.bit_length() - 1
    m = [0] * (NCOL + 1)
    for i in range(1, s + 1):
        m[i] = 1 if d == 1 else 2 * (splitmix(d << 16 | c << 8 | i) % (1 << (i - 1))) + 1
    for k in range(s + 1, NCOL + 1):
        v = m[k - s] ^ (m[k - s] << s)
        for j in range(1, s):
            if (p >> (s - j)) & 1:
                v ^= m[k - j] << j
        m[k] = v
    return [(m[k] << (32 - k)) & 0xffffffff for k in range(1, NCOL + 1)]

def points(cols, n):
    # Gray-code order visits the same point set of the first n = 2^k indices.
    out, v = [], 0
    for i in range(n):
        out.append(v)
        b = ((i + 1) & -(i + 1)).bit_length() - 1
        if b < len(cols):
            v ^= cols[b]
    return out

def good(ca, cb):
    for n, bits in ((4096, 3), (16384, 4)):
        xa, xb = points(ca, n), points(cb, n)
        g = 1 << bits
        cnt = [0] * (g * g)
        for x, y in zip(xa, xb):
            cnt[(y >> (32 - bits)) * g + (x >> (32 - bits))] += 1
        e = n / (g * g)
        if min(cnt) < e / 4 or max(cnt) > 7 * e / 4:
            return False
    return True

P = polys()
cols = {1: columns(P[0], 1, 0)}
choice = []
for d in range(2, 1024):
    c = 0
    while True:
        cand = columns(P[d - 1], d, c)
        if good(cols[d - 1], cand):
            break
        c += 1
    cols[d] = cand
    choice.append(c)
for i in range(0, len(choice), 32):
    print("    " + ", ".join(str(v) for v in choice[i:i + 32]) + ",")
print(f"// max candidate {max(choice)}, retried dims {sum(1 for c in choice if c)}", file=sys.stderr)
