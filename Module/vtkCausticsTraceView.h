/**
 * @file   vtkCausticsTraceView.h
 * @brief  The view a screen-space technique traces photons in (internal, not wrapped).
 *
 * Screen-space tracing (000 §2) finds a photon's next surface only among the
 * surfaces its layered depth image holds. Traced in the camera's own view, a
 * refractor or mirror outside the frame is not there, and photons pass it
 * unbent: the caustic then depends on how the camera frames the scene.
 *
 * The camera's view is exact when its frustum holds every specular actor: the
 * frustum is convex, so every segment from a specular surface to a visible
 * receiver, and every occluder on it, lies inside it too. Otherwise the photons
 * are traced in a fitted view: orthographic, around the box that holds the
 * specular actors and the part of the scene the camera sees. That box is convex
 * as well, so the same argument holds; the price is resolution, as the fitted
 * view spreads the same pixels over a larger region.
 *
 * The fitted view looks half-way between the camera's direction and the first
 * light's, turned 15 degrees about its up axis. A surface seen edge-on is missing
 * from a layered depth image: half-way to the light, receivers are seen from
 * their lit side even when the camera grazes them, and the turn keeps walls
 * parallel to an axis-aligned camera from being edge-on. (Measured on the pool
 * and a sweep of 25 cameras, TestCameraIndependence: along the camera's own axis
 * the pool's sunlit wall vanished, and at 10 degrees elevation the floor was
 * seen edge-on, relative L2 0.11.)
 * Landed photons are world positions, so they are splatted into the camera's view
 * either way.
 */
#ifndef vtkCausticsTraceView_h
#define vtkCausticsTraceView_h

#include "vtkRenderingCausticsModule.h" // For export macro

namespace caustics
{
struct SceneData;

/** How a screen-space technique picks the view it traces photons in. */
enum class TraceViewMode : int
{
  Automatic = 0, ///< the camera's, unless a specular actor lies outside it: then Fitted
  Camera = 1,    ///< always the camera's (the paper's; framing-dependent)
  Fitted = 2     ///< always the fitted orthographic view
};

/** A view photons are traced in: matrices (column-major, as GL wants them). */
struct TraceView
{
  float WorldToClip[16] = {};
  float ClipToWorld[16] = {};
  double ViewOrigin[4] = { 0, 0, 0, 1 }; ///< eye (w = 1) or view direction (w = 0)
  bool Fitted = false;                   ///< not the camera's own view
};

/**
 * The view to trace in for this frame's camera (scene.View), at width x height
 * pixels. `specular` is the box (xmin, xmax, ymin, ymax, zmin, zmax) of the specular
 * surfaces the photons can meet: the union of the photon frusta's LightView::focus,
 * which leaves out a mirror whose light reaches nothing in view. The fitted view
 * holds it and what the camera sees; stretched to hold such a mirror too it spread
 * its pixels over empty space (the ball lens zoomed to 12 degrees: its caustic with a
 * mirror 12 m away and 30 m away differed by 49 %). nullptr: every specular actor
 * (scene.SpecularBounds). Whether the camera's own view will do is decided on every
 * specular actor either way (FrustumHoldsSpecular()).
 */
VTKRENDERINGCAUSTICS_EXPORT TraceView ChooseTraceView(const SceneData& scene,
  TraceViewMode mode, int width, int height, const double* specular = nullptr);

/**
 * True when every vertex of every reflector and refractor lies inside the
 * camera's clip volume (scene.View): the camera's view is then exact to trace in.
 */
VTKRENDERINGCAUSTICS_EXPORT bool FrustumHoldsSpecular(const SceneData& scene);

/** True when every corner of the box lies inside the clip volume of worldToClip (row-major). */
VTKRENDERINGCAUSTICS_EXPORT bool FrustumHoldsBox(
  const double worldToClip[16], const double bounds[6]);
}

#endif
