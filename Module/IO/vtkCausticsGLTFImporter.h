/**
 * @class   vtkCausticsGLTFImporter
 * @brief   glTF 2.0 scene import for caustics: VTK's importer plus IOR, transmission, physical
 *          lights and cameras, with validation.
 *
 * VTK 9.1's vtkGLTFImporter makes one actor per mesh primitive with the PBR
 * metallic-roughness material, but it ignores KHR_materials_ior and
 * KHR_materials_transmission, places positional lights one local unit off their
 * node (it transforms vtkLight's default position (0, 0, 1) by the node's
 * matrix), gives point lights no distance falloff, applies no camera unless
 * told which, silently drops out-of-range material indices, and crashes on
 * cyclic node graphs, files without scenes or out-of-range mesh indices. This
 * subclass keeps VTK's reading and actor building and adds the rest:
 * 1. ImportBegin() checks the file with jsoncpp before VTK's loader sees it:
 *    JSON syntax, asset version 2.x, required extensions, every index (scene,
 *    node, mesh, material, accessor, buffer view, buffer, camera, light, texture,
 *    image, sampler, skin), finite numbers everywhere, buffer and accessor sizes,
 *    accessor bounds, the accessor types glTF allows for vertex attributes, the
 *    chunks of a .glb, a node graph without cycles or shared children and at most
 *    MAX_NODE_DEPTH levels deep, and physical ranges (IOR in
 *    [1, MAX_IOR], factors in [0, 1], intensities within float range, cone
 *    angles, camera frusta, selected camera index); sparse accessors are refused;
 * 2. it then runs VTK's vtkGLTFDocumentLoader (through a lower-case alias for a
 *    ".GLTF" or ".GLB" name, and with images and textures dropped: they are never
 *    decoded, as caustics read constant factors only) and checks what it decoded: vertex
 *    indices within the vertex count and finite, non-degenerate world transforms
 *    for lights and cameras. Any failure leaves the renderer untouched, returns
 *    false from Update()/Read() and sets GetLastError() to one line naming the
 *    file and the problem;
 * 3. ImportActors() lets the base class build the actors, then sets each
 *    vtkProperty from its glTF material (PBR, base colour, metallic, roughness,
 *    KHR_materials_ior as BaseIOR with the glTF default 1.5,
 *    KHR_materials_transmission and KHR_materials_volume through
 *    vtkCausticsMaterial) and names the actor after its node or mesh;
 * 4. ImportLights() replaces the base class: KHR_lights_punctual lights at
 *    their node's world position, travelling along the node's world -z axis,
 *    with the glTF "intensity" read in this module's radiometric units (see
 *    vtkCausticsSceneData.h): irradiance in W/m^2 for directional lights, radiant
 *    intensity in W/sr for point and spot lights, per unit of "color". This
 *    differs from glTF's photometric lux and candela on purpose: caustics are
 *    computed in watts. Positional lights get VTK attenuation (0, 0, 1) so VTK's
 *    own shading falls off as 1/r^2; the spot's outer cone becomes the
 *    vtkLight cone angle and its inner cone the light's
 *    vtkCausticsSceneExtractor::INNER_CONE_ANGLE() (degrees); "range" is ignored
 *    (physical lights have no cut-off);
 * 5. ImportCameras() replaces the base class: every glTF camera placed by the
 *    first scene node that uses it (GetCamera(i)), and the one selected by
 *    SetCamera() copied into the renderer's active camera: perspective yfov as
 *    the vertical view angle, znear/zfar as clipping range, orthographic ymag as
 *    parallel scale. The aspect ratio the file asks for is given by
 *    GetCameraAspectRatio(); the image size decides the actual one.
 *
 * The format coverage and the mapping table are in docs/scene-input.md.
 */
#ifndef vtkCausticsGLTFImporter_h
#define vtkCausticsGLTFImporter_h

#include "vtkGLTFImporter.h"
#include "vtkIOCausticsModule.h" // For export macro

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class vtkActor;

class VTKIOCAUSTICS_EXPORT vtkCausticsGLTFImporter : public vtkGLTFImporter
{
public:
  static vtkCausticsGLTFImporter* New();
  vtkTypeMacro(vtkCausticsGLTFImporter, vtkGLTFImporter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Imports the file into the first renderer of the render window (one is made
   * when none is set, as vtkImporter does). Returns false, with GetLastError() set
   * and nothing added to the renderer, when the file cannot be imported. These
   * hide vtkImporter's void versions of VTK 9.1; through a vtkImporter pointer the
   * outcome is still in GetLastError().
   */
  bool Read();
  bool Update() { return this->Read(); }
  ///@}

  ///@{
  /**
   * Limits of what the GPU passes represent, checked by this importer and by
   * caustics-render's options (docs/scene-input.md). The passes compute in 32-bit
   * floats (largest 3.4e38): an intensity is multiplied by solid angles, 1/r^2 and
   * photon densities, so 1e30 leaves 1e8 of headroom; an IOR of 1e20 already gives
   * NaN in the screen-space refraction, while real materials stay below 5, so 100
   * is the cap; medium coefficients above 1e9 per metre (opaque within a nanometre)
   * are not physical and their products overflow, and an attenuation distance
   * below 1e-9 m would give such a coefficient.
   */
  static constexpr double MAX_IOR = 100.0;
  static constexpr double MAX_LIGHT_INTENSITY = 1e30;
  static constexpr double MAX_MEDIUM_COEFFICIENT = 1e9;
  static constexpr double MIN_ATTENUATION_DISTANCE = 1e-9;
  ///@}

  /**
   * Deepest node hierarchy imported, in levels (a root node is level 1). VTK 9.1's
   * glTF loader computes world transforms recursively, one stack frame per level
   * (vtkGLTFDocumentLoader::BuildGlobalTransforms), so a chain of 100000 nodes, each
   * the only child of the previous one, overflowed the stack; deeper documents are
   * refused before VTK reads them. The importer's own walks are iterative.
   */
  static constexpr int MAX_NODE_DEPTH = 1000;

  /** One line naming the file and the problem of the last import; empty after a success. */
  const char* GetLastError() const { return this->LastError.c_str(); }

  ///@{
  /**
   * Which glTF camera to apply to the renderer's active camera: an index into
   * the file's "cameras". Default 0: the first camera if the file has any (a file
   * without cameras keeps the renderer's camera). -1 (any negative value) keeps
   * the renderer's camera. An index beyond the file's cameras fails the import.
   */
  void SetCamera(vtkIdType index) override;
  vtkGetMacro(CameraIndex, vtkIdType);
  ///@}

  /**
   * Width over height of the applied camera as the file gives it (perspective
   * aspectRatio, orthographic xmag / ymag); 0 when the file gives none or no
   * camera was applied.
   */
  vtkGetMacro(CameraAspectRatio, double);

  ///@{
  /** As in vtkGLTFImporter, but safe to call before an import (0 cameras, 0 animations). */
  vtkIdType GetNumberOfCameras() override;
  std::string GetCameraName(vtkIdType index) override;
  vtkIdType GetNumberOfAnimations() override;
  bool IsAnimationEnabled(vtkIdType index) override;
  void UpdateTimeStep(double time) override;
  ///@}

  /**
   * Where an actor of the last import comes from: glTF node, mesh, primitive
   * (index within the mesh) and material (-1 when the primitive has none).
   * Returns false for actors this importer did not create.
   */
  bool GetActorSource(vtkActor* actor, int& node, int& mesh, int& primitive, int& material);

protected:
  vtkCausticsGLTFImporter();
  ~vtkCausticsGLTFImporter() override;

  int ImportBegin() override;
  void ImportActors(vtkRenderer* renderer) override;
  void ImportCameras(vtkRenderer* renderer) override;
  void ImportLights(vtkRenderer* renderer) override;

  /** Steps 1 and 2 of the class description; ImportBegin() adds a last-resort exception guard. */
  int CheckAndLoad();

  /** Records and reports an error about the file; always returns 0 (ImportBegin's failure). */
  int Fail(const std::string& problem);

  vtkIdType CameraIndex = 0;
  double CameraAspectRatio = 0.0;
  std::string LastError;

private:
  vtkCausticsGLTFImporter(const vtkCausticsGLTFImporter&) = delete;
  void operator=(const vtkCausticsGLTFImporter&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;

  ///@{
  /**
   * The steps of CheckAndLoad(), in order: read the file; check its extension
   * against its container and split a binary one into JSON and BIN chunk; parse
   * the JSON; check the document and the camera index; run VTK's loader; check
   * the vertex indices VTK decoded and the world transforms of the scene's nodes.
   * Each returns 1, or Fail()'s 0.
   */
  int ReadFile(const std::string& path, std::string& contents);
  int SplitContainer(const std::string& path, const std::string& contents, std::string& json,
    bool& binary, std::size_t& binSize);
  int ParseJSON(const std::string& json);
  int ValidateDocument(const std::string& path, bool binary, std::size_t binSize);
  int RunLoader(const std::string& path, bool binary);
  int CheckVertexIndices();
  int CheckSceneNodes();
  ///@}
};

#endif
