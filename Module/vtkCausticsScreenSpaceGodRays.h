/**
 * @class   vtkCausticsScreenSpaceGodRays
 * @brief   God-rays of photon segments in a homogeneous medium, as lines of radiance.
 *
 * 000_54cf099eeccf42d9.txt §3.2 in physical units, for
 * vtkCausticsScreenSpacePhotonPass:
 * 1. Begin() clears an accumulation image (RGBA32F, the view's size);
 * 2. Draw() draws every traced photon segment outside refractors (from where its
 *    line starts, clipped to the scene's bounds and the view, to its first hit or
 *    where it leaves) as a line primitive with additive blending. Each fragment
 *    stands for the length dl of segment projecting to one step of the line and
 *    adds the radiance it scatters towards the camera,
 *    L = sigma_s p(theta) flux exp(-sigma_t s) exp(-sigma_t s') dl / A in
 *    W/(m^2 sr), with p the Henyey-Greenstein phase function, s and s' the paths
 *    in the medium along the photon and to the camera, A the pixel's footprint at
 *    the fragment; fragments behind the visible surface are dropped;
 * 3. Finish() blurs the image with a normalized separable Gaussian of the
 *    settings' GodRayBlurPixels standard deviation (constant screen-space support, as the paper)
 *    into the pass's volume texture.
 * The medium fills the scene's bounding box and not the refractors, as in the
 * reference renderer (docs/reference.md).
 */
#ifndef vtkCausticsScreenSpaceGodRays_h
#define vtkCausticsScreenSpaceGodRays_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include <memory> // For std::unique_ptr

class vtkOpenGLRenderWindow;
class vtkCausticsCameraOpticalDepth;
class vtkTextureObject;
class vtkWindow;

namespace caustics
{
struct Medium;
struct ScreenSpaceSettings;
namespace gl
{
class MediumBuffer;
}
}

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsScreenSpaceGodRays : public vtkObject
{
public:
  static vtkCausticsScreenSpaceGodRays* New();
  vtkTypeMacro(vtkCausticsScreenSpaceGodRays, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /** The camera and scene the segments are seen in. */
  struct View
  {
    const float* WorldToClip = nullptr; ///< column-major
    const float* ClipToWorld = nullptr; ///< column-major
    int Width = 0, Height = 0;
    double ViewOrigin[4] = { 0, 0, 0, 1 }; ///< eye (w = 1) or view direction (w = 0)
    double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
    const caustics::Medium* Medium = nullptr;
    /** Its density grid on the GPU (null or empty: homogeneous). */
    const caustics::gl::MediumBuffer* MediumGrid = nullptr;
    /** The grid's optical depth from the camera (vtkCausticsRenderPass builds it), or null. */
    vtkCausticsCameraOpticalDepth* CameraOpticalDepth = nullptr;
    vtkTextureObject* OpaqueDepth = nullptr;     ///< window depth, receivers and reflectors
    vtkTextureObject* RefractiveDepth = nullptr; ///< window depth, refractors
  };

  /** Clears the accumulation image for a width x height view. */
  bool Begin(vtkOpenGLRenderWindow* renWin, int width, int height);

  /**
   * Draws the segments of one trace: rays, payloads (flux), screen lines and hits
   * as vtkCausticsScreenSpaceLineTracer leaves them, and the tracer's argument
   * buffer (a draw of two vertices per ray at byte 16).
   */
  bool Draw(vtkOpenGLRenderWindow* renWin, const View& view, unsigned int rayBuffer,
    unsigned int payloadBuffer, unsigned int lineBuffer, unsigned int hitBuffer,
    unsigned int argumentBuffer);

  /**
   * Blurs the accumulated radiance into `volume` (made RGBA32F of the view's size),
   * with the settings' GodRayBlurPixels standard deviation (0 copies).
   */
  bool Finish(vtkOpenGLRenderWindow* renWin, const caustics::ScreenSpaceSettings& settings,
    vtkTextureObject* volume);
#endif

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsScreenSpaceGodRays();
  ~vtkCausticsScreenSpaceGodRays() override;

private:
  vtkCausticsScreenSpaceGodRays(const vtkCausticsScreenSpaceGodRays&) = delete;
  void operator=(const vtkCausticsScreenSpaceGodRays&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
