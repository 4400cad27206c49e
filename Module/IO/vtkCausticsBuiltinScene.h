/**
 * @class   vtkCausticsBuiltinScene
 * @brief   Deterministic, parameterized caustic scenes: ball lens, pool, ring, bunny.
 *
 * Populate() fills a renderer with actors (materials set through
 * vtkCausticsMaterial), physical lights and a camera:
 * - "ball-lens" (default): glass sphere (IOR 1.5, radius 1) centred 3 units above a
 *   white Lambertian floor (albedo 0.8), directional light straight down, 1 W/m^2;
 * - "pool": water height field (IOR 1.33, sum of sines animated by Time) over a
 *   tiled floor with four walls, sun light at 60 degrees elevation, camera above;
 * - "ring": polished silver cylinder wall on the floor, light 20 degrees above the
 *   horizon: the nephroid (coffee-cup) caustic;
 * - "bunny": glass Stanford bunny (Data/bunny.ply) in a Cornell box lit by a spot
 *   light under the ceiling;
 * - "underwater": the pool over murky water whose density varies: a plankton layer
 *   half a metre down in smooth lumps, over a faint haze (a heterogeneous
 *   vtkCausticsMedium, made procedurally): the waves' light shafts in the water;
 * - "smoke-lens": the ball lens lit by a spot light 4 m above it, focusing into a
 *   lumpy ball of smoke (heterogeneous medium) on the floor.
 * The scene's y axis points up; lengths are metres. Nothing is random.
 */
#ifndef vtkCausticsBuiltinScene_h
#define vtkCausticsBuiltinScene_h

#include "vtkObject.h"
#include "vtkIOCausticsModule.h" // For export macro

#include <memory> // For std::unique_ptr
#include <string> // For std::string
#include <vector> // For std::vector

class vtkRenderer;

class VTKIOCAUSTICS_EXPORT vtkCausticsBuiltinScene : public vtkObject
{
public:
  static vtkCausticsBuiltinScene* New();
  vtkTypeMacro(vtkCausticsBuiltinScene, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Which scene: "ball-lens" (default), "pool", "ring", "bunny", "underwater" or
   * "smoke-lens". The last two attach a vtkCausticsMedium to the renderer; Populate()
   * detaches any other.
   */
  vtkSetStdStringFromCharMacro(SceneName);
  vtkGetCharFromStdStringMacro(SceneName);
  ///@}

  /** Names Populate() accepts. */
  static std::vector<std::string> GetSceneNames();
  /** True when name is one of GetSceneNames(). */
  static bool IsSceneName(const std::string& name);
  /** True for the scenes that attach a participating medium (underwater, smoke-lens). */
  static bool IsMediaScene(const std::string& name);

  ///@{
  /** Animation time in seconds (moves the pool's waves). Default 0. */
  vtkSetMacro(Time, double);
  vtkGetMacro(Time, double);
  ///@}

  ///@{
  /**
   * Index of refraction of the scene's refractor (ball, water, bunny); 0 (default)
   * keeps the scene's own (1.5, 1.33, 1.5). Must be 0 or >= 1.
   */
  vtkSetMacro(RefractiveIndex, double);
  vtkGetMacro(RefractiveIndex, double);
  ///@}

  ///@{
  /** Tessellation multiplier for curved/height-field surfaces in [0.25, 8]. Default 1. */
  vtkSetClampMacro(Tessellation, double, 0.25, 8.0);
  vtkGetMacro(Tessellation, double);
  ///@}

  ///@{
  /**
   * Folder holding bunny.ply. Default: the environment variable CAUSTICS_DATA_DIR
   * if set, else the module's data found from where its library is loaded
   * (`<prefix>/share/vtkcaustics/data` once installed; `build/share/...` in a build tree).
   */
  vtkSetStdStringFromCharMacro(DataDirectory);
  vtkGetCharFromStdStringMacro(DataDirectory);
  ///@}

  /**
   * Removes the renderer's actors and lights and adds the scene's, sets the camera.
   * Returns false (with an error naming the problem) on an unknown scene name, a bad
   * parameter or a missing data file; the renderer is then left empty.
   */
  bool Populate(vtkRenderer* renderer);

  /**
   * Applies the current Time to a renderer populated by this object (moves the
   * pool's water in place; other scenes are static).
   */
  void UpdateTime(double time);

  /** Last error message, empty when none. */
  const char* GetLastError() const { return this->LastError.c_str(); }

protected:
  vtkCausticsBuiltinScene();
  ~vtkCausticsBuiltinScene() override;

  std::string SceneName = "ball-lens";
  std::string DataDirectory;
  std::string LastError;
  double Time = 0.0;
  double RefractiveIndex = 0.0;
  double Tessellation = 1.0;

private:
  vtkCausticsBuiltinScene(const vtkCausticsBuiltinScene&) = delete;
  void operator=(const vtkCausticsBuiltinScene&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;

  /** Keeps `message` as the last error, reports it, returns false. */
  bool Fail(const std::string& message);
  /** False, with the error, for an unknown scene or a bad parameter. */
  bool CheckSettings();
  /** RefractiveIndex, or the scene's own where it is 0. */
  double IndexOfRefraction(double sceneDefault) const;
  ///@{
  /** The scenes' actors, lights and camera. */
  void AddBallLens(vtkRenderer* renderer);
  void AddSmokeLens(vtkRenderer* renderer);
  /** The glass ball (radius 1, 3 m up) over the white floor: ball lens and smoke lens. */
  void AddGlassBallOverFloor(vtkRenderer* renderer);
  void AddPool(vtkRenderer* renderer);
  void AddRing(vtkRenderer* renderer);
  bool AddBunny(vtkRenderer* renderer);
  ///@}
};

#endif
