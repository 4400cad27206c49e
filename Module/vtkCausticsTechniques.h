/**
 * @class   vtkCausticsTechniques
 * @brief   Registry of the caustics techniques by name, for the CLI, the benchmark and users.
 *
 * Every technique is a vtkCausticsRenderPass subclass. Names:
 * - "none": vtkCausticsRenderPass itself (VTK shading plus the shared buffers);
 * - "screen-space": vtkCausticsScreenSpacePhotonPass (docs/technique-screen-space.md);
 * - "caustic-maps": vtkCausticsHierarchicalCausticMapPass (docs/technique-caustic-maps.md).
 * "best" names the technique the CLI uses by default: "screen-space", the more accurate
 * on two of the four built-in scenes (caustic-maps on the other two,
 * docs/benchmarks.md) and the only one that shows refractors refracting the scene.
 */
#ifndef vtkCausticsTechniques_h
#define vtkCausticsTechniques_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro
#include "vtkSmartPointer.h"            // For return value

#include <functional> // For std::function
#include <string>     // For std::string
#include <vector> // For std::vector

class vtkCausticsRenderPass;
class vtkRenderer;

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsTechniques : public vtkObject
{
public:
  static vtkCausticsTechniques* New();
  vtkTypeMacro(vtkCausticsTechniques, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Registered names, "best" excluded. */
  static std::vector<std::string> GetNames();
  /** The name "best" stands for when nothing is known about the scene. */
  static std::string GetBestName();
  /**
   * The name "best" stands for in `renderer`'s scene, from the features it has
   * (docs/benchmarks.md, "Which technique is best"): reflectors, and open
   * refractors that are not a sheet (caustics::IsSheet), take screen-space; closed
   * refractors and open sheets (a water surface) alone take caustic maps; without a
   * GPU the CPU technique where it measured better. A scattering medium does not
   * decide. GetBestName() without a scene.
   */
  static std::string GetBestNameFor(vtkRenderer* renderer);
#ifndef __VTK_WRAP__
  /** A new pass for `name` (or "best"); nullptr for an unknown name. */
  static vtkSmartPointer<vtkCausticsRenderPass> Create(const std::string& name);

  /**
   * Registers a technique of another module (which this one cannot link, e.g. the
   * CPU technique of VTK::RenderingCausticsCPU, which links Embree). A name already
   * registered is replaced. Thread-unsafe: register before rendering.
   */
  static void Register(const std::string& name, const std::string& description,
    std::function<vtkSmartPointer<vtkCausticsRenderPass>()> make);
#endif
  /** Create() for wrapped languages (Python): the caller owns the new pass. */
  VTK_NEWINSTANCE static vtkCausticsRenderPass* NewPass(const std::string& name);
  /** One line per technique: name and what it is. */
  static std::string Describe();

protected:
  vtkCausticsTechniques() = default;
  ~vtkCausticsTechniques() override = default;

private:
  vtkCausticsTechniques(const vtkCausticsTechniques&) = delete;
  void operator=(const vtkCausticsTechniques&) = delete;
};

#endif
