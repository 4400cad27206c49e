// caustics-ceilings: this machine's OpenGL throughput ceilings for the two kinds of
// work that dominate the caustics stages, measured with plain GL in an off-screen
// VTK (or EGL) window, so that docs/benchmarks.md can say how far each stage is
// from what the implementation can do at all:
//
// 1. one-pixel point splats with additive blending into an RGBA32F target (the
//    photon splats), in splats/s;
// 2. horizontal lines whose fragments each do 8 texel fetches from a 2D array
//    texture and write an RG32UI texel (the screen-space line tracer), in
//    fragments/s.
//
//   caustics-ceilings [--size N] [--splats N] [--lines N] [--line-length N] [--repeats N]
//
// Each ceiling is drawn once untimed, once with its GPU work counted
// (vtkCausticsTimings::CountWork: the counted fragments must equal the drawn ones,
// which checks the counting the benchmark relies on), then timed: glFinish, draw,
// glFinish, median over the repeats.
#include "CausticsCommandLine.h"

#include "vtkCausticsTimings.h"
#include "vtkCausticsWindowFactory.h"

#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderer.h"
#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace
{
using caustics_cli::NoWindowError;
using caustics_cli::UsageError;

const char* Usage = R"(usage: caustics-ceilings [options]

Measures this machine's OpenGL throughput ceilings for the caustics stages' two
main kinds of work (plain GL, off-screen window; median over repeats):
  splats   one-pixel points, additive blending into an RGBA32F target (splats/s)
  lines    horizontal lines, 8 texel fetches per fragment from a 2D array
           texture, RG32UI output (fragments/s)
It also checks that vtkCausticsTimings counts the fragments drawn (CountWork).

Options:
  --size N                   side of the splat target and of the fetched texture
                             layers, 16..4096 (default 256)
  --splats N                 points per repeat, 1..1e8 (default 1048576)
  --lines N                  lines per repeat (the line target's height),
                             1..16384 (default 4096)
  --line-length N            fragments per line (the line target's width),
                             1..16384 (default 256)
  --repeats N                timed repeats, 1..100 (default 7)
  --help                     this text
)";

struct Options
{
  int Size = 256;
  int Splats = 1 << 20;
  int Lines = 4096;
  int LineLength = 256;
  int Repeats = 7;
  bool Help = false;
};

Options Parse(int argc, char* argv[])
{
  Options options;
  caustics_cli::Arguments arguments;
  using caustics_cli::ParseInteger;
  arguments.Flag("--help", [&] { options.Help = true; });
  arguments.Flag("-h", [&] { options.Help = true; });
  arguments.Value("--size",
    [&](const std::string& option, const std::string& value)
    { options.Size = ParseInteger(option, value, 16, 4096); });
  arguments.Value("--splats",
    [&](const std::string& option, const std::string& value)
    { options.Splats = static_cast<int>(caustics_cli::ParseCount(option, value, 1, 1e8)); });
  arguments.Value("--lines",
    [&](const std::string& option, const std::string& value)
    { options.Lines = ParseInteger(option, value, 1, 16384); });
  arguments.Value("--line-length",
    [&](const std::string& option, const std::string& value)
    { options.LineLength = ParseInteger(option, value, 1, 16384); });
  arguments.Value("--repeats",
    [&](const std::string& option, const std::string& value)
    { options.Repeats = ParseInteger(option, value, 1, 100); });
  for (const auto& positional : arguments.Parse(argc, argv))
  {
    throw UsageError("unexpected argument '" + positional + "' (see --help)");
  }
  return options;
}

// ---------------------------------------------------------------------------
// Plain GL: programs and render targets.
// ---------------------------------------------------------------------------

GLuint CompileStage(GLenum type, const char* source, const char* name)
{
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok)
  {
    char log[2048] = "";
    glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
    std::string message = log;
    std::replace(message.begin(), message.end(), '\n', ' ');
    throw std::runtime_error(std::string(name) + " does not compile: " + message);
  }
  return shader;
}

GLuint MakeProgram(const char* vertex, const char* fragment, const char* name)
{
  const GLuint program = glCreateProgram();
  const GLuint vs = CompileStage(GL_VERTEX_SHADER, vertex, name);
  const GLuint fs = CompileStage(GL_FRAGMENT_SHADER, fragment, name);
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok)
  {
    throw std::runtime_error(std::string(name) + " does not link");
  }
  return program;
}

/** A width x height texture of `format` and a framebuffer drawing into it. */
struct Target
{
  GLuint Texture = 0;
  GLuint Framebuffer = 0;
  int Width = 0, Height = 0;

  void Create(GLenum format, int width, int height)
  {
    this->Width = width;
    this->Height = height;
    glCreateTextures(GL_TEXTURE_2D, 1, &this->Texture);
    glTextureStorage2D(this->Texture, 1, format, width, height);
    glCreateFramebuffers(1, &this->Framebuffer);
    glNamedFramebufferTexture(this->Framebuffer, GL_COLOR_ATTACHMENT0, this->Texture, 0);
    if (glCheckNamedFramebufferStatus(this->Framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    {
      throw std::runtime_error("a render target is incomplete");
    }
  }
  void Bind() const
  {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, this->Framebuffer);
    glViewport(0, 0, this->Width, this->Height);
  }
  void Release()
  {
    glDeleteFramebuffers(1, &this->Framebuffer);
    glDeleteTextures(1, &this->Texture);
  }
};

// ---------------------------------------------------------------------------
// The two ceilings.
// ---------------------------------------------------------------------------

// Points scattered by a hash of their index over the whole target, one pixel each.
const char* SplatVS = R"(#version 450 core
uniform ivec2 size;
void main()
{
  uint h = uint(gl_VertexID) * 2654435761u;
  h ^= h >> 15;
  h *= 2246822519u;
  h ^= h >> 13;
  uvec2 pixel = uvec2(h % uint(size.x), (h / uint(size.x)) % uint(size.y));
  gl_Position = vec4((vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0, 0.0, 1.0);
  gl_PointSize = 1.0;
}
)";
const char* SplatFS = R"(#version 450 core
layout(location = 0) out vec4 flux;
void main() { flux = vec4(1.0e-3, 2.0e-3, 3.0e-3, 1.0); }
)";

// Line i covers row i from x = 0.25 to length + 0.25: exactly `length` fragments.
const char* LineVS = R"(#version 450 core
uniform ivec2 size; // length, lines
void main()
{
  float x = (gl_VertexID % 2 == 0 ? 0.25 : float(size.x) + 0.25) / float(size.x);
  float y = (float(gl_VertexID / 2) + 0.5) / float(size.y);
  gl_Position = vec4(vec2(x, y) * 2.0 - 1.0, 0.0, 1.0);
}
)";
const char* LineFS = R"(#version 450 core
uniform sampler2DArray layers;
layout(location = 0) out uvec2 hit;
void main()
{
  ivec3 extent = textureSize(layers, 0);
  ivec2 pixel = ivec2(gl_FragCoord.xy) % extent.xy;
  vec4 sum = vec4(0.0);
  for (int layer = 0; layer < 8; ++layer)
  {
    sum += texelFetch(layers, ivec3(pixel, layer), 0);
  }
  hit = uvec2(floatBitsToUint(sum.x + sum.y), floatBitsToUint(sum.z + sum.w));
}
)";

/** One ceiling: how to draw a repeat, the work it does, and what was measured. */
struct Ceiling
{
  std::string Name;
  std::string Unit;         // what the rate counts: "splats", "fragments"
  long long Primitives = 0; // drawn per repeat
  long long Fragments = 0;  // expected per repeat
  long long Counted = -1;   // counted by vtkCausticsTimings (-1: no counters)
  std::vector<double> Seconds;
  std::function<void()> Draw;
  double PerSecond() const;
};

double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double Ceiling::PerSecond() const
{
  const double units = this->Unit == "splats" ? this->Primitives : this->Fragments;
  return units / Median(this->Seconds);
}

/** The splat ceiling's GL objects: a program and an RGBA32F target, blended additively. */
struct SplatScene
{
  GLuint Program = 0;
  GLuint VertexArray = 0;
  Target Flux;

  void Create(const Options& options)
  {
    this->Program = MakeProgram(SplatVS, SplatFS, "the splat program");
    glCreateVertexArrays(1, &this->VertexArray);
    this->Flux.Create(GL_RGBA32F, options.Size, options.Size);
  }
  void Draw(int splats) const
  {
    this->Flux.Bind();
    glUseProgram(this->Program);
    glUniform2i(glGetUniformLocation(this->Program, "size"), this->Flux.Width, this->Flux.Height);
    glBindVertexArray(this->VertexArray);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glDrawArrays(GL_POINTS, 0, splats);
    glDisable(GL_BLEND);
  }
  void Release()
  {
    glDeleteProgram(this->Program);
    glDeleteVertexArrays(1, &this->VertexArray);
    this->Flux.Release();
  }
};

/** The line ceiling's GL objects: a program, 8 RGBA32F layers to fetch, an RG32UI target. */
struct LineScene
{
  GLuint Program = 0;
  GLuint VertexArray = 0;
  GLuint Layers = 0;
  Target Hits;

  void Create(const Options& options)
  {
    this->Program = MakeProgram(LineVS, LineFS, "the line program");
    glCreateVertexArrays(1, &this->VertexArray);
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &this->Layers);
    glTextureStorage3D(this->Layers, 1, GL_RGBA32F, options.Size, options.Size, 8);
    const std::vector<float> texels(
      static_cast<std::size_t>(options.Size) * options.Size * 4, 0.5f);
    for (int layer = 0; layer < 8; ++layer)
    {
      glTextureSubImage3D(this->Layers, 0, 0, 0, layer, options.Size, options.Size, 1, GL_RGBA,
        GL_FLOAT, texels.data());
    }
    this->Hits.Create(GL_RG32UI, options.LineLength, options.Lines);
  }
  void Draw() const
  {
    this->Hits.Bind();
    glUseProgram(this->Program);
    glUniform2i(glGetUniformLocation(this->Program, "size"), this->Hits.Width, this->Hits.Height);
    glUniform1i(glGetUniformLocation(this->Program, "layers"), 0);
    glBindTextureUnit(0, this->Layers);
    glBindVertexArray(this->VertexArray);
    glDrawArrays(GL_LINES, 0, 2 * this->Hits.Height);
  }
  void Release()
  {
    glDeleteProgram(this->Program);
    glDeleteVertexArrays(1, &this->VertexArray);
    glDeleteTextures(1, &this->Layers);
    this->Hits.Release();
  }
};

// ---------------------------------------------------------------------------
// The run.
// ---------------------------------------------------------------------------

/** An off-screen window with its context current (one frame rendered). */
vtkSmartPointer<vtkOpenGLRenderWindow> MakeContext(std::string& how)
{
  vtkSmartPointer<vtkRenderWindow> window = vtkCausticsWindowFactory::Create(true, &how);
  auto* glWindow = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!glWindow)
  {
    throw NoWindowError(how.empty() ? "no OpenGL window" : how);
  }
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  window->SetMultiSamples(0);
  window->SetSize(16, 16);
  window->Render();
  window->RemoveRenderer(renderer);
  glWindow->MakeCurrent();
  // VTK leaves its window's scissor box (16 x 16 here) and tests enabled: draw everywhere.
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  int major = 0, minor = 0;
  glWindow->GetOpenGLVersion(major, minor);
  if (major * 10 + minor < 45)
  {
    throw std::runtime_error(
      "needs OpenGL 4.5; this context is " + std::to_string(major) + "." + std::to_string(minor));
  }
  return glWindow;
}

/** What vtkCausticsTimings counted for the named stage: fragments written, primitives. */
std::pair<long long, long long> Counted(vtkCausticsTimings* timings, const std::string& name)
{
  for (int s = 0; s < timings->GetNumberOfStages(); ++s)
  {
    if (name == timings->GetStageName(s))
    {
      return { timings->GetStageWork(s, vtkCausticsTimings::FRAGMENTS_WRITTEN),
        timings->GetStageWork(s, vtkCausticsTimings::PRIMITIVES_SUBMITTED) };
    }
  }
  return { -1, -1 };
}

/**
 * Draws every ceiling once inside an enclosing stage with CountWork on, and checks
 * what vtkCausticsTimings counted: each ceiling's fragments and primitives, and the
 * enclosing stage's as their sums (a nested stage's work counts in its parent's).
 */
void CountWork(std::vector<Ceiling>& ceilings, vtkCausticsTimings* timings)
{
  timings->CountWorkOn();
  timings->BeginFrame();
  timings->StartStage("all ceilings");
  for (const Ceiling& ceiling : ceilings)
  {
    timings->StartStage(ceiling.Name.c_str());
    ceiling.Draw();
    timings->StopStage(ceiling.Name.c_str());
  }
  timings->StopStage("all ceilings");
  timings->EndFrame();
  const auto all = Counted(timings, "all ceilings");
  if (all.first < 0)
  {
    return; // no pipeline statistics queries here: nothing to check
  }
  std::pair<long long, long long> sum{ 0, 0 };
  for (Ceiling& ceiling : ceilings)
  {
    const auto counted = Counted(timings, ceiling.Name);
    ceiling.Counted = counted.first;
    sum = { sum.first + counted.first, sum.second + counted.second };
    if (counted.first != ceiling.Fragments || counted.second != ceiling.Primitives)
    {
      throw std::runtime_error("vtkCausticsTimings counted " + std::to_string(counted.first) +
        " fragments and " + std::to_string(counted.second) + " primitives for " + ceiling.Name +
        ", " + std::to_string(ceiling.Fragments) + " and " + std::to_string(ceiling.Primitives) +
        " drawn");
    }
  }
  if (all != sum)
  {
    throw std::runtime_error("vtkCausticsTimings counted " + std::to_string(all.first) +
      " fragments for the enclosing stage, " + std::to_string(sum.first) + " in its nested stages");
  }
}

/** glFinish, draw, glFinish: the wall time of one repeat, `repeats` times. */
void Time(Ceiling& ceiling, int repeats)
{
  ceiling.Draw(); // untimed: first-use costs (shader variants, texture residency)
  for (int repeat = 0; repeat < repeats; ++repeat)
  {
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    ceiling.Draw();
    glFinish();
    ceiling.Seconds.push_back(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
}

std::string Millions(double value)
{
  std::ostringstream text;
  text << std::fixed << std::setprecision(value >= 1e7 ? 1 : 2) << value / 1e6 << " M";
  return text.str();
}

void PrintTable(const std::vector<Ceiling>& ceilings, const std::string& how, int repeats)
{
  const char* threads = std::getenv("LP_NUM_THREADS");
  std::cout << "caustics-ceilings: " << glGetString(GL_RENDERER) << ", OpenGL "
            << glGetString(GL_VERSION) << ", window " << how << ", "
            << std::thread::hardware_concurrency() << " hardware threads, LP_NUM_THREADS "
            << (threads ? threads : "unset") << "; median of " << repeats << " repeat(s)\n";
  std::cout << std::left << std::setw(44) << "ceiling" << std::right << std::setw(12)
            << "primitives" << std::setw(12) << "fragments" << std::setw(12) << "counted"
            << std::setw(11) << "median ms"
            << "  rate\n";
  for (const Ceiling& ceiling : ceilings)
  {
    std::cout << std::left << std::setw(44) << ceiling.Name << std::right << std::setw(12)
              << ceiling.Primitives << std::setw(12) << ceiling.Fragments << std::setw(12)
              << (ceiling.Counted < 0 ? std::string("-") : std::to_string(ceiling.Counted))
              << std::setw(11) << std::fixed << std::setprecision(2)
              << 1000.0 * Median(ceiling.Seconds) << "  " << Millions(ceiling.PerSecond()) << " "
              << ceiling.Unit << "/s\n";
  }
}

int Run(const Options& options)
{
  std::string how;
  vtkSmartPointer<vtkOpenGLRenderWindow> window = MakeContext(how);
  SplatScene splats;
  splats.Create(options);
  LineScene lines;
  lines.Create(options);
  const long long lineFragments = static_cast<long long>(options.Lines) * options.LineLength;
  std::vector<Ceiling> ceilings = {
    { "one-pixel splats, additive RGBA32F", "splats", options.Splats, options.Splats, -1, {},
      [&] { splats.Draw(options.Splats); } },
    { "lines, 8 texel fetches per fragment", "fragments", options.Lines, lineFragments, -1, {},
      [&] { lines.Draw(); } },
  };
  vtkNew<vtkCausticsTimings> timings;
  CountWork(ceilings, timings);
  for (Ceiling& ceiling : ceilings)
  {
    Time(ceiling, options.Repeats);
  }
  PrintTable(ceilings, how, options.Repeats);
  timings->ReleaseGraphicsResources();
  splats.Release();
  lines.Release();
  if (glGetError() != GL_NO_ERROR)
  {
    throw std::runtime_error("an OpenGL call failed");
  }
  return 0;
}
}

int main(int argc, char* argv[])
{
  return caustics_cli::RunMain("caustics-ceilings", caustics_cli::LoggedErrors::Fail,
    [&](caustics_cli::OneLineOutputWindow*)
    {
      const Options options = Parse(argc, argv);
      if (options.Help)
      {
        std::cout << Usage;
        return 0;
      }
      return Run(options);
    });
}
