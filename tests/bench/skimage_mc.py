#!/usr/bin/python3
"""skimage_mc.py: the marching-cubes anchor of the mesh benchmark, and the Hausdorff measure of both meshes.

usage: skimage_mc.py anchor SHAPE DEPTH [-n RUNS]
       skimage_mc.py hausdorff SHAPE MESH.ply
       skimage_mc.py --help | --version

SHAPE is `sphere` (|P| = 1) or `ellipsoid` (|P - F1| + |P - F2| = 2.4, foci (+-0.8, 0, 0): a
prolate spheroid of semi-axes 1.2, sqrt(0.8), sqrt(0.8)); the grid is the one Locus
polygonises at DEPTH: 2^DEPTH + 1 samples a side over the cube [-1.25, 1.25]^3 (the scenes'
`bound`). `anchor` evaluates f = distance sum - c on that grid with numpy (float64) and runs
scikit-image's marching_cubes at level 0, median of RUNS (default 3) runs of both, and prints
  BENCH mesh-skimage-SHAPE SECONDS s eval_s=... mc_s=... triangles=... vertices=...
          hausdorff=... h_mesh_to_surface=... h_surface_to_mesh=...
With SKIMAGE_MC_ONCE=1 in the environment, `anchor SHAPE DEPTH` only evaluates and extracts
once (the bench times the whole command: start-up, imports, field, marching cubes).
`hausdorff` reads a binary little-endian PLY (locus-render -o NAME.ply) and prints
  HAUSDORFF hausdorff=... h_mesh_to_surface=... h_surface_to_mesh=... triangles=...
The Hausdorff distance to the exact surface is the larger of two one-sided distances:
mesh to surface, the exact distance of every vertex, edge midpoint and triangle centroid to
the surface (closed form for the sphere, Newton's foot point on the meridian ellipse for the
spheroid); surface to mesh, the exact point-to-triangle distance from 200,000 points spread
over the surface to the triangles owning the 24 nearest of 7 samples per triangle (centroid,
edge midpoints, points towards the corners), then exactly (every triangle near enough) for the
points whose bound may be the largest.
Needs Debian python3-scipy, and python3-skimage for `anchor` (run by /usr/bin/python3).
"""
import os
import struct
import sys
import time

try:
    import numpy as np
    from scipy.spatial import cKDTree
    if len(sys.argv) > 1 and sys.argv[1] == "anchor":
        from skimage.measure import marching_cubes
except ImportError:
    if os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3") and \
            os.path.exists("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    sys.stderr.write("skimage_mc.py: numpy, scipy or skimage missing (apt-get install python3-skimage python3-scipy)\n")
    sys.exit(69)

HALF = 1.25
A, B = 1.2, np.sqrt(0.8)


def field(shape, x, y, z):
    """f of the scene, as Locus evaluates it."""
    if shape == "sphere":
        return np.sqrt(x * x + y * y + z * z) - 1.0
    return np.sqrt((x - 0.8) ** 2 + y * y + z * z) + np.sqrt((x + 0.8) ** 2 + y * y + z * z) - 2.4


def dist_surface(shape, p):
    """Exact distance of the points p (n x 3) to the shape's surface."""
    if shape == "sphere":
        return np.abs(np.linalg.norm(p, axis=1) - 1.0)
    # the meridian plane (x, rho): distance to the ellipse (A cos t, B sin t) by Newton on t
    qx, qr = p[:, 0], np.hypot(p[:, 1], p[:, 2])
    t = np.arctan2(qr / B, qx / A)
    for _ in range(12):
        c, s = np.cos(t), np.sin(t)
        ex, er = A * c - qx, B * s - qr
        f = -ex * A * s + er * B * c
        df = A * A * s * s + B * B * c * c - ex * A * c - er * B * s
        t = t - f / np.where(np.abs(df) > 1e-300, df, 1e-300)
    return np.hypot(A * np.cos(t) - qx, B * np.sin(t) - qr)


def surface_points(shape, n=200000):
    """n points spread over the surface (a Fibonacci sphere, stretched for the spheroid)."""
    i = np.arange(n) + 0.5
    z = 1 - 2 * i / n
    r = np.sqrt(1 - z * z)
    phi = np.pi * (1 + 5 ** 0.5) * i
    u = np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)
    if shape == "sphere":
        return u
    return u * np.array([A, B, B])


def point_triangle(p, a, b, c):
    """Distance from each point p[i] to the triangle a[i] b[i] c[i] (Ericson's closest point)."""
    dot = lambda u, v: np.einsum("ij,ij->i", u, v)
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = dot(ab, ap), dot(ac, ap)
    bp = p - b
    d3, d4 = dot(ab, bp), dot(ac, bp)
    cp = p - c
    d5, d6 = dot(ab, cp), dot(ac, cp)
    vc, vb, va = d1 * d4 - d3 * d2, d5 * d2 - d1 * d6, d3 * d6 - d5 * d4
    with np.errstate(all="ignore"):
        v_ab = d1 / (d1 - d3)
        w_ac = d2 / (d2 - d6)
        w_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        den = 1 / (va + vb + vc)
    conds = [(d1 <= 0) & (d2 <= 0), (d3 >= 0) & (d4 <= d3), (vc <= 0) & (d1 >= 0) & (d3 <= 0),
             (d6 >= 0) & (d5 <= d6), (vb <= 0) & (d2 >= 0) & (d6 <= 0),
             (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)]
    choices = [a, b, a + v_ab[:, None] * ab, c, a + w_ac[:, None] * ac, b + w_bc[:, None] * (c - b)]
    inside = a + ab * (vb * den)[:, None] + ac * (vc * den)[:, None]
    q = np.select([k[:, None] for k in conds], choices, inside)
    return np.linalg.norm(p - q, axis=1)


def hausdorff(shape, verts, faces):
    """(hausdorff, mesh to surface, surface to mesh) of the mesh against the exact surface."""
    tri = verts[faces]
    samples = np.concatenate([verts, tri.mean(axis=1), (tri[:, 0] + tri[:, 1]) / 2,
                              (tri[:, 1] + tri[:, 2]) / 2, (tri[:, 2] + tri[:, 0]) / 2])
    h_ms = float(dist_surface(shape, samples).max())
    s = surface_points(shape)
    # candidate triangles: those owning the 24 samples nearest to the point, 7 samples a triangle
    # (centroid, edge midpoints, points towards the corners), so that long thin triangles are found
    w = np.array([[1, 1, 1], [1, 1, 0], [0, 1, 1], [1, 0, 1], [4, 1, 1], [1, 4, 1], [1, 1, 4]], float)
    w /= w.sum(axis=1)[:, None]
    pts = np.einsum("kj,tjc->tkc", w, tri).reshape(-1, 3)
    _, near = cKDTree(pts).query(s, k=24)
    near //= len(w)
    best = np.full(len(s), np.inf)
    for j in range(near.shape[1]):
        t = tri[near[:, j]]
        best = np.minimum(best, point_triangle(s, t[:, 0], t[:, 1], t[:, 2]))
    # best is an upper bound of each point's distance; make it exact for the points that may
    # hold the maximum: every triangle within best of p has its centroid within best + R of p
    # (R: the largest centroid-to-corner distance), in batches from the largest bound down
    cen = tri.mean(axis=1)
    rmax = float(np.linalg.norm(tri - cen[:, None, :], axis=2).max())
    tree = cKDTree(cen)
    order = np.argsort(-best)
    exact = 0.0
    for k in range(0, len(order), 500):
        if k and exact >= best[order[k]]:
            break
        for i in order[k:k + 500]:
            cand = np.array(tree.query_ball_point(s[i], best[i] + rmax), dtype=np.int64)
            t = tri[cand]
            p = np.repeat(s[i][None, :], len(cand), axis=0)
            best[i] = point_triangle(p, t[:, 0], t[:, 1], t[:, 2]).min()
            exact = max(exact, best[i])
    h_sm = exact
    return max(h_ms, h_sm), h_ms, h_sm


def read_ply(path):
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    head = data[:end].decode().split("\n")
    if head[1] != "format binary_little_endian 1.0":
        raise SystemExit("skimage_mc.py: %s: expected a binary little-endian PLY" % path)
    nv = int([l for l in head if l.startswith("element vertex")][0].split()[2])
    nf = int([l for l in head if l.startswith("element face")][0].split()[2])
    verts = np.frombuffer(data, dtype="<f4", count=3 * nv, offset=end).reshape(nv, 3).astype(np.float64)
    rec = np.frombuffer(data, dtype=np.dtype([("n", "u1"), ("v", "<i4", 3)]), count=nf, offset=end + 12 * nv)
    if nf and not (rec["n"] == 3).all():
        raise SystemExit("skimage_mc.py: %s: expected triangles" % path)
    return verts, rec["v"].astype(np.int64)


def anchor(shape, depth, runs):
    n = 2 ** depth + 1
    h = 2 * HALF / 2 ** depth
    te, tm = [], []
    for _ in range(runs):
        t0 = time.perf_counter()
        g = np.linspace(-HALF, HALF, n)
        x, y, z = np.meshgrid(g, g, g, indexing="ij")
        vol = field(shape, x, y, z)
        t1 = time.perf_counter()
        verts, faces, _, _ = marching_cubes(vol, level=0.0, spacing=(h, h, h))
        t2 = time.perf_counter()
        te.append(t1 - t0)
        tm.append(t2 - t1)
        del x, y, z, vol
    verts = verts - HALF
    hd, h_ms, h_sm = hausdorff(shape, verts, faces)
    med = lambda v: sorted(v)[len(v) // 2]
    tot = sorted(a + b for a, b in zip(te, tm))[len(te) // 2]
    print("skimage marching_cubes on %d^3 samples: %d triangles, %.4f s (field %.4f s, marching cubes %.4f s), "
          "Hausdorff %.3g" % (n, len(faces), tot, med(te), med(tm), hd))
    print("BENCH mesh-skimage-%s %.6f s eval_s=%.6f mc_s=%.6f triangles=%d vertices=%d hausdorff=%.4g "
          "h_mesh_to_surface=%.4g h_surface_to_mesh=%.4g grid=%d" %
          (shape, tot, med(te), med(tm), len(faces), len(verts), hd, h_ms, h_sm, n))


def main(argv):
    if len(argv) > 1 and argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0
    if len(argv) > 1 and argv[1] == "--version":
        print("skimage_mc.py 1")
        return 0
    if len(argv) == 4 and argv[1] == "anchor" and argv[2] in ("sphere", "ellipsoid") and os.environ.get("SKIMAGE_MC_ONCE"):
        # one field and extraction, nothing measured: the whole command's wall time is the figure
        n = 2 ** int(argv[3]) + 1
        g = np.linspace(-HALF, HALF, n)
        x, y, z = np.meshgrid(g, g, g, indexing="ij")
        verts, faces, _, _ = marching_cubes(field(argv[2], x, y, z), level=0.0)
        print("%d triangles" % len(faces))
        return 0
    if len(argv) >= 4 and argv[1] == "anchor" and argv[2] in ("sphere", "ellipsoid"):
        runs = int(argv[5]) if len(argv) == 6 and argv[4] == "-n" else 3
        anchor(argv[2], int(argv[3]), runs)
        return 0
    if len(argv) == 4 and argv[1] == "hausdorff" and argv[2] in ("sphere", "ellipsoid"):
        verts, faces = read_ply(argv[3])
        hd, h_ms, h_sm = hausdorff(argv[2], verts, faces)
        print("HAUSDORFF hausdorff=%.4g h_mesh_to_surface=%.4g h_surface_to_mesh=%.4g triangles=%d vertices=%d"
              % (hd, h_ms, h_sm, len(faces), len(verts)))
        return 0
    sys.stderr.write("usage: skimage_mc.py anchor sphere|ellipsoid DEPTH [-n RUNS] | hausdorff sphere|ellipsoid MESH.ply\n")
    return 64


if __name__ == "__main__":
    sys.exit(main(sys.argv))
