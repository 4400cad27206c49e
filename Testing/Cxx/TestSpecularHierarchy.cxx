// The specular triangles' hierarchy that the camera view traces (vtkCausticsSpecularHierarchy):
// which meshes are convex solids (the automatic setting traces the others), and a
// hierarchy that holds every valid triangle once, inside its nodes' boxes.
#include "vtkCausticsSceneData.h"
#include "vtkCausticsSpecularHierarchy.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace
{
/** `source`'s triangles with point normals, moved by `offset`, as a scene mesh. */
caustics::Mesh MeshOf(vtkAlgorithm* source, const double offset[3] = nullptr)
{
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(source->GetOutputPort());
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(triangles->GetOutputPort());
  normals->SplittingOff();
  normals->Update();
  vtkPolyData* poly = normals->GetOutput();
  caustics::Mesh mesh;
  vtkDataArray* n = poly->GetPointData()->GetNormals();
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i)
  {
    double p[3];
    poly->GetPoint(i, p);
    for (int a = 0; a < 3; ++a)
    {
      mesh.positions.push_back(static_cast<float>(p[a] + (offset ? offset[a] : 0.0)));
      mesh.normals.push_back(static_cast<float>(n->GetComponent(i, a)));
    }
  }
  vtkNew<vtkIdList> cell;
  for (vtkIdType c = 0; c < poly->GetNumberOfCells(); ++c)
  {
    poly->GetCellPoints(c, cell);
    for (vtkIdType k = 0; k < cell->GetNumberOfIds(); ++k)
    {
      mesh.indices.push_back(static_cast<std::uint32_t>(cell->GetId(k)));
    }
  }
  return mesh;
}

caustics::Mesh Sphere(const double offset[3] = nullptr)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(16);
  return MeshOf(sphere, offset);
}

/** Two meshes' triangles as one. */
caustics::Mesh Join(const caustics::Mesh& a, const caustics::Mesh& b)
{
  caustics::Mesh joined = a;
  const auto first = static_cast<std::uint32_t>(a.positions.size() / 3);
  joined.positions.insert(joined.positions.end(), b.positions.begin(), b.positions.end());
  joined.normals.insert(joined.normals.end(), b.normals.begin(), b.normals.end());
  for (std::uint32_t index : b.indices)
  {
    joined.indices.push_back(index + first);
  }
  return joined;
}

std::int32_t Bits(float value)
{
  std::int32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}
}

TEST(SpecularHierarchy, ConvexSolids)
{
  EXPECT_TRUE(vtkCausticsSpecularHierarchy::IsConvex(Sphere()));
  // A dent: one vertex pushed to the centre.
  caustics::Mesh dented = Sphere();
  const std::size_t middle = dented.positions.size() / 6;
  for (int a = 0; a < 3; ++a)
  {
    dented.positions[3 * middle + a] *= 0.5f;
  }
  EXPECT_FALSE(vtkCausticsSpecularHierarchy::IsConvex(dented));
  // Open: a sheet (the pool's water), a sphere less one triangle.
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(4, 4);
  EXPECT_FALSE(vtkCausticsSpecularHierarchy::IsConvex(MeshOf(plane)));
  caustics::Mesh open = Sphere();
  open.indices.resize(open.indices.size() - 3);
  EXPECT_FALSE(vtkCausticsSpecularHierarchy::IsConvex(open));
  // Two balls: convex at every edge, yet a ray leaving one meets the other.
  const double aside[3] = { 3.0, 0.0, 0.0 };
  EXPECT_FALSE(vtkCausticsSpecularHierarchy::IsConvex(Join(Sphere(), Sphere(aside))));
  // No normals, or nothing: not known to be convex.
  caustics::Mesh bare = Sphere();
  bare.normals.clear();
  EXPECT_FALSE(vtkCausticsSpecularHierarchy::IsConvex(bare));
  EXPECT_FALSE(vtkCausticsSpecularHierarchy::IsConvex(caustics::Mesh()));
}

TEST(SpecularHierarchy, HoldsEveryValidTriangleOnceInsideItsBoxes)
{
  caustics::SceneData scene;
  scene.Materials.resize(3);
  scene.Materials[0].role = caustics::Role::Refractor;
  scene.Materials[1].role = caustics::Role::Receiver;
  scene.Materials[2].role = caustics::Role::Reflector;
  scene.Meshes.push_back(Sphere());
  scene.Meshes.back().material = 0;
  const double aside[3] = { 3.0, 0.0, 0.0 };
  scene.Meshes.push_back(Sphere(aside)); // a receiver: not traced
  scene.Meshes.back().material = 1;
  const double above[3] = { 0.0, 3.0, 0.0 };
  scene.Meshes.push_back(Sphere(above));
  scene.Meshes.back().material = 2;
  // Bad triangles are dropped: a NaN corner, a degenerate one, an index out of range.
  caustics::Mesh& mirror = scene.Meshes.back();
  const std::size_t valid = scene.Meshes[0].TriangleCount() + mirror.TriangleCount();
  mirror.positions.push_back(std::numeric_limits<float>::quiet_NaN());
  mirror.positions.push_back(0.0f);
  mirror.positions.push_back(0.0f);
  mirror.normals.insert(mirror.normals.end(), { 0.0f, 1.0f, 0.0f });
  const auto nan = static_cast<std::uint32_t>(mirror.positions.size() / 3 - 1);
  mirror.indices.insert(mirror.indices.end(), { 0, 1, nan, 0, 0, 1, 0, 1, 100000 });

  std::vector<float> nodes, triangles;
  vtkCausticsSpecularHierarchy::Build(scene, nodes, triangles);
  ASSERT_EQ(triangles.size(), valid * 24);
  ASSERT_EQ(nodes.size() % 8, 0u);
  std::vector<int> seen(valid, 0);
  int leaves = 0;
  for (std::size_t node = 0; node < nodes.size() / 8; ++node)
  {
    const float* lo = &nodes[8 * node];
    const float* hi = &nodes[8 * node + 4];
    const std::int32_t count = Bits(hi[3]);
    if (count == 0)
    {
      // Both children inside their parent's box.
      for (std::size_t child : { node + 1, static_cast<std::size_t>(Bits(lo[3])) })
      {
        ASSERT_LT(child, nodes.size() / 8);
        for (int a = 0; a < 3; ++a)
        {
          EXPECT_GE(nodes[8 * child + a], lo[a]);
          EXPECT_LE(nodes[8 * child + 4 + a], hi[a]);
        }
      }
      continue;
    }
    ++leaves;
    EXPECT_LE(count, 4);
    const std::int32_t first = Bits(lo[3]);
    for (std::int32_t t = first; t < first + count; ++t)
    {
      ASSERT_LT(static_cast<std::size_t>(t), valid);
      ++seen[t];
      const float* p = &triangles[24 * t];
      for (int corner = 0; corner < 3; ++corner)
      {
        for (int a = 0; a < 3; ++a)
        {
          const float x = p[a] + (corner == 0 ? 0.0f : p[4 * corner + a]);
          EXPECT_GE(x, lo[a] - 1e-5f);
          EXPECT_LE(x, hi[a] + 1e-5f);
        }
      }
      EXPECT_TRUE(p[3] == 0.0f || p[3] == 2.0f) << "the material of a traced mesh";
    }
  }
  EXPECT_GT(leaves, 1);
  for (std::size_t t = 0; t < valid; ++t)
  {
    EXPECT_EQ(seen[t], 1) << "triangle " << t;
  }
  // Nothing specular: an empty hierarchy.
  scene.Materials[0].role = caustics::Role::Receiver;
  scene.Materials[2].role = caustics::Role::Receiver;
  vtkCausticsSpecularHierarchy::Build(scene, nodes, triangles);
  EXPECT_TRUE(nodes.empty());
  EXPECT_TRUE(triangles.empty());
}
