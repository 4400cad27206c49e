/**
 * @class   vtkCausticsScreenSpaceLineTracer
 * @brief   First hits of many rays against a layered depth image, by rasterizing each ray as a
 * line.
 *
 * The screen-space ray tracing of 000_54cf099eeccf42d9.txt §2.1-2.2, for photon
 * rays (the transfer map), shadow rays or any other ray list on the GPU:
 * 1. prepare: from the ray count (a GPU counter, never read back), the indirect
 *    arguments of every following draw and dispatch;
 * 2. line setup: each ray is clipped to the scene bounds and the view frustum and
 *    projected; its line gets n_f = max(its length in pixels, MinimumLineLength)
 *    fragments;
 * 3. line tracing: each ray is drawn as a horizontal line in its own row of an
 *    offscreen target (RG32UI, RowsPerBatch rows; more rays are drawn in several
 *    batches), starting at the left column. A fragment knows where on the screen
 *    its step of the ray projects and tests every peeled layer of every object of
 *    the vtkCausticsLayeredDepth there: a surface sample P with normal N is hit
 *    when the ray meets P's tangent plane within the step (widened by Tolerance,
 *    in metres) and within two pixel footprints of P. Its own surface is ignored
 *    for two pixels after the origin. Each fragment writes its nearest hit or a
 *    miss, stamped with the batch, so the target is never cleared;
 * 4. first-hit reduction: after each batch, one work group per row takes the
 *    nearest hit of its fragments with a log-step reduction in shared memory and
 *    writes the ray's hit. Steps 3 and 4 alternate per batch and are timed as one
 *    stage, "line tracing".
 *
 * Inputs: a shader storage buffer of rays (SspRay, 32 bytes: origin xyz + state,
 * direction xyz + material index of the surface left; state 0 rays are skipped)
 * and a counter buffer whose first uint is the number of rays. Output: a buffer of
 * SspHit (32 bytes: hit position xyz + t in m, -1 for none; normal as modelled +
 * material index), one per ray. Layouts: glsl/vtkCausticsScreenSpaceCommon.glsl.
 * GL objects grow with the capacity and the view size, never per frame.
 */
#ifndef vtkCausticsScreenSpaceLineTracer_h
#define vtkCausticsScreenSpaceLineTracer_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include <memory> // For std::unique_ptr
#include <string> // For std::string

namespace caustics
{
struct ScreenSpaceSettings;
}

class vtkCausticsLayeredDepth;
class vtkCausticsTimings;
class vtkOpenGLRenderWindow;
class vtkWindow;

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsScreenSpaceLineTracer : public vtkObject
{
public:
  static vtkCausticsScreenSpaceLineTracer* New();
  vtkTypeMacro(vtkCausticsScreenSpaceLineTracer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Timings to report the stages to (see Trace()), or nullptr. Not owned. */
  void SetTimings(vtkCausticsTimings* timings);

#ifndef __VTK_WRAP__
  /** What the rays are traced against: a layered depth image and its view. */
  struct View
  {
    vtkCausticsLayeredDepth* Layers = nullptr;
    const float* WorldToClip = nullptr;      ///< column-major, the LDI's
    double Bounds[6] = { 0, 0, 0, 0, 0, 0 }; ///< scene bounds (m): rays are clipped to them
    double ViewOrigin[4] = { 0, 0, 0, 1 };   ///< eye (w = 1) or view direction (w = 0)
    /**
     * World-space intersection tolerance (m): how far beyond a fragment's step of
     * the ray a surface may lie and still be hit (the paper's epsilon, §5); the
     * settings' Tolerance() for the scene.
     */
    double Tolerance = 0.01;
  };

  /**
   * Traces up to `capacity` rays of `rayBuffer` (count in the first uint of
   * `counterBuffer`) in batches of the settings' RowsPerBatch rays (§2.1: "if the
   * number of rows in the render target is less than the number of photons, the
   * process is repeated"; capped by the GPU's largest texture), each line at least
   * MinimumLineLength fragments long (rays almost parallel to the view), naming the timed stages
   * "<stagePrefix>line setup" and
   * "<stagePrefix>line tracing" (rasterization and first-hit reduction). The hits
   * are in GetHitBuffer() afterwards. Returns false on a GL or program failure.
   */
  bool Trace(vtkOpenGLRenderWindow* renWin, const caustics::ScreenSpaceSettings& settings,
    const View& view, unsigned int rayBuffer, unsigned int counterBuffer, int capacity,
    const std::string& stagePrefix);
#endif

  /** Hits of the last Trace() (SspHit per ray). */
  unsigned int GetHitBuffer() const;
  /** Screen lines of the last Trace() (SspLine per ray: 48 bytes). */
  unsigned int GetLineBuffer() const;
  /**
   * Indirect arguments of the last Trace(): a dispatch of one thread per ray in
   * groups of 64 at byte 0, and a draw of two vertices per ray at byte 16.
   */
  unsigned int GetArgumentBuffer() const;
  /** Batches of RowsPerBatch rows the last Trace() issued (for the capacity). */
  int GetNumberOfBatches() const;

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsScreenSpaceLineTracer();
  ~vtkCausticsScreenSpaceLineTracer() override;

private:
  vtkCausticsScreenSpaceLineTracer(const vtkCausticsScreenSpaceLineTracer&) = delete;
  void operator=(const vtkCausticsScreenSpaceLineTracer&) = delete;

  struct Batch; // one Trace()'s inputs and sizes
  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
