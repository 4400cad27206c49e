/**
 * @class   vtkCausticsCameraOpticalDepth
 * @brief   The medium's optical depth from the camera, as a volume built once per frame.
 *
 * A heterogeneous medium dims every surface and every scattering point by the
 * transmittance towards the camera. Marching the NanoVDB density for each pixel and each
 * god-ray fragment repeats the same integral many times over (on llvmpipe it dominated
 * the smoke-lens frame: 7 s of compositing at 64^2). This stage integrates it once per
 * frame into a 3D texture over the camera's frustum (003_653219b45420e98f.txt, section
 * 5.4, "transmittance volume"):
 * 1. columns: one viewing ray per cell of PixelsPerColumn^2 pixels (4 x 4 by default, at
 *    least 64 cells each way), from the near plane through the cell's centre;
 * 2. slices: Slices distances along each ray, spaced evenly over the range where the
 *    medium's box lies, each holding the optical depth (density x m) from the near plane
 *    to there, accumulated slice by slice with the tile-skipping march of
 *    CausticsMediumOpticalDepth (vtkCausticsCommon.glsl);
 * 3. a shader reads the optical depth to any point in view with one trilinear fetch
 *    (CausticsCameraOpticalDepth); points outside the view fall back to the march.
 * It is rebuilt every frame the scene has a density grid (the camera, the grid or its
 * placement may have changed); textures are allocated on first use and resize only.
 * The error is that of linear interpolation between columns and slices of a smooth
 * integral; TestMediumGPU measures it against the per-pixel march.
 */
#ifndef vtkCausticsCameraOpticalDepth_h
#define vtkCausticsCameraOpticalDepth_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include <memory> // For std::unique_ptr

class vtkCausticsShaderProgram;
class vtkOpenGLRenderWindow;
class vtkWindow;
namespace caustics
{
struct SceneData;
namespace gl
{
class MediumBuffer;
}
}

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsCameraOpticalDepth : public vtkObject
{
public:
  static vtkCausticsCameraOpticalDepth* New();
  vtkTypeMacro(vtkCausticsCameraOpticalDepth, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Off: every stage marches the density towards the camera per pixel and per god-ray
   * fragment (exact, slow on software renderers). Default on.
   */
  vtkSetMacro(Enabled, bool);
  vtkGetMacro(Enabled, bool);
  vtkBooleanMacro(Enabled, bool);
  ///@}

  ///@{
  /** Viewport pixels per column, each way, in [1, 64], with at least 64 columns. Default 4. */
  vtkSetClampMacro(PixelsPerColumn, int, 1, 64);
  vtkGetMacro(PixelsPerColumn, int);
  ///@}

  ///@{
  /** Slices along each viewing ray, in [2, 512]. Default 64. */
  vtkSetClampMacro(Slices, int, 2, 512);
  vtkGetMacro(Slices, int);
  ///@}

#ifndef __VTK_WRAP__
  /**
   * Integrates the optical depth for `scene`'s camera over a width x height viewport.
   * Returns false, leaving nothing to read, when disabled, when the scene has no density
   * grid on the GPU or when the medium's box lies behind the camera.
   */
  bool Build(vtkOpenGLRenderWindow* window, int width, int height,
    const caustics::SceneData& scene, const caustics::gl::MediumBuffer* grid);
#endif

  /** True after a successful Build() (until the next one fails, or Invalidate()). */
  bool IsValid() const;
  /** Nothing to read this frame (no density grid): SetDefine() removes the define. */
  void Invalidate();

  /**
   * Gives a bound program the volume: the define CAUSTICS_CAMERA_OPTICAL_DEPTH must be
   * set (SetDefine(program)) before Bind; then this sets the uniforms and activates the
   * texture. Call Deactivate() after drawing.
   */
  void SetDefine(vtkCausticsShaderProgram* program) const;
  void SetUniforms(vtkCausticsShaderProgram* program);
  void Deactivate();

  /** Frees the texture and the program. */
  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkCausticsCameraOpticalDepth();
  ~vtkCausticsCameraOpticalDepth() override;

  bool Enabled = true;
  int PixelsPerColumn = 4;
  int Slices = 64;

private:
  vtkCausticsCameraOpticalDepth(const vtkCausticsCameraOpticalDepth&) = delete;
  void operator=(const vtkCausticsCameraOpticalDepth&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
