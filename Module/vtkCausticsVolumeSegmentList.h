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
 * 2. per light, Reserve() before the trace: room for the most segments the
 *    technique's settings allow (its CPU-side bound), when this OpenGL holds them
 *    (VolumeSegmentCapacity: one warning per change of the settings when it does not;
 *    the records grow only: a steady scene allocates nothing; the count is zeroed on
 *    the GPU), BindForAppend() with the tracer's program bound
 *    (CAUSTICS_VOLUME_APPEND_*_BINDING and the capacity), then Draw() after it: the
 *    stage re-samples and draws the appended segments (their count stays on the GPU;
 *    beyond the capacity they would be dropped, which the bound rules out);
 * 3. Finish(): the Gaussian into the frame's volume layer.
 * Not a vtkObject (kept out of wrapping); the owner calls Release() with its context.
 */
#ifndef vtkCausticsVolumeSegmentList_h
#define vtkCausticsVolumeSegmentList_h

#include "vtkCausticsDeviceLimits.h" // For caustics::gl::DeviceLimits
#include "vtkCausticsGLUtilities.h"  // For caustics::gl::StorageBuffer
#include "vtkCausticsTraceView.h"   // For caustics::TraceView
#include "vtkCausticsVolumeLines.h" // For vtkCausticsVolumeLines::Segments
#include "vtkNew.h"                 // For vtkNew

#include <cstddef> // For std::size_t
#include <string>  // For std::string

class vtkCausticsCameraOpticalDepth;
class vtkCausticsGBuffer;
class vtkCausticsSceneGeometry;
class vtkCausticsShaderProgram;
class vtkObject;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

namespace caustics
{
struct SceneData;
namespace gl
{
class MediumBuffer;

/**
 * How many volume segments a technique gets room for. The tracers append on the GPU
 * and nobody reads the count back, so a list shorter than what a trace appends would
 * silently lose the volume caustic's light. A technique states the most segments its
 * settings allow in one trace (its worst case, a CPU-side bound); the capacity is that
 * bound when this OpenGL holds it: the records (vtkCausticsVolumeLines::SegmentBytes
 * each) and the stage's (pieces + 1) optical depths per segment (4 bytes each) must
 * each fit in GL_MAX_SHADER_STORAGE_BLOCK_SIZE (a larger buffer is only partly visible
 * to the shaders), and both in the memory budget (caustics::gl::QueryDeviceLimits).
 * Where the bound does not fit, the capacity is what fits and the owner warns once
 * per change of the settings, naming the knobs that lower the bound.
 */
class VTKRENDERINGCAUSTICS_EXPORT VolumeSegmentCapacity
{
public:
  struct Sizing
  {
    long long WorstCase = 0; ///< segments the settings allow in one trace
    long long Fitting = 0;   ///< segments this OpenGL holds at `Pieces` pieces each
    int Pieces = 1;          ///< optical-depth pieces per segment (vtkCausticsVolumeLines)
    int Capacity = 1;        ///< min(WorstCase, Fitting), at least 1
    bool IsShort() const { return this->Fitting < this->WorstCase; }
  };

  /** The sizing for `worstCase` segments of `pieces` pieces within `limits`. */
  static Sizing Fit(const DeviceLimits& limits, long long worstCase, int pieces);

  /**
   * The capacity for this trace on `renWin`'s context (its limits are queried once).
   * When short, `owner` warns once per change of the sizing: `bound` is the formula
   * of `worstCase` in the owner's knobs (e.g. "NumberOfPhotons x 2 x MaximumEvents"),
   * `knobs` the ones to lower. Nothing is built or queried on a frame that repeats
   * the last one's sizing.
   */
  int Choose(vtkOpenGLRenderWindow* renWin, vtkObject* owner, long long worstCase, int pieces,
    const char* bound, const char* knobs);

  /** The last Choose()'s sizing. */
  const Sizing& GetSizing() const { return this->Last; }
  /** The warning Choose() gave last (empty: none since the sizing fit). */
  const std::string& GetWarning() const { return this->Warning; }

  /** Forgets the context's limits (the owner's ReleaseGraphicsResources()). */
  void Release() { this->Queried = false; }

private:
  DeviceLimits Limits;
  bool Queried = false;
  Sizing Last;
  std::string Warning;
};

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
    vtkCausticsSceneGeometry* Geometry = nullptr; ///< its material table
    int EyeMaterial = -1; ///< the closed refractor the eye is in (FrameInputs::EyeMaterial)
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
  /** Who warns when the settings allow more segments than fit (the technique's pass). */
  void SetOwner(vtkObject* owner) { this->Owner = owner; }
  /**
   * Room for `worstCase` segments, the most the owner's settings allow in one trace
   * (`bound`: its formula; `knobs`: what lowers it), or for what this OpenGL holds
   * with a warning (VolumeSegmentCapacity), and a zero count; before a trace.
   * `subSegments` and `grid` (a density grid) give the stage's pieces per segment.
   */
  void Reserve(vtkOpenGLRenderWindow* renWin, long long worstCase, int subSegments, bool grid,
    const char* bound, const char* knobs);
  /** The last Reserve()'s sizing (worst case, what fits, the capacity). */
  const VolumeSegmentCapacity& GetCapacity() const { return this->Sizer; }
  /**
   * Segments the last trace appended (may exceed the capacity: those were dropped).
   * A GPU->CPU read-back for tests and diagnostics, never called while rendering.
   */
  unsigned int ReadAppendedCount() const;
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
  VolumeSegmentCapacity Sizer;
  vtkObject* Owner = nullptr;
  bool On = false;
  const SceneData* Scene = nullptr; // this frame's
  TraceView Camera;                 // this frame's camera: eye, inverse matrix
  int Width = 0, Height = 0;
};
}
}

#endif
