#!/usr/bin/python3
"""Independent check of the paper's plate element (doc/validation/plates.md,
"The paper's element (Przemieniecki)").

A small NumPy/SciPy re-implementation of the bending part only of CoShell's
clamped square plate (L = 10, D = 100, q = 1, lumped load, all boundary
DoFs fixed) on the same structured meshes (same vertex order per triangle as
source/mesh/mesh.cc), with the Przemieniecki incomplete cubic built in one of
two frames:

  edge     x axis along edge 0->1 of each triangle (what coshell does)
  global   the global x axis for every triangle (no rotation)

It prints the centre deflection and its relative error against
0.126532 q L^4/D for refinement levels 0..4 and writes
doc/validation/przemieniecki_frame_probe.csv. The 'edge' column must
reproduce coshell's numbers (doc/validation/clamped_square_pressure.csv);
the 'global' column shows what the frame choice does. In global axes the
9x9 interpolation matrix C is singular for some triangles (e.g. crossed
pattern); such runs are reported as 'singular'.

  /usr/bin/python3 doc/scripts/przemieniecki_frame_probe.py
"""
import csv
import os

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
E, NU, H, L, Q = 1.092e6, 0.3, 0.1, 10.0, 1.0
D = E * H ** 3 / (12 * (1 - NU ** 2))
REFERENCE = 0.00126532 * Q * L ** 4 / D
DMAT = D * np.array([[1, NU, 0], [NU, 1, 0], [0, 0, (1 - NU) / 2]])


def rectangle(n, pattern):
    """Vertices and counter-clockwise triangles as in mesh::make_rectangle."""
    verts = [(L * i / n, L * j / n) for j in range(n + 1) for i in range(n + 1)]
    gv = lambda i, j: j * (n + 1) + i
    cells = []
    for j in range(n):
        for i in range(n):
            v00, v10, v01, v11 = gv(i, j), gv(i + 1, j), gv(i, j + 1), gv(i + 1, j + 1)
            if pattern == "crossed":
                c = len(verts)
                verts.append((L * (i + 0.5) / n, L * (j + 0.5) / n))
                cells += [(v00, v10, c), (v10, v11, c), (v11, v01, c), (v01, v00, c)]
            elif pattern == "same-diagonal" or (i + j) % 2 == 0:
                cells += [(v00, v10, v11), (v00, v11, v01)]
            else:
                cells += [(v00, v10, v01), (v10, v11, v01)]
    return np.array(verts), cells


def interpolation_matrix(planar):
    """C of u = C c, rows (w, dw/dy, -dw/dx) per vertex."""
    C = np.zeros((9, 9))
    for v, (x, y) in enumerate(planar):
        C[3 * v] = [1, x, y, x * x, x * y, y * y, x ** 3, x * y * y, y ** 3]
        C[3 * v + 1] = [0, 0, 1, 0, x, 2 * y, 0, 2 * x * y, 3 * y * y]
        C[3 * v + 2] = [0, -1, 0, -2 * x, -y, 0, -3 * x * x, -y * y, 0]
    return C


def przemieniecki(planar):
    """9x9 stiffness on (w, dw/dy, -dw/dx) per vertex in the coordinates
    given; None when C is singular (same test as coshell: reciprocal
    condition number of C in coordinates scaled by the longest edge)."""
    scale = max(np.linalg.norm(planar[a] - planar[b])
                for a, b in ((0, 1), (1, 2), (2, 0)))
    s = np.linalg.svd(interpolation_matrix(planar / scale), compute_uv=False)
    if s[-1] / s[0] < 1e-12:
        return None
    C = interpolation_matrix(planar)
    Cinv = np.linalg.inv(C)
    area = 0.5 * abs(np.cross(planar[1] - planar[0], planar[2] - planar[0]))
    K = np.zeros((9, 9))
    for a, b in ((0, 1), (1, 2), (2, 0)):
        x, y = (planar[a] + planar[b]) / 2
        Qm = np.zeros((3, 9))
        Qm[0, 3], Qm[0, 6] = 2, 6 * x
        Qm[1, 5], Qm[1, 7], Qm[1, 8] = 2, 2 * x, 6 * y
        Qm[2, 4], Qm[2, 7] = 2, 4 * y
        B = -Qm @ Cinv
        K += area / 3 * B.T @ DMAT @ B
    return K


def solve(n, pattern, frame):
    verts, cells = rectangle(n, pattern)
    ndof = 3 * len(verts)
    rows, cols, vals = [], [], []
    f = np.zeros(ndof)
    for cell in cells:
        p = verts[list(cell)]
        if frame == "edge":
            e1 = (p[1] - p[0]) / np.linalg.norm(p[1] - p[0])
            e2 = np.array([-e1[1], e1[0]])
        else:
            e1, e2 = np.array([1.0, 0.0]), np.array([0.0, 1.0])
        planar = np.array([[(q - p[0]) @ e1, (q - p[0]) @ e2] for q in p])
        K = przemieniecki(planar)
        if K is None:
            return None
        # local (w, theta_x, theta_y) = T global; rotations are vectors.
        T = np.zeros((9, 9))
        R = np.array([e1, e2])
        for v in range(3):
            T[3 * v, 3 * v] = 1
            T[3 * v + 1:3 * v + 3, 3 * v + 1:3 * v + 3] = R
        Kg = T.T @ K @ T
        dofs = [3 * v + c for v in cell for c in range(3)]
        for a in range(9):
            for b in range(9):
                rows.append(dofs[a]); cols.append(dofs[b]); vals.append(Kg[a, b])
        area = 0.5 * abs(np.cross(p[1] - p[0], p[2] - p[0]))
        for v in cell:
            f[3 * v] += Q * area / 3
    K = sp.csr_matrix((vals, (rows, cols)), shape=(ndof, ndof))
    tol = 1e-9 * L
    fixed = np.zeros(ndof, bool)
    for v, (x, y) in enumerate(verts):
        if min(x, y, L - x, L - y) < tol:
            fixed[3 * v:3 * v + 3] = True
    free = np.where(~fixed)[0]
    u = np.zeros(ndof)
    u[free] = spla.spsolve(K[free][:, free].tocsc(), f[free])
    centre = np.argmin(np.linalg.norm(verts - [L / 2, L / 2], axis=1))
    return u[3 * centre]


def main():
    out = os.path.join(ROOT, "doc", "validation", "przemieniecki_frame_probe.csv")
    rows = []
    for pattern in ["crossed", "same-diagonal", "alternating"]:
        for level in range(5):
            n = 4 * 2 ** level
            row = {"pattern": pattern, "level": level}
            for frame in ["edge", "global"]:
                w = solve(n, pattern, frame)
                row[f"{frame}_w"] = "singular" if w is None else f"{w:.6g}"
                row[f"{frame}_relative_error"] = (
                    "" if w is None else f"{abs(w / REFERENCE - 1):.4g}")
            rows.append(row)
            print(row, flush=True)
    with open(out, "w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


if __name__ == "__main__":
    main()
