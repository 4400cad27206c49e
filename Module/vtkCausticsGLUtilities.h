/**
 * @file   vtkCausticsGLUtilities.h
 * @brief  Small GL helpers shared by the caustics stages (not wrapped).
 *
 * Textures are (re)allocated only when their size or format changes, so the
 * stages create no GL objects per frame; read-back turns a texture into a
 * vtkImageData array for tests and debugging (never used in the render path).
 */
#ifndef vtkCausticsGLUtilities_h
#define vtkCausticsGLUtilities_h

#include "vtkRenderingCausticsModule.h" // For export macro
#include "vtkSmartPointer.h"            // For vtkSmartPointer

#include <string> // For std::string

class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkTextureObject;

namespace caustics
{
namespace gl
{
/**
 * Makes `texture` a width x height 2D texture of the given sized internal format
 * (GL_RGBA32F, GL_R32UI, GL_DEPTH_COMPONENT32F, ...), nearest filtering, clamped;
 * reallocates only when size or format differ. Returns true if it (re)allocated.
 */
VTKRENDERINGCAUSTICS_EXPORT bool EnsureTexture(vtkTextureObject* texture,
  vtkOpenGLRenderWindow* renWin, int width, int height, unsigned int internalFormat);

/** Row-major double matrix (vtkMatrix4x4 layout) to column-major floats for GL. */
VTKRENDERINGCAUSTICS_EXPORT void ToColumnMajor(const double rowMajor[16], float columnMajor[16]);

/**
 * Downloads a 2D texture (float or integer colour, or depth) into a new image whose
 * point data has one array `arrayName` with `components` components (the first
 * `components` channels of the texture). For tests and debugging only: it stalls.
 */
VTKRENDERINGCAUSTICS_EXPORT vtkSmartPointer<vtkImageData> ReadTexture(
  vtkTextureObject* texture, const std::string& arrayName, int components);

/** A vertex array with no attributes, for drawing a full-screen triangle from gl_VertexID. */
class VTKRENDERINGCAUSTICS_EXPORT FullScreenTriangle
{
public:
  ~FullScreenTriangle();
  /** Draws 3 vertices (glsl/vtkCausticsFullScreenVS.glsl makes the triangle). */
  void Draw();
  void Release();

private:
  unsigned int VertexArray = 0;
};
}
}

#endif
