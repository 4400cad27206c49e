/**
 * @class   vtkCausticsShaderProgram
 * @brief   A GLSL 4.50 program (vertex/geometry/fragment, or compute) owned by a pass.
 *
 * VTK 9.1's vtkShaderProgram knows no compute shaders and prepends `#version 150`,
 * so the caustics stages, which need SSBOs, image atomics and compute shaders,
 * build their programs with this small class instead:
 *
 * 1. the owner sets the stage sources once (embedded `glsl/*.glsl` strings) and
 *    optional compile-time defines;
 * 2. the first Bind() compiles and links; later binds only call glUseProgram, so
 *    nothing is recompiled per frame (a define or source change triggers one
 *    recompile at the next Bind());
 * 3. Unbind() hands the context back to VTK's shader cache, so VTK's own mappers
 *    re-bind their programs afterwards;
 * 4. ReleaseGraphicsResources() deletes the GL program.
 *
 * Every source gets `#version 450 core`, then the defines, then the binding
 * table shared with the host (vtkCausticsBindings.h), then the common include
 * (vtkCausticsCommon.glsl), prepended. A program with the define
 * CAUSTICS_MEDIUM_GRID also gets NanoVDB's PNanoVDB.h (as GLSL) before the common
 * include, reading the density grid's storage buffer: only the programs that follow a
 * heterogeneous medium pay for its compilation.
 */

#ifndef vtkCausticsShaderProgram_h
#define vtkCausticsShaderProgram_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class vtkOpenGLRenderWindow;
class vtkWindow;

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsShaderProgram : public vtkObject
{
public:
  static vtkCausticsShaderProgram* New();
  vtkTypeMacro(vtkCausticsShaderProgram, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Stage sources. Either vertex+fragment (geometry optional) or compute alone.
   * A name for error messages is given with SetName().
   */
  void SetVertexSource(const char* source);
  void SetGeometrySource(const char* source);
  void SetFragmentSource(const char* source);
  void SetComputeSource(const char* source);
  void SetName(const char* name);
  const char* GetName() const;
  ///@}

  /**
   * Sets a `#define name value` line. Changing a value recompiles at the next Bind().
   */
  void SetDefine(const char* name, const char* value);
  void SetDefine(const char* name, int value);
  /** Drops a define (recompiles at the next Bind() if it was set). */
  void RemoveDefine(const char* name);
  bool HasDefine(const char* name) const;

  /**
   * Compiles and links if needed, then makes this program current.
   * Returns false (and reports the compiler log through vtkErrorMacro) on failure.
   */
  bool Bind(vtkOpenGLRenderWindow* renWin);

  /**
   * Makes no program current and tells VTK's shader cache, so that VTK's mappers
   * bind their own programs again.
   */
  void Unbind(vtkOpenGLRenderWindow* renWin);

  /** True once compiled and linked. */
  bool IsReady() const;

  /** Last compile or link error, empty when none. */
  const char* GetLastError() const;

  ///@{
  /**
   * Uniform setters; the program must be bound. Unknown names are ignored (the
   * GLSL compiler drops unused uniforms), as VTK's vtkShaderProgram does not.
   */
  void SetUniformi(const char* name, int v);
  void SetUniformu(const char* name, unsigned int v);
  void SetUniformf(const char* name, float v);
  void SetUniform2i(const char* name, int x, int y);
  void SetUniform2f(const char* name, float x, float y);
  void SetUniform3f(const char* name, float x, float y, float z);
  void SetUniform3f(const char* name, const float v[3]);
  void SetUniform4f(const char* name, const float v[4]);
  void SetUniformMatrix4(const char* name, const float* columnMajor16);
  void SetUniformMatrix3(const char* name, const float* columnMajor9);
  ///@}

  /** glDispatchCompute with work group counts, then nothing else. */
  void Dispatch(unsigned int x, unsigned int y = 1, unsigned int z = 1);

  /** Dispatch enough groups of the given local size to cover count x count2 items. */
  void DispatchCovering(unsigned int items, unsigned int localSize);
  void DispatchCovering2D(unsigned int w, unsigned int h, unsigned int localW, unsigned int localH);

  /** Deletes the GL program. */
  void ReleaseGraphicsResources(vtkWindow* win);

  ///@{
  /**
   * Programs compiled and linked by every instance in this process, and the wall
   * time (ms) their glCompileShader/glLinkProgram calls took: where a process's first
   * frame spends on compilation (the driver may still compile per draw state, e.g.
   * llvmpipe's shader variants, inside the stages). Thread-safe.
   */
  static long long GetNumberOfBuilds();
  static double GetBuildMilliseconds();
  ///@}

protected:
  vtkCausticsShaderProgram();
  ~vtkCausticsShaderProgram() override;

private:
  vtkCausticsShaderProgram(const vtkCausticsShaderProgram&) = delete;
  void operator=(const vtkCausticsShaderProgram&) = delete;

  bool Build();
  int Location(const char* name);

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
