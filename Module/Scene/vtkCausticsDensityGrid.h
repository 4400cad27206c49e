/**
 * @file   vtkCausticsDensityGrid.h
 * @brief  caustics::DensityGrid: the density of a heterogeneous medium, read from OpenVDB.
 *
 * A float grid (a fog volume: density >= 0, 0 outside) read from a .vdb file, placed in
 * the world and scaled, that the CPU reference samples and that the GPU passes will
 * upload as NanoVDB. OpenVDB stays inside vtkCausticsDensityGrid.cxx: this header names
 * none of its types, so that users of the scene module do not need OpenVDB's headers.
 *
 * Values are immutable once loaded; Placed() gives a copy sharing the voxels with another
 * placement and scale, so snapshots (caustics::Medium) hold it by shared_ptr cheaply.
 *
 * Paper: ../shared/papers/003_*.txt, section 5.4 (heterogeneous media).
 */
#ifndef vtkCausticsDensityGrid_h
#define vtkCausticsDensityGrid_h

#include "vtkCausticsSceneData.h"   // For caustics::Vec3
#include "vtkCausticsSceneModule.h" // For export macro

#include <cstddef> // For std::size_t
#include <cstdint> // For std::uint64_t
#include <memory>  // For std::shared_ptr
#include <string>  // For std::string

namespace caustics
{
class VTKCAUSTICSSCENE_EXPORT DensityGrid
{
public:
  /** Density scale above which a value is taken for a mistake (densities are O(1)). */
  static constexpr double MaximumScale = 1e6;

  /**
   * Reads float grid `gridName` of `file`. On failure returns null with `error` set to
   * one line naming the problem: missing or unreadable file, not a VDB or truncated,
   * no such grid (the file's grids are listed), a grid that is not a float scalar grid
   * (its type named), a level set, or a grid with no active voxel. Negative and NaN
   * values are set to 0 (a density cannot be negative); `warning` then says how many.
   */
  static std::shared_ptr<const DensityGrid> Load(
    const std::string& file, const std::string& gridName, std::string& error, std::string& warning);

  /** Most voxels a dense density may have (FromDense): 2^28, 1 GiB of floats. */
  static constexpr double MaximumDenseVoxels = 268435456.0;

  /**
   * A sparse grid made from dense values (e.g. a vtkImageData's point scalars):
   * `values` has dimensions[0] x [1] x [2] floats, x fastest; voxel (i, j, k) sits at
   * indexToWorld (row-major 4x4, column vectors, as vtkMatrix4x4; null: identity) times
   * (i, j, k, 1). Zero voxels stay inactive (cost nothing on the GPU). Fails with one
   * line on: no values, a dimension < 1, more than MaximumDenseVoxels, a non-finite or
   * non-invertible affine transform, no non-zero value. Negative and NaN values are
   * set to 0, counted in `warning`, as Load() does. GetFileName() is empty; `name`
   * stands in for the grid's name.
   */
  static std::shared_ptr<const DensityGrid> FromDense(const float* values, const int dimensions[3],
    const double indexToWorld[16], const std::string& name, std::string& error,
    std::string& warning);

  /**
   * This grid with another placement: `matrix` (row-major 4x4, as vtkMatrix4x4; null:
   * identity) applied after the file's own index-to-world transform, and densities
   * multiplied by `scale`. Shares the voxels.
   */
  std::shared_ptr<const DensityGrid> Placed(const double matrix[16], double scale) const;

  /** Density x scale at a world point: trilinear (openvdb::tools::BoxSampler), 0 outside. */
  double Sample(const Vec3& world) const;

  /**
   * World box (xmin, xmax, ymin, ymax, zmin, zmax) outside which the density is 0: the
   * active voxels' bounding box grown by the interpolation's one-voxel reach, placed.
   */
  void GetWorldBounds(double bounds[6]) const;

  /** Largest density x scale anywhere: a majorant for tracking. */
  double GetMajorant() const;
  /**
   * A lower bound of density x scale over a world box (xmin, xmax, ...): the smallest
   * active value when the box lies inside the active voxels' centres and every voxel
   * there is active (a dense block, as a fog volume covering the scene is), else 0.
   * Tracking handles this part of the extinction in closed form.
   */
  double GetMinimum(const double worldBox[6]) const;
  /** Mean density x scale over the active voxels. */
  double GetMeanDensity() const;
  double GetScale() const;
  /** The placement matrix, row-major (identity when none was given). */
  const double* GetMatrix() const;

  /** Hash of the voxels' coordinates and values and the file's transform (not the placement). */
  std::uint64_t GetContentHash() const;

  ///@{
  /**
   * Memory of the grid as NanoVDB (what the GPU will upload) and as a dense float
   * array over the active voxels' bounding box, in bytes.
   */
  std::size_t GetNanoVDBBytes() const;
  std::size_t GetDenseBytes() const;
  ///@}
  /** The NanoVDB grid, GetNanoVDBBytes() long, for upload to the GPU. */
  const void* GetNanoVDBData() const;
  /**
   * World to the grid's index space (voxel centres at integers), row-major: the inverse
   * of the placement matrix, then the file's own transform (linear: affine). The GPU
   * samples the NanoVDB grid with it.
   */
  void GetWorldToIndex(double matrix[16]) const;

  std::int64_t GetActiveVoxelCount() const;
  const std::string& GetFileName() const;
  const std::string& GetGridName() const;

  ~DensityGrid();

private:
  DensityGrid();
  // Checks and clears a float grid (an openvdb::FloatGrid::Ptr, kept out of this header)
  // and builds the statistics and the NanoVDB copy: the common end of Load and FromDense.
  static std::shared_ptr<const DensityGrid> FromGrid(std::shared_ptr<void> floatGrid,
    const std::string& fileName, const std::string& gridName, const std::string& named,
    std::string& error, std::string& warning);
  struct Voxels;                        // the OpenVDB and NanoVDB grids and their statistics
  std::shared_ptr<const Voxels> Shared; // shared by every placement of the same load
  double Matrix[16];
  double InverseMatrix[16];
  double Scale = 1.0;
};
}

#endif
