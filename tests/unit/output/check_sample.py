#!/usr/bin/python3
"""Checks a directory written by output_sample_writer with h5py and an XML parser.

Every DataItem of fields.xdmf must name an existing HDF5 file (relative to the XDMF file) and a
dataset whose shape matches Dimensions; the temporal collection has one grid per fields_*.h5.
"""
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def check_mesh(d):
    with h5py.File(os.path.join(d, "mesh.h5"), "r") as f:
        geo, topo, body = f["geometry"], f["topology"], f["body"]
        if geo.ndim != 2 or geo.shape[1] != 3 or geo.dtype != np.float64:
            fail(f"geometry {geo.shape} {geo.dtype}")
        if topo.ndim != 2 or topo.shape[1] != 4 or topo.dtype != np.int64:
            fail(f"topology {topo.shape} {topo.dtype}")
        if body.shape != (topo.shape[0],) or body.dtype != np.int32:
            fail(f"body {body.shape} {body.dtype}")
        t = topo[()]
        if t.min() < 0 or t.max() >= geo.shape[0]:
            fail("topology indices out of range")
        return geo.shape[0], topo.shape[0]


def check_frames(d, n, e):
    frames = sorted(x for x in os.listdir(d) if x.startswith("fields_") and x.endswith(".h5"))
    if not frames:
        fail("no fields_*.h5")
    for name in frames:
        with h5py.File(os.path.join(d, name), "r") as f:
            for key, shape in (("displacement", (n, 3)), ("velocity", (n, 3)), ("von_mises", (e,))):
                if f[key].shape != shape or f[key].dtype != np.float64:
                    fail(f"{name}:{key} {f[key].shape} {f[key].dtype}")
            float(f["time"][()])
    return frames


def check_xdmf(d, frames):
    root = ET.parse(os.path.join(d, "fields.xdmf")).getroot()
    coll = root.find("Domain/Grid")
    if coll.get("GridType") != "Collection" or coll.get("CollectionType") != "Temporal":
        fail("no temporal collection")
    grids = coll.findall("Grid")
    if len(grids) != len(frames):
        fail(f"{len(grids)} grids for {len(frames)} frames")
    referenced = set()
    times = []
    for g in grids:
        times.append(float(g.find("Time").get("Value")))
        if g.find("Topology").get("TopologyType") != "Tetrahedron":
            fail("topology type")
        if g.find("Geometry").get("GeometryType") != "XYZ":
            fail("geometry type")
        names = {a.get("Name"): a.get("Center") for a in g.findall("Attribute")}
        if names != {"displacement": "Node", "velocity": "Node", "von_mises": "Cell",
                     "contact_status": "Node", "normal_force": "Node", "slip": "Node",
                     "body": "Cell"}:
            fail(f"attributes {names}")
        for item in g.iter("DataItem"):
            fname, dset = item.text.strip().split(":")
            referenced.add(fname)
            dims = tuple(int(x) for x in item.get("Dimensions").split())
            with h5py.File(os.path.join(d, fname), "r") as f:
                if f[dset].shape != dims:
                    fail(f"{fname}:{dset} shape {f[dset].shape} vs Dimensions {dims}")
    if times != sorted(times):
        fail(f"times not increasing: {times}")
    if not set(frames) <= referenced or "mesh.h5" not in referenced:
        fail(f"unreferenced files: {set(frames) - referenced}")


def main():
    d = sys.argv[1]
    n, e = check_mesh(d)
    frames = check_frames(d, n, e)
    check_xdmf(d, frames)
    if any(".tmp." in x for x in os.listdir(d)):
        fail("temporary file left")
    print(f"OK: {n} nodes, {e} tets, {len(frames)} frames")


if __name__ == "__main__":
    main()
