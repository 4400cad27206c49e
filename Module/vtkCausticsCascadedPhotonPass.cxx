#include "vtkCausticsCascadedPhotonPass.h"

#include "vtkCausticsBindings.h"
#include "vtkCausticsCascadedTraceCS.h" // The cascade's compute shader
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsOptics.h"                // Surface interaction (shared)
#include "vtkCausticsPhotonBufferCommon.h"    // CausticsView and its projections (shared)
#include "vtkCausticsPhotonBufferUtilities.h" // The views' uniforms
#include "vtkCausticsPhotonEmitter.h"
#include "vtkCausticsPhotonGrid.h" // caustics::PhotonStatistics
#include "vtkCausticsPhotonSplatter.h"
#include "vtkCausticsPhotonStatistics.h" // Where the photons' light went (shared)
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkCausticsTimings.h"
#include "vtkCausticsVolumeLinesCommon.h" // The volume caustics' segments (shared)
#include "vtkCausticsVolumeSegmentList.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkCausticsCascadedPhotonPass);

namespace
{
double Diagonal(const double bounds[6])
{
  const double dx = bounds[1] - bounds[0], dy = bounds[3] - bounds[2], dz = bounds[5] - bounds[4];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

/** A well-mixed 32-bit hash (the frame's offsets and seed). */
unsigned int Mix(unsigned int x)
{
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

constexpr int NumberOfInputs = 11;
const char* const InputNames[NumberOfInputs] = { "emitPosition", "emitDirection", "emitFlux",
  "opaquePosition", "opaqueNormal", "frontPosition", "frontNormal", "backPosition", "backNormal",
  "cameraPosition", "cameraNormal" };
}

struct vtkCausticsCascadedPhotonPass::Internals
{
  vtkNew<vtkCausticsPhotonEmitter> Emitter;       // 1. the first specular event (shared)
  vtkNew<vtkCausticsGBuffer> Opaque;              // 2. receivers and reflectors from the light
  vtkNew<vtkCausticsGBuffer> Front;               //    refractors' nearest faces from the light
  vtkNew<vtkCausticsGBuffer> Back;                //    refractors' farthest faces from the light
  vtkNew<vtkCausticsShaderProgram> Program;       // 3-4. sampling and the cascade
  vtkNew<vtkCausticsPhotonSplatter> Splatter;     // 5. irradiance (shared)
  caustics::gl::PhotonPlanes Landed;              // the cascade's output, with kernel radii
  caustics::PhotonGrid Grid;                      // the landed photons' grid, for the splatter
  caustics::gl::VolumeSegmentList VolumeSegments; // stretches in air -> volume caustics
  caustics::hcm::StatisticsBuffer Statistics;     // where the photons' light went (shared)
};

vtkCausticsCascadedPhotonPass::vtkCausticsCascadedPhotonPass()
  : Internal(new Internals)
{
  auto& s = *this->Internal;
  s.VolumeSegments.SetOwner(this);
  s.Program->SetName("cascaded photon trace");
  const std::string source = std::string(vtkCausticsOptics) + vtkCausticsPhotonBufferCommon +
    vtkCausticsVolumeLinesCommon + vtkCausticsPhotonStatistics + vtkCausticsCascadedTraceCS;
  s.Program->SetComputeSource(source.c_str());
  s.Emitter->SetSplitFresnel(true); // both branches: the trace chooses one by roulette
  s.Back->KeepFarthestOn();
  this->SetSpecularShadows(true);   // its photons replace the light the specular actors block
  this->SetRefractionTracing(true); // the base pass's camera view of glass and mirrors
  // Paper 002, section 3.3: the jittered estimate is denoised with SVGF (the shared stage).
  this->DenoiseOn();
}

vtkCausticsCascadedPhotonPass::~vtkCausticsCascadedPhotonPass() = default;

void vtkCausticsCascadedPhotonPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const caustics::CascadedSettings& knobs = this->Settings;
  os << indent << "NumberOfPhotons: " << knobs.NumberOfPhotons << "\n";
  os << indent << "CameraStage: " << (knobs.CameraStage ? "on" : "off") << "\n";
  os << indent << "MarchHiddenStarts: " << (knobs.MarchHiddenStarts ? "on" : "off") << "\n";
  os << indent << "MarchSteps: " << knobs.MarchSteps << "\n";
  os << indent << "MaximumEvents: " << knobs.MaximumEvents << "\n";
  os << indent << "KernelSpacings: " << knobs.KernelSpacings << "\n";
  os << indent << "VolumeBlurPixels: " << knobs.VolumeBlurPixels << " px\n";
  os << indent << "VolumeSubSegments: " << knobs.VolumeSubSegments << "\n";
  os << indent << "FrameIndex: " << this->FrameIndex << "\n";
  os << indent << "Sampling: R2 sequence, per-frame Cranley-Patterson rotation\n";
}

vtkCausticsRenderPass::CausticNeeds vtkCausticsCascadedPhotonPass::GetCausticNeeds()
{
  CausticNeeds needs;
  needs.LitSpecular = true; // a light must reach a specular actor
  return needs;
}

vtkCausticsRenderPass::PhotonStorage vtkCausticsCascadedPhotonPass::GetPhotonStorage()
{
  // Per emitter slot (N x 2N): the three light layers (28 B per texel, two slots per
  // texel). Beside the grid: the landed records and radii (52 B per sampled photon).
  return { 3.0 * 14.0, 0.0, 52.0 * this->Settings.NumberOfPhotons, false };
}

bool vtkCausticsCascadedPhotonPass::RenderCausticIrradiance(const FrameInputs& in)
{
  bool ok = true;
  // A scattering medium: the photons' stretches in air become volume caustics.
  this->Internal->VolumeSegments.Begin(in.Window, *in.Scene, in.Width, in.Height);
  // Where the photons' light goes, one count for every light: each photon stands
  // for N^2 / NumberOfPhotons emitter texels.
  const double n = in.LightBuffers->GetResolution();
  this->Internal->Statistics.Begin(
    *in.Scene, in.LightBuffers, n * n / std::max(1, this->Settings.NumberOfPhotons));
  for (int light = 0; ok && light < in.LightBuffers->GetNumberOfLights(); ++light)
  {
    if (!in.LightBuffers->GetView(light).valid || this->Settings.NumberOfPhotons <= 0)
    {
      continue;
    }
    // The caustic store (shared) after the trace: the landed photons, the light's shadow.
    auto& s = *this->Internal;
    ok = this->Emit(in, light) && this->RenderLightLayers(in, light) && this->Trace(in, light) &&
      this->StoreCaustic(in, light, s.Landed.Records(), s.Grid.Width, s.Grid.Height,
        s.Grid.MaximumPhotonFlux) &&
      this->DrawVolumeLines(in) && this->Splat(in);
  }
  ++this->FrameIndex; // the next frame is a fresh, independent estimate
  return ok;
}

const caustics::hcm::StatisticsBuffer* vtkCausticsCascadedPhotonPass::GetStatisticsBuffer()
{
  return &this->Internal->Statistics;
}

bool vtkCausticsCascadedPhotonPass::Emit(const FrameInputs& in, int light)
{
  this->BeginStage("cascaded emit");
  const bool ok =
    this->Internal->Emitter->Emit(in.Window, in.LightBuffers, light, in.Geometry, *in.Scene);
  this->EndStage("cascaded emit");
  return ok;
}

bool vtkCausticsCascadedPhotonPass::RenderLightLayers(const FrameInputs& in, int light)
{
  auto& s = *this->Internal;
  const caustics::LightView& view = in.LightBuffers->GetView(light);
  const int n = s.Emitter->GetGrid().BranchRows;
  float lightToClip[16];
  caustics::gl::ToColumnMajor(view.worldToClip, lightToClip);
  const int opaque = vtkCausticsSceneGeometry::RoleBit(1) | vtkCausticsSceneGeometry::RoleBit(2);
  const int refractors = vtkCausticsSceneGeometry::RoleBit(3);
  this->BeginStage("cascaded light layers");
  const bool ok = s.Opaque->Render(in.Window, in.Geometry, lightToClip, n, n, opaque) &&
    s.Front->Render(in.Window, in.Geometry, lightToClip, n, n, refractors) &&
    s.Back->Render(in.Window, in.Geometry, lightToClip, n, n, refractors);
  this->EndStage("cascaded light layers");
  return ok;
}

bool vtkCausticsCascadedPhotonPass::Trace(const FrameInputs& in, int light)
{
  auto& s = *this->Internal;
  const caustics::PhotonGrid& emitted = s.Emitter->GetGrid();
  const caustics::LightView& view = in.LightBuffers->GetView(light);
  const caustics::Light& source = in.Scene->Lights[light];
  const int photons = this->Settings.NumberOfPhotons;
  const int width = std::max(1, static_cast<int>(std::ceil(std::sqrt(double(photons)))));
  const int height = (photons + width - 1) / width;
  const double texelsPerPhoton =
    double(emitted.BranchRows) * double(emitted.BranchRows) / double(photons);

  // The landed photons' grid: what the splatter draws.
  s.Grid = emitted;
  s.Grid.Width = width;
  s.Grid.Height = height;
  s.Grid.BranchRows = height;
  s.Grid.MaximumPhotonFlux = emitted.MaximumPhotonFlux * texelsPerPhoton;
  s.Landed.EnsureWithRadius(in.Window, width, height); // reallocates on a change only
  s.Grid.Emitted = s.Landed.Records();

  this->BeginStage("cascaded trace");
  caustics::gl::SetMediumDefine(s.Program, in.MediumGrid); // recompiles only when it changes
  s.VolumeSegments.SetAppendDefine(s.Program);             // likewise
  if (s.VolumeSegments.IsOn())
  {
    // Travel() appends a stretch per event in air, and an event that leaves the
    // light's view appends two (the stretch to where it left, then the camera view's
    // to its hit or out of the scene): 2 x MaximumEvents per photon at most.
    s.VolumeSegments.Reserve(in.Window,
      2LL * static_cast<long long>(photons) * this->Settings.MaximumEvents,
      this->Settings.VolumeSubSegments, in.MediumGrid && in.MediumGrid->HasGrid(),
      "NumberOfPhotons x 2 x MaximumEvents", "NumberOfPhotons or MaximumEvents");
  }
  if (!s.Program->Bind(in.Window))
  {
    this->EndStage("cascaded trace");
    return false;
  }
  vtkTextureObject* inputs[NumberOfInputs] = { emitted.Emitted.Position, emitted.Emitted.Direction,
    emitted.Emitted.Flux, s.Opaque->GetPositionTexture(), s.Opaque->GetNormalTexture(),
    s.Front->GetPositionTexture(), s.Front->GetNormalTexture(), s.Back->GetPositionTexture(),
    s.Back->GetNormalTexture(), in.CameraGBuffer->GetPositionTexture(),
    in.CameraGBuffer->GetNormalTexture() };
  for (int i = 0; i < NumberOfInputs; ++i)
  {
    inputs[i]->Activate();
    s.Program->SetUniformi(InputNames[i], inputs[i]->GetTextureUnit());
  }
  s.Landed.BindImages(0, GL_WRITE_ONLY);
  s.Landed.BindRadiusImage(3, GL_WRITE_ONLY);

  caustics::hcm::SetViewUniforms(s.Program, "lightView", view, emitted.Width, emitted.BranchRows);
  caustics::hcm::SetCameraViewUniforms(s.Program, "cameraView", in.Scene->View);
  s.Program->SetUniformi("emitResolution", emitted.BranchRows);
  s.Program->SetUniformi("emitBranches", emitted.Height > emitted.BranchRows ? 2 : 1);
  s.Program->SetUniform2i("photonGrid", width, height);
  s.Program->SetUniformi("photonCount", photons);
  // The frame's rotation of the R2 sequence and the roulette's seed.
  const unsigned int frame = this->FrameIndex;
  s.Program->SetUniformu("frameOffsetX", Mix(2u * frame + 1u));
  s.Program->SetUniformu("frameOffsetY", Mix(2u * frame + 2u));
  s.Program->SetUniformu("frameSeed", Mix(frame ^ 0x5bd1e995u));
  s.Program->SetUniformf("fluxScale", static_cast<float>(texelsPerPhoton));
  s.Program->SetUniformi("lightType", static_cast<int>(source.type));
  s.Program->SetUniform3f("lightOrigin", static_cast<float>(source.position[0]),
    static_cast<float>(source.position[1]), static_cast<float>(source.position[2]));
  s.Program->SetUniformi("cameraStage", this->Settings.CameraStage ? 1 : 0);
  s.Program->SetUniformi("marchHiddenStarts", this->Settings.MarchHiddenStarts ? 1 : 0);
  s.Program->SetUniformi("marchSteps", this->Settings.MarchSteps);
  s.Program->SetUniformi("maximumEvents", this->Settings.MaximumEvents);
  s.Program->SetUniformf("airLength", static_cast<float>(1.01 * Diagonal(in.Scene->Bounds)));
  s.Program->SetUniformf("spacings", static_cast<float>(this->Settings.KernelSpacings));
  s.Statistics.Bind(s.Program);
  caustics::gl::SetMediumUniforms(s.Program, *in.Scene, in.MediumGrid);
  if (s.VolumeSegments.IsOn())
  {
    s.VolumeSegments.BindForAppend(s.Program);
  }
  s.Program->DispatchCovering2D(width, height, 8, 8);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  s.Program->Unbind(in.Window);
  for (unsigned int i = 0; i < 4; ++i)
  {
    glBindImageTexture(i, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  }
  for (vtkTextureObject* input : inputs)
  {
    input->Deactivate();
  }
  this->EndStage("cascaded trace");
  return true;
}

bool vtkCausticsCascadedPhotonPass::DrawVolumeLines(const FrameInputs& in)
{
  auto& s = *this->Internal;
  if (!s.VolumeSegments.IsOn())
  {
    return true;
  }
  this->BeginStage("cascaded volume lines");
  const bool ok = s.VolumeSegments.Draw(in.Window,
    { in.WorldToClip, in.MediumGrid, in.CameraOpticalDepth, in.CameraGBuffer,
      in.RefractiveGBuffer, in.Geometry, in.EyeMaterial },
    this->Settings.VolumeSubSegments);
  this->EndStage("cascaded volume lines");
  return ok;
}

bool vtkCausticsCascadedPhotonPass::RenderVolumeRadiance(
  const FrameInputs& in, vtkTextureObject* target)
{
  auto& s = *this->Internal;
  if (!s.VolumeSegments.IsOn())
  {
    return false; // no scattering medium: no volume stage
  }
  this->BeginStage("cascaded volume blur");
  const bool ok = s.VolumeSegments.Finish(in.Window, this->Settings.VolumeBlurPixels, target);
  this->EndStage("cascaded volume blur");
  return ok;
}

bool vtkCausticsCascadedPhotonPass::Splat(const FrameInputs& in)
{
  auto& s = *this->Internal;
  this->BeginStage("cascaded splat");
  const bool ok =
    this->SplatInCameraView(in, s.Splatter, s.Grid, s.Landed.Records(), s.Landed.KernelRadius());
  this->EndStage("cascaded splat");
  return ok;
}

const caustics::gl::VolumeSegmentList* vtkCausticsCascadedPhotonPass::GetVolumeSegmentList() const
{
  return &this->Internal->VolumeSegments;
}

void vtkCausticsCascadedPhotonPass::ReleaseTechniqueResources(vtkWindow* w)
{
  auto& s = *this->Internal;
  s.Emitter->ReleaseGraphicsResources(w);
  s.Opaque->ReleaseGraphicsResources(w);
  s.Front->ReleaseGraphicsResources(w);
  s.Back->ReleaseGraphicsResources(w);
  s.Program->ReleaseGraphicsResources(w);
  s.Splatter->ReleaseGraphicsResources(w);
  s.Landed.Release(w);
  s.VolumeSegments.Release(w);
  s.Statistics.Release();
}
