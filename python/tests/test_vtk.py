"""`Results.write_vtk`: the .vtu file reads back with meshio (which has no PolyData reader) with
the results' points, one line cell per edge and their fields; the .vtp file is the same data as
VTK PolyData, read here with the standard XML parser."""

import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest

import rodnet


def test_vtu_reads_back_with_meshio(networks, tmp_path):
    res = rodnet.load_scene(networks / "cantilever.ron").solve()
    rod = res.to_dict()["rods"][0]
    res.write_vtk(tmp_path / "r.vtu")
    m = meshio.read(tmp_path / "r.vtu")
    assert np.array_equal(m.points, np.array(rod["points"]))
    assert [c.type for c in m.cells] == ["line"]
    n = len(rod["points"])
    assert np.array_equal(m.cells[0].data, [[k, k + 1] for k in range(n - 1)])
    axial = [f["axial"] for f in rod["forces"]]
    assert np.array_equal(m.cell_data["axial"][0].ravel(), axial)
    moved = np.array(rod["points"]) - np.array(rod["rest_points"])
    assert np.array_equal(m.point_data["displacement"], moved)
    assert np.array_equal(m.point_data["bending_stress"].ravel(), rod["bending_stress"])


def test_vtp_is_polydata_with_the_same_arrays(networks, tmp_path):
    res = rodnet.load_scene(networks / "cantilever.ron").solve()
    res.write_vtk(tmp_path / "r.vtp")
    root = ET.parse(tmp_path / "r.vtp").getroot()
    assert root.get("type") == "PolyData"
    piece = root.find("PolyData/Piece")
    assert piece.get("NumberOfPoints") == "41" and piece.get("NumberOfLines") == "40"
    arrays = {a.get("Name"): a.text.split() for a in piece.iter("DataArray")}
    twist = [float(x) for x in arrays["twist"]]
    assert twist == res.twist(0).tolist()
    with pytest.raises(ValueError, match=r"\.vtp"):
        res.write_vtk(tmp_path / "r.vtk")
