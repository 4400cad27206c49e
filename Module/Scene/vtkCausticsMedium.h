/**
 * @class   vtkCausticsMedium
 * @brief   A participating medium (fog, smoke, murky water) for volume caustics.
 *
 * Single scattering with a Henyey-Greenstein phase function. Coefficients are per
 * RGB channel in 1/m per unit density (scene units are metres). Without a density
 * grid the density is 1 everywhere: a homogeneous medium with exactly these
 * coefficients. LoadDensity() makes it heterogeneous (../shared/papers/003_*.txt
 * section 5.4): the density of an OpenVDB float grid (a fog volume) times
 * DensityScale, placed by DensityMatrix, multiplies the coefficients.
 * Attach it to a renderer with AttachTo(); every caustics pass and the reference
 * renderer then read it from the renderer's information (MEDIUM key), so a scene
 * carries its own medium.
 */
#ifndef vtkCausticsMedium_h
#define vtkCausticsMedium_h

#include "vtkCausticsSceneModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::shared_ptr
#include <string> // For std::string

class vtkImageData;
class vtkInformationObjectBaseKey;
class vtkMatrix4x4;
class vtkRenderer;
namespace caustics
{
class DensityGrid;
}

class VTKCAUSTICSSCENE_EXPORT vtkCausticsMedium : public vtkObject
{
public:
  static vtkCausticsMedium* New();
  vtkTypeMacro(vtkCausticsMedium, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Scattering coefficient sigma_s, 1/m per unit density, per RGB channel. Default 0.
   * Negative or non-finite values are refused with an error (the old value stays).
   */
  void SetScatteringCoefficient(double r, double g, double b);
  void SetScatteringCoefficient(const double rgb[3])
  {
    this->SetScatteringCoefficient(rgb[0], rgb[1], rgb[2]);
  }
  vtkGetVector3Macro(ScatteringCoefficient, double);
  ///@}

  ///@{
  /**
   * Absorption coefficient sigma_a, 1/m per unit density, per RGB channel. Default 0.
   * Validated likewise.
   */
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

  ///@{
  /**
   * Whether the medium also fills the refractors its density reaches into. Off
   * (default): refractors hold none, as glass in fog or smoke; light inside them
   * loses only their own attenuation. On: the medium is there too, as murky water
   * under a water surface; its density then says where it is (a grid below the
   * surface keeps the air above clear).
   *
   * The volume lines are seen along straight camera rays up to the first surface,
   * refractors included (003 §5.3, and the reference's camera rays), so a medium
   * inside a refractor shows in the volume layer only to a camera inside it.
   */
  vtkSetMacro(FillsRefractors, bool);
  vtkGetMacro(FillsRefractors, bool);
  vtkBooleanMacro(FillsRefractors, bool);
  ///@}

  ///@{
  /**
   * Reads the density from float grid `gridName` of OpenVDB file `vdbFile` (a fog
   * volume). Returns false with one error line naming the problem, keeping the previous
   * density: missing file, not a VDB or truncated, no such grid (the file's grids are
   * listed), a grid of another type than float (named), a level set, an empty grid.
   * Negative and NaN voxels are set to 0 with one warning giving their count.
   * RemoveDensity() makes the medium homogeneous again (density 1 everywhere).
   */
  bool LoadDensity(const char* vdbFile, const char* gridName = "density");
  /**
   * Takes the density from a volume VTK already holds: the first component of point
   * array `arrayName` of `image` (null: its active scalars), one value per point, placed
   * by the image's origin, spacing and direction (then by DensityMatrix, like a file's
   * grid). Zero points are left out of the sparse grid, so a mostly empty volume costs
   * what its content does. Returns false with one error line, keeping the previous
   * density: no image or no such array, a non-numeric array, an image with no non-zero
   * value, more than 2^28 points. Negative and NaN values become 0, with one warning.
   */
  bool SetDensityData(vtkImageData* image, const char* arrayName = nullptr);
  void RemoveDensity();
  /** True once a density grid is loaded. */
  bool HasDensity() const;
  /**
   * The loaded file and grid names; empty without a density grid. A density from
   * SetDensityData() has no file name and "vtkImageData:<array>" as its grid name.
   */
  const char* GetDensityFileName() const;
  const char* GetDensityGridName() const;
  /** Why the last LoadDensity() failed (the error's line); empty after a success. */
  const char* GetLastError() const { return this->LastError.c_str(); }
  ///@}

  ///@{
  /**
   * Factor on the grid's densities (unitless). Default 1. Negative, non-finite or
   * larger than 1e6 (surely a unit mistake) is refused with an error (the old value stays).
   */
  void SetDensityScale(double scale);
  vtkGetMacro(DensityScale, double);
  ///@}

  ///@{
  /**
   * Placement of the grid in the world, like an actor's user matrix: applied after the
   * file's own index-to-world transform. Default nullptr (identity). Must be affine and
   * invertible (else ignored, with a warning). Changes to the matrix count as changes
   * to the medium (GetMTime()).
   */
  void SetDensityMatrix(vtkMatrix4x4* matrix);
  vtkGetObjectMacro(DensityMatrix, vtkMatrix4x4);
  ///@}

#ifndef __VTK_WRAP__
  /**
   * The density grid placed by DensityMatrix and scaled by DensityScale (shared with the
   * loaded grid's voxels); null without a density grid. Scene snapshots hold it.
   */
  std::shared_ptr<const caustics::DensityGrid> GetDensity();
#endif

  /** Includes the density matrix's modification time. */
  vtkMTimeType GetMTime() override;

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
  vtkCausticsMedium();
  ~vtkCausticsMedium() override;

  double ScatteringCoefficient[3] = { 0, 0, 0 };
  double AbsorptionCoefficient[3] = { 0, 0, 0 };
  double Anisotropy = 0.0;
  bool FillsRefractors = false;
  double DensityScale = 1.0;
  vtkMatrix4x4* DensityMatrix = nullptr;
  std::shared_ptr<const caustics::DensityGrid> LoadedDensity; // as read, unplaced
  std::shared_ptr<const caustics::DensityGrid> PlacedDensity; // GetDensity()'s, kept while valid
  vtkMTimeType PlacedTime = 0;                                // GetMTime() it was placed at
  std::string LastError;

private:
  /** Sets one of the per-channel coefficients (1/m) after checking it. */
  void SetCoefficient(const char* what, double (&coefficient)[3], double r, double g, double b);

  vtkCausticsMedium(const vtkCausticsMedium&) = delete;
  void operator=(const vtkCausticsMedium&) = delete;
};

#endif
