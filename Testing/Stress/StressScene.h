/**
 * Random scenes for the caustics stress driver (CausticsStress.cxx).
 *
 * One seed makes one scene, the same on every run and machine: the generator
 * draws from std::mt19937_64 through its own uniform mapping (the standard
 * distributions differ between library implementations). A scene holds
 * - 1 to 3 specular objects (none in one scene of 10): glass of IOR 1 to 4, or
 *   mirrors; spheres, boxes and random meshes (a jittered sphere, or a soup of
 *   random triangles);
 * - 0 to 3 receivers: a floor (most scenes), boxes, spheres, random meshes;
 * - sometimes broken triangles (zero area, a NaN corner, NaN normals) in any object;
 * - 1 to 3 lights (none in one scene of 12): directional (some grazing the floor at
 *   under 1 degree), point and spot, some placed inside a specular object;
 * - a perspective or parallel camera, sometimes looking away from the scene;
 * - sometimes a participating medium;
 * - in one scene of 12, one input a user should not give (a light of NaN or 1e30
 *   W/sr or at Inf, a glass of IOR NaN or 1e6, an actor scaled by 0 or at NaN);
 * - in one scene of 33, a light buffer of 8192^2 photons, more than a technique
 *   may hold on llvmpipe (a refusal in one line, no caustics);
 * all at one scale between 1e-3 and 1e4 m. About one scene in 25 is empty.
 */
#ifndef StressScene_h
#define StressScene_h

#include <cstdint>
#include <random>
#include <string>

class vtkRenderer;

namespace stress
{
/** Portable draws from a 64-bit Mersenne twister. */
class Random
{
public:
  explicit Random(std::uint64_t seed)
    : Engine(seed)
  {
  }
  /** Uniform in [0, 1). */
  double Uniform() { return static_cast<double>(this->Engine() >> 11) * 0x1.0p-53; }
  double Uniform(double low, double high) { return low + (high - low) * this->Uniform(); }
  /** Uniform integer in [low, high]. */
  int Integer(int low, int high)
  {
    return low + static_cast<int>(this->Uniform() * (high - low + 1));
  }
  bool Chance(double p) { return this->Uniform() < p; }

private:
  std::mt19937_64 Engine;
};

/** What a seed made, for the failure report and the batch statistics. */
struct SceneSummary
{
  std::string Text; ///< one line: scale, objects, lights, camera
  int Width = 128, Height = 128;
  int Photons = 64; ///< LightBufferResolution
  double Scale = 1.0;
  /**
   * VTK itself is given a non-finite light (the abuse cases NaN intensity, light
   * at Inf): VTK 9.1 then shades NaN pixels, which the layers carrying VTK's colour
   * (FinalColor, TechniqueColor) show. The module skips such a light with a warning.
   */
  bool VtkShadesNaN = false;
};

/** Fills the (empty) renderer with the scene of `seed` and says what it made. */
SceneSummary MakeScene(std::uint64_t seed, vtkRenderer* renderer);
}

#endif
