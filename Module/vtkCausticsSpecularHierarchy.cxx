#include "vtkCausticsSpecularHierarchy.h"

#include "vtkCausticsBindings.h" // CAUSTICS_SPECULAR_*_BINDING
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkObjectFactory.h"
#include "vtk_glew.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <numeric>
#include <tuple>

vtkStandardNewMacro(vtkCausticsSpecularHierarchy);

namespace
{
constexpr int FloatsPerNode = 8;
constexpr int FloatsPerTriangle = 24;
constexpr int LeafTriangles = 4;

float AsFloat(std::int32_t bits)
{
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

bool IsSpecular(caustics::Role role)
{
  return role == caustics::Role::Reflector || role == caustics::Role::Refractor;
}

struct Triangle
{
  std::array<float, 9> corners; // three xyz
  std::array<float, 9> normals;
  float material;
  std::array<float, 3> centroid;
};

/** The triangles of reflector and refractor meshes whose corners are finite and
 * distinct (a degenerate or NaN triangle can never be met). */
std::vector<Triangle> SpecularTriangles(const caustics::SceneData& scene)
{
  std::vector<Triangle> triangles;
  for (const caustics::Mesh& mesh : scene.Meshes)
  {
    if (!IsSpecular(caustics::MeshRole(scene, mesh)))
    {
      continue;
    }
    const std::size_t vertices = mesh.positions.size() / 3;
    const bool normals = mesh.normals.size() == mesh.positions.size();
    for (std::size_t k = 0; k + 2 < mesh.indices.size(); k += 3)
    {
      Triangle t;
      bool valid = true;
      for (int c = 0; c < 3 && valid; ++c)
      {
        const std::uint32_t v = mesh.indices[k + c];
        valid = v < vertices;
        for (int a = 0; a < 3 && valid; ++a)
        {
          t.corners[3 * c + a] = mesh.positions[3 * v + a];
          t.normals[3 * c + a] = normals ? mesh.normals[3 * v + a] : 0.0f;
          valid = std::isfinite(t.corners[3 * c + a]) && std::isfinite(t.normals[3 * c + a]);
        }
      }
      if (!valid)
      {
        continue;
      }
      float e1[3], e2[3];
      for (int a = 0; a < 3; ++a)
      {
        e1[a] = t.corners[3 + a] - t.corners[a];
        e2[a] = t.corners[6 + a] - t.corners[a];
      }
      const float cross[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0] };
      const float area2 = cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2];
      if (!(area2 > 0.0f) || !std::isfinite(area2))
      {
        continue;
      }
      for (int a = 0; a < 3; ++a)
      {
        t.centroid[a] = (t.corners[a] + t.corners[3 + a] + t.corners[6 + a]) / 3.0f;
      }
      t.material = static_cast<float>(mesh.material);
      triangles.push_back(t);
    }
  }
  return triangles;
}

/** Builds the subtree of triangles [first, last) of `order` depth-first into `nodes`. */
void BuildNode(const std::vector<Triangle>& triangles, std::vector<int>& order, int first,
  int last, std::vector<float>& nodes)
{
  const std::size_t self = nodes.size();
  nodes.resize(self + FloatsPerNode);
  float lo[3] = { 1e30f, 1e30f, 1e30f }, hi[3] = { -1e30f, -1e30f, -1e30f };
  float clo[3] = { 1e30f, 1e30f, 1e30f }, chi[3] = { -1e30f, -1e30f, -1e30f };
  for (int i = first; i < last; ++i)
  {
    const Triangle& t = triangles[order[i]];
    for (int a = 0; a < 3; ++a)
    {
      for (int c = 0; c < 3; ++c)
      {
        lo[a] = std::min(lo[a], t.corners[3 * c + a]);
        hi[a] = std::max(hi[a], t.corners[3 * c + a]);
      }
      clo[a] = std::min(clo[a], t.centroid[a]);
      chi[a] = std::max(chi[a], t.centroid[a]);
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    nodes[self + a] = lo[a];
    nodes[self + 4 + a] = hi[a];
  }
  const int count = last - first;
  int axis = 0;
  for (int a = 1; a < 3; ++a)
  {
    axis = chi[a] - clo[a] > chi[axis] - clo[axis] ? a : axis;
  }
  if (count <= LeafTriangles || !(chi[axis] > clo[axis]))
  {
    // A leaf: its triangles are the ones [first, last) of the final order.
    nodes[self + 3] = AsFloat(first);
    nodes[self + 7] = AsFloat(count);
    return;
  }
  const int middle = first + count / 2;
  std::nth_element(order.begin() + first, order.begin() + middle, order.begin() + last,
    [&](int a, int b) { return triangles[a].centroid[axis] < triangles[b].centroid[axis]; });
  BuildNode(triangles, order, first, middle, nodes);
  nodes[self + 3] = AsFloat(static_cast<std::int32_t>(nodes.size() / FloatsPerNode));
  nodes[self + 7] = AsFloat(0);
  BuildNode(triangles, order, middle, last, nodes);
}
}

struct vtkCausticsSpecularHierarchy::Internals
{
  caustics::gl::StorageBuffer Nodes;
  caustics::gl::StorageBuffer Triangles;
  vtkIdType NodeCount = 0;
  vtkIdType TriangleCount = 0;
  int Builds = 0;
  int NonConvex = 0;
  bool Built = false;
  std::vector<std::tuple<unsigned long, int, int>> Key;
};

vtkCausticsSpecularHierarchy::vtkCausticsSpecularHierarchy()
  : Internal(new Internals)
{
}

vtkCausticsSpecularHierarchy::~vtkCausticsSpecularHierarchy()
{
  if (this->Internal->Nodes.Handle() || this->Internal->Triangles.Handle())
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): GL buffers leaked");
  }
}

void vtkCausticsSpecularHierarchy::Build(
  const caustics::SceneData& scene, std::vector<float>& nodes, std::vector<float>& triangles)
{
  nodes.clear();
  triangles.clear();
  const std::vector<Triangle> specular = SpecularTriangles(scene);
  if (specular.empty())
  {
    return;
  }
  std::vector<int> order(specular.size());
  std::iota(order.begin(), order.end(), 0);
  nodes.reserve(2 * specular.size() / LeafTriangles * FloatsPerNode + FloatsPerNode);
  BuildNode(specular, order, 0, static_cast<int>(order.size()), nodes);
  triangles.reserve(specular.size() * FloatsPerTriangle);
  for (int index : order)
  {
    const Triangle& t = specular[index];
    const float* p = t.corners.data();
    const float block[FloatsPerTriangle] = { p[0], p[1], p[2], t.material, //
      p[3] - p[0], p[4] - p[1], p[5] - p[2], 0.0f,                         //
      p[6] - p[0], p[7] - p[1], p[8] - p[2], 0.0f,                         //
      t.normals[0], t.normals[1], t.normals[2], 0.0f,                      //
      t.normals[3], t.normals[4], t.normals[5], 0.0f,                      //
      t.normals[6], t.normals[7], t.normals[8], 0.0f };
    triangles.insert(triangles.end(), block, block + FloatsPerTriangle);
  }
}

bool vtkCausticsSpecularHierarchy::Update(const caustics::SceneData& scene)
{
  auto& in = *this->Internal;
  std::vector<std::tuple<unsigned long, int, int>> key = caustics::MeshKey(scene);
  if (in.Built && key == in.Key)
  {
    return true;
  }
  std::vector<float> nodes, triangles;
  Build(scene, nodes, triangles);
  in.NonConvex = 0;
  for (const caustics::Mesh& mesh : scene.Meshes)
  {
    in.NonConvex +=
      IsSpecular(caustics::MeshRole(scene, mesh)) && mesh.TriangleCount() > 0 && !IsConvex(mesh) ? 1 : 0;
  }
  in.NodeCount = static_cast<vtkIdType>(nodes.size() / FloatsPerNode);
  in.TriangleCount = static_cast<vtkIdType>(triangles.size() / FloatsPerTriangle);
  // Empty buffers still bind (16 bytes): the shader reads nothing when the count is 0.
  in.Nodes.Allocate(std::max<std::size_t>(nodes.size() * 4, 16));
  in.Triangles.Allocate(std::max<std::size_t>(triangles.size() * 4, 16));
  if (!in.Nodes.Handle() || !in.Triangles.Handle())
  {
    vtkErrorMacro(<< "could not allocate the specular hierarchy's buffers ("
                  << nodes.size() * 4 + triangles.size() * 4 << " bytes)");
    in.NodeCount = in.TriangleCount = 0;
    return false;
  }
  if (!nodes.empty())
  {
    in.Nodes.Write(0, nodes.size() * 4, nodes.data());
    in.Triangles.Write(0, triangles.size() * 4, triangles.data());
  }
  in.Key = std::move(key);
  in.Built = true;
  ++in.Builds;
  return true;
}

void vtkCausticsSpecularHierarchy::Bind(vtkCausticsShaderProgram* program) const
{
  auto& in = *this->Internal;
  const bool ready = in.Nodes.Handle() && in.Triangles.Handle();
  if (ready)
  {
    in.Nodes.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SPECULAR_NODE_BINDING);
    in.Triangles.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SPECULAR_TRIANGLE_BINDING);
  }
  program->SetUniformi("specularNodeCount", ready ? static_cast<int>(in.NodeCount) : 0);
}

void vtkCausticsSpecularHierarchy::BindTraced(
  const vtkCausticsSpecularHierarchy* traced, vtkCausticsShaderProgram* program)
{
  program->SetUniformi("exactSpecular", traced ? 1 : 0);
  if (traced)
  {
    traced->Bind(program);
  }
  else
  {
    program->SetUniformi("specularNodeCount", 0);
  }
}

vtkIdType vtkCausticsSpecularHierarchy::GetNumberOfTriangles() const
{
  return this->Internal->TriangleCount;
}

vtkIdType vtkCausticsSpecularHierarchy::GetNumberOfNodes() const
{
  return this->Internal->NodeCount;
}

int vtkCausticsSpecularHierarchy::GetNumberOfNonConvexMeshes() const
{
  return this->Internal->NonConvex;
}

bool vtkCausticsSpecularHierarchy::IsConvex(const caustics::Mesh& mesh)
{
  const std::size_t vertices = mesh.positions.size() / 3;
  const std::size_t count = mesh.TriangleCount();
  if (count < 4 || mesh.normals.size() != mesh.positions.size())
  {
    return false;
  }
  // Vertices welded by position: meshes repeat them along seams.
  std::map<std::array<float, 3>, std::uint32_t> welded;
  std::vector<std::uint32_t> id(vertices);
  float lo[3] = { 1e30f, 1e30f, 1e30f }, hi[3] = { -1e30f, -1e30f, -1e30f };
  for (std::size_t v = 0; v < vertices; ++v)
  {
    const std::array<float, 3> p = { mesh.positions[3 * v], mesh.positions[3 * v + 1],
      mesh.positions[3 * v + 2] };
    id[v] = welded.emplace(p, static_cast<std::uint32_t>(welded.size())).first->second;
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  }
  const double size = std::sqrt(double(hi[0] - lo[0]) * (hi[0] - lo[0]) +
    double(hi[1] - lo[1]) * (hi[1] - lo[1]) + double(hi[2] - lo[2]) * (hi[2] - lo[2]));
  // Each triangle's plane, its unit normal turned as its vertex normals point.
  std::vector<std::array<double, 4>> planes(count);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> edges;
  for (std::size_t t = 0; t < count; ++t)
  {
    std::array<std::uint32_t, 3> corner;
    double p[3][3], normal[3] = { 0, 0, 0 };
    for (int c = 0; c < 3; ++c)
    {
      const std::uint32_t v = mesh.indices[3 * t + c];
      if (v >= vertices)
      {
        return false;
      }
      corner[c] = id[v];
      for (int a = 0; a < 3; ++a)
      {
        p[c][a] = mesh.positions[3 * v + a];
        normal[a] += mesh.normals[3 * v + a];
      }
    }
    const double e1[3] = { p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2] };
    const double e2[3] = { p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2] };
    double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
      e1[0] * e2[1] - e1[1] * e2[0] };
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(length > 0.0) || !std::isfinite(length))
    {
      return false;
    }
    const double sign = n[0] * normal[0] + n[1] * normal[1] + n[2] * normal[2] < 0.0 ? -1.0 : 1.0;
    for (int a = 0; a < 3; ++a)
    {
      n[a] *= sign / length;
    }
    planes[t] = { n[0], n[1], n[2], -(n[0] * p[0][0] + n[1] * p[0][1] + n[2] * p[0][2]) };
    for (int c = 0; c < 3; ++c)
    {
      const std::uint32_t a = corner[c], b = corner[(c + 1) % 3];
      edges[{ std::min(a, b), std::max(a, b) }].push_back(t);
    }
  }
  // One piece: two separate balls are convex at every edge, yet a ray leaving one
  // meets the other.
  std::vector<std::size_t> parent(count);
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&parent](std::size_t t) {
    while (parent[t] != t)
    {
      t = parent[t] = parent[parent[t]];
    }
    return t;
  };
  std::size_t pieces = count;
  const double slack = 1e-5 * size;
  for (const auto& edge : edges)
  {
    if (edge.second.size() != 2)
    {
      return false; // an open or non-manifold edge
    }
    const std::size_t a = root(edge.second[0]), b = root(edge.second[1]);
    if (a != b)
    {
      parent[a] = b;
      --pieces;
    }
    for (int k = 0; k < 2; ++k)
    {
      const std::size_t self = edge.second[k], other = edge.second[1 - k];
      const std::array<double, 4>& plane = planes[self];
      for (int c = 0; c < 3; ++c)
      {
        const std::uint32_t v = mesh.indices[3 * other + c];
        const double height = plane[0] * mesh.positions[3 * v] +
          plane[1] * mesh.positions[3 * v + 1] + plane[2] * mesh.positions[3 * v + 2] + plane[3];
        if (height > slack)
        {
          return false;
        }
      }
    }
  }
  return pieces == 1;
}

int vtkCausticsSpecularHierarchy::GetNumberOfBuilds() const
{
  return this->Internal->Builds;
}

void vtkCausticsSpecularHierarchy::ReleaseGraphicsResources(vtkWindow*)
{
  auto& in = *this->Internal;
  in.Nodes.Release();
  in.Triangles.Release();
  in.Built = false;
  in.Key.clear();
  in.NodeCount = in.TriangleCount = 0;
}

void vtkCausticsSpecularHierarchy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Triangles: " << this->Internal->TriangleCount << "\n";
  os << indent << "Nodes: " << this->Internal->NodeCount << "\n";
  os << indent << "Builds: " << this->Internal->Builds << "\n";
  os << indent << "NonConvexMeshes: " << this->Internal->NonConvex << "\n";
}
