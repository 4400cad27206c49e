/**
 * @class   vtkCausticsVolumeLines
 * @brief   Line-based volume caustics: photon segments drawn as lines of in-scattered radiance.
 *
 * 003_653219b45420e98f.txt §4-5 (Eq. 3: a sum over light-ray segments of
 * tau(v, x) sigma_s(x) p L_in(x) dx), in physical units, on the photon paths of any
 * technique. A technique hands its segments after specular events in one neutral
 * layout (CausticsVolumeSegment in glsl/vtkCausticsVolumeLinesCommon.glsl: origin,
 * unit direction, the drawn part [t0, t1] in m, the flux at the origin in W) and a
 * count that lives on the GPU; then
 * 1. Begin() clears an accumulation image (RGBA32F, the view's size);
 * 2. Draw(), per batch of segments:
 *    a. re-sampling (compute, §5.2): each segment is split into `subSegments` equal
 *       pieces and the optical depth along the photon, from its origin, is
 *       integrated ONCE per segment, cumulatively, and stored at every piece's
 *       vertex (a heterogeneous medium's NanoVDB density is marched; a homogeneous
 *       medium needs one piece and the closed form); the same pass writes the
 *       indirect draw of the lines;
 *    b. light-ray blending (§5.2, Eq. 3): every segment is drawn whole as a line
 *       with additive blending (pieces shorter than a pixel would be lost to the
 *       rasterization rules). Each fragment stands for the length dl of segment
 *       that projects to one step of its line and adds
 *       L = sigma_s(x) p(theta) flux exp(-sigma_t tau_light) T_camera dl / A in
 *       W/(m^2 sr): p the Henyey-Greenstein phase function, tau_light interpolated
 *       between the vertices of the fragment's piece, T_camera one fetch of the
 *       camera optical-depth volume (vtkCausticsCameraOpticalDepth; without it,
 *       the march to the camera), A the pixel's footprint at the fragment.
 *       Fragments behind the visible surface are dropped (§5.3);
 * 3. Finish() filters the image with a normalized separable Gaussian of
 *    `blurPixels` standard deviation into the frame's volume texture: the paper's
 *    normalized Gaussian re-distribution of the irregular line samples (Fig. 5),
 *    here of constant screen-space support, which also fills lines that are too
 *    sparse on screen; its weights are normalized over the taps inside the image
 *    (lines outside the view are not drawn: unknown there, not dark).
 * The medium fills the scene's bounding box and not the refractors, as in the
 * reference renderer (docs/reference.md). Steps, knobs and measured figures:
 * docs/technique-volume-caustics.md.
 */
#ifndef vtkCausticsVolumeLines_h
#define vtkCausticsVolumeLines_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include <memory> // For std::unique_ptr

class vtkOpenGLRenderWindow;
class vtkCausticsCameraOpticalDepth;
class vtkCausticsSceneGeometry;
class vtkTextureObject;
class vtkWindow;

namespace caustics
{
struct Medium;
namespace gl
{
class MediumBuffer;
}
}

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsVolumeLines : public vtkObject
{
public:
  static vtkCausticsVolumeLines* New();
  vtkTypeMacro(vtkCausticsVolumeLines, vtkObject);
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
    /**
     * The material table: the absorption of the refractors that pieces lie in when
     * the medium fills them, and of the eye's refractor (EyeMaterial, -1: none).
     */
    vtkCausticsSceneGeometry* Geometry = nullptr;
    int EyeMaterial = -1;
  };

  /**
   * A technique's segments on the GPU: `Buffer` holds `Capacity` CausticsVolumeSegment
   * records (48 bytes each); how many are valid is the uint at byte 4 x `CountWord` of
   * `CountBuffer` (written by the GPU; never read back). A segment with t1 <= t0 draws
   * nothing.
   */
  struct Segments
  {
    unsigned int Buffer = 0;
    unsigned int CountBuffer = 0;
    unsigned int CountWord = 0;
    int Capacity = 0;
  };

  /** Bytes of one CausticsVolumeSegment record. */
  static constexpr int SegmentBytes = 48;

  /**
   * The pieces Draw() cuts a segment into: `subSegments` in [1, 64] in a density grid
   * (`grid`), else one (0, the march, also allocates one). Draw() holds (pieces + 1)
   * optical depths of 4 bytes per segment of the Segments' capacity.
   */
  static int PiecesFor(bool grid, int subSegments);

  /** Clears the accumulation image for a width x height view. */
  bool Begin(vtkOpenGLRenderWindow* renWin, int width, int height);

  /**
   * Re-samples and draws one batch of segments (steps 2a-b). `subSegments` (>= 1):
   * the pieces of a segment in a heterogeneous medium, whose fragments interpolate the
   * light-side optical depth linearly between their vertices; a homogeneous medium
   * draws one (its optical depth is linear along the segment). 0: a comparison mode
   * (the former god-rays) that marches the density per fragment instead.
   */
  bool Draw(
    vtkOpenGLRenderWindow* renWin, const View& view, const Segments& segments, int subSegments);

  /**
   * Filters the accumulated radiance into `volume` (made RGBA32F of the view's size)
   * with a normalized Gaussian of `blurPixels` standard deviation (0 copies).
   */
  bool Finish(vtkOpenGLRenderWindow* renWin, double blurPixels, vtkTextureObject* volume);
#endif

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsVolumeLines();
  ~vtkCausticsVolumeLines() override;

private:
  vtkCausticsVolumeLines(const vtkCausticsVolumeLines&) = delete;
  void operator=(const vtkCausticsVolumeLines&) = delete;

  bool Resample(
    vtkOpenGLRenderWindow* renWin, const View& view, const Segments& segments, int pieces);
  bool DrawLines(
    vtkOpenGLRenderWindow* renWin, const View& view, const Segments& segments, int pieces);

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
