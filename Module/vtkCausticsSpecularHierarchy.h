/**
 * @class   vtkCausticsSpecularHierarchy
 * @brief   The scene's glass and mirror triangles in a bounding volume hierarchy on the
 *          GPU, so that the camera view meets them where the geometry puts them.
 *
 * The camera view of glass and mirrors (vtkCausticsScreenSpaceRefraction) finds the
 * surfaces a ray meets in images: the refractors' layered depth image and the distance
 * impostors' cube maps. Both lose what they cannot hold: layers past the last one,
 * surfaces a cube map's centre does not see (a concave object such as the bunny), the
 * face normal that tells a ray's side of a coarse mesh. Tracing the specular triangles
 * themselves removes that for the interfaces the light crosses; what lies around them
 * still comes from the images.
 *
 * Update() builds the hierarchy on the CPU (median splits along the longest axis of
 * the triangles' centroids, at most four triangles a leaf, depth-first order) and
 * uploads it only when a reflector or refractor mesh changed (its version, the meshes'
 * count or their materials' roles): GetNumberOfBuilds() counts that. Bind() binds it
 * for glsl/vtkCausticsSpecularTrace.glsl at CAUSTICS_SPECULAR_NODE_BINDING and
 * CAUSTICS_SPECULAR_TRIANGLE_BINDING.
 */
#ifndef vtkCausticsSpecularHierarchy_h
#define vtkCausticsSpecularHierarchy_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include <memory> // For std::unique_ptr
#include <vector> // For std::vector

namespace caustics
{
struct Mesh;
struct SceneData;
}
class vtkCausticsShaderProgram;
class vtkWindow;

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsSpecularHierarchy : public vtkObject
{
public:
  static vtkCausticsSpecularHierarchy* New();
  vtkTypeMacro(vtkCausticsSpecularHierarchy, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /**
   * Rebuilds and uploads the hierarchy when the scene's reflectors or refractors changed
   * since the last call (the context must be current). False on a GL failure.
   */
  bool Update(const caustics::SceneData& scene);

  /**
   * The hierarchy of `scene`'s reflector and refractor triangles, as uploaded:
   * `nodes` holds 8 floats a node (box minimum, then the right child's index for an
   * inner node or the first triangle's for a leaf, as float bits; box maximum, then
   * the leaf's triangle count, 0 for an inner node, as float bits; the left child
   * follows its parent); `triangles` holds 24 floats a triangle (vertex 0 and the
   * material index, edges 0→1 and 0→2, the three vertex normals). No GL.
   */
  static void Build(
    const caustics::SceneData& scene, std::vector<float>& nodes, std::vector<float>& triangles);

  /**
   * Whether `mesh` bounds a convex solid: closed (every edge, its vertices welded by
   * position, shared by exactly two triangles) and convex at every edge (each
   * triangle's far corner lies on the inner side of its neighbour's plane, within
   * 1e-5 of the mesh's size; the faces turned out as the vertex normals point). A
   * ray that leaves such a solid cannot meet it again, and the layered depth image
   * and refractor map hold all of it. No GL.
   */
  static bool IsConvex(const caustics::Mesh& mesh);
#endif

  /** Binds the hierarchy's buffers; sets `specularNodeCount` (0: nothing to trace). */
  void Bind(vtkCausticsShaderProgram* program) const;

  /**
   * For a stage that traces glass and mirrors as triangles where asked: sets
   * `exactSpecular` (1 with a hierarchy, 0 with null) and binds `traced` if any.
   */
  static void BindTraced(const vtkCausticsSpecularHierarchy* traced, vtkCausticsShaderProgram* program);

  /** Triangles in the hierarchy. */
  vtkIdType GetNumberOfTriangles() const;
  /** Nodes in the hierarchy. */
  vtkIdType GetNumberOfNodes() const;
  /** Reflector and refractor meshes that are not convex solids (IsConvex), as of Update(). */
  int GetNumberOfNonConvexMeshes() const;
  /** How many times Update() rebuilt it (the geometry changed). */
  int GetNumberOfBuilds() const;

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsSpecularHierarchy();
  ~vtkCausticsSpecularHierarchy() override;

private:
  vtkCausticsSpecularHierarchy(const vtkCausticsSpecularHierarchy&) = delete;
  void operator=(const vtkCausticsSpecularHierarchy&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
