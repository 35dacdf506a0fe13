"""What the verification checkers and scripts/bench_cycles.py share.

- Reading unsatmpm's output back: the .pvd series, material-point .vtu files, CSV histories.
- Each case's constants read from its own case.yaml, so that a checker never restates them.
- The infiltration column (V1, V2): the series solution of its linearised problem and the suction
  profiles of a run against it.
"""
import csv
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import yaml
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader


# --- reading output -------------------------------------------------------------------------

def series(run_dir, name="points"):
    """[(time, path)] of a .pvd collection, in file order."""
    root = ET.parse(Path(run_dir) / f"{name}.pvd").getroot()
    return [(float(d.get("timestep")), Path(run_dir) / d.get("file"))
            for d in root.iter("DataSet")]


def read_points(path):
    """Positions (n x 3) and a dict of point-data arrays of one material-point .vtu."""
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(path))
    reader.Update()
    grid = reader.GetOutput()
    if grid.GetNumberOfPoints() == 0:
        raise RuntimeError(f"{path}: no points read")
    pd = grid.GetPointData()
    arrays = {pd.GetArrayName(i): vtk_to_numpy(pd.GetArray(i)) for i in range(pd.GetNumberOfArrays())}
    return vtk_to_numpy(grid.GetPoints().GetData()), arrays


def read_csv(path):
    """Columns of a CSV file as numpy arrays, by header name."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], np.array(rows[1:], dtype=float)
    return {name: data[:, i] for i, name in enumerate(header)}


# --- case constants -------------------------------------------------------------------------

def case_doc(path):
    """The case file at `path` (a case.yaml, or the folder holding one) as a dict."""
    path = Path(path)
    if path.is_dir():
        path = path / "case.yaml"
    return yaml.safe_load(path.read_text())


def body_height(doc, body=0, axis=None):
    """Extent of a box body along `axis` (default: the last, the vertical) [m]."""
    box = doc["bodies"][body]["box"]
    axis = len(box["max"]) - 1 if axis is None else axis
    return float(box["max"][axis]) - float(box["min"][axis])


@dataclass(frozen=True)
class Column:
    """The infiltration column of a case file: height h [m], porosity n, intrinsic permeability
    kappa [m^2], liquid viscosity mu [Pa s] and bulk modulus k_l [Pa], the linear retention's
    a_s [1/Pa] and the initial suction s0 [Pa]."""
    h: float
    n: float
    kappa: float
    mu: float
    k_l: float
    a_s: float
    s0: float

    @classmethod
    def from_case(cls, path):
        doc = case_doc(path)
        material, liquid = doc["materials"][0], doc["fluids"]["liquid"]
        return cls(h=body_height(doc), n=float(material["porosity"]),
                   kappa=float(material["intrinsic_permeability"]),
                   mu=float(liquid["viscosity"]), k_l=float(liquid["bulk_modulus"]),
                   a_s=float(material["retention"]["a_s"]),
                   s0=float(doc["bodies"][0]["initial_state"]["suction"]))

    def diffusivity(self, a_s=None):
        """C = kappa / (mu n a_s) [m^2/s] (the case's a_s unless given)."""
        return self.kappa / (self.mu * self.n * (self.a_s if a_s is None else a_s))


# --- the infiltration series ----------------------------------------------------------------

def infiltration_series(z, T, terms=400):
    """s / s0 at relative depth z (array) and time factor T: sum_m (2 / M) sin(M z)
    exp(-M^2 T), M = pi (2m + 1) / 2 (the linearised column with s = 0 at the top, impervious
    bottom)."""
    m = np.arange(terms)
    M = np.pi * (2 * m + 1) / 2
    return np.sum((2 / M)[:, None] * np.sin(np.outer(M, z)) * np.exp(-(M ** 2) * T)[:, None], axis=0)


def suction_profiles(run_dir, column, diffusivity, axis=0):
    """[(T, depth, s/s0, s/s0 of the series, arrays)] at the output times after t = 0, points
    sorted by depth = h - coordinate along `axis`; `arrays` are the .vtu's point data."""
    out = []
    for t, f in series(run_dir)[1:]:
        x, a = read_points(f)
        depth = column.h - x[:, axis]
        order = np.argsort(depth)
        T = diffusivity * t / column.h ** 2
        out.append((T, depth[order], a["suction"][order] / column.s0,
                    infiltration_series(depth[order] / column.h, T), a))
    return out
