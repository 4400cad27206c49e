// Compiles a compute program, runs it, checks its output; checks that a broken
// program reports its compiler log instead of crashing; and that a VTK actor
// still renders after our program was bound (shader-cache hand-back).
#include "vtkCausticsShaderProgram.h"

#include "vtkActor.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"
#include "vtk_glew.h"

#include <cmath>
#include <iostream>
#include <vector>

int TestCausticsShaderProgram(int, char*[])
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  vtkNew<vtkRenderWindow> window;
  window->SetMultiSamples(0);
  window->SetOffScreenRendering(1);
  window->SetSize(64, 64);
  window->AddRenderer(renderer);
  window->Render();
  auto* glWindow = vtkOpenGLRenderWindow::SafeDownCast(window);

  vtkNew<vtkCausticsShaderProgram> program;
  program->SetName("square");
  program->SetDefine("SCALE", 3);
  program->SetComputeSource(R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Data { float values[]; };
void main() { uint i = gl_GlobalInvocationID.x; values[i] = SCALE * float(i * i); }
)");
  const int count = 256;
  GLuint buffer = 0;
  glGenBuffers(1, &buffer);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
  glBufferData(GL_SHADER_STORAGE_BUFFER, count * sizeof(float), nullptr, GL_DYNAMIC_READ);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
  if (!program->Bind(glWindow))
  {
    std::cerr << "compute program failed: " << program->GetLastError() << "\n";
    return EXIT_FAILURE;
  }
  program->DispatchCovering(count, 64);
  program->Unbind(glWindow);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<float> values(count);
  glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, count * sizeof(float), values.data());
  glDeleteBuffers(1, &buffer);
  for (int i = 0; i < count; ++i)
  {
    if (std::abs(values[i] - 3.0f * i * i) > 1e-3f * (1.0f + 3.0f * i * i))
    {
      std::cerr << "value " << i << " is " << values[i] << "\n";
      return EXIT_FAILURE;
    }
  }
  program->ReleaseGraphicsResources(window);

  // A syntax error must be reported, not crash, and not be retried every call.
  vtkNew<vtkCausticsShaderProgram> broken;
  broken->SetName("broken");
  broken->SetComputeSource("layout(local_size_x = 1) in; void main() { this is not glsl; }");
  vtkNew<vtkTest::ErrorObserver> errors;
  broken->AddObserver(vtkCommand::ErrorEvent, errors);
  if (broken->Bind(glWindow) ||
    std::string(broken->GetLastError()).find("compute") == std::string::npos)
  {
    std::cerr << "broken program was not reported: '" << broken->GetLastError() << "'\n";
    return EXIT_FAILURE;
  }
  if (!errors->GetError())
  {
    std::cerr << "the compile failure was not reported through vtkErrorMacro\n";
    return EXIT_FAILURE;
  }
  errors->Clear();
  if (broken->Bind(glWindow) || errors->GetError())
  {
    std::cerr << "a failed program must be reported once, not on every Bind()\n";
    return EXIT_FAILURE;
  }
  broken->ReleaseGraphicsResources(window);

  // VTK renders normally after our program was current.
  window->Render();
  unsigned char* pixels = window->GetPixelData(32, 32, 32, 32, 1);
  const bool sphereDrawn = pixels[0] + pixels[1] + pixels[2] > 0;
  delete[] pixels;
  if (!sphereDrawn)
  {
    std::cerr << "VTK did not draw the sphere after our program was bound\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
