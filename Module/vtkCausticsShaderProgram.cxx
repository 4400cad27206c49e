#include "vtkCausticsShaderProgram.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtk_glew.h"

#include "vtkCausticsBindingsSource.h" // embedded vtkCausticsBindings.h
#include "vtkCausticsCommon.h"         // embedded glsl/vtkCausticsCommon.glsl
#include "vtkCausticsPNanoVDBSource.h" // embedded nanovdb/PNanoVDB.h

#include <atomic>
#include <chrono>
#include <map>
#include <sstream>
#include <unordered_map>

vtkStandardNewMacro(vtkCausticsShaderProgram);

struct vtkCausticsShaderProgram::Internals
{
  std::string Name = "unnamed";
  std::string Vertex, Geometry, Fragment, Compute;
  std::map<std::string, std::string> Defines;
  GLuint Program = 0;
  bool Dirty = true;
  bool Failed = false;
  std::string LastError;
  std::unordered_map<std::string, GLint> Locations;
};

vtkCausticsShaderProgram::vtkCausticsShaderProgram()
  : Internal(new Internals)
{
}

vtkCausticsShaderProgram::~vtkCausticsShaderProgram()
{
  if (this->Internal->Program != 0)
  {
    vtkErrorMacro(<< "program '" << this->Internal->Name
                  << "' destroyed before ReleaseGraphicsResources(): GL program leaked");
  }
}

void vtkCausticsShaderProgram::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Name: " << this->Internal->Name << "\n";
  os << indent << "Kind: " << (this->Internal->Compute.empty() ? "raster" : "compute") << "\n";
  os << indent << "Ready: " << this->IsReady() << "\n";
  os << indent << "Defines: " << this->Internal->Defines.size() << "\n";
  for (const auto& define : this->Internal->Defines)
  {
    os << indent.GetNextIndent() << define.first << " = " << define.second << "\n";
  }
  if (!this->Internal->LastError.empty())
  {
    os << indent << "LastError: " << this->Internal->LastError << "\n";
  }
}

namespace
{
// Every instance's builds in this process (GetNumberOfBuilds, GetBuildMilliseconds).
std::atomic<long long> Builds{ 0 };
std::atomic<long long> BuildNanoseconds{ 0 };

void AssignSource(std::string& target, const char* source, bool& dirty)
{
  const std::string value = source ? source : "";
  if (value != target)
  {
    target = value;
    dirty = true;
  }
}

const char* StageName(GLenum stage)
{
  switch (stage)
  {
    case GL_VERTEX_SHADER:
      return "vertex";
    case GL_GEOMETRY_SHADER:
      return "geometry";
    case GL_FRAGMENT_SHADER:
      return "fragment";
    default:
      return "compute";
  }
}

/**
 * What every stage's source starts with: the version, the defines, then the
 * binding table (the common include declares the material table at
 * CAUSTICS_MATERIAL_BINDING, and the stages name their buffers' binding points)
 * and the common include.
 */
std::string SourcePrefix(const std::map<std::string, std::string>& defines)
{
  std::ostringstream header;
  header << "#version 450 core\n";
  for (const auto& define : defines)
  {
    header << "#define " << define.first << " " << define.second << "\n";
  }
  header << vtkCausticsBindingsSource << "\n";
  if (defines.count("CAUSTICS_MEDIUM_GRID"))
  {
    // PNanoVDB's GLSL reads its buffer as the global array pnanovdb_buf_data.
    header << "#define PNANOVDB_GLSL\n"
              "layout(std430, binding = CAUSTICS_MEDIUM_GRID_BINDING) readonly buffer "
              "CausticsMediumGrid\n{\n  uint pnanovdb_buf_data[];\n};\n"
           << vtkCausticsPNanoVDBSource << "\n";
  }
  header << vtkCausticsCommon << "\n#line 1\n";
  return header.str();
}

/** Compiles one stage; on failure `error` gets the program's name and the log. */
bool CompileStage(GLuint shader, GLenum stage, const std::string& source, const std::string& name,
  std::string& error)
{
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint status = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &status);
  if (status)
  {
    return true;
  }
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(std::max(length, 1), '\0');
  glGetShaderInfoLog(shader, length, nullptr, &log[0]);
  error = "program '" + name + "': " + StageName(stage) + " shader failed to compile:\n" + log;
  return false;
}

/** Links the program; on failure `error` gets the program's name and the log. */
bool LinkProgram(GLuint program, const std::string& name, std::string& error)
{
  glLinkProgram(program);
  GLint status = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &status);
  if (status)
  {
    return true;
  }
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(std::max(length, 1), '\0');
  glGetProgramInfoLog(program, length, nullptr, &log[0]);
  error = "program '" + name + "' failed to link:\n" + log;
  return false;
}
}

void vtkCausticsShaderProgram::SetVertexSource(const char* source)
{
  AssignSource(this->Internal->Vertex, source, this->Internal->Dirty);
}
void vtkCausticsShaderProgram::SetGeometrySource(const char* source)
{
  AssignSource(this->Internal->Geometry, source, this->Internal->Dirty);
}
void vtkCausticsShaderProgram::SetFragmentSource(const char* source)
{
  AssignSource(this->Internal->Fragment, source, this->Internal->Dirty);
}
void vtkCausticsShaderProgram::SetComputeSource(const char* source)
{
  AssignSource(this->Internal->Compute, source, this->Internal->Dirty);
}
void vtkCausticsShaderProgram::SetName(const char* name)
{
  this->Internal->Name = name ? name : "unnamed";
}
const char* vtkCausticsShaderProgram::GetName() const
{
  return this->Internal->Name.c_str();
}

void vtkCausticsShaderProgram::SetDefine(const char* name, const char* value)
{
  auto& current = this->Internal->Defines[name];
  if (current != value)
  {
    current = value;
    this->Internal->Dirty = true;
  }
}

void vtkCausticsShaderProgram::RemoveDefine(const char* name)
{
  if (this->Internal->Defines.erase(name))
  {
    this->Internal->Dirty = true;
  }
}

bool vtkCausticsShaderProgram::HasDefine(const char* name) const
{
  return this->Internal->Defines.count(name) != 0;
}

void vtkCausticsShaderProgram::SetDefine(const char* name, int value)
{
  this->SetDefine(name, std::to_string(value).c_str());
}

bool vtkCausticsShaderProgram::IsReady() const
{
  return this->Internal->Program != 0 && !this->Internal->Dirty;
}

const char* vtkCausticsShaderProgram::GetLastError() const
{
  return this->Internal->LastError.c_str();
}

bool vtkCausticsShaderProgram::Build()
{
  auto& in = *this->Internal;
  if (in.Program != 0)
  {
    glDeleteProgram(in.Program);
    in.Program = 0;
  }
  in.Locations.clear();
  in.LastError.clear();
  std::vector<std::pair<GLenum, const std::string*>> stages;
  if (!in.Compute.empty())
  {
    stages.emplace_back(GL_COMPUTE_SHADER, &in.Compute);
  }
  else if (in.Vertex.empty() || in.Fragment.empty())
  {
    in.LastError = "program '" + in.Name + "' needs vertex and fragment sources";
    return false;
  }
  else
  {
    stages.emplace_back(GL_VERTEX_SHADER, &in.Vertex);
    if (!in.Geometry.empty())
    {
      stages.emplace_back(GL_GEOMETRY_SHADER, &in.Geometry);
    }
    stages.emplace_back(GL_FRAGMENT_SHADER, &in.Fragment);
  }

  const auto start = std::chrono::steady_clock::now();
  const std::string prefix = SourcePrefix(in.Defines);
  const GLuint program = glCreateProgram();
  std::vector<GLuint> shaders;
  bool ok = true;
  for (const auto& stage : stages)
  {
    shaders.push_back(glCreateShader(stage.first));
    ok = CompileStage(shaders.back(), stage.first, prefix + *stage.second, in.Name, in.LastError) &&
      ok;
    glAttachShader(program, shaders.back());
  }
  ok = ok && LinkProgram(program, in.Name, in.LastError);
  for (GLuint shader : shaders)
  {
    glDetachShader(program, shader);
    glDeleteShader(shader);
  }
  ++Builds;
  BuildNanoseconds += std::chrono::duration_cast<std::chrono::nanoseconds>(
    std::chrono::steady_clock::now() - start)
                        .count();
  if (!ok)
  {
    glDeleteProgram(program);
    return false;
  }
  in.Program = program;
  in.Dirty = false;
  return true;
}

bool vtkCausticsShaderProgram::Bind(vtkOpenGLRenderWindow* renWin)
{
  auto& in = *this->Internal;
  // VTK's shader cache skips glUseProgram when it believes its program is still
  // current; release it so VTK re-binds after our stage.
  renWin->GetShaderCache()->ReleaseCurrentShader();
  if (in.Dirty || in.Program == 0)
  {
    if (in.Failed && !in.Dirty)
    {
      return false; // already reported; do not spam the log every frame
    }
    if (!this->Build())
    {
      in.Failed = true;
      in.Dirty = false;
      vtkErrorMacro(<< in.LastError);
      return false;
    }
    in.Failed = false;
  }
  glUseProgram(in.Program);
  return true;
}

void vtkCausticsShaderProgram::Unbind(vtkOpenGLRenderWindow* renWin)
{
  glUseProgram(0);
  renWin->GetShaderCache()->ReleaseCurrentShader();
}

int vtkCausticsShaderProgram::Location(const char* name)
{
  auto& in = *this->Internal;
  auto it = in.Locations.find(name);
  if (it == in.Locations.end())
  {
    it = in.Locations.emplace(name, glGetUniformLocation(in.Program, name)).first;
  }
  return it->second;
}

void vtkCausticsShaderProgram::SetUniformi(const char* name, int v)
{
  glUniform1i(this->Location(name), v);
}
void vtkCausticsShaderProgram::SetUniformu(const char* name, unsigned int v)
{
  glUniform1ui(this->Location(name), v);
}
void vtkCausticsShaderProgram::SetUniformf(const char* name, float v)
{
  glUniform1f(this->Location(name), v);
}
void vtkCausticsShaderProgram::SetUniform2i(const char* name, int x, int y)
{
  glUniform2i(this->Location(name), x, y);
}
void vtkCausticsShaderProgram::SetUniform2f(const char* name, float x, float y)
{
  glUniform2f(this->Location(name), x, y);
}
void vtkCausticsShaderProgram::SetUniform3f(const char* name, float x, float y, float z)
{
  glUniform3f(this->Location(name), x, y, z);
}
void vtkCausticsShaderProgram::SetUniform3f(const char* name, const float v[3])
{
  glUniform3fv(this->Location(name), 1, v);
}
void vtkCausticsShaderProgram::SetUniform4f(const char* name, const float v[4])
{
  glUniform4fv(this->Location(name), 1, v);
}
void vtkCausticsShaderProgram::SetUniformMatrix4(const char* name, const float* m)
{
  glUniformMatrix4fv(this->Location(name), 1, GL_FALSE, m);
}
void vtkCausticsShaderProgram::SetUniformMatrix3(const char* name, const float* m)
{
  glUniformMatrix3fv(this->Location(name), 1, GL_FALSE, m);
}

void vtkCausticsShaderProgram::Dispatch(unsigned int x, unsigned int y, unsigned int z)
{
  if (x > 0 && y > 0 && z > 0)
  {
    glDispatchCompute(x, y, z);
  }
}

void vtkCausticsShaderProgram::DispatchCovering(unsigned int items, unsigned int localSize)
{
  this->Dispatch((items + localSize - 1) / localSize);
}

void vtkCausticsShaderProgram::DispatchCovering2D(
  unsigned int w, unsigned int h, unsigned int localW, unsigned int localH)
{
  this->Dispatch((w + localW - 1) / localW, (h + localH - 1) / localH);
}

void vtkCausticsShaderProgram::ReleaseGraphicsResources(vtkWindow*)
{
  auto& in = *this->Internal;
  if (in.Program != 0)
  {
    glDeleteProgram(in.Program);
    in.Program = 0;
  }
  in.Locations.clear();
  in.Dirty = true;
  in.Failed = false;
}

long long vtkCausticsShaderProgram::GetNumberOfBuilds()
{
  return Builds;
}

double vtkCausticsShaderProgram::GetBuildMilliseconds()
{
  return 1e-6 * static_cast<double>(BuildNanoseconds);
}
