#!/usr/bin/python3
"""Independent reader and checker for VTK XML UnstructuredGrid (.vtu) files, their
parallel index (.pvtu: the pieces of a distributed run) and ParaView collections (.pvd). Standard library only (xml.etree, base64, struct):
it shares no code with perimorph's writer and needs no VTK installation.

Supported .vtu data: DataArray format="ascii", or format="binary" (inline
base64, uncompressed) with header_type UInt32 or UInt64 and either byte order.
The binary block may be encoded as one base64 stream of header + data (VTK's
own layout) or as two separately padded streams (meshio's layout).

Usage:
  read_vtu.py FILE.vtu [--expect-points N] [--expect-cells M]
              [--expect-cell-type quad|hexahedron|line|vertex|ID]
              [--expect-point-array NAME:COMPONENTS]... [--expect-cell-array NAME:COMPONENTS]...
              [--print]
  read_vtu.py --pvd FILE.pvd [--expect-steps K] [--print]

Always checked: a single Piece; Points Float with 3 components and finite
values; connectivity/offsets/types consistent (offsets increasing, last offset
== len(connectivity), indices in range, node count matching the cell type);
every array length == count * NumberOfComponents with finite values; quads
and hexes not degenerate or self-intersecting (catches a wrong node order).
Exit status 0 if every check passes, 1 with a message on stderr otherwise.
"""

import argparse
import base64
import math
import os
import struct
import sys
import xml.etree.ElementTree as ET

TYPES = {  # VTK type name -> (struct code, size in bytes)
    "Int8": ("b", 1), "UInt8": ("B", 1), "Int16": ("h", 2), "UInt16": ("H", 2),
    "Int32": ("i", 4), "UInt32": ("I", 4), "Int64": ("q", 8), "UInt64": ("Q", 8),
    "Float32": ("f", 4), "Float64": ("d", 8),
}
CELL_NODES = {1: 1, 3: 2, 9: 4, 12: 8}  # VTK_VERTEX, VTK_LINE, VTK_QUAD, VTK_HEXAHEDRON
CELL_NAMES = {"vertex": 1, "line": 3, "quad": 9, "hexahedron": 12}


class CheckError(Exception):
    """A file that does not match the format or an expectation."""


def _decode_binary(text, vtk_type, header_type, byte_order):
    code, size = TYPES[vtk_type]
    hcode, hsize = TYPES[header_type]
    end = "<" if byte_order == "LittleEndian" else ">"
    s = "".join(text.split())
    candidates = []
    try:  # one stream: base64(header + data)
        raw = base64.b64decode(s, validate=True)
        candidates.append((raw[:hsize], raw[hsize:]))
    except ValueError:
        pass
    hchars = 4 * ((hsize + 2) // 3)
    try:  # two streams: base64(header) + base64(data)
        candidates.append((base64.b64decode(s[:hchars], validate=True),
                           base64.b64decode(s[hchars:], validate=True)))
    except ValueError:
        pass
    for header, data in candidates:
        if len(header) < hsize:
            continue
        (nbytes,) = struct.unpack(end + hcode, header[:hsize])
        if nbytes == len(data):
            if nbytes % size:
                raise CheckError(f"binary block of {nbytes} bytes is not a whole number of {vtk_type}")
            return list(struct.unpack(f"{end}{nbytes // size}{code}", data))
    raise CheckError("binary DataArray: invalid base64 or byte count header does not match the data")


def _read_array(elem, header_type, byte_order):
    vtk_type = elem.get("type")
    if vtk_type not in TYPES:
        raise CheckError(f"DataArray '{elem.get('Name')}': unsupported type {vtk_type}")
    fmt = elem.get("format", "ascii")
    text = elem.text or ""
    if fmt == "ascii":
        conv = float if vtk_type.startswith("Float") else int
        try:
            values = [conv(tok) for tok in text.split()]
        except ValueError as e:
            raise CheckError(f"DataArray '{elem.get('Name')}': bad ascii value ({e})") from None
    elif fmt == "binary":
        values = _decode_binary(text, vtk_type, header_type, byte_order)
    else:
        raise CheckError(f"DataArray '{elem.get('Name')}': unsupported format '{fmt}'")
    try:
        comps = int(elem.get("NumberOfComponents", "1"))
    except ValueError:
        raise CheckError(f"DataArray '{elem.get('Name')}': bad NumberOfComponents") from None
    if comps < 1:
        raise CheckError(f"DataArray '{elem.get('Name')}': NumberOfComponents {comps} < 1")
    return {"name": elem.get("Name", ""), "type": vtk_type, "components": comps, "values": values}


def _check_array(arr, count, where):
    n = count * arr["components"]
    if len(arr["values"]) != n:
        raise CheckError(f"{where} array '{arr['name']}': {len(arr['values'])} values, expected "
                         f"{n} ({count} x {arr['components']})")
    bad = [i for i, v in enumerate(arr["values"]) if not math.isfinite(v)]
    if bad:
        raise CheckError(f"{where} array '{arr['name']}': {len(bad)} non-finite values (first at {bad[0]})")


def _sub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _norm(a):
    return math.sqrt(a[0] ** 2 + a[1] ** 2 + a[2] ** 2)


def _polygon_area(pts):
    """Magnitude of the vector area; ~0 for a 'bowtie' (wrongly ordered) quad."""
    s = [0.0, 0.0, 0.0]
    for i, p in enumerate(pts):
        c = _cross(p, pts[(i + 1) % len(pts)])
        s = [s[k] + c[k] for k in range(3)]
    return 0.5 * _norm(s)


HEX_FACES = [(0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]


def _check_cell_shape(cell, vtk_type, pts):
    p = [pts[n] for n in cell]
    size = max(_norm(_sub(a, b)) for a in p for b in p)
    if size == 0.0:
        raise CheckError("cell with all nodes at one point")
    faces = [tuple(range(4))] if vtk_type == 9 else HEX_FACES
    for f in faces:
        if _polygon_area([p[i] for i in f]) <= 1e-10 * size * size:
            raise CheckError(f"degenerate or self-intersecting face {f} (wrong VTK node order?)")


def read_vtu(path, shape_check=True):
    """Parses and checks a .vtu; returns a dict with points, cells, point/cell arrays."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError) as e:
        raise CheckError(f"cannot parse XML: {e}") from None
    if root.tag != "VTKFile" or root.get("type") != "UnstructuredGrid":
        raise CheckError("root is not <VTKFile type=\"UnstructuredGrid\">")
    if root.get("compressor"):
        raise CheckError("compressed data is not supported")
    header_type = root.get("header_type", "UInt32")
    byte_order = root.get("byte_order", "LittleEndian")
    if header_type not in ("UInt32", "UInt64") or byte_order not in ("LittleEndian", "BigEndian"):
        raise CheckError(f"bad header_type {header_type} or byte_order {byte_order}")
    pieces = root.findall("./UnstructuredGrid/Piece")
    if len(pieces) != 1:
        raise CheckError(f"expected exactly one Piece, found {len(pieces)}")
    piece = pieces[0]
    try:
        npoints = int(piece.get("NumberOfPoints"))
        ncells = int(piece.get("NumberOfCells"))
    except (TypeError, ValueError):
        raise CheckError("Piece lacks integer NumberOfPoints / NumberOfCells") from None

    def arrays(xpath):
        return [_read_array(e, header_type, byte_order) for e in piece.findall(xpath)]

    pts_arrays = arrays("./Points/DataArray")
    if len(pts_arrays) != 1 or pts_arrays[0]["components"] != 3 or not pts_arrays[0]["type"].startswith("Float"):
        raise CheckError("Points must hold one Float DataArray with 3 components")
    _check_array(pts_arrays[0], npoints, "Points")
    xyz = pts_arrays[0]["values"]
    points = [xyz[3 * i:3 * i + 3] for i in range(npoints)]

    cells = {a["name"]: a for a in arrays("./Cells/DataArray")}
    for name in ("connectivity", "offsets", "types"):
        if name not in cells:
            raise CheckError(f"Cells lacks the '{name}' array")
    conn, offsets, types = (cells[n]["values"] for n in ("connectivity", "offsets", "types"))
    if len(offsets) != ncells or len(types) != ncells:
        raise CheckError(f"offsets ({len(offsets)}) / types ({len(types)}) do not match NumberOfCells {ncells}")
    if (offsets[-1] if offsets else 0) != len(conn):
        raise CheckError(f"last offset {offsets[-1] if offsets else 0} != connectivity length {len(conn)}")
    if any(n < 0 or n >= npoints for n in conn):
        raise CheckError(f"connectivity index outside [0, {npoints})")
    cell_list, start = [], 0
    for c in range(ncells):
        end, t = offsets[c], types[c]
        if t not in CELL_NODES:
            raise CheckError(f"cell {c}: unsupported VTK cell type {t}")
        if end - start != CELL_NODES[t]:
            raise CheckError(f"cell {c}: {end - start} nodes, VTK type {t} needs {CELL_NODES[t]}")
        cell_list.append(conn[start:end])
        if shape_check and t in (9, 12):
            try:
                _check_cell_shape(cell_list[-1], t, points)
            except CheckError as e:
                raise CheckError(f"cell {c}: {e}") from None
        start = end

    result = {"path": path, "points": points, "cells": cell_list, "types": types,
              "point_data": {}, "cell_data": {}}
    for key, xpath, count in (("point_data", "./PointData/DataArray", npoints),
                              ("cell_data", "./CellData/DataArray", ncells)):
        for arr in arrays(xpath):
            _check_array(arr, count, key)
            if arr["name"] in result[key]:
                raise CheckError(f"duplicate {key} array '{arr['name']}'")
            result[key][arr["name"]] = arr
    return result


def read_pvtu(path, shape_check=True):
    """Parses a .pvtu (the pieces of a distributed run, one per process) and every piece it lists;
    checks that each piece holds the declared arrays and, where the pieces carry a cell array `cell`
    (perimorph's: the cell's number in the whole mesh), that they hold every cell exactly once.
    Returns one grid in read_vtu's form: cells in the order of `cell` (which is then dropped), the
    pieces' points one after the other (a point on a boundary between pieces appears in each)."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError) as e:
        raise CheckError(f"cannot parse XML: {e}") from None
    grid = root.find("./PUnstructuredGrid")
    if root.tag != "VTKFile" or root.get("type") != "PUnstructuredGrid" or grid is None:
        raise CheckError("root is not <VTKFile type=\"PUnstructuredGrid\"> with a <PUnstructuredGrid>")
    declared = {key: {a.get("Name"): int(a.get("NumberOfComponents", "1")) for a in grid.findall(xpath)}
                for key, xpath in (("point_data", "./PPointData/PDataArray"),
                                   ("cell_data", "./PCellData/PDataArray"))}
    ppoints = grid.findall("./PPoints/PDataArray")
    if len(ppoints) != 1 or ppoints[0].get("NumberOfComponents") != "3":
        raise CheckError("PPoints must declare one PDataArray with 3 components")
    sources = [p.get("Source") for p in grid.findall("./Piece")]
    if not sources or not all(sources):
        raise CheckError("no Piece, or a Piece without Source")
    merged = {"path": path, "points": [], "cells": [], "types": [], "point_data": {}, "cell_data": {},
              "pieces": len(sources)}
    cell_values = {}
    for src in sources:
        full = os.path.join(os.path.dirname(path), src)
        if not os.path.isfile(full):
            raise CheckError(f"piece '{src}' does not exist")
        try:
            piece = read_vtu(full, shape_check)
        except CheckError as e:
            raise CheckError(f"{src}: {e}") from None
        for key in ("point_data", "cell_data"):
            have = {n: a["components"] for n, a in piece[key].items()}
            if have != declared[key]:
                raise CheckError(f"{src}: {key} arrays {have}, the index declares {declared[key]}")
        shift = len(merged["points"])
        merged["points"] += piece["points"]
        merged["cells"] += [[n + shift for n in c] for c in piece["cells"]]
        merged["types"] += piece["types"]
        for key, store in (("point_data", merged["point_data"]), ("cell_data", cell_values)):
            for name, arr in piece[key].items():
                store.setdefault(name, {"name": name, "type": arr["type"], "components": arr["components"],
                                        "values": []})["values"] += arr["values"]
    if "cell" in cell_values:
        ids = [int(x) for x in cell_values.pop("cell")["values"]]
        if sorted(ids) != list(range(len(ids))):
            raise CheckError(f"the pieces' `cell` numbers are not each cell 0..{len(ids) - 1} once")
        order = sorted(range(len(ids)), key=ids.__getitem__)
        merged["cells"] = [merged["cells"][i] for i in order]
        merged["types"] = [merged["types"][i] for i in order]
        for arr in cell_values.values():
            k = arr["components"]
            arr["values"] = [v for i in order for v in arr["values"][k * i:k * i + k]]
    merged["cell_data"] = cell_values
    return merged


def read_grid(path, shape_check=True):
    """read_pvtu for a .pvtu, read_vtu otherwise."""
    return read_pvtu(path, shape_check) if path.endswith(".pvtu") else read_vtu(path, shape_check)


def read_pvd(path, shape_check=True):
    """Parses a .pvd and every .vtu (or .pvtu and its pieces) it lists; returns [(time, vtu dict)]."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError) as e:
        raise CheckError(f"cannot parse XML: {e}") from None
    if root.tag != "VTKFile" or root.get("type") != "Collection" or root.find("./Collection") is None:
        raise CheckError("root is not <VTKFile type=\"Collection\"> with a <Collection>")
    steps = []
    for ds in root.findall("./Collection/DataSet"):
        rel = ds.get("file")
        try:
            time = float(ds.get("timestep", "0"))
        except ValueError:
            raise CheckError(f"DataSet '{rel}': bad timestep") from None
        if not rel or not math.isfinite(time):
            raise CheckError("DataSet without file or with non-finite timestep")
        full = os.path.join(os.path.dirname(path), rel)
        if not os.path.isfile(full):
            raise CheckError(f"referenced file '{rel}' does not exist")
        try:
            steps.append((time, read_grid(full, shape_check)))
        except CheckError as e:
            raise CheckError(f"{rel}: {e}") from None
    return steps


def summary(vtu):
    lines = [f"{vtu['path']}: {len(vtu['points'])} points, {len(vtu['cells'])} cells, "
             f"types {sorted(set(vtu['types']))}"]
    for key in ("point_data", "cell_data"):
        for name, arr in vtu[key].items():
            v = arr["values"]
            rng = f"[{min(v):.6g}, {max(v):.6g}]" if v else "[]"
            lines.append(f"  {key} {name}: {arr['components']} components, range {rng}")
    return "\n".join(lines)


def _name_components(spec):
    name, sep, comps = spec.rpartition(":")
    if not sep or not name or not comps.isdigit():
        raise argparse.ArgumentTypeError(f"expected NAME:COMPONENTS, got '{spec}'")
    return name, int(comps)


def main(argv):
    ap = argparse.ArgumentParser(description="Check a .vtu or .pvd file independently of VTK.")
    ap.add_argument("file", nargs="?", help=".vtu (or .pvtu) file to check")
    ap.add_argument("--pvd", help=".pvd collection to check (every referenced .vtu must parse)")
    ap.add_argument("--expect-points", type=int)
    ap.add_argument("--expect-cells", type=int)
    ap.add_argument("--expect-cell-type")
    ap.add_argument("--expect-point-array", type=_name_components, action="append", default=[])
    ap.add_argument("--expect-cell-array", type=_name_components, action="append", default=[])
    ap.add_argument("--expect-steps", type=int, help="with --pvd: number of DataSet entries")
    ap.add_argument("--no-shape-check", action="store_true", help="skip the degenerate-cell check")
    ap.add_argument("--print", action="store_true", help="print a summary")
    args = ap.parse_args(argv)
    if (args.file is None) == (args.pvd is None):
        ap.error("give exactly one of FILE.vtu or --pvd FILE.pvd")

    target = args.pvd or args.file
    try:
        if args.pvd:
            steps = read_pvd(args.pvd, not args.no_shape_check)
            if args.expect_steps is not None and len(steps) != args.expect_steps:
                raise CheckError(f"{len(steps)} steps, expected {args.expect_steps}")
            if args.print:
                print(f"{args.pvd}: {len(steps)} steps")
                for time, vtu in steps:
                    print(f"t = {time:g}: {summary(vtu)}")
            return 0
        vtu = read_grid(args.file, not args.no_shape_check)
        if args.expect_points is not None and len(vtu["points"]) != args.expect_points:
            raise CheckError(f"{len(vtu['points'])} points, expected {args.expect_points}")
        if args.expect_cells is not None and len(vtu["cells"]) != args.expect_cells:
            raise CheckError(f"{len(vtu['cells'])} cells, expected {args.expect_cells}")
        if args.expect_cell_type is not None:
            t = args.expect_cell_type
            want = CELL_NAMES[t] if t in CELL_NAMES else int(t) if t.isdigit() else None
            if want is None:
                raise CheckError(f"unknown cell type '{t}'")
            if any(x != want for x in vtu["types"]):
                raise CheckError(f"cell types {sorted(set(vtu['types']))}, expected only {want}")
        for key, expected in (("point_data", args.expect_point_array), ("cell_data", args.expect_cell_array)):
            for name, comps in expected:
                arr = vtu[key].get(name)
                if arr is None:
                    raise CheckError(f"no {key} array '{name}' (have {sorted(vtu[key])})")
                if arr["components"] != comps:
                    raise CheckError(f"{key} array '{name}' has {arr['components']} components, expected {comps}")
        if args.print:
            print(summary(vtu))
        return 0
    except CheckError as e:
        print(f"read_vtu: {target}: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
