// Paper §2.1: relief construction. The steps live in their own files: the six distance fields
// (geodesic_distance.cpp), their upper envelope along every edge (relief_envelope.cpp), the split of the faces a
// relief boundary crosses (relief_refinement.cpp), and the components (relief_components.cpp).
#include "prm/remesh/reliefs.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "geodesic_distance.h"
#include "prm/error.h"
#include "prm/vec3.h"
#include "relief_axes.h"
#include "relief_components.h"
#include "relief_refinement.h"
#include "relief_topology.h"

namespace prm::remesh {

std::array<uint8_t, 3> relief_colour(int axis, int id) {
  // +x red, -x orange, +y green, -y yellow, +z blue, -z purple; reliefs of one axis never touch, the lightness
  // varies a little per relief so that they can still be told apart.
  static const uint8_t base[kReliefAxes][3] = {{228, 26, 28},  {255, 127, 0}, {77, 175, 74},
                                               {235, 205, 50}, {55, 126, 184}, {152, 78, 163}};
  const double shade = 0.8 + 0.2 * static_cast<double>((static_cast<uint32_t>(id) * 2654435761u) % 1000u) / 1000.0;
  const auto& b = base[static_cast<size_t>(((axis % kReliefAxes) + kReliefAxes) % kReliefAxes)];
  return {static_cast<uint8_t>(b[0] * shade), static_cast<uint8_t>(b[1] * shade), static_cast<uint8_t>(b[2] * shade)};
}

namespace {

void check_options(const ReliefOptions& o) {
  if (!(o.tau > 0) || !(o.tau < 1.0 / std::sqrt(3.0)))
    throw InputError("tau must be in (0, 1/sqrt(3)) = (0, 0.5773...), got " + std::to_string(o.tau));
  if (!(o.snap >= 0) || !(o.snap < 0.25))
    throw InputError("the edge snap must be in [0, 0.25), got " + std::to_string(o.snap));
  if (!(o.min_relief_triangles >= 0))
    throw InputError("min_relief_triangles must not be negative, got " + std::to_string(o.min_relief_triangles));
  if (!(o.merge_facing > 0) || !(o.merge_facing < 1.0 / std::sqrt(3.0)))
    throw InputError("merge_facing must be in (0, 1/sqrt(3)), got " + std::to_string(o.merge_facing));
}

}  // namespace

ReliefLayout build_reliefs(const Mesh& input, const ReliefOptions& options) {
  check_options(options);
  if (input.triangles.empty()) throw InputError("the mesh has no faces");
  for (size_t f = 0; f < input.triangles.size(); ++f) {
    const Tri& t = input.triangles[f];
    for (uint32_t v : t)
      if (v >= input.positions.size())
        throw InputError("face " + std::to_string(f) + " uses vertex " + std::to_string(v) + " of " +
                         std::to_string(input.positions.size()));
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      throw InputError("face " + std::to_string(f) + " uses a vertex twice (prm repair removes such faces)");
  }

  const VertexStar star = vertex_star(input, !options.naive);
  const auto adjacency = edge_adjacency(input, star);  // throws on a non-manifold edge
  const PinchReport pinch = find_pinched_vertices(input, star);
  if (pinch.pinched > 0)
    throw InputError("vertex " + std::to_string(pinch.first) + " joins " + std::to_string(pinch.fans) +
                     " separate fans of faces (a pinch; " + std::to_string(pinch.pinched) +
                     " such vertices): the relief construction needs a 2-manifold (prm repair splits pinches)");
  const Mesh& mesh = input;
  const size_t nf = mesh.triangles.size();
  ReliefLayout out;
  const std::vector<Vec3> normals = face_unit_normals(mesh);
  std::vector<int8_t> closest(nf);
  for (size_t f = 0; f < nf; ++f) closest[f] = static_cast<int8_t>(closest_axis(normals[f]));

  std::vector<int8_t> axis;
  if (options.naive) {
    out.mesh.positions = mesh.positions;
    out.mesh.triangles = mesh.triangles;
    axis = closest;
    out.source_face.resize(nf);
    std::iota(out.source_face.begin(), out.source_face.end(), 0);
  } else {
    const std::vector<AxisValues> fields =
        axis_distance_fields(mesh, star, normals, options.tau, options.geodesic, options.parallel);
    Refinement r = refine_along_relief_boundaries(mesh, adjacency, fields, closest, options.snap, options.parallel);
    out.mesh = std::move(r.mesh);
    axis = std::move(r.axis);
    out.source_face = std::move(r.source_face);
    out.split_faces = r.split_faces;
    out.inner_points = r.inner_points;
  }

  const auto refined_adjacency = options.naive ? adjacency : edge_adjacency(out.mesh, vertex_star(out.mesh, false));
  label_components(out.mesh, refined_adjacency, axis, out.face_relief, out.reliefs);
  if (!options.naive && options.min_relief_triangles > 0) {
    double area = 0;
    for (const Relief& r : out.reliefs) area += r.area;
    std::vector<Vec3> refined_normals(out.mesh.triangles.size());
    for (size_t f = 0; f < refined_normals.size(); ++f)
      refined_normals[f] = normals[static_cast<size_t>(out.source_face[f])];
    out.merged_reliefs = merge_small_reliefs(out.mesh, refined_adjacency, refined_normals,
                                             std::min(options.merge_facing, options.tau),
                                             options.min_relief_triangles * area / static_cast<double>(nf), 4, axis,
                                             out.face_relief, out.reliefs);
  }
  out.boundary_length = relief_boundary_length(out.mesh, refined_adjacency, out.face_relief);

  // Face properties for the PLY file and the pictures (paper Fig. 1, 2, 10: the layout colour-coded).
  if (!options.view_properties) return out;
  const size_t rf = out.mesh.triangles.size();
  std::vector<double> rel(rf), red(rf), green(rf), blue(rf);
  for (size_t f = 0; f < rf; ++f) {
    const int32_t id = out.face_relief[f];
    rel[f] = id;
    const auto c = relief_colour(out.reliefs[static_cast<size_t>(id)].axis, id);
    red[f] = c[0];
    green[f] = c[1];
    blue[f] = c[2];
  }
  out.mesh.set_face_property("relief", ScalarType::Int32, std::move(rel));
  out.mesh.set_face_property("red", ScalarType::UInt8, std::move(red));
  out.mesh.set_face_property("green", ScalarType::UInt8, std::move(green));
  out.mesh.set_face_property("blue", ScalarType::UInt8, std::move(blue));
  for (size_t r = 0; r < out.reliefs.size(); ++r)
    out.mesh.comments.push_back("prm-relief " + std::to_string(r) + " axis " + std::to_string(out.reliefs[r].axis));
  return out;
}

}  // namespace prm::remesh
