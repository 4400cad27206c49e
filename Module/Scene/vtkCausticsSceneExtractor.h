/**
 * @class   vtkCausticsSceneExtractor
 * @brief   Snapshot of a vtkRenderer for caustics: triangles, materials, lights, camera, medium.
 *
 * Every caustics stage, on the GPU and in the CPU reference, reads the scene
 * through this class so that they all see the same thing:
 * 1. visible actors (assemblies walked like VTK's pickers do) are classified by
 *    vtkCausticsMaterial; role "none" is skipped;
 * 2. each actor's polygonal input is triangulated, given normals if it has none,
 *    and transformed to world space. This is cached per actor and redone only
 *    when the input, the mapper or the actor's matrix changes (a Mesh::version bump
 *    tells GPU consumers to re-upload);
 * 3. bad geometry is repaired or dropped with a warning naming the actor:
 *    triangles with NaN/Inf vertices or zero area are dropped, invalid vertex
 *    normals are replaced by the face normal;
 * 4. switched-on lights become physical lights (see vtkCausticsSceneData.h for
 *    units): directional when not positional, spot when positional with a cone
 *    angle < 90 degrees, point otherwise; headlights follow the camera;
 * 5. the active camera gives the pixel-exact world-to-clip transform for the
 *    requested image size; the medium comes from vtkCausticsMedium::GetFrom().
 */
#ifndef vtkCausticsSceneExtractor_h
#define vtkCausticsSceneExtractor_h

#include "vtkObject.h"
#include "vtkCausticsSceneModule.h" // For export macro

#include "vtkCausticsSceneData.h" // For caustics::SceneData

#include <memory> // For std::unique_ptr

class vtkInformationDoubleKey;
class vtkRenderer;

class VTKCAUSTICSSCENE_EXPORT vtkCausticsSceneExtractor : public vtkObject
{
public:
  static vtkCausticsSceneExtractor* New();
  vtkTypeMacro(vtkCausticsSceneExtractor, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Metallic surfaces rougher than this are diffuse receivers, not mirrors.
   * Default 0.3 (002_97e66a5090de9b07.txt §3.1).
   */
  vtkSetClampMacro(RoughnessCutoff, double, 0.0, 1.0);
  vtkGetMacro(RoughnessCutoff, double);
  ///@}

  /**
   * Refreshes the snapshot for an image of width x height pixels. Returns false if
   * the renderer is null or has no camera.
   */
  bool Update(vtkRenderer* renderer, int width, int height);

#ifndef __VTK_WRAP__
  /** The snapshot made by the last Update(). */
  const caustics::SceneData& GetScene() const;
#endif

  ///@{
  /** Summary of the last Update(). */
  int GetNumberOfMeshes() const;
  int GetNumberOfLights() const;
  vtkIdType GetNumberOfTriangles() const;
  int GetNumberOfMeshesWithRole(int role) const;
  /** Triangles dropped (NaN/Inf vertex or zero area) over all meshes. */
  vtkIdType GetNumberOfDroppedTriangles() const;
  /** Vertex normals that were invalid and replaced by face normals. */
  vtkIdType GetNumberOfRepairedNormals() const;
  ///@}

  /** Inner cone half-angle of a spot light in degrees, on vtkLight::GetInformation(). */
  static vtkInformationDoubleKey* INNER_CONE_ANGLE();

  /** Drops all cached geometry. */
  void ClearCache();

protected:
  vtkCausticsSceneExtractor();
  ~vtkCausticsSceneExtractor() override;

  double RoughnessCutoff = 0.3;

private:
  vtkCausticsSceneExtractor(const vtkCausticsSceneExtractor&) = delete;
  void operator=(const vtkCausticsSceneExtractor&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
