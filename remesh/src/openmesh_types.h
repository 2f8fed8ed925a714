// The half-edge mesh of the remesher's collapse and flip stages (OpenMesh, BSD licence).
#pragma once

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

namespace prm::remesh {

struct OMTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge | OpenMesh::Attributes::Status);
};

using OMesh = OpenMesh::TriMesh_ArrayKernelT<OMTraits>;

}  // namespace prm::remesh
