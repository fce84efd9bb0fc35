#!/usr/bin/python3
"""Edits the per-entry states of a checkpoint (docs/THEORY.md §11.7: 5 values per active entry,
slip, the direction of its last slip, off) for the hostile cases, and writes the checksum again
so that the edit reaches checkpoint_check (unless --keep-checksum).

    checkpoint_state.py FILE EDIT [--keep-checksum]

EDIT: sliding (only check that some entry slides, with a unit direction), drop-last (one value
fewer), slip-2 (an entry's slip = 2), slip-no-direction (a sliding entry's direction 0), dir-nan,
off-while-sliding (a sliding entry off = 1), flip-slip (a sliding entry sticks)."""
import struct
import sys

import h5py
import numpy as np

MASK, PRIME, OFFSET = (1 << 64) - 1, 1099511628211, 14695981039346656037


def fnv(h, data):
    for b in data:
        h = ((h ^ b) * PRIME) & MASK
    return h


def fnv_vector(h, v):
    """A stored vector: its length (uint64), then its doubles (src/output/checkpoint_meta.cpp)."""
    h = fnv(h, struct.pack('<Q', len(v)))
    return fnv(h, np.asarray(v, dtype='<f8').tobytes())


def checksum(f, state):
    h = OFFSET
    for name in ['scalars', 'u', 'V', 'last_increment', 'active', 'normal_force']:
        h = fnv_vector(h, f[name][:])
    if len(state):
        h = fnv_vector(h, state)
    return fnv(h, bytes(f.attrs['model']))


def main():
    path, edit = sys.argv[1], sys.argv[2]
    with h5py.File(path, 'r+') as f:
        state = f['state'][:].reshape(-1, 5)
        sliding = np.flatnonzero(state[:, 0] == 1)
        assert len(state) == len(f['normal_force']), 'one state per active entry'
        assert len(sliding) > 0, 'no entry slides at the checkpoint'
        norms = np.linalg.norm(state[sliding, 1:4], axis=1)
        assert np.all(np.abs(norms - 1) < 1e-12), norms
        k = sliding[0]
        if edit == 'sliding':
            print('%d of %d entries slide' % (len(sliding), len(state)))
            return
        if edit == 'drop-last':
            flat = state.reshape(-1)[:-1]
        else:
            if edit == 'slip-2':
                state[k, 0] = 2
            elif edit == 'slip-no-direction':
                state[k, 1:4] = 0
            elif edit == 'dir-nan':
                state[k, 2] = float('nan')
            elif edit == 'off-while-sliding':
                state[k, 4] = 1
            elif edit == 'flip-slip':
                state[k, 0] = 0
            else:
                sys.exit('unknown edit ' + edit)
            flat = state.reshape(-1)
        del f['state']
        f.create_dataset('state', data=flat, dtype='<f8')
        if '--keep-checksum' not in sys.argv:
            f.attrs.modify('checksum', np.uint64(checksum(f, flat)))


if __name__ == '__main__':
    main()
