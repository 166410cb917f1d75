#!/usr/bin/env python3
"""Prints the first 1023 primitive polynomials over GF(2) (bit i = coefficient of x^i), in order
of degree and value, as the C++ initializer in src/lucerna/sampling/sequences.h. Order test: x has
multiplicative order 2^s - 1 modulo p. tests/sampling/global_samplers_test.cpp re-derives the list."""

def mulmod(a, b, p, s):
    r = 0
    while b:
        if b & 1:
            r ^= a
        b >>= 1
        a <<= 1
        if a >> s & 1:
            a ^= p
    return r

def powmod(x, e, p, s):
    r = 1
    while e:
        if e & 1:
            r = mulmod(r, x, p, s)
        x = mulmod(x, x, p, s)
        e >>= 1
    return r

def primitive(p, s):
    n = (1 << s) - 1
    x = 1 if s == 1 else 2
    if powmod(x, n, p, s) != 1:
        return False
    m, q = n, 2
    while q * q <= m:
        if m % q == 0:
            while m % q == 0:
                m //= q
            if powmod(x, n // q, p, s) == 1:
                return False
        q += 1
    return not (m > 1 and powmod(x, n // m, p, s) == 1)

out = []
s = 1
while len(out) < 1023:
    for p in range((1 << s) | 1, 2 << s, 2):
        if len(out) < 1023 and primitive(p, s):
            out.append(p)
    s += 1
for i in range(0, len(out), 16):
    print("    " + ", ".join(str(v) for v in out[i:i + 16]) + ",")
