/**
 * @class   caustics::gl::VolumeSegmentList
 * @brief   A tracer's photon segments appended on the GPU, drawn as line-based volume caustics.
 *
 * The tracers that follow photons in place (caustic maps: vtkCausticsPhotonBuffer's
 * trace; cascaded: glsl/vtkCausticsCascadedTraceCS.glsl) keep no path after the
 * trace, so each appends every straight piece after a specular event as it travels
 * it, with CausticsAppendVolumeSegment (glsl/vtkCausticsVolumeLinesCommon.glsl,
 * compiled in with CAUSTICS_VOLUME_SEGMENT_APPEND), and this list hands them to the
 * one volume-scattering stage, vtkCausticsVolumeLines (003_653219b45420e98f.txt
 * §4-5). Per frame:
 * 1. Begin(): with a scattering medium only (IsOn()), the stage's accumulation image
 *    is cleared and the camera's view taken; without one nothing runs and the
 *    tracers compile without the writes (SetAppendDefine());
 * 2. per light, Reset() before the trace (the records grow only: a steady scene
 *    allocates nothing; the count is zeroed on the GPU), BindForAppend() with the
 *    tracer's program bound (CAUSTICS_VOLUME_APPEND_*_BINDING and the capacity), then
 *    Draw() after it: the stage re-samples and draws the appended segments (their
 *    count stays on the GPU; beyond the capacity they are dropped);
 * 3. Finish(): the Gaussian into the frame's volume layer.
 * Not a vtkObject (kept out of wrapping); the owner calls Release() with its context.
 */
#ifndef vtkCausticsVolumeSegmentList_h
#define vtkCausticsVolumeSegmentList_h

#include "vtkCausticsGLUtilities.h" // For caustics::gl::StorageBuffer
#include "vtkCausticsTraceView.h"   // For caustics::TraceView
#include "vtkCausticsVolumeLines.h" // For vtkCausticsVolumeLines::Segments
#include "vtkNew.h"                 // For vtkNew

#include <cstddef> // For std::size_t

class vtkCausticsCameraOpticalDepth;
class vtkCausticsGBuffer;
class vtkCausticsShaderProgram;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

namespace caustics
{
struct SceneData;
namespace gl
{
class MediumBuffer;

class VTKRENDERINGCAUSTICS_EXPORT VolumeSegmentList
{
public:
  /** What the stage reads besides the segments: the frame's camera buffers and medium. */
  struct Frame
  {
    const float* WorldToClip = nullptr; ///< the camera, column-major
    const MediumBuffer* MediumGrid = nullptr;
    vtkCausticsCameraOpticalDepth* CameraOpticalDepth = nullptr;
    vtkCausticsGBuffer* Camera = nullptr;     ///< receivers and reflectors
    vtkCausticsGBuffer* Refractive = nullptr; ///< refractors
  };

  VolumeSegmentList();
  ~VolumeSegmentList();
  VolumeSegmentList(const VolumeSegmentList&) = delete;
  VolumeSegmentList& operator=(const VolumeSegmentList&) = delete;

  /** True when `scene`'s medium scatters light: the stage has something to draw. */
  static bool IsNeeded(const SceneData& scene);

  /**
   * The stage's view of a frame: `camera` (ChooseTraceView of the camera, width x
   * height) holds the inverse matrix and the eye; it and `frame` must outlive the view.
   * Every technique that draws volume lines builds its view here.
   */
  static vtkCausticsVolumeLines::View MakeView(
    const SceneData& scene, const TraceView& camera, int width, int height, const Frame& frame);

  /** Starts the frame (step 1); returns IsOn(). */
  bool Begin(vtkOpenGLRenderWindow* renWin, const SceneData& scene, int width, int height);
  /** Whether this frame draws volume caustics. */
  bool IsOn() const { return this->On; }

  /** Compiles the appends into `program` this frame, or leaves them out (before Bind()). */
  void SetAppendDefine(vtkCausticsShaderProgram* program) const;
  /** Room for `capacity` segments (at least one) and a zero count, before a trace. */
  void Reset(int capacity);
  /** Binds both buffers and sets the capacity in `program`, which must be bound. */
  void BindForAppend(vtkCausticsShaderProgram* program) const;
  /** Re-samples and draws the segments appended since Reset() (step 2). */
  bool Draw(vtkOpenGLRenderWindow* renWin, const Frame& frame, int subSegments);
  /** The Gaussian of `blurPixels` into `volume` (step 3). */
  bool Finish(vtkOpenGLRenderWindow* renWin, double blurPixels, vtkTextureObject* volume);

  /** The appended segments, as vtkCausticsVolumeLines::Draw() reads them. */
  vtkCausticsVolumeLines::Segments GetSegments() const;
  /** Bytes of the segment records and count on the GPU. */
  std::size_t Bytes() const { return this->Records.Bytes() + this->Count.Bytes(); }

  void Release(vtkWindow* win);

private:
  vtkNew<vtkCausticsVolumeLines> Lines;
  StorageBuffer Records; // CausticsVolumeSegment records
  StorageBuffer Count;   // word 0: segments appended (may exceed the capacity)
  int Capacity = 0;
  bool On = false;
  const SceneData* Scene = nullptr; // this frame's
  TraceView Camera;                 // this frame's camera: eye, inverse matrix
  int Width = 0, Height = 0;
};
}
}

#endif
