/**
 * @class   vtkCausticsGBuffer
 * @brief   Geometry buffer of the caustics scene seen through one view (camera or light).
 *
 * Rasterizes the vtkCausticsSceneGeometry triangles of chosen roles into:
 * - Position (RGBA32F): world position, w = material index (-1 where no surface);
 * - Normal (RGBA16F): interpolated world normal as modelled (not flipped to face
 *   the viewer), w = role (caustics::Role);
 * - Albedo (RGBA16F): diffuse albedo, a = IOR;
 * - Depth (DEPTH_COMPONENT32F): window depth of the view's projection.
 * The caustics render pass keeps two for the camera (opaque roles: receivers and
 * reflectors; and refractors) and vtkCausticsLightBuffers one per light.
 * Textures are allocated on first use and when the size changes, never per frame.
 * A Render() whose inputs are those of the targets held keeps them and draws
 * nothing (ReuseUnchanged, on by default): the same window, geometry object and
 * geometry content (vtkCausticsSceneGeometry::GetContentVersion(), renewed when a
 * mesh, the layout or a material changes), world-to-clip matrix, size, role mask,
 * KeepFarthest, Albedo and the peel. ReleaseGraphicsResources() and a failed Render()
 * keep nothing.
 *
 * SetPeelBehind() makes it a second layer: of each pixel, the nearest surface behind
 * the one another G-buffer of the same view and size shows there, among the surfaces
 * that face the view (a depth peel, as vtkCausticsLayeredDepth's, but of one layer and
 * facing ones only). The caustic map uses it for receivers hidden from the light by
 * nearer receivers.
 */
#ifndef vtkCausticsGBuffer_h
#define vtkCausticsGBuffer_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include "vtkNew.h" // For vtkNew members

#include <cstdint> // For std::uint64_t
#include <vector>  // For std::vector

class vtkCausticsSceneGeometry;
class vtkCausticsShaderProgram;
class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsGBuffer : public vtkObject
{
public:
  static vtkCausticsGBuffer* New();
  vtkTypeMacro(vtkCausticsGBuffer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Renders the geometry of roles in roleMask (vtkCausticsSceneGeometry::RoleBit) with
   * a world-to-clip matrix (column-major, as GL wants it) into width x height targets.
   * Returns false if the program or framebuffer could not be made.
   */
  bool Render(vtkOpenGLRenderWindow* renWin, vtkCausticsSceneGeometry* geometry,
    const float worldToClip[16], int width, int height, int roleMask);

  ///@{
  /** The targets (valid after the first Render()). */
  vtkTextureObject* GetPositionTexture() { return this->PositionTexture; }
  vtkTextureObject* GetNormalTexture() { return this->NormalTexture; }
  vtkTextureObject* GetAlbedoTexture() { return this->AlbedoTexture; }
  vtkTextureObject* GetDepthTexture() { return this->DepthTexture; }
  vtkOpenGLFramebufferObject* GetFramebuffer() { return this->Framebuffer; }
  ///@}

  vtkGetVector2Macro(Size, int);

  ///@{
  /**
   * Keep the farthest surface of each pixel instead of the nearest (depth test
   * GREATER, depth cleared to 0): e.g. the back faces of convex refractors seen
   * from a light, without relying on triangle winding. Default off.
   */
  vtkSetMacro(KeepFarthest, bool);
  vtkGetMacro(KeepFarthest, bool);
  vtkBooleanMacro(KeepFarthest, bool);
  ///@}

  ///@{
  /**
   * Keep the targets of the last Render() when its inputs are unchanged (the list
   * in the class description). Default on.
   */
  vtkSetMacro(ReuseUnchanged, bool);
  vtkGetMacro(ReuseUnchanged, bool);
  vtkBooleanMacro(ReuseUnchanged, bool);
  ///@}

  ///@{
  /**
   * Draw the Albedo target. Off, the G-buffer holds position, normal and depth only
   * and GetAlbedoTexture() has no storage (handle 0). Only the camera's opaque
   * G-buffer's albedo is read (composite, refraction): the camera's refractive
   * G-buffer, the shadow maps (8 MB less at their default 1024 texels), the caustic
   * map's receivers, the photon buffer's layers and the distance impostors' faces
   * turn it off. Default on.
   */
  vtkSetMacro(Albedo, bool);
  vtkGetMacro(Albedo, bool);
  vtkBooleanMacro(Albedo, bool);
  ///@}

  /**
   * Peel behind `front` (a G-buffer of the same view and size, rendered first; null:
   * no peel, the default): keep, at each pixel, the nearest surface farther than
   * `front`'s there whose modelled normal faces the view. `viewOrigin` is the view's
   * eye (w = 1) or, for an orthographic view, its direction of sight (w = 0).
   * `front` must outlive the peel (ClearPeel() forgets it).
   */
  void SetPeelBehind(vtkCausticsGBuffer* front, const double viewOrigin[4]);
  void ClearPeel() { this->PeelFront = nullptr; }

  /** Whether the last Render() kept the targets it already held (nothing changed). */
  vtkGetMacro(LastRenderReused, bool);

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsGBuffer();
  ~vtkCausticsGBuffer() override;

  vtkNew<vtkTextureObject> PositionTexture;
  vtkNew<vtkTextureObject> NormalTexture;
  vtkNew<vtkTextureObject> AlbedoTexture;
  vtkNew<vtkTextureObject> DepthTexture;
  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  vtkNew<vtkCausticsShaderProgram> Program;
  int Size[2] = { 0, 0 };
  bool KeepFarthest = false;
  bool Albedo = true;
  bool ReuseUnchanged = true;
  bool LastRenderReused = false;
  vtkCausticsGBuffer* PeelFront = nullptr; // not owned
  double PeelViewOrigin[4] = { 0, 0, 0, 1 };
  std::vector<std::uint64_t> Key; // the inputs of the targets held; empty: none

private:
  vtkCausticsGBuffer(const vtkCausticsGBuffer&) = delete;
  void operator=(const vtkCausticsGBuffer&) = delete;
};

#endif
