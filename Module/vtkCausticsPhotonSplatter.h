/**
 * @class   vtkCausticsPhotonSplatter
 * @brief   Deposits photon hits on receivers as energy-normalized kernels: irradiance in W/m^2.
 *
 * The shared last stage of the photon techniques: receiver-oriented splats
 * (000_54cf099eeccf42d9.txt §3.1, Eq. 1) into any view that has a G-buffer (the
 * camera, for screen-space techniques; a light, for caustic maps as in
 * 001_7c07a484f7a872bb.txt). Unlike the papers' splats, the kernel is normalized:
 * 1. each hit (position, receiver normal, kernel radius r in m, flux in W) is drawn
 *    as a point sprite covering its disk as the view sees it; the radius is
 *    widened or narrowed to stay within [MinimumRadiusPixels, MaximumRadiusPixels]
 *    of the view, and the kernel is normalized for the radius actually used; the
 *    sprites are drawn with a guard band around the view, so that a hit just outside
 *    it still lights the pixels inside that its kernel covers;
 * 2. each covered pixel takes its surface point x from the view's G-buffer and,
 *    if x is a receiver lying on the photon's tangent plane (within
 *    PlaneTolerance radii) with a normal agreeing within NormalTolerance, adds
 *    flux x K(d), K the Epanechnikov kernel 2/(pi r^2)(1 - d^2/r^2) of the
 *    in-plane distance d. K integrates to 1 over the plane, so every fully
 *    visible photon deposits exactly its flux — no scene-dependent scale factor;
 * 3. with KeepFluxAtReceiverEnds (the default), the kernels are drawn into the
 *    splatter's own target together with their mean radius at each pixel, and each
 *    pixel is then added to the caller's target divided by the share of its own
 *    disc that lies on its receiver (glsl/vtkCausticsPhotonSplatEndsFS.glsl): within
 *    a kernel of a receiver's end (a floor meeting a wall, a table's edge) the
 *    disc holds photons only on its receiver part, and the estimate read that share
 *    of the light (0.58 of it on the pool's corner lines). The reference renderer
 *    divides its estimate the same way (docs/reference.md). A single view cannot
 *    always tell an end from an occluder: docs/accuracy.md, "Kernels at a receiver's
 *    end", says which it takes for which.
 * The caller binds the target framebuffer (RGBA32F, same size as the G-buffer);
 * the splatter blends additively into it (alpha counts contributions).
 *
 * With Reconstruction TRIANGLES (caustic triangles; Umenhoffer, Patow and
 * Szirmay-Kalos, "Caustic triangles on the GPU"), neighbouring photons of the grid
 * that landed together on one receiver form triangles, each depositing the flux of
 * the half grid cell between them over exactly the area it landed on, box-filtered
 * over the pixels (glsl/vtkCausticsPhotonTriangleCommon.glsl). It needs no radius
 * and keeps folds and focal lines sharp. Where neighbours diverge (another receiver
 * or path, a silhouette, a triangle stretched beyond TriangleStretch spacings),
 * the photons splat the share of their flux no valid triangle carried, so every
 * photon still deposits exactly its flux.
 */
#ifndef vtkCausticsPhotonSplatter_h
#define vtkCausticsPhotonSplatter_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include "vtkNew.h" // For vtkNew members

class vtkCausticsGBuffer;
class vtkCausticsShaderProgram;
class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

namespace caustics
{
struct PhotonGrid;
struct PhotonRecords;
namespace gl
{
class FullScreenTriangle;
}
}

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsPhotonSplatter : public vtkObject
{
public:
  static vtkCausticsPhotonSplatter* New();
  vtkTypeMacro(vtkCausticsPhotonSplatter, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Smallest kernel radius in target pixels. Default 1.5. */
  vtkSetClampMacro(MinimumRadiusPixels, double, 0.5, 64.0);
  vtkGetMacro(MinimumRadiusPixels, double);
  ///@}

  ///@{
  /** Largest kernel radius in target pixels (bounds the cost). Default 24. */
  vtkSetClampMacro(MaximumRadiusPixels, double, 1.0, 360.0);
  vtkGetMacro(MaximumRadiusPixels, double);
  ///@}

  ///@{
  /** Largest distance of a receiving point off the photon's tangent plane, in radii. Default 0.5.
   */
  vtkSetClampMacro(PlaneTolerance, double, 0.0, 10.0);
  vtkGetMacro(PlaneTolerance, double);
  ///@}

  ///@{
  /** Smallest cosine between the photon's and the pixel's receiver normals. Default 0.8. */
  vtkSetClampMacro(NormalTolerance, double, -1.0, 1.0);
  vtkGetMacro(NormalTolerance, double);
  ///@}

  ///@{
  /**
   * Divide each pixel's splatted irradiance by the share of its kernel's disc that
   * lies on its receiver (step 3 above), so that the light along a receiver's end is
   * not lost. Off: the kernels add straight into the caller's target, as before.
   * Default on.
   */
  vtkSetMacro(KeepFluxAtReceiverEnds, bool);
  vtkGetMacro(KeepFluxAtReceiverEnds, bool);
  vtkBooleanMacro(KeepFluxAtReceiverEnds, bool);
  ///@}

  ///@{
  /**
   * The receivers' axis-aligned bounds (xmin, xmax, ymin, ymax, zmin, zmax), or
   * nullptr (the default) where they are not known. With KeepFluxAtReceiverEnds, a
   * point of a kernel's disc outside the view is taken to lie on its receiver only
   * inside them: the image cannot show that a wall whose top is just above its border
   * ends there, the bounds can. Copied; the render passes set the frame's
   * (vtkCausticsRenderPass::FrameInputs::ReceiverBounds).
   */
  void SetReceiverBounds(const double bounds[6]);
  bool GetReceiverBounds(double bounds[6]) const;
  ///@}

  /** How landed photons become irradiance. */
  enum Reconstructions
  {
    SPLATS = 0,   ///< one kernel per photon
    TRIANGLES = 1 ///< caustic triangles between grid neighbours, splats where they diverge
  };

  ///@{
  /** SPLATS or TRIANGLES. Default SPLATS. */
  vtkSetClampMacro(Reconstruction, int, SPLATS, TRIANGLES);
  vtkGetMacro(Reconstruction, int);
  void SetReconstructionToSplats() { this->SetReconstruction(SPLATS); }
  void SetReconstructionToTriangles() { this->SetReconstruction(TRIANGLES); }
  ///@}

  ///@{
  /**
   * Longest edge of a caustic triangle, in the photons' unoccluded spacings on the
   * receiver (the spacing they would have without the specular surfaces). Longer
   * triangles span a silhouette or a change of path, and splat. Default 8.
   */
  vtkSetClampMacro(TriangleStretch, double, 1.0, 1000.0);
  vtkGetMacro(TriangleStretch, double);
  ///@}

#ifndef __VTK_WRAP__
  /**
   * Splats the photons of `grid` that landed, `landed` in the photon record layout of
   * vtkCausticsPhotonGrid.h (position.w > 0 marks one), each with its kernel radius
   * (m) from `kernelRadius` (R32F, the grid's size), into the bound framebuffer, whose
   * pixels' surfaces are in `target` (same size), seen through worldToClip
   * (column-major). Returns false if the program failed.
   */
  bool Splat(vtkOpenGLRenderWindow* renWin, const caustics::PhotonGrid& grid,
    const caustics::PhotonRecords& landed, vtkTextureObject* kernelRadius,
    vtkCausticsGBuffer* target, const float worldToClip[16]);
#endif

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsPhotonSplatter();
  ~vtkCausticsPhotonSplatter() override;

  double MinimumRadiusPixels = 1.5;
  double MaximumRadiusPixels = 24.0;
  double PlaneTolerance = 0.5;
  double NormalTolerance = 0.8;
  int Reconstruction = SPLATS;
  double TriangleStretch = 8.0;
  bool KeepFluxAtReceiverEnds = true;
  bool HasReceiverBounds = false;
  double ReceiverBounds[6] = { 0, 0, 0, 0, 0, 0 };
  vtkNew<vtkCausticsShaderProgram> Program;
  vtkNew<vtkCausticsShaderProgram> ClassifyProgram; // which triangles are valid
  vtkNew<vtkCausticsShaderProgram> TriangleProgram;
  vtkNew<vtkTextureObject> TriangleMask; // R32UI, one texel per grid cell
  unsigned int VertexArray = 0;
  // KeepFluxAtReceiverEnds: the kernels alone, the target's size.
  vtkNew<vtkTextureObject> KernelIrradiance; // RGBA32F, as the caller's target
  vtkNew<vtkTextureObject> KernelRadii;      // RG32F: sum of w, sum of w r (w: deposit luminance)
  vtkNew<vtkOpenGLFramebufferObject> KernelFramebuffer;
  vtkNew<vtkCausticsShaderProgram> EndsProgram; // adds them, divided by the disc's share
  caustics::gl::FullScreenTriangle* Triangle;

private:
  // Splat() in steps (the caller's framebuffer stays bound).
  void SetRecordUniforms(vtkCausticsShaderProgram* program, const caustics::PhotonGrid& grid,
    const caustics::PhotonRecords& landed, const int size[2], const float worldToClip[16]);
  bool ClassifyTriangles(vtkOpenGLRenderWindow* renWin, const caustics::PhotonGrid& grid,
    const caustics::PhotonRecords& landed, const int size[2], const float worldToClip[16]);
  bool DrawTriangles(vtkOpenGLRenderWindow* renWin, const caustics::PhotonGrid& grid,
    const caustics::PhotonRecords& landed, vtkCausticsGBuffer* target,
    const float worldToClip[16]);
  bool DrawSplats(vtkOpenGLRenderWindow* renWin, const caustics::PhotonGrid& grid,
    const caustics::PhotonRecords& landed, vtkTextureObject* kernelRadius,
    vtkCausticsGBuffer* target, const float worldToClip[16]);
  // KeepFluxAtReceiverEnds: DrawSplats into the splatter's own target, then AddKernels.
  bool SplatKeepingEnds(vtkOpenGLRenderWindow* renWin, const caustics::PhotonGrid& grid,
    const caustics::PhotonRecords& landed, vtkTextureObject* kernelRadius,
    vtkCausticsGBuffer* target, const float worldToClip[16]);
  bool AddKernels(
    vtkOpenGLRenderWindow* renWin, vtkCausticsGBuffer* target, const float worldToClip[16]);

  vtkCausticsPhotonSplatter(const vtkCausticsPhotonSplatter&) = delete;
  void operator=(const vtkCausticsPhotonSplatter&) = delete;
};

#endif
