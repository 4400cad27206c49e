/**
 * @class   vtkCausticsLayeredDepth
 * @brief   Layered depth image of the caustics scene by depth peeling, as deep as the scene is.
 *
 * The layered depth image (LDI) of 000_54cf099eeccf42d9.txt §2.2: every surface
 * along every pixel's ray, not only the nearest, so that screen-space tracing can
 * find intersections with occluded geometry. Seen through any world-to-clip matrix
 * (the camera's, or a light's for techniques that trace from the light). Per frame:
 * 1. count: the geometry of the chosen roles is rasterized once without depth test;
 *    each fragment adds one to its pixel's counter (image atomics) in its object's
 *    slice;
 * 2. reduce: a log-step max reduction over the pixels gives each object's depth
 *    complexity (the deepest pixel), all on the GPU;
 * 3. finalize: the number of layers to peel is the depth complexity, capped at
 *    MaximumNumberOfLayers; a one-thread pass writes it into the layer table and
 *    gates the indirect draw commands of every layer, so layers beyond the depth
 *    complexity are never drawn and nothing is read back to the CPU;
 * 4. peel: layer k keeps, per pixel, the nearest fragment strictly behind layer
 *    k - 1 (depth test against ping-ponged depth buffers) and stores world position
 *    + material index, normal (as modelled) + role, and window depth.
 * With PerObject on, every mesh (up to MaximumNumberOfObjects; the rest share the
 * last) gets its own LDI, peeled from its own triangles only: a scene of many
 * objects then costs each object's own depth complexity rather than the scene's
 * ("separate depth images for each object", §2.2).
 *
 * Consumers read the textures and the layer table (a shader storage buffer) on the
 * GPU. Layout of the table, std430 (glsl/vtkCausticsScreenSpaceCommon.glsl):
 *   uvec4 header: x objects, y layer cap, z depth complexity (largest over the
 *                 objects, uncapped), w layers allocated;
 *   uvec4 objects[]: x first layer of the object in the textures, y layers peeled
 *                 (valid), z the object's depth complexity, w 0.
 * Layers of an object at or beyond its y are stale and must not be read.
 * All GL objects are made on first use and when the size, cap or object count
 * changes; programs compile once. A Render() whose inputs are those of the layers
 * held (the same view matrix, size and settings, and the same meshes: versions,
 * material slots and roles) keeps them and draws nothing (ReuseUnchanged): a still
 * camera over a still scene pays for its layers once.
 */
#ifndef vtkCausticsLayeredDepth_h
#define vtkCausticsLayeredDepth_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include <memory> // For std::unique_ptr

class vtkCausticsSceneGeometry;
class vtkCausticsTimings;
class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkWindow;

namespace caustics
{
struct SceneData;
}

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsLayeredDepth : public vtkObject
{
public:
  static vtkCausticsLayeredDepth* New();
  vtkTypeMacro(vtkCausticsLayeredDepth, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Most layers peeled per object, in [1, 16]. Fewer are peeled when the depth
   * complexity is lower. Default 8 (§2.2: "it is usually sufficient to only
   * consider up to eight depth layers").
   */
  vtkSetClampMacro(MaximumNumberOfLayers, int, 1, 16);
  vtkGetMacro(MaximumNumberOfLayers, int);
  ///@}

  ///@{
  /**
   * Roles drawn, as a vtkCausticsSceneGeometry role mask (RoleBit of receivers,
   * reflectors, refractors). Default all three.
   */
  vtkSetClampMacro(RoleMask, int, 0, 14);
  vtkGetMacro(RoleMask, int);
  ///@}

  ///@{
  /** One LDI per object (mesh) instead of one for the scene. Default off. */
  vtkSetMacro(PerObject, bool);
  vtkGetMacro(PerObject, bool);
  vtkBooleanMacro(PerObject, bool);
  ///@}

  ///@{
  /**
   * With PerObject on, the most separate LDIs, in [1, 64]; further meshes share the
   * last one. Memory grows with objects x MaximumNumberOfLayers. Default 16.
   */
  vtkSetClampMacro(MaximumNumberOfObjects, int, 1, 64);
  vtkGetMacro(MaximumNumberOfObjects, int);
  ///@}

  ///@{
  /**
   * Keep the layers of the last Render() when its inputs are unchanged: the
   * world-to-clip matrix, the size, the settings above and, per mesh, its version
   * (renewed by vtkCausticsSceneExtractor when its triangles or its actor's matrix
   * change), material slot and role. What the layers hold depends on nothing else
   * (material properties such as the index of refraction are read by the
   * consumers from the material table). Default on.
   */
  vtkSetMacro(ReuseUnchanged, bool);
  vtkGetMacro(ReuseUnchanged, bool);
  vtkBooleanMacro(ReuseUnchanged, bool);
  ///@}

  /** Whether the last Render() kept the layers it already held (nothing changed). */
  bool GetLastRenderReused() const;

  /**
   * Timings to report the stages to ("<StagePrefix>depth complexity" and
   * "<StagePrefix>depth peeling"), or nullptr. Not owned.
   */
  void SetTimings(vtkCausticsTimings* timings, const char* stagePrefix);

#ifndef __VTK_WRAP__
  /**
   * Builds the LDI of `geometry` (uploaded from `scene` this frame) seen through
   * worldToClip (column-major) at width x height. Returns false, with an error
   * naming the problem, on a bad size or a GL/program failure.
   */
  bool Render(vtkOpenGLRenderWindow* renWin, vtkCausticsSceneGeometry* geometry,
    const caustics::SceneData& scene, const float worldToClip[16], int width, int height);
#endif

  ///@{
  /**
   * GL names of the results (2D array textures of GetNumberOfAllocatedLayers()
   * layers): Position RGBA32F (xyz world, w material index, -1 where no surface),
   * Normal RGBA16F (xyz as modelled, w role), Depth R32F (window depth, 1 where no
   * surface); Complexity R32UI (per pixel and object: fragments counted).
   */
  unsigned int GetPositionTexture() const;
  unsigned int GetNormalTexture() const;
  unsigned int GetDepthTexture() const;
  unsigned int GetComplexityTexture() const;
  /** The layer table (see the class description). */
  unsigned int GetTableBuffer() const;
  ///@}

  /** Objects of the last Render() (1 without PerObject). */
  int GetNumberOfObjects() const;
  /** Layers allocated: objects x MaximumNumberOfLayers. */
  int GetNumberOfAllocatedLayers() const;
  /** Size of the last Render(). */
  int GetWidth() const;
  int GetHeight() const;

  ///@{
  /**
   * Read-backs of the last Render(), for tests and debugging only (they stall the
   * GPU): the depth complexity (largest over the objects, uncapped), the layers
   * peeled for an object, and one layer of a texture ("Position", "Normal",
   * "Depth" or "Complexity" (per object)) as a point-data array named after it.
   */
  int ReadDepthComplexity();
  int ReadNumberOfPeeledLayers(int object);
  bool ReadLayer(const char* texture, int layer, vtkImageData* output);
  ///@}

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsLayeredDepth();
  ~vtkCausticsLayeredDepth() override;

  int MaximumNumberOfLayers = 8;
  int RoleMask = 2 | 4 | 8;
  bool PerObject = false;
  int MaximumNumberOfObjects = 16;
  bool ReuseUnchanged = true;

private:
  vtkCausticsLayeredDepth(const vtkCausticsLayeredDepth&) = delete;
  void operator=(const vtkCausticsLayeredDepth&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;

#ifndef __VTK_WRAP__
  ///@{
  /** Steps of Render() that can fail: they say why with vtkErrorMacro. */
  bool CheckInputs(
    vtkCausticsSceneGeometry* geometry, const caustics::SceneData& scene, int width, int height);
  bool CheckUploaded(vtkCausticsSceneGeometry* geometry, vtkTypeUInt64 sceneIndices);
  bool AllocateTargets(int objects, int layers, int width, int height);
  ///@}
#endif
};

#endif
