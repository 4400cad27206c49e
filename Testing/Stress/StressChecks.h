/**
 * What the caustics stress driver checks after each frame (CausticsStress.cxx).
 *
 * - Finite: every output layer the frame made (final colour, caustic, direct and
 *   volume irradiance or radiance, technique colour, camera G-buffers, per-light
 *   buffers) holds no NaN or Inf, and the caustic irradiance is >= 0.
 * - Energy: the caustic flux on the visible receivers, sum over receiver pixels of
 *   E x A (A: receiver area the pixel sees, from its corner rays on the surface's
 *   tangent plane, as the CPU reference's PixelArea), never exceeds what the lights
 *   send into the specular objects. The bound per light and channel is the flux
 *   into the specular objects' bounding sphere (centre and half-diagonal of
 *   SceneData::SpecularBounds), its radius widened by 3/N (N = LightBufferResolution:
 *   a light-buffer texel across that sphere, so a texel only partly on the sphere
 *   keeps its whole flux): directional E pi R^2, point or spot I x the sphere's solid
 *   angle (4 pi from inside it). Fresnel weights, absorption and media only take
 *   from it. The pixel sum is a quadrature of kernels at least 1.5 pixels wide, so
 *   the test allows it 10 % above the bound.
 * - Errors: any error message makes the frame a failure unless it is one line and
 *   the frame produced no caustic output (a clear refusal).
 */
#ifndef StressChecks_h
#define StressChecks_h

#include <string>
#include <vector>

class vtkCausticsRenderPass;

namespace stress
{
/** Caustic flux and its bound (W per channel). */
struct Energy
{
  double Flux[3] = { 0, 0, 0 };
  double Bound[3] = { 0, 0, 0 };
  /** Largest flux / bound over the channels (0 when nothing is lit). */
  double Ratio() const;
};

/**
 * Names of layers of the last frame holding NaN/Inf (or a negative caustic).
 * Without `vtkColour`, the layers that carry VTK's own shading (FinalColor,
 * TechniqueColor) are not read: for scenes where VTK is given non-finite input.
 */
std::vector<std::string> NonFiniteLayers(vtkCausticsRenderPass* pass, bool vtkColour);

/** The last frame's caustic flux on visible receivers and the bound above. */
Energy MeasureEnergy(vtkCausticsRenderPass* pass);

/** Allowed flux / bound (quadrature slack, see above). */
constexpr double EnergySlack = 1.1;

/** Captures VTK's error and warning messages (installed as VTK's output window). */
struct Messages
{
  /** Installs the capture (once per process). */
  static void Install();
  /** Error messages since the last Clear(), reduced to the text after "(0x...): ". */
  static const std::vector<std::string>& Errors();
  static int Warnings();
  static void Clear();
  /** While off, messages are dropped (ReadBuffer of a layer the frame lacks). */
  static void SetListening(bool on);
};
}

#endif
