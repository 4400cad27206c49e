/**
 * @class   vtkCausticsPhotonBufferHierarchy
 * @brief   Hierarchical gather of a photon buffer into caustic map splats (GPU lists).
 *
 * The second pass of hierarchical caustic mapping (001_7c07a484f7a872bb.txt §3),
 * on compute shaders with indirect dispatch:
 * 1. Validity mipmap (§3.1): node (x, y) of level k covers 2^k x 2^k photons and
 *    stores how many are valid (landed on a receiver), the bounding box of the
 *    caustic map texels they land in, and their mean flux and hit position over
 *    the 4^k slots.
 *    Levels 1..S are built, S the first level at most TraversalStartResolution
 *    nodes wide (16: the paper's 16^2 start).
 * 2. Traversal (§3.1), breadth first from level S down: a node with no valid
 *    photon discards its subtree; otherwise its four children are appended to
 *    the work list of level k - 1, whose length sets the indirect dispatch of that
 *    level. Level 0 is the photons themselves.
 * 3. Clustering (§3.2, ClusterMode): a node whose 4^k photons are all valid and
 *    all land in one caustic map texel (DoChildrenConverge) becomes one splat at
 *    their centroid with the intensity modifier 4^k applied to the node's mean
 *    flux, i.e. the exact total of its photons. Tested at the last
 *    level only (k = 1) or at all levels.
 * 4. TransformPhotons (§3.3): the kernel radius from the beam's divergence, Eq. 2
 *    with the max-distance approximation: r_i = sqrt(A_i (N.D_i) / (omega_i d_i^2))
 *    with A_i = (largest distance to the adjacent valid photons)^2, times the
 *    unoccluded beam's footprint radius and SplatScale; with SPLAT_VARYING_MULTIRES
 *    the caustic map level trunc(log2(max(1, D_i / SplatSizeThreshold))) for the
 *    diameter D_i in finest-level pixels. Splats needing level 4 or coarser are
 *    splatted into level 3 or, with DropCoarseSplats (the paper's choice),
 *    dropped; their flux is counted either way. SPLAT_CONSTANT is the paper's
 *    baseline (ConstantSplatRadius pixels), SPLAT_VARYING_SINGLE the Eq. 2 radius
 *    in the finest level only.
 * 5. The result: per caustic map level, a list of splat entries (photon index and
 *    cluster level) and glDrawArraysIndirect arguments, for vtkCausticsCausticMap.
 * GATHER_FLAT (Wyman & Davis 2006, improved as §4 says: photons fetched by index,
 * nothing copied) transforms every photon of the buffer instead of steps 1-3.
 *
 * Why compute shaders and not the paper's geometry shaders with transform
 * feedback: the traversal is a stream compaction whose output size is known only
 * on the GPU. Compute shaders with SSBO atomics and glDispatchComputeIndirect (GL
 * 4.3) express it directly and run on Mesa's llvmpipe and desktop GPUs alike; the
 * transform-feedback route needs one feedback buffer per level plus
 * glDrawTransformFeedback or a query read back per level, and geometry shaders
 * that emit variable output are slow on both.
 *
 * The knobs named above (ClusterMode, SplatScale, ...) are members of
 * caustics::CausticMapSettings, which Gather() takes by const reference.
 *
 * GPU counters (items processed per level, valid photons, clusters, splats per
 * level, coarse splats and flux per level) are kept every frame in the control
 * buffer and read back only by GetCounters(), which stalls.
 */
#ifndef vtkCausticsPhotonBufferHierarchy_h
#define vtkCausticsPhotonBufferHierarchy_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include "vtkNew.h" // For vtkNew members

#include <memory> // For std::unique_ptr
#include <vector> // For std::vector

class vtkCausticsShaderProgram;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

namespace caustics
{
struct Camera;
struct CausticMapSettings;
struct LightView;
struct PhotonGrid;
struct PhotonRecords;
namespace gl
{
class StorageBuffer;
}
}

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsPhotonBufferHierarchy : public vtkObject
{
public:
  static vtkCausticsPhotonBufferHierarchy* New();
  vtkTypeMacro(vtkCausticsPhotonBufferHierarchy, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /**
   * Gathers the photons of `grid` that landed (`landed`, in the photon record layout of
   * vtkCausticsPhotonGrid.h), into splat lists for a
   * caustic map seen through `mapView` (CausticMapResolution texels per side at the
   * finest level) as `settings` says (the gather, cluster and splat modes and
   * sizes); `lightType` is caustics::Light::Type; `camera` (may be null: no camera
   * floor) is the view MinimumCameraSplatRadius refers to. Returns false if a
   * program failed.
   */
  bool Gather(vtkOpenGLRenderWindow* renWin, const caustics::CausticMapSettings& settings,
    const caustics::PhotonGrid& grid, const caustics::PhotonRecords& landed,
    const caustics::LightView& mapView, int lightType, const caustics::Camera* camera);

  /** GPU counters of the last Gather(); flux in W summed over RGB. */
  struct Counters
  {
    int StartLevel = 0;                           ///< S (0 for the flat gather)
    long long Processed[16] = { 0 };              ///< items processed per level (0 = photons)
    long long TotalProcessed = 0;                 ///< sum over the levels
    long long Valid = 0;                          ///< valid photons in the photon buffer
    long long Clusters = 0;                       ///< clusters splatted as one
    long long ClusteredPhotons = 0;               ///< photons inside them
    long long Splats[4] = { 0, 0, 0, 0 };         ///< splats per caustic map level
    long long CoarseSplats = 0;                   ///< splats that needed level >= 4
    double SplatFlux[4] = { 0.0, 0.0, 0.0, 0.0 }; ///< flux splatted per level
    double CoarseFlux = 0.0;                      ///< flux of the coarse splats
    /** Flux of the coarse splats over all gathered flux (dropped or not). */
    double CoarseFluxFraction = 0.0;
    /** Flux dropped (settings' DropCoarseSplats) over all gathered flux; 0 when kept. */
    double DroppedFluxFraction = 0.0;
  };

  /** Reads the counters of the last Gather() (stalls the GPU). False if none. */
  bool GetCounters(Counters& counters);

  ///@{
  /** GPU lists for vtkCausticsCausticMap (valid after Gather()). */
  const caustics::gl::StorageBuffer& GetControlBuffer() const;
  const caustics::gl::StorageBuffer& GetSplatBuffer() const;
  const caustics::gl::StorageBuffer& GetNodeBuffer() const;
  /** Entries reserved per caustic map level in the splat buffer. */
  unsigned int GetSplatRegion() const
  {
    return this->SplatRegion;
  }
  /** First node of mipmap level k >= 1 in the node buffer, and nodes per row. */
  unsigned int GetNodeOffset(int k) const;
  int GetNodeRowLength(int k) const;
  /** Byte offset of caustic map level j's glDrawArraysIndirect arguments. */
  static unsigned int GetDrawArgumentsOffset(int j);
  ///@}
#endif

  /** Kernel radius (m) of each photon transformed by the last Gather() (R32F). */
  vtkTextureObject* GetSplatRadiusTexture()
  {
    return this->SplatRadius;
  }

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsPhotonBufferHierarchy();
  ~vtkCausticsPhotonBufferHierarchy() override;

  vtkNew<vtkCausticsShaderProgram> BuildProgram;
  vtkNew<vtkCausticsShaderProgram> GatherPrograms[3]; // flat, traversal nodes, photons
  vtkNew<vtkCausticsShaderProgram> ArgumentsProgram;
  vtkNew<vtkTextureObject> SplatRadius;
  unsigned int SplatRegion = 0;
  double FluxUnit = 1.0;
  bool LastGatherFlat = false;       // the last Gather()'s mode, for GetCounters()
  bool LastDropCoarseSplats = false; // and whether it dropped the coarse splats
  int StartLevel = 0;
  std::vector<int> LevelWidth, LevelHeight; // level k: nodes (k >= 1) or photons (k = 0)
  std::vector<unsigned int> NodeOffset, ListOffset;

private:
  vtkCausticsPhotonBufferHierarchy(const vtkCausticsPhotonBufferHierarchy&) = delete;
  void operator=(const vtkCausticsPhotonBufferHierarchy&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal; // the GPU buffers

  void Layout(int width, int height, int startResolution);
  bool BuildMipmap(vtkOpenGLRenderWindow* renWin, const caustics::PhotonRecords& landed,
    const caustics::LightView& mapView, int mapResolution);
  bool Traverse(vtkOpenGLRenderWindow* renWin, const caustics::CausticMapSettings& settings,
    const caustics::PhotonGrid& grid, const caustics::PhotonRecords& landed,
    const caustics::LightView& mapView, int lightType, const caustics::Camera* camera);
  /** Traverse() in steps: the uniforms of every level, and those of level k. */
  void SetGatherUniforms(vtkCausticsShaderProgram* gather,
    const caustics::CausticMapSettings& settings, const caustics::PhotonGrid& grid,
    const caustics::LightView& mapView, int lightType, const caustics::Camera* camera);
  void SetLevelUniforms(vtkCausticsShaderProgram* gather,
    const caustics::CausticMapSettings& settings, int k, bool implicit);
};

#endif
