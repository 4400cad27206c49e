/**
 * @class   vtkCausticsMedium
 * @brief   A homogeneous participating medium (fog, smoke, murky water) for volume caustics.
 *
 * Single scattering with a Henyey-Greenstein phase function. Coefficients are per
 * RGB channel in 1/m (scene units are metres). Attach it to a renderer with
 * AttachTo(); every caustics pass and the reference renderer then read it from the
 * renderer's information (MEDIUM key), so a scene carries its own medium.
 */
#ifndef vtkCausticsMedium_h
#define vtkCausticsMedium_h

#include "vtkCausticsSceneModule.h" // For export macro
#include "vtkObject.h"

class vtkInformationObjectBaseKey;
class vtkRenderer;

class VTKCAUSTICSSCENE_EXPORT vtkCausticsMedium : public vtkObject
{
public:
  static vtkCausticsMedium* New();
  vtkTypeMacro(vtkCausticsMedium, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Scattering coefficient sigma_s, 1/m, per RGB channel. Default 0. Negative or
   * non-finite values are refused with an error (the old value stays).
   */
  void SetScatteringCoefficient(double r, double g, double b);
  void SetScatteringCoefficient(const double rgb[3])
  {
    this->SetScatteringCoefficient(rgb[0], rgb[1], rgb[2]);
  }
  vtkGetVector3Macro(ScatteringCoefficient, double);
  ///@}

  ///@{
  /** Absorption coefficient sigma_a, 1/m, per RGB channel. Default 0. Validated likewise. */
  void SetAbsorptionCoefficient(double r, double g, double b);
  void SetAbsorptionCoefficient(const double rgb[3])
  {
    this->SetAbsorptionCoefficient(rgb[0], rgb[1], rgb[2]);
  }
  vtkGetVector3Macro(AbsorptionCoefficient, double);
  ///@}

  ///@{
  /** Henyey-Greenstein anisotropy g in [-0.99, 0.99]. Default 0 (isotropic). */
  vtkSetClampMacro(Anisotropy, double, -0.99, 0.99);
  vtkGetMacro(Anisotropy, double);
  ///@}

  /** True when any scattering coefficient is positive. */
  bool IsScattering() const;

  /**
   * True when any extinction coefficient (scattering + absorption) is positive: the
   * medium dims light even when it scatters none (an absorption-only medium).
   */
  bool IsAttenuating() const;

  /** Attaches this medium to a renderer (replacing any other); nullptr detaches. */
  static void AttachTo(vtkRenderer* renderer, vtkCausticsMedium* medium);
  /** The medium attached to a renderer, or nullptr. */
  static vtkCausticsMedium* GetFrom(vtkRenderer* renderer);

  /** Key under which a renderer holds its medium. */
  static vtkInformationObjectBaseKey* MEDIUM();

protected:
  vtkCausticsMedium() = default;
  ~vtkCausticsMedium() override = default;

  double ScatteringCoefficient[3] = { 0, 0, 0 };
  double AbsorptionCoefficient[3] = { 0, 0, 0 };
  double Anisotropy = 0.0;

private:
  vtkCausticsMedium(const vtkCausticsMedium&) = delete;
  void operator=(const vtkCausticsMedium&) = delete;
};

#endif
