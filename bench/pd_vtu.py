"""Reading PeriDEAL's output in the benchmark scripts: deal.II's binary,
zlib-compressed VTU, one cell per node, the node at the centre of its cell.

    sys.path.insert(0, <bench>); from pd_vtu import read_pvtu
"""
import base64
import os
import struct
import xml.etree.ElementTree as ET
import zlib

import numpy as np


def _decode(text, dtype):
    text = "".join(text.split())
    n_blocks = struct.unpack("<I", base64.b64decode(text[:8])[:4])[0]
    header = 4 * (3 + n_blocks)
    header_b64 = 4 * ((header + 2) // 3)
    raw = base64.b64decode(text[header_b64:])
    sizes = struct.unpack("<%dI" % n_blocks,
                          base64.b64decode(text[:header_b64])[12:header])
    data, pos = b"", 0
    for size in sizes:
        data += zlib.decompress(raw[pos:pos + size])
        pos += size
    return np.frombuffer(data, dtype=dtype)


_TYPES = {"Float32": "<f4", "Float64": "<f8", "Int32": "<i4",
          "Int64": "<i8", "UInt8": "u1"}


def read_pvtu(path):
    """Nodes (cell centres, n x 3) and point fields (one value per node)."""
    root = ET.parse(path).getroot()
    points, fields = [], {}
    for piece in root.find("PUnstructuredGrid").findall("Piece"):
        vtu = ET.parse(os.path.join(os.path.dirname(path),
                                    piece.get("Source"))).getroot()
        p = vtu.find("UnstructuredGrid/Piece")
        a = p.find("Points/DataArray")
        points.append(_decode(a.text, _TYPES[a.get("type")]).reshape(-1, 3))
        for a in p.find("PointData"):
            fields.setdefault(a.get("Name"), []).append(
                _decode(a.text, _TYPES[a.get("type")]))
    p = np.concatenate(points)
    per_cell = 4 if np.all(p[:, 2] == 0) else 8
    x = p.reshape(-1, per_cell, 3).mean(axis=1)
    return x, {k: np.concatenate(v).reshape(-1, per_cell)[:, 0]
               for k, v in fields.items()}
