#!/usr/bin/python3
"""How deep the boundary nodes of each body lie inside the other deformable bodies, at every
written step of a run, from its fields alone (mesh.h5 and fields_*.h5 of `Output/every`), that
is independently of the contact code: a node is inside a body when it lies in one of that
body's tetrahedra, and its depth is its distance to that body's boundary triangles.

    /usr/bin/python3 tools/penetration.py out/case [--every-step]

Prints, for each ordered pair of bodies, the deepest boundary node of one inside the other over
the run (and, with --every-step, per step). Node-to-segment contact constrains the slave nodes
only: the slave-in-master line is the contact's penetration; master nodes may enter the slave
between its nodes. Rigid surfaces have no volume and are not checked. Needs numpy and h5py (Debian: python3-numpy, python3-h5py).
"""
import argparse, glob, os, sys

import h5py
import numpy as np


def boundary_faces(tets):
    """The triangles that belong to one tetrahedron only."""
    faces = np.concatenate([tets[:, [0, 1, 2]], tets[:, [0, 1, 3]], tets[:, [0, 2, 3]], tets[:, [1, 2, 3]]])
    key = np.sort(faces, axis=1)
    _, first, count = np.unique(key, axis=0, return_index=True, return_counts=True)
    return faces[first[count == 1]]


def point_triangle_distance(p, a, b, c):
    """Distance from each point p (n, 3) to each triangle (a, b, c) (m, 3): (n, m)."""
    p = p[:, None, :]
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = (ab * ap).sum(-1), (ac * ap).sum(-1)
    bp = p - b
    d3, d4 = (ab * bp).sum(-1), (ac * bp).sum(-1)
    cp = p - c
    d5, d6 = (ab * cp).sum(-1), (ac * cp).sum(-1)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    denom = va + vb + vc
    denom = np.where(denom == 0, 1e-300, denom)
    v, w = vb / denom, vc / denom
    q = a + v[..., None] * ab + w[..., None] * ac  # interior projection
    # the regions outside the triangle: clamp to the nearest edge point
    for (e0, e1) in ((a, b), (a, c), (b, c)):
        e = e1 - e0
        t = np.clip(((p - e0) * e).sum(-1) / np.maximum((e * e).sum(-1), 1e-300), 0, 1)
        qe = e0 + t[..., None] * e
        inside = (v >= 0) & (w >= 0) & (v + w <= 1)
        closer = ((p - qe) ** 2).sum(-1) < ((p - q) ** 2).sum(-1)
        q = np.where((~inside & closer)[..., None], qe, q)
    return np.sqrt(((p - q) ** 2).sum(-1))


def inside_depths(x, tets, faces, nodes, block=4000000):
    """Depth of each of `nodes` inside the body (tets, boundary faces) at positions x; 0 outside.
    Nodes are tested in blocks of at most `block` (node, tet) pairs, so memory stays bounded on
    large meshes."""
    depth = np.zeros(len(nodes))
    v = x[tets]  # (T, 4, 3)
    lo, hi = v.min(1), v.max(1)
    p_all = x[nodes]
    near = np.nonzero(np.all((p_all >= lo.min(0)) & (p_all <= hi.max(0)), axis=1))[0]
    a, b, c = x[faces[:, 0]], x[faces[:, 1]], x[faces[:, 2]]
    step = max(1, block // max(1, len(tets)))
    for k in range(0, len(near), step):
        idx = near[k:k + step]
        p = p_all[idx]
        cand = np.all((p[:, None, :] >= lo[None]) & (p[:, None, :] <= hi[None]), axis=2)
        ni, ti = np.nonzero(cand)
        if len(ni) == 0:
            continue
        T = v[ti]
        M = np.stack([T[:, 1] - T[:, 0], T[:, 2] - T[:, 0], T[:, 3] - T[:, 0]], axis=2)
        good = np.abs(np.linalg.det(M)) > 0  # a flat tetrahedron holds no point
        lam = np.zeros((len(ni), 3))
        lam[good] = np.linalg.solve(M[good], (p[ni[good]] - T[good, 0])[..., None])[..., 0]
        tol = 1e-12
        ok = good & np.all(lam > tol, axis=1) & (lam.sum(1) < 1 - tol)
        hit = np.unique(ni[ok])
        for j in range(0, len(hit), max(1, block // max(1, len(faces)))):
            h = hit[j:j + max(1, block // max(1, len(faces)))]
            depth[idx[h]] = point_triangle_distance(p[h], a, b, c).min(axis=1)
    return depth


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('run', help='the output directory of a run (mesh.h5, fields_*.h5)')
    ap.add_argument('--every-step', action='store_true', help='print the deepest node of every step')
    a = ap.parse_args()
    mesh = os.path.join(a.run, 'mesh.h5')
    files = sorted(glob.glob(os.path.join(a.run, 'fields_*.h5')))
    if not os.path.exists(mesh) or not files:
        sys.exit('penetration.py: %s holds no mesh.h5 and fields_*.h5 (run with Output/every > 0)' % a.run)
    with h5py.File(mesh, 'r') as m:
        X, tets, body = m['geometry'][:], m['topology'][:], m['body'][:]
    bodies = sorted(set(body.tolist()))
    parts = {}
    for b in bodies:
        t = tets[body == b]
        f = boundary_faces(t)
        parts[b] = (t, f, np.unique(f))
    # per ordered pair (the body whose boundary nodes enter, the body entered): the deepest
    worst = {(o, b): (0.0, None, None, None) for b in bodies for o in bodies if o != b}
    for name in files:
        with h5py.File(name, 'r') as d:
            x = X + d['displacement'][:]
            step = int(d['step'][()])
            time = float(d['time'][()])
        for (o, b) in worst:
            t, f, _ = parts[b]
            nodes = parts[o][2]
            dep = inside_depths(x, t, f, nodes)
            k = int(np.argmax(dep))
            if a.every_step and dep[k] > 0:
                print('step %d t = %.6g: nodes of body %d inside body %d: deepest %.3e (node %d)'
                      % (step, time, o, b, dep[k], nodes[k]))
            if dep[k] > worst[(o, b)][0]:
                worst[(o, b)] = (dep[k], int(nodes[k]), step, time)
    print('%d written steps; bodies numbered in input order from 0 (node-to-segment contact keeps '
          'the slave nodes out of the master: read the slave-in-master line)' % len(files))
    for (o, b), w in worst.items():
        if w[1] is None:
            print('  nodes of body %d inside body %d: none' % (o, b))
        else:
            print('  nodes of body %d inside body %d: deepest %.3e (node %d) at step %d, t = %.6g'
                  % ((o, b) + w))


if __name__ == '__main__':
    main()
