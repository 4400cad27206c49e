/**
 * @class   vtkCausticsProgressiveMean
 * @brief   The mean of a still scene's frames: caustic irradiance and volume radiance.
 *
 * Photon techniques estimate the caustic from a finite set of photons; a still scene
 * seen by a still camera can do better by averaging frames whose photons differ.
 * vtkCausticsRenderPass (ProgressiveFrames) hands this class a key of everything a
 * frame depends on:
 * 1. Begin(key) says which frame of the run this one is: 0 after any change of the
 *    key (the run restarts), 1, 2, ... while it stays the same, and -1 once
 *    `Frames` frames are averaged (the mean is complete: the caustic stages are
 *    skipped and the textures keep it);
 * 2. GridOffset(k) is the light buffers' texel-grid offset for frame k (the R2
 *    low-discrepancy sequence; 0 for frame 0, so a first frame is the same image as
 *    without averaging); techniques that draw new photons every frame by themselves
 *    (cascaded, impostors) get new photons either way;
 * 3. Add() folds the frame's textures into the running mean, in place: the caustic
 *    irradiance (W/m^2) and, if the frame wrote one, the volume radiance
 *    (W/(m^2 sr)), both RGBA32F of the view's size.
 * The mean of k frames of N^2 photons holds k N^2 photons' worth of samples: its
 * noise falls as frames are added, its bias is that of one frame.
 */
#ifndef vtkCausticsProgressiveMean_h
#define vtkCausticsProgressiveMean_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include <cstdint> // For std::uint64_t
#include <memory>  // For std::unique_ptr
#include <vector>  // For std::vector

class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsProgressiveMean : public vtkObject
{
public:
  static vtkCausticsProgressiveMean* New();
  vtkTypeMacro(vtkCausticsProgressiveMean, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Frames averaged at most, in [1, 4096]; 1: no averaging (every frame new). Default 1. */
  vtkSetClampMacro(Frames, int, 1, 4096);
  vtkGetMacro(Frames, int);
  ///@}

  /** Frames in the mean the textures hold now (0: none since the last change). */
  int GetFramesAveraged() const;

  /** Drops the mean: the next Begin() restarts the run. */
  void Reset();

#ifndef __VTK_WRAP__
  /**
   * The frame's place in the run for a frame whose inputs are `key`: 0 restarts
   * (the key changed, Reset(), or Frames is 1), k > 0 the k-th frame after it, -1
   * when Frames frames are in the mean already (nothing to render).
   */
  int Begin(const std::vector<std::uint64_t>& key);

  /**
   * Adds the frame's estimate to the mean (frame Begin() gave) and leaves the mean
   * in the textures. `volume` may be null (no volume layer this frame). Returns false
   * on a GL failure, after which the run restarts.
   */
  bool Add(vtkOpenGLRenderWindow* renWin, vtkTextureObject* caustic, vtkTextureObject* volume);
#endif

  /** The light-grid offset for frame k, each component in [-0.5, 0.5) texels; (0, 0) for k = 0. */
  static void GridOffset(int k, double offset[2]);

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsProgressiveMean();
  ~vtkCausticsProgressiveMean() override;

  int Frames = 1;

private:
  vtkCausticsProgressiveMean(const vtkCausticsProgressiveMean&) = delete;
  void operator=(const vtkCausticsProgressiveMean&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
