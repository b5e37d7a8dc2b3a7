"""Reading a dataset or a string attribute of an HDF5 file through h5dump (hdf5-tools), for the
bench scripts' tables: the scripts need no Python HDF5 module, only Debian's h5dump."""
import subprocess

import numpy as np


def values(path, name):
    """The dataset `name` of `path` as a flat list of strings (numbers as written, %.10g)."""
    out = subprocess.run(["h5dump", "-d", name, "-y", "-w", "0", "-m", "%.10g", path],
                         capture_output=True, text=True, check=True).stdout
    body = out.split("DATA {")[1].split("}")[0]
    return [x.strip().strip('"') for x in body.replace("\n", " ").split(",") if x.strip()]


def dataset(path, name):
    """The numeric dataset `name` of `path`, flattened."""
    return np.array([float(x) for x in values(path, name)])


def attribute(path, name):
    """The string attribute `name` of the root group of `path`."""
    out = subprocess.run(["h5dump", "-a", name, path], capture_output=True, text=True,
                         check=True).stdout
    return out.split('(0): "')[1].split('"')[0]
