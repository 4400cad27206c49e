/**
 * @class   vtkCausticsPhotonSpacing
 * @brief   Widens landed photons' kernel radii to the spacing of their grid neighbours.
 *
 * The shared stage between a transport that lands photons and the splatter
 * (vtkCausticsPhotonSplatter): a transport's own radius (a few pixel footprints, or a
 * few spacings of the unoccluded beam) fits where the specular surfaces focus the light,
 * but where they spread it photons one texel apart in the light land many spacings
 * apart, and the splats print the photon grid into the caustic as dots and rings.
 * Widen() gives each landed photon at least `spacings` times the spacing of its grid
 * neighbours on the same surface side (glsl/vtkCausticsPhotonSpacingCS.glsl), by one of
 * two estimates:
 * - AREA: the receiver area the spacing vectors along the grid's two axes span, which
 *   stays sharp along folds (the ring's nephroid). For records of one bounce
 *   (screen-space), whose neighbours took the same number of events.
 * - MEAN_DISTANCE: the mean distance to the neighbours. For records of whole paths
 *   (the impostor trace), where a neighbour may have taken another branch at a later
 *   event: the area two such photons span is no density (the glass bunny: 41.8 %
 *   relative L2 and flux 0.968 by area, against 35.8 % and 0.995 by distance,
 *   TestImpostorPhotonPass).
 * Where it finds no neighbour, the nearest photon in a 9 x 9 window of the grid gives
 * the spacing. Splats are energy-normalized, so this moves no flux, it only spreads it.
 *
 * Screen-space and the impostor technique run it. The caustic maps size their splats
 * from the beams' divergence instead (001 §3.3, Eq. 2); cascaded's photons are drawn at
 * random from the light's texels, so their grid neighbours are not the light's.
 */
#ifndef vtkCausticsPhotonSpacing_h
#define vtkCausticsPhotonSpacing_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include "vtkNew.h" // For vtkNew members

class vtkCausticsShaderProgram;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

namespace caustics
{
struct PhotonGrid;
struct PhotonRecords;
}

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsPhotonSpacing : public vtkObject
{
public:
  static vtkCausticsPhotonSpacing* New();
  vtkTypeMacro(vtkCausticsPhotonSpacing, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** How the neighbours' spacing is estimated (see the class description). */
  enum Estimates
  {
    AREA = 0,
    MEAN_DISTANCE = 1
  };

#ifndef __VTK_WRAP__
  /**
   * Widens the radii (m, R32F, the grid's size) of the photons of `grid` that landed
   * (`landed`, the record layout of vtkCausticsPhotonGrid.h) to `spacings` times their
   * neighbours' spacing by `estimate`, never narrowing one; `spacings` 0 leaves them.
   * `stretch` > 0 ignores neighbours farther than that many unoccluded spacings (the
   * photon's footprint without the specular surfaces); 0 takes any. Returns false if
   * the program failed.
   */
  bool Widen(vtkOpenGLRenderWindow* renWin, const caustics::PhotonGrid& grid,
    const caustics::PhotonRecords& landed, vtkTextureObject* radius, double spacings, int estimate,
    double stretch = 0.0);
#endif

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsPhotonSpacing();
  ~vtkCausticsPhotonSpacing() override;

private:
  vtkNew<vtkCausticsShaderProgram> Program;

  vtkCausticsPhotonSpacing(const vtkCausticsPhotonSpacing&) = delete;
  void operator=(const vtkCausticsPhotonSpacing&) = delete;
};

#endif
