"""Reads STEP files with OpenCASCADE (the cadquery-ocp package), a kernel independent of
flexopt: for each file, whether it was read, its solids and shells, whether BRepCheck finds
the shape valid and its shells closed, its volume, its exact bounding box, and its faces by
the kind of their surface, as one JSON object on stdout (keyed by file)."""
import json
import sys

from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepCheck import BRepCheck_Analyzer, BRepCheck_NoError, BRepCheck_Shell
from OCP.BRepGProp import BRepGProp
from OCP.Bnd import Bnd_Box
from OCP.GeomAbs import GeomAbs_Cylinder, GeomAbs_Plane
from OCP.GProp import GProp_GProps
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_FACE, TopAbs_SHELL, TopAbs_SOLID
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS


def shapes(shape, kind):
    found = []
    explorer = TopExp_Explorer(shape, kind)
    while explorer.More():
        found.append(explorer.Current())
        explorer.Next()
    return found


report = {}
for path in sys.argv[1:]:
    reader = STEPControl_Reader()
    if reader.ReadFile(path) != IFSelect_RetDone:
        report[path] = {"read": False}
        continue
    roots = reader.TransferRoots()
    shape = reader.OneShape()
    shells = shapes(shape, TopAbs_SHELL)
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    box = Bnd_Box()
    BRepBndLib.AddOptimal_s(shape, box, False, False)
    faces = shapes(shape, TopAbs_FACE)
    kinds = [BRepAdaptor_Surface(TopoDS.Face(f)).GetType() for f in faces]
    report[path] = {
        "read": True,
        "roots": roots,
        "solids": len(shapes(shape, TopAbs_SOLID)),
        "shells": len(shells),
        "valid": BRepCheck_Analyzer(shape).IsValid(),
        "closed": all(
            BRepCheck_Shell(TopoDS.Shell(s)).Closed() == BRepCheck_NoError for s in shells
        ),
        "volume": props.Mass(),
        "box": [
            box.GetXMin(),
            box.GetYMin(),
            box.GetZMin(),
            box.GetXMax(),
            box.GetYMax(),
            box.GetZMax(),
        ],
        "faces": len(faces),
        "planes": sum(k == GeomAbs_Plane for k in kinds),
        "cylinders": sum(k == GeomAbs_Cylinder for k in kinds),
    }
json.dump(report, sys.stdout)
