"""Reading unsatmpm output back: the .pvd series, material-point .vtu files, CSV histories."""
import csv
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader


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
