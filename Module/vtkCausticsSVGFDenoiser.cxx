#include "vtkCausticsSVGFDenoiser.h"

#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsSVGFAtrousCS.h"
#include "vtkCausticsSVGFCommon.h"
#include "vtkCausticsSVGFReprojectCS.h"
#include "vtkCausticsSVGFTemporalCS.h"
#include "vtkCausticsSVGFVarianceCS.h"

#include <algorithm>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkCausticsSVGFDenoiser);

namespace
{
// The steps' programs, in the order Denoise() runs them.
enum Program
{
  REPROJECT = 0, // history at this frame's pixels
  TEMPORAL = 1,  // colour and moments accumulated
  VARIANCE = 2,  // luminance variance
  DEVIATION = 3, // a-trous: blurred deviation of luminance
  NORMALIZE = 4, // a-trous: first Sinkhorn step of the weights' balance
  BALANCE = 5,   // a-trous: second Sinkhorn step
  ATROUS = 6,    // a-trous: one wavelet iteration with the balanced weights
  PROGRAMS = 7
};

constexpr unsigned int LocalSize = 16; // the shaders' local_size_x/y

void BindImage(unsigned int unit, vtkTextureObject* texture, unsigned int access,
  unsigned int format = GL_RGBA32F)
{
  glBindImageTexture(unit, texture->GetHandle(), 0, GL_FALSE, 0, access, format);
}

void CopyTexture(vtkTextureObject* from, vtkTextureObject* to, int width, int height)
{
  glCopyImageSubData(from->GetHandle(), GL_TEXTURE_2D, 0, 0, 0, 0, to->GetHandle(), GL_TEXTURE_2D,
    0, 0, 0, 0, width, height, 1);
}

void Barrier()
{
  // Image stores, then image loads, copies or texture fetches (the composite).
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
}
}

struct vtkCausticsSVGFDenoiser::Internals
{
  vtkNew<vtkCausticsShaderProgram> Programs[PROGRAMS];
  vtkNew<vtkTextureObject> Raw;                // the input as it came (W/m^2)
  vtkNew<vtkTextureObject> HistoryColor;       // rgb W/m^2
  vtkNew<vtkTextureObject> HistoryMoments;     // m1, m2, frames
  vtkNew<vtkTextureObject> ReprojectedColor;   // the history at this frame's pixels
  vtkNew<vtkTextureObject> ReprojectedMoments; //
  vtkNew<vtkTextureObject> Filter[2];          // rgb W/m^2, a: variance (ping-pong)
  vtkNew<vtkTextureObject> Deviation;          // R32F: blurred deviation of luminance
  vtkNew<vtkTextureObject> Balance[2];         // R32F: the a-trous weights' balance
  vtkNew<vtkTextureObject> PreviousPosition;   // the last frame's G-buffer
  vtkNew<vtkTextureObject> PreviousNormal;     //
  vtkNew<vtkTextureObject> Counts;             // R32UI 2 x 1: receivers, reprojected
  float PreviousWorldToClip[16] = {};
  bool Released = true; // nothing allocated, or all released
};

vtkCausticsSVGFDenoiser::vtkCausticsSVGFDenoiser()
  : Internal(new Internals)
{
  const char* names[PROGRAMS] = { "SVGF reproject", "SVGF temporal", "SVGF variance",
    "SVGF a-trous deviation", "SVGF a-trous normalize", "SVGF a-trous balance", "SVGF a-trous" };
  const char* sources[PROGRAMS] = { vtkCausticsSVGFReprojectCS, vtkCausticsSVGFTemporalCS,
    vtkCausticsSVGFVarianceCS, vtkCausticsSVGFAtrousCS, vtkCausticsSVGFAtrousCS,
    vtkCausticsSVGFAtrousCS, vtkCausticsSVGFAtrousCS };
  for (int i = 0; i < PROGRAMS; ++i)
  {
    auto& program = this->Internal->Programs[i];
    program->SetName(names[i]);
    program->SetComputeSource((std::string(vtkCausticsSVGFCommon) + sources[i]).c_str());
    program->SetDefine("CAUSTICS_NO_MATERIALS", 1);
    if (i >= DEVIATION)
    {
      program->SetDefine("SVGF_ATROUS_STAGE", i - DEVIATION); // the shader's stages, in order
    }
  }
}

vtkCausticsSVGFDenoiser::~vtkCausticsSVGFDenoiser()
{
  if (!this->Internal->Released)
  {
    vtkErrorMacro(<< "destroyed with graphics resources not released: call "
                     "ReleaseGraphicsResources() first");
  }
}

void vtkCausticsSVGFDenoiser::ResetHistory()
{
  this->HasHistory = false;
}

vtkTextureObject* vtkCausticsSVGFDenoiser::GetRawTexture()
{
  return this->Internal->Raw;
}

bool vtkCausticsSVGFDenoiser::Denoise(const Inputs& in)
{
  if (!in.Window || !in.Irradiance || !in.GBuffer || !in.Camera || in.Width < 1 || in.Height < 1)
  {
    return false;
  }
  if (this->EnsureTextures(in))
  {
    this->HasHistory = false; // a new size: nothing of the last frame lines up
  }
  this->FramesSinceReset = this->HasHistory ? this->FramesSinceReset : 0;
  // Without a history nothing lit otherwise can linger: the light field counts as still.
  const int still = 1 << 30;
  const int sinceChange = in.LightChanged ? 0 : std::min(this->FramesSinceLightChanged + 1, still);
  this->FramesSinceLightChanged = this->HasHistory ? sinceChange : still;
  CopyTexture(in.Irradiance, this->Internal->Raw, in.Width, in.Height);
  const bool ok = this->Reproject(in) && this->Accumulate(in) && this->EstimateVariance(in) &&
    this->FilterAtrous(in);
  if (!ok)
  {
    CopyTexture(this->Internal->Raw, in.Irradiance, in.Width, in.Height);
    this->HasHistory = false;
    return false;
  }
  this->KeepForNextFrame(in);
  return true;
}

bool vtkCausticsSVGFDenoiser::EnsureTextures(const Inputs& in)
{
  auto& s = *this->Internal;
  s.Released = false;
  const int w = in.Width, h = in.Height;
  vtkTextureObject* colour[] = { s.Raw, s.HistoryColor, s.HistoryMoments, s.ReprojectedColor,
    s.ReprojectedMoments, s.Filter[0], s.Filter[1], s.PreviousPosition };
  bool resized = false;
  for (vtkTextureObject* texture : colour)
  {
    resized |= caustics::gl::EnsureTexture(texture, in.Window, w, h, GL_RGBA32F);
  }
  resized |= caustics::gl::EnsureTexture(s.PreviousNormal, in.Window, w, h, GL_RGBA16F);
  for (vtkTextureObject* texture : { s.Deviation.Get(), s.Balance[0].Get(), s.Balance[1].Get() })
  {
    resized |= caustics::gl::EnsureTexture(texture, in.Window, w, h, GL_R32F);
  }
  caustics::gl::EnsureTexture(s.Counts, in.Window, 2, 1, GL_R32UI);
  return resized;
}

void vtkCausticsSVGFDenoiser::SetCommonUniforms(const Inputs& in, int index)
{
  vtkCausticsShaderProgram* program = this->Internal->Programs[index];
  const caustics::Camera& camera = *in.Camera;
  program->SetUniform2i("size", in.Width, in.Height);
  program->SetUniform3f("eye", static_cast<float>(camera.position[0]),
    static_cast<float>(camera.position[1]), static_cast<float>(camera.position[2]));
  const double pi = std::acos(-1.0);
  const double angle = 2.0 * std::tan(0.5 * camera.viewAngle * pi / 180.0) / in.Height;
  program->SetUniformf("pixelAngle", camera.parallel ? 0.0f : static_cast<float>(angle));
  program->SetUniformf("pixelSize",
    camera.parallel ? static_cast<float>(2.0 * camera.parallelScale / in.Height) : 0.0f);
  program->SetUniformf("sigmaDepth", static_cast<float>(this->Settings.SigmaDepth));
  program->SetUniformf("sigmaNormal", static_cast<float>(this->Settings.SigmaNormal));
  BindImage(0, in.GBuffer->GetPositionTexture(), GL_READ_ONLY);
  BindImage(1, in.GBuffer->GetNormalTexture(), GL_READ_ONLY, GL_RGBA16F);
}

bool vtkCausticsSVGFDenoiser::Reproject(const Inputs& in)
{
  auto& s = *this->Internal;
  vtkCausticsShaderProgram* program = s.Programs[REPROJECT];
  if (!program->Bind(in.Window))
  {
    return false;
  }
  const unsigned int zero = 0;
  glClearTexImage(s.Counts->GetHandle(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  this->SetCommonUniforms(in, REPROJECT);
  BindImage(2, s.PreviousPosition, GL_READ_ONLY);
  BindImage(3, s.PreviousNormal, GL_READ_ONLY, GL_RGBA16F);
  BindImage(4, s.HistoryColor, GL_READ_ONLY);
  BindImage(5, s.HistoryMoments, GL_READ_ONLY);
  BindImage(6, s.ReprojectedColor, GL_WRITE_ONLY);
  BindImage(7, s.ReprojectedMoments, GL_WRITE_ONLY);
  BindImage(8, s.Counts, GL_READ_WRITE, GL_R32UI);
  program->SetUniformMatrix4("previousWorldToClip", s.PreviousWorldToClip);
  program->SetUniformi("hasHistory", this->HasHistory ? 1 : 0);
  program->SetUniformf("depthTolerance", static_cast<float>(this->Settings.DepthTolerance));
  program->SetUniformf("normalTolerance", static_cast<float>(this->Settings.NormalTolerance));
  program->DispatchCovering2D(in.Width, in.Height, LocalSize, LocalSize);
  Barrier();
  program->Unbind(in.Window);
  return true;
}

bool vtkCausticsSVGFDenoiser::Accumulate(const Inputs& in)
{
  auto& s = *this->Internal;
  vtkCausticsShaderProgram* program = s.Programs[TEMPORAL];
  if (!program->Bind(in.Window))
  {
    return false;
  }
  this->SetCommonUniforms(in, TEMPORAL);
  BindImage(2, in.Irradiance, GL_READ_ONLY);
  BindImage(3, s.ReprojectedColor, GL_READ_ONLY);
  BindImage(4, s.ReprojectedMoments, GL_READ_ONLY);
  BindImage(5, s.Filter[0], GL_WRITE_ONLY);
  BindImage(6, s.HistoryMoments, GL_WRITE_ONLY);
  BindImage(7, s.Counts, GL_READ_ONLY, GL_R32UI);
  const caustics::DenoiserSettings& settings = this->Settings;
  program->SetUniformf("temporalAlpha", static_cast<float>(settings.TemporalAlpha));
  program->SetUniformf("momentsAlpha", static_cast<float>(settings.MomentsAlpha));
  program->SetUniformf("maximumFrames", static_cast<float>(settings.MaximumHistoryLength));
  // Light moves over the receivers only while what lights them changes; a still light
  // field is left alone (the rejection would bias it, see the shader), once a history
  // from before the last change has had MaximumHistoryLength frames to fade.
  const bool lightStill = this->FramesSinceLightChanged > settings.MaximumHistoryLength;
  program->SetUniformf(
    "rejectSigmas", lightStill ? 0.0f : static_cast<float>(settings.HistoryRejectionSigmas));
  program->SetUniformf("minimumFraction", static_cast<float>(settings.MinimumReprojectedFraction));
  program->DispatchCovering2D(in.Width, in.Height, LocalSize, LocalSize);
  Barrier();
  program->Unbind(in.Window);
  return true;
}

bool vtkCausticsSVGFDenoiser::EstimateVariance(const Inputs& in)
{
  auto& s = *this->Internal;
  vtkCausticsShaderProgram* program = s.Programs[VARIANCE];
  if (!program->Bind(in.Window))
  {
    return false;
  }
  this->SetCommonUniforms(in, VARIANCE);
  BindImage(2, s.HistoryMoments, GL_READ_ONLY);
  BindImage(3, s.Filter[0], GL_READ_WRITE);
  program->SetUniformf("spatialFrames", static_cast<float>(this->Settings.SpatialVarianceFrames));
  program->DispatchCovering2D(in.Width, in.Height, LocalSize, LocalSize);
  Barrier();
  program->Unbind(in.Window);
  return true;
}

bool vtkCausticsSVGFDenoiser::FilterAtrous(const Inputs& in)
{
  auto& s = *this->Internal;
  const int iterations = this->Settings.AtrousIterations;
  const int keep = std::min(this->Settings.HistoryIteration, iterations);
  if (keep == 0)
  {
    CopyTexture(s.Filter[0], s.HistoryColor, in.Width, in.Height);
  }
  if (iterations == 0)
  {
    CopyTexture(s.Filter[0], in.Irradiance, in.Width, in.Height);
    Barrier();
    return true;
  }
  for (int i = 0; i < iterations; ++i)
  {
    // The last iteration writes the result where the input was.
    vtkTextureObject* source = s.Filter[i % 2];
    vtkTextureObject* destination = i + 1 == iterations ? in.Irradiance : s.Filter[(i + 1) % 2];
    if (!this->AtrousStage(in, DEVIATION, i, source, s.Deviation) ||
      !this->AtrousStage(in, NORMALIZE, i, source, s.Balance[0]) ||
      !this->AtrousStage(in, BALANCE, i, source, s.Balance[1]) ||
      !this->AtrousStage(in, ATROUS, i, source, destination))
    {
      return false;
    }
    if (i + 1 == keep)
    {
      CopyTexture(destination, s.HistoryColor, in.Width, in.Height);
    }
  }
  return true;
}

bool vtkCausticsSVGFDenoiser::AtrousStage(
  const Inputs& in, int stage, int iteration, vtkTextureObject* source, vtkTextureObject* output)
{
  auto& s = *this->Internal;
  vtkCausticsShaderProgram* program = s.Programs[stage];
  if (!program->Bind(in.Window))
  {
    return false;
  }
  this->SetCommonUniforms(in, stage);
  program->SetUniformf("sigmaLuminance", static_cast<float>(this->Settings.SigmaLuminance));
  program->SetUniformi("stepSize", 1 << iteration);
  BindImage(2, source, GL_READ_ONLY);
  BindImage(3, output, GL_WRITE_ONLY, stage == ATROUS ? GL_RGBA32F : GL_R32F);
  BindImage(4, s.Deviation, GL_READ_ONLY, GL_R32F);
  BindImage(5, s.Balance[stage == ATROUS ? 1 : 0], GL_READ_ONLY, GL_R32F); // the last step's
  program->DispatchCovering2D(in.Width, in.Height, LocalSize, LocalSize);
  Barrier();
  program->Unbind(in.Window);
  return true;
}

void vtkCausticsSVGFDenoiser::KeepForNextFrame(const Inputs& in)
{
  auto& s = *this->Internal;
  CopyTexture(in.GBuffer->GetPositionTexture(), s.PreviousPosition, in.Width, in.Height);
  CopyTexture(in.GBuffer->GetNormalTexture(), s.PreviousNormal, in.Width, in.Height);
  caustics::gl::ToColumnMajor(in.Camera->worldToClip, s.PreviousWorldToClip);
  Barrier();
  this->HasHistory = true;
  this->FramesSinceReset = std::min(this->FramesSinceReset + 1, 1 << 30);
}

void vtkCausticsSVGFDenoiser::ReleaseGraphicsResources(vtkWindow* w)
{
  auto& s = *this->Internal;
  for (auto& program : s.Programs)
  {
    program->ReleaseGraphicsResources(w);
  }
  vtkTextureObject* textures[] = { s.Raw, s.HistoryColor, s.HistoryMoments, s.ReprojectedColor,
    s.ReprojectedMoments, s.Filter[0], s.Filter[1], s.Deviation, s.Balance[0], s.Balance[1],
    s.PreviousPosition, s.PreviousNormal, s.Counts };
  for (vtkTextureObject* texture : textures)
  {
    texture->ReleaseGraphicsResources(w);
  }
  s.Released = true;
  this->HasHistory = false;
  this->FramesSinceReset = 0;
}

void vtkCausticsSVGFDenoiser::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const caustics::DenoiserSettings& s = this->Settings;
  os << indent << "TemporalAlpha: " << s.TemporalAlpha << "\n";
  os << indent << "MomentsAlpha: " << s.MomentsAlpha << "\n";
  os << indent << "MaximumHistoryLength: " << s.MaximumHistoryLength << "\n";
  os << indent << "SpatialVarianceFrames: " << s.SpatialVarianceFrames << "\n";
  os << indent << "AtrousIterations: " << s.AtrousIterations << "\n";
  os << indent << "HistoryIteration: " << s.HistoryIteration << "\n";
  os << indent << "SigmaDepth: " << s.SigmaDepth << "\n";
  os << indent << "SigmaNormal: " << s.SigmaNormal << "\n";
  os << indent << "SigmaLuminance: " << s.SigmaLuminance << "\n";
  os << indent << "HistoryRejectionSigmas: " << s.HistoryRejectionSigmas << "\n";
  os << indent << "DepthTolerance: " << s.DepthTolerance << "\n";
  os << indent << "NormalTolerance: " << s.NormalTolerance << "\n";
  os << indent << "MinimumReprojectedFraction: " << s.MinimumReprojectedFraction << "\n";
  os << indent << "HasHistory: " << this->HasHistory << "\n";
  os << indent << "FramesSinceReset: " << this->FramesSinceReset << "\n";
  os << indent << "FramesSinceLightChanged: " << this->FramesSinceLightChanged << "\n";
}
