"""tools/penetration.py on a hand-made run: a tetrahedron (body 0) and a second one (body 1) with
one vertex inside the first, written as the fields of two steps. The depth of that vertex is its
distance to the first tetrahedron's faces, known in closed form: 0.1 at step 0 (0.1 from three
faces), min(0.2, 0.25, 0.3, 0.25 / sqrt(3)) = 0.1443 at step 1; no vertex of body 0 lies inside
body 1."""
import math, os, re, subprocess, sys, tempfile

import h5py
import numpy as np

tool = sys.argv[1]
X = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1],
              [0.1, 0.1, 0.1], [2, 2, 2], [2, 3, 2], [3, 2, 2]], dtype=float)
with tempfile.TemporaryDirectory() as d:
    with h5py.File(os.path.join(d, 'mesh.h5'), 'w') as m:
        m['geometry'] = X
        m['topology'] = np.array([[0, 1, 2, 3], [4, 5, 6, 7]], dtype=np.int64)
        m['body'] = np.array([0, 1], dtype=np.int32)
    for step, moved in ((0, [0.1, 0.1, 0.1]), (1, [0.2, 0.25, 0.3])):
        u = np.zeros_like(X)
        u[4] = np.array(moved) - X[4]
        with h5py.File(os.path.join(d, 'fields_%08d.h5' % step), 'w') as f:
            f['displacement'] = u
            f['step'] = np.int64(step)
            f['time'] = float(step)
    out = subprocess.run([sys.executable, tool, d, '--every-step'], capture_output=True, text=True, check=True).stdout
print(out)
m = re.search(r'nodes of body 1 inside body 0: deepest ([0-9.e+-]+) \(node (\d+)\) at step (\d+)', out)
assert m, 'no depth for body 1 inside body 0'
assert abs(float(m[1]) - 0.25 / math.sqrt(3)) < 1e-3 * 0.1443 and m[2] == '4' and m[3] == '1', m.groups()
s0 = re.search(r'step 0 t = 0: nodes of body 1 inside body 0: deepest ([0-9.e+-]+)', out)
assert s0 and abs(float(s0[1]) - 0.1) < 1e-4, s0 and s0.groups()
assert 'nodes of body 0 inside body 1: none' in out
print('ok')
