#!/usr/bin/python3
"""Compares two HDF5 files object by object: every dataset's values bit for bit (and shape, dtype),
and every attribute, apart from the build version. Prints what differs, datasets first; exit 1 when a
dataset differs, 2 when only attributes differ, 0 when both are the same.
usage: compare_h5.py A.h5 B.h5"""
import sys

import h5py
import numpy as np


def items(f):
    out = {}

    def visit(name, obj):
        out[name] = obj
    f.visititems(visit)
    out["/"] = f
    return out


def same(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    if a.dtype.kind == "f":
        return np.array_equal(a.view(np.uint8 if a.dtype.itemsize == 1 else f"u{a.dtype.itemsize}"),
                              b.view(np.uint8 if b.dtype.itemsize == 1 else f"u{b.dtype.itemsize}"))
    return np.array_equal(a, b)


def main():
    fa, fb = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
    ia, ib = items(fa), items(fb)
    data, attrs = [], []
    for name in sorted(set(ia) | set(ib)):
        if name not in ia or name not in ib:
            (data if isinstance((ia.get(name) or ib.get(name)), h5py.Dataset) else attrs).append(
                f"{name}: only in {'A' if name in ia else 'B'}")
            continue
        a, b = ia[name], ib[name]
        if isinstance(a, h5py.Dataset) and not same(a[()], b[()]):
            data.append(f"{name}: values differ")
        for key in sorted(set(a.attrs) | set(b.attrs)):
            if key == "version" and name.endswith("creator"):
                continue
            if key not in a.attrs or key not in b.attrs:
                attrs.append(f"{name}@{key}: only in {'A' if key in a.attrs else 'B'}")
            elif not same(a.attrs[key], b.attrs[key]):
                attrs.append(f"{name}@{key}: differs")
    for line in data + attrs:
        print(line)
    sys.exit(1 if data else 2 if attrs else 0)


if __name__ == "__main__":
    main()
