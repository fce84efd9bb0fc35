#!/usr/bin/python3
"""Forges a checkpoint for the hostile cases: an edit a run never writes, then (unless the edit
is about the file's structure) the checksum written again, as a forger can (FNV-1a is not a
MAC), so that the edit reaches the checks behind the checksum.

    checkpoint_forge.py FILE EDIT

Structure (checksum kept; refused before any dataset is read): u-2d (u as N x 3), u-wide
(u as 2 x 500000 zeros), scalars-2d (1 x 8), active-2d (1 x 5n), checksum-array (two values),
model-array (two strings).
Contents (checksum written again): duplicate-entries (every active entry twice), xi-outside
(every entry at xi = eta = -3), facet-zero (every entry on facet 0), facet-rotated (each entry
on the next entry's facet), time-early (t = 1e-300), time-late (t + dt / 2), dt-huge
(dt = 1e300), dt-above-nominal (dt = 2 nominal dt)."""
import sys

import h5py
import numpy as np

from checkpoint_state import checksum


def replace(f, name, data):
    del f[name]
    f.create_dataset(name, data=np.asarray(data, dtype='<f8'))


def structure(f, edit):
    if edit == 'u-2d':
        replace(f, 'u', f['u'][:].reshape(-1, 3))
    elif edit == 'u-wide':
        replace(f, 'u', np.zeros((2, 500000)))
    elif edit == 'scalars-2d':
        replace(f, 'scalars', f['scalars'][:].reshape(1, -1))
    elif edit == 'active-2d':
        assert len(f['active']) > 0, 'no active entry'
        replace(f, 'active', f['active'][:].reshape(1, -1))
    elif edit == 'checksum-array':
        s = f.attrs['checksum']
        del f.attrs['checksum']
        f.attrs.create('checksum', np.array([s, s], dtype='<u8'))
    elif edit == 'model-array':
        m = bytes(f.attrs['model'])
        del f.attrs['model']
        f.attrs.create('model', np.array([m, m], dtype='S%d' % len(m)))
    else:
        return False
    return True


def contents(f, edit):
    s = f['scalars'][:]
    active = f['active'][:]
    if edit == 'duplicate-entries':
        assert len(active) > 0, 'no active entry'
        for n in ['active', 'normal_force', 'state']:
            replace(f, n, np.concatenate([f[n][:], f[n][:]]))
    elif edit == 'xi-outside':
        assert len(active) > 0, 'no active entry'
        a = active.reshape(-1, 5)
        a[:, 3:5] = -3
        replace(f, 'active', a.ravel())
    elif edit in ('facet-zero', 'facet-rotated'):
        assert len(active) > 1, 'fewer than two active entries'
        a = active.reshape(-1, 5)
        # every entry on facet 0, or on the facet of the next entry; xi kept, inside the facet
        a[:, 2] = 0 if edit == 'facet-zero' else np.roll(a[:, 2], 1)
        replace(f, 'active', a.ravel())
    elif edit in ('time-early', 'time-late', 'dt-huge', 'dt-above-nominal'):
        if edit == 'time-early':
            s[1] = 1e-300
        elif edit == 'time-late':
            s[1] += 0.5 * s[7]
        elif edit == 'dt-huge':
            s[2] = 1e300
        else:
            s[2] = 2 * s[7]
        replace(f, 'scalars', s)
    else:
        sys.exit('unknown edit ' + edit)
    state = f['state'][:] if 'state' in f else np.zeros(0)
    f.attrs.modify('checksum', np.uint64(checksum(f, state)))


def main():
    path, edit = sys.argv[1], sys.argv[2]
    with h5py.File(path, 'r+') as f:
        if not structure(f, edit):
            contents(f, edit)


if __name__ == '__main__':
    main()
