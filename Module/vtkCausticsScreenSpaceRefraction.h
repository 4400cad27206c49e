/**
 * @class   vtkCausticsScreenSpaceRefraction
 * @brief   Refraction of viewing rays through refractors, traced in screen space.
 *
 * 000_54cf099eeccf42d9.txt §4, for vtkCausticsScreenSpacePhotonPass. One
 * full-screen pass over the pixels whose visible surface is a refractor (and that
 * VTK drew there):
 * 1. the viewing ray is split at the refractor's first layer with the exact
 *    dielectric Fresnel reflectance; the reflected part is marched outside;
 * 2. the refracted part is marched through the refractor's own layered depth image
 *    one pixel per step, with one lookup per layer (the paper's monotonic-layer
 *    assumption: the n-th intersection lies in the (n+1)-th layer) until it passes
 *    the next layer (or comes in front of the current one), where it is refracted
 *    out (Fresnel-weighted; total internal reflection keeps it inside), up to
 *    MaximumEvents interfaces, with Beer-Lambert absorption inside;
 * 3. outside, the ray ends at the first surface of the camera's opaque G-buffer it
 *    passes (what the camera would see without the refractor, the paper's Fig. 10
 *    approximation), re-enters a further layer of the refractor, or leaves the
 *    scene or the view: the background colour (the environment);
 * 4. a surface's colour is the one the composite gives it where VTK shows it,
 *    else albedo x (direct + caustic irradiance), VTK's display units.
 * With distance impostors (Inputs::Impostors, 004_4da4b323b51d1415.txt §2-4) the
 * rays after the first surface are traced against vtkCausticsDistanceImpostors'
 * cube maps instead (Method 1), or where the march leaves the view or the scene
 * (Method 2); an impostor hit on a surface the camera does not show takes the
 * map's colour (albedo x unshadowed direct irradiance, no caustic).
 * The output colour has alpha 1 where it replaces VTK's colour, 0 elsewhere.
 * Only the pixels of the screen rectangle the reflectors' and refractors' bounds
 * (Inputs::SpecularBounds) project to are traced, the rest cleared: every pixel the
 * pass writes shows a point inside those bounds.
 */
#ifndef vtkCausticsScreenSpaceRefraction_h
#define vtkCausticsScreenSpaceRefraction_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include <memory> // For std::unique_ptr

class vtkCausticsDistanceImpostors;
class vtkCausticsGBuffer;
class vtkCausticsLayeredDepth;
class vtkCausticsSceneGeometry;
class vtkCausticsSpecularHierarchy;
namespace caustics
{
struct SceneData;
}
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsScreenSpaceRefraction : public vtkObject
{
public:
  static vtkCausticsScreenSpaceRefraction* New();
  vtkTypeMacro(vtkCausticsScreenSpaceRefraction, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Most refractor interfaces a viewing ray crosses after its entry, in [1, 16]. Default 8 (the render pass sets it to its RefractionEvents). */
  vtkSetClampMacro(MaximumEvents, int, 1, 16);
  vtkGetMacro(MaximumEvents, int);
  ///@}

  enum
  {
    EXACT_OFF = 0,
    EXACT_ON = 1,
    EXACT_AUTOMATIC = 2
  };

  ///@{
  /**
   * Whether the camera view traces the glass and mirror triangles themselves (a
   * bounding volume hierarchy, vtkCausticsSpecularHierarchy) for the interfaces its
   * paths cross, instead of finding them in the refractors' layered depth image and
   * the distance impostors' refractor maps. What lies around them still comes from
   * the screen and the impostors. The images lose concave glass (the bunny: relative
   * L2 71 % against 58 %), open surfaces such as water and mirror walls, and the face
   * that tells a ray's side of a coarse mesh; for convex solids they hold everything,
   * and tracing costs time (the ball lens at 512²: about 50 % more for this stage).
   * EXACT_AUTOMATIC (the default) traces where some reflector or refractor is not a
   * convex solid (vtkCausticsSpecularHierarchy::IsConvex).
   */
  vtkSetClampMacro(ExactSpecularGeometry, int, EXACT_OFF, EXACT_AUTOMATIC);
  vtkGetMacro(ExactSpecularGeometry, int);
  ///@}

  /** Whether the last Render() traced the specular triangles. */
  vtkGetMacro(TracedSpecularGeometry, bool);

#ifndef __VTK_WRAP__
  /**
   * Whether Render() will trace `scene`'s specular triangles (ExactSpecularGeometry);
   * brings the hierarchy up to date (the context must be current). Then the march
   * consults no refractor layer beyond the first.
   */
  bool WillTraceSpecularGeometry(const caustics::SceneData& scene);
#endif

  /** The hierarchy the camera view traces (rebuilt only when glass or mirrors change). */
  vtkCausticsSpecularHierarchy* GetSpecularHierarchy();

  ///@{
  /**
   * Whether a viewing ray that crosses glass or water also follows the part Fresnel
   * reflects there (one deferred branch: the internal reflections inside glass).
   * Default on: without it the ball lens's glass seen from beside or below is 14 to
   * 34 % too dark (relative L2 34 % against 12 % from beside); it doubles the stage's
   * time on the ball lens at 512² on llvmpipe (115 -> 229 ms; docs/accuracy.md). A
   * uniform: switching it recompiles nothing.
   */
  vtkSetMacro(InternalReflections, bool);
  vtkGetMacro(InternalReflections, bool);
  vtkBooleanMacro(InternalReflections, bool);
  ///@}

#ifndef __VTK_WRAP__
  /** Everything the pass reads. */
  struct Inputs
  {
    vtkCausticsLayeredDepth* RefractorLayers = nullptr; ///< refractors only, one object
    vtkCausticsGBuffer* Opaque = nullptr;               ///< the camera's opaque G-buffer
    vtkCausticsSceneGeometry* Geometry = nullptr;       ///< for the material table
    const caustics::SceneData* Scene = nullptr; ///< its glass and mirrors, traced exactly
    vtkTextureObject* DelegateColor = nullptr;
    vtkTextureObject* DelegateDepth = nullptr;
    vtkTextureObject* CausticIrradiance = nullptr;
    vtkTextureObject* DirectIrradiance = nullptr; ///< may be nullptr (taken as 0)
    /** VTK's shading that specular actors block (per unit albedo), taken off VTK's colour
     * as the composite does; nullptr: none. */
    vtkTextureObject* LostShading = nullptr;
    const float* WorldToClip = nullptr;           ///< column-major
    int Width = 0, Height = 0;
    double ViewOrigin[4] = { 0, 0, 0, 1 }; ///< eye (w = 1) or view direction (w = 0)
    /** The material of the refractor the eye is in (a camera inside glass), -1: air. */
    int EyeMaterial = -1;
    double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
    /** Reflectors' and refractors' bounds (SceneData::SpecularBounds): the pixels
     * traced are those of their screen rectangle. */
    double SpecularBounds[6] = { 0, 0, 0, 0, 0, 0 };
    double Background[3] = { 0, 0, 0 };
    double Tolerance = 0.0; ///< m
    /** Rays after the first surface: 0 screen-space march, 1 distance impostors, 2 the
     * march then the impostors where it leaves the view or the scene. */
    int Method = 0;
    vtkCausticsDistanceImpostors* Impostors = nullptr; ///< updated; needed by methods 1, 2
  };

  /** Writes the colours into `target` (made RGBA32F, Width x Height). */
  bool Render(vtkOpenGLRenderWindow* renWin, const Inputs& inputs, vtkTextureObject* target);

  /**
   * The pixels (x, y, width, height) that the box `bounds` (xmin, xmax, ymin, ymax,
   * zmin, zmax) covers through `worldToClip` (column-major) in a width x height
   * image, with a pixel of margin, clamped to the image; the whole image when a
   * corner is not in front of the eye, none (zero size) for an empty box or one
   * beside the view.
   */
  static void ScreenRectangle(
    const float worldToClip[16], const double bounds[6], int width, int height, int rect[4]);
#endif

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsScreenSpaceRefraction();
  ~vtkCausticsScreenSpaceRefraction() override;

  int MaximumEvents = 8;
  bool InternalReflections = true;
  int ExactSpecularGeometry = EXACT_AUTOMATIC;
  bool TracedSpecularGeometry = false;

private:
  vtkCausticsScreenSpaceRefraction(const vtkCausticsScreenSpaceRefraction&) = delete;
  void operator=(const vtkCausticsScreenSpaceRefraction&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
