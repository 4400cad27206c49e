/**
 * @class   vtkCausticsSceneGeometry
 * @brief   The caustics scene's triangles and materials on the GPU, drawn by role.
 *
 * Every caustics stage (G-buffers, light buffers, depth peeling, photon tracing)
 * draws the same geometry with its own shaders; this class owns it:
 * 1. Upload() copies a vtkCausticsSceneExtractor snapshot into one vertex buffer
 *    (world position, normal, material index per vertex; meshes ordered by role
 *    so each role is one contiguous range) and one index buffer. Only meshes
 *    whose version changed are re-sent; buffers are reallocated only when the
 *    scene's layout (mesh count or sizes) changes.
 * 2. The material table goes to a shader storage buffer bound at
 *    CAUSTICS_MATERIAL_BINDING (layout in glsl/vtkCausticsCommon.glsl).
 * 3. Draw(roleMask) binds the vertex array and issues one indexed draw per
 *    contiguous range of the requested roles. Vertex attributes: location 0
 *    position (vec3), 1 normal (vec3), 2 material index (uint).
 * The vertex and index buffers can also be bound as shader storage buffers for
 * compute stages (GetVertexBuffer/GetIndexBuffer, 7 words per vertex).
 */
#ifndef vtkCausticsSceneGeometry_h
#define vtkCausticsSceneGeometry_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include "vtkCausticsSceneData.h" // For caustics::SceneData

#include <memory> // For std::unique_ptr

class vtkOpenGLRenderWindow;
class vtkWindow;

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsSceneGeometry : public vtkObject
{
public:
  static vtkCausticsSceneGeometry* New();
  vtkTypeMacro(vtkCausticsSceneGeometry, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Bit for a role in a role mask: RoleBit(vtkCausticsMaterial::ROLE_RECEIVER), ... */
  static constexpr int RoleBit(int role) { return 1 << role; }
  static constexpr int AllRoles = 2 | 4 | 8;
  static constexpr int SpecularRoles = 4 | 8;

#ifndef __VTK_WRAP__
  /** Sends what changed since the last upload. Returns false on a GL failure. */
  bool Upload(const caustics::SceneData& scene, vtkOpenGLRenderWindow* renWin);
#endif

  /** Binds the material table at CAUSTICS_MATERIAL_BINDING. */
  void BindMaterials();

  /** Draws all triangles whose mesh role is in roleMask (the caller binds a program). */
  void Draw(int roleMask);

  /** Triangles of the given roles. */
  vtkIdType GetNumberOfTriangles(int roleMask) const;

  ///@{
  /** GL names of the buffers, for compute stages. */
  unsigned int GetVertexBuffer() const;
  unsigned int GetIndexBuffer() const;
  unsigned int GetMaterialBuffer() const;
  ///@}

  /** Bytes uploaded by the last Upload() (0 when nothing changed). */
  vtkIdType GetLastUploadBytes() const;

  /**
   * A number renewed (unique in the process) whenever what Draw() draws or the
   * material table holds changes: an Upload() that sent a mesh, changed the layout
   * or the materials, and ReleaseGraphicsResources(). Stages that keep what they
   * drew from this geometry compare it.
   */
  vtkTypeUInt64 GetContentVersion() const;

  /** Deletes all GL objects. */
  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsSceneGeometry();
  ~vtkCausticsSceneGeometry() override;

private:
  vtkCausticsSceneGeometry(const vtkCausticsSceneGeometry&) = delete;
  void operator=(const vtkCausticsSceneGeometry&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;

  ///@{
  /**
   * Steps of Upload(): make the vertex array and buffers on first use; grow the
   * vertex and index buffers to a new layout; send the materials when they changed.
   */
  void CreateBuffers();
  void ReserveMeshBuffers(std::size_t vertices, std::size_t indices);
  void UploadMaterials(const caustics::SceneData& scene);
  ///@}
};

#endif
