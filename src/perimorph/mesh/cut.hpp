#pragma once
// Pre-cracks: split the mesh's nodes along a planar cut so the local model can
// open a crack; the cut is also stored in Mesh::cuts as geometry.

#include "perimorph/mesh/mesh.hpp"

namespace perimorph::mesh {

struct CutReport {
  Index faces_cut = 0;    ///< interior faces lying on the cut
  Index nodes_split = 0;  ///< new nodes created
};

/// Splits `mesh` along `cut`. An interior face is cut when all its nodes lie on
/// the cut (within 1e-8 of the smallest cell size). Around each node of a cut
/// face, the incident cells are grouped into components connected through
/// uncut faces containing that node; every component after the first receives
/// its own copy of the node. So a crack front inside the body stays closed
/// (its cells connect around the front) and a crack reaching the boundary
/// opens all the way. Node sets containing a split node gain its copies.
/// Throws InputError if no mesh face lies on the cut (the cut must follow
/// element faces).
CutReport split_along_cut(Mesh& mesh, const Cut& cut);

/// Splits `mesh` along the given cell faces (a pre-crack read from a mesh
/// file, e.g. a Gmsh physical curve or surface): the nodes of the interior
/// faces among them are split as split_along_cut does, and every face (an
/// interior one, or a boundary face where the file already split the nodes)
/// joins Mesh::cuts as geometry for the non-local model: a point (1D), a
/// segment (2D), two triangles (3D). Faces given from both sides count once.
CutReport split_along_faces(Mesh& mesh, const std::vector<CellFace>& faces);

}  // namespace perimorph::mesh
