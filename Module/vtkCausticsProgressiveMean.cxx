#include "vtkCausticsProgressiveMean.h"

#include "vtkCausticsScreenSpaceUtilities.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsProgressiveMeanCS.h"

#include <cmath>

vtkStandardNewMacro(vtkCausticsProgressiveMean);

struct vtkCausticsProgressiveMean::Internals
{
  caustics::ssp::Texture CausticMean; // RGBA32F, W/m^2
  caustics::ssp::Texture VolumeMean;  // RGBA32F, W/(m^2 sr)
  vtkNew<vtkCausticsShaderProgram> Program;
  std::vector<std::uint64_t> Key; // the run's inputs
  bool Running = false;           // Key holds a run
  int Frame = 0;                  // what the last Begin() returned
  int CausticFrames = 0;          // frames in each mean
  int VolumeFrames = 0;

  bool Fold(vtkOpenGLRenderWindow* renWin, vtkTextureObject* frame, caustics::ssp::Texture& mean,
    int& frames);
};

bool vtkCausticsProgressiveMean::Internals::Fold(
  vtkOpenGLRenderWindow* renWin, vtkTextureObject* frame, caustics::ssp::Texture& mean, int& frames)
{
  const int width = static_cast<int>(frame->GetWidth());
  const int height = static_cast<int>(frame->GetHeight());
  if (mean.Ensure(width, height, 0, GL_RGBA32F))
  {
    frames = 0; // a new size: nothing held
  }
  vtkCausticsShaderProgram* p = this->Program;
  if (!p->Bind(renWin))
  {
    return false;
  }
  p->SetUniform2i("size", width, height);
  p->SetUniformf("weight", 1.0f / static_cast<float>(frames + 1));
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
  glBindImageTexture(0, frame->GetHandle(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  glBindImageTexture(1, mean.Handle, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  p->DispatchCovering2D(width, height, 16, 16);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  p->Unbind(renWin);
  ++frames;
  return true;
}

vtkCausticsProgressiveMean::vtkCausticsProgressiveMean()
  : Internal(new Internals)
{
  this->Internal->Program->SetName("progressive mean");
  this->Internal->Program->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  this->Internal->Program->SetComputeSource(vtkCausticsProgressiveMeanCS);
}

vtkCausticsProgressiveMean::~vtkCausticsProgressiveMean() = default;

int vtkCausticsProgressiveMean::GetFramesAveraged() const
{
  return this->Internal->Running ? this->Internal->CausticFrames : 0;
}

void vtkCausticsProgressiveMean::Reset()
{
  auto& in = *this->Internal;
  in.Running = false;
  in.Key.clear();
  in.CausticFrames = in.VolumeFrames = 0;
}

int vtkCausticsProgressiveMean::Begin(const std::vector<std::uint64_t>& key)
{
  auto& in = *this->Internal;
  if (this->Frames <= 1 || !in.Running || key != in.Key)
  {
    this->Reset();
    in.Key = key;
    in.Running = this->Frames > 1;
    in.Frame = 0;
    return 0;
  }
  in.Frame = in.CausticFrames >= this->Frames ? -1 : in.CausticFrames;
  return in.Frame;
}

bool vtkCausticsProgressiveMean::Add(
  vtkOpenGLRenderWindow* renWin, vtkTextureObject* caustic, vtkTextureObject* volume)
{
  auto& in = *this->Internal;
  if (!in.Running || in.Frame < 0 || !caustic)
  {
    return true; // not averaging, or the mean is complete
  }
  if (in.Frame == 0)
  {
    in.CausticFrames = in.VolumeFrames = 0;
  }
  bool ok = in.Fold(renWin, caustic, in.CausticMean, in.CausticFrames);
  if (ok && volume)
  {
    ok = in.Fold(renWin, volume, in.VolumeMean, in.VolumeFrames);
  }
  if (!ok)
  {
    this->Reset();
  }
  return ok;
}

void vtkCausticsProgressiveMean::GridOffset(int k, double offset[2])
{
  // R2 (the generalized golden ratio in 2-D), started at the cell's centre.
  const double a1 = 0.7548776662466927, a2 = 0.5698402909980532;
  const double n = k > 0 ? static_cast<double>(k) : 0.0;
  offset[0] = std::fmod(0.5 + a1 * n, 1.0) - 0.5;
  offset[1] = std::fmod(0.5 + a2 * n, 1.0) - 0.5;
}

void vtkCausticsProgressiveMean::ReleaseGraphicsResources(vtkWindow* win)
{
  auto& in = *this->Internal;
  in.CausticMean.Release();
  in.VolumeMean.Release();
  in.Program->ReleaseGraphicsResources(win);
  this->Reset();
}

void vtkCausticsProgressiveMean::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Frames: " << this->Frames << "\n";
  os << indent << "FramesAveraged: " << this->GetFramesAveraged() << "\n";
}
