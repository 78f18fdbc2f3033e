#!/usr/bin/env python3
"""sample_mesh.py MESH.off N SEED OUT.xyz: N points uniformly on the triangles of an OFF mesh
(area-weighted, Python's random with SEED: the same file on every machine). Used by
scripts/result_checksums.sh; needs only python3."""
import bisect, math, random, sys

def main():
    mesh, n, seed, out = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
    words = open(mesh).read().split()
    nv, nf = int(words[1]), int(words[2])
    i = 4
    V = [tuple(float(w) for w in words[i + 3 * j:i + 3 * j + 3]) for j in range(nv)]
    i += 3 * nv
    F = []
    for _ in range(nf):
        k = int(words[i])
        F.append(tuple(int(w) for w in words[i + 1:i + 1 + k]))
        i += 1 + k
    def area(t):
        a, b, c = (V[v] for v in t[:3])
        u = [b[q] - a[q] for q in range(3)]
        w = [c[q] - a[q] for q in range(3)]
        x, y, z = u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]
        return math.sqrt(x * x + y * y + z * z)
    cumulative, total = [], 0.
    for t in F:
        total += area(t)
        cumulative.append(total)
    rng = random.Random(seed)
    with open(out, 'w') as f:
        for _ in range(n):
            t = F[bisect.bisect_left(cumulative, rng.random() * total)]
            r1, r2 = rng.random(), rng.random()
            if r1 + r2 > 1:
                r1, r2 = 1 - r1, 1 - r2
            a, b, c = (V[v] for v in t[:3])
            f.write("%.9g %.9g %.9g\n" % tuple(a[q] + r1 * (b[q] - a[q]) + r2 * (c[q] - a[q]) for q in range(3)))

if __name__ == '__main__':
    main()
