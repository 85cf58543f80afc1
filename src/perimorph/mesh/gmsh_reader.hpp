#pragma once
// Meshes from Gmsh files (.msh format 4.1 or 2.2), read through Gmsh's own
// library (libgmsh): first-order quadrilaterals in 2D, hexahedra in 3D, and
// the file's physical groups as named sets.

#include "perimorph/mesh/mesh.hpp"

#include <string>

namespace perimorph::mesh {

/// Reads the mesh of dimension `dim` (2 or 3) in the Gmsh file `path`.
///
/// Cells: the elements of dimension `dim`, which must all be first-order
/// quadrilaterals (2D) or hexahedra (3D), in the order of their element tags;
/// a 2D mesh lies in the plane z = 0. Nodes: those of the cells, in the order
/// of their node tags (a node no cell uses is dropped).
///
/// Sets, named by the physical group's name (an unnamed group is
/// "point_T", "curve_T", "surface_T" or "volume_T" for its tag T):
///  - a group of dimension `dim` (a physical surface in 2D, volume in 3D): a
///    cell set;
///  - a group of dimension `dim` − 1 (a physical curve in 2D, surface in 3D):
///    a face set, every cell face its elements cover (an interior face from
///    both sides), usable wherever a node set is (Mesh::nodes_of_set);
///  - a group of lower dimension (points; curves in 3D): a node set;
///  - "all" (every cell, a cell set) and "boundary" (the faces of one cell only,
///    a face set and a node set).
///
/// Throws InputError naming the file for: a missing or unreadable file; a
/// .geo file (it must be meshed first); a format version other than 4.1 and
/// 2.2; no element of dimension `dim` (with the usual cause: physical groups
/// that leave the domain out); elements of any other type in dimension `dim`
/// (the type, how many, and how to recombine); a 2D mesh outside z = 0; an
/// inverted cell (a non-positive Jacobian at one of its corners: the element
/// tag and its centroid); two groups of one name, or a group named "all" or
/// "boundary"; a lower-dimensional element of a face group that is no cell's
/// face; anything Gmsh itself reports.
Mesh read_gmsh(const std::string& path, int dim);

}  // namespace perimorph::mesh
