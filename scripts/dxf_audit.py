"""Audits DXF files with ezdxf, an independent reader: for each file, the errors and fixes of
its audit, the header's extents and thickness, and the extents ezdxf computes from the
entities on the OUTLINE layer, as one JSON object on stdout (keyed by file)."""
import json
import sys

import ezdxf
from ezdxf import bbox

report = {}
for path in sys.argv[1:]:
    doc = ezdxf.readfile(path)
    auditor = doc.audit()
    outline = bbox.extents(doc.modelspace().query('*[layer=="OUTLINE"]'))
    report[path] = {
        "errors": [e.message for e in auditor.errors],
        "fixes": [e.message for e in auditor.fixes],
        "extmin": list(doc.header.get("$EXTMIN", (0, 0, 0))),
        "extmax": list(doc.header.get("$EXTMAX", (0, 0, 0))),
        "thickness": doc.header.get("$THICKNESS", 0.0),
        "outline_min": list(outline.extmin),
        "outline_max": list(outline.extmax),
        "layers": [layer.dxf.name for layer in doc.layers],
        "texts": [t.dxf.text for t in doc.modelspace().query("TEXT")],
    }
json.dump(report, sys.stdout)
