#include "vtkCausticsImpostorPhotonPass.h"

#include "vtkCausticsBindings.h" // CAUSTICS_IMPOSTOR_CAUSTIC_IMAGE
#include "vtkCausticsDistanceImpostors.h"
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsImpostorCommon.h"         // Hit() over the cube maps (shared)
#include "vtkCausticsImpostorPhotonTraceCS.h"  // The trace's compute shader
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsOptics.h" // Surface interaction (shared)
#include "vtkCausticsPhotonBufferCommon.h" // AllFinite (shared)
#include "vtkCausticsPhotonBufferUtilities.h" // caustics::hcm::StatisticsBuffer
#include "vtkCausticsPhotonEmitter.h"
#include "vtkCausticsPhotonSpacing.h"
#include "vtkCausticsPhotonSplatter.h"
#include "vtkCausticsPhotonStatistics.h" // Where the photons' light went (shared)
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsScreenSpaceUtilities.h" // TextureUnits
#include "vtkCausticsShaderProgram.h"
#include "vtkCausticsSpecularHierarchy.h"
#include "vtkCausticsSpecularTrace.h" // Glass and mirror triangles (shared)
#include "vtkCausticsTimings.h"
#include "vtkObjectFactory.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkCausticsImpostorPhotonPass);

namespace
{
/** A well-mixed 32-bit hash (the frame's roulette seed). */
unsigned int Mix(unsigned int x)
{
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

void SetVector(vtkCausticsShaderProgram* p, const char* name, const double v[3])
{
  p->SetUniform3f(
    name, static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
}
}

struct vtkCausticsImpostorPhotonPass::Internals
{
  vtkNew<vtkCausticsPhotonEmitter> Emitter;   // 1. the first specular event (shared)
  vtkNew<vtkCausticsShaderProgram> Program;   // 3. the trace against the maps
  vtkNew<vtkCausticsPhotonSpacing> Spacing;   //    kernel radii from the landed neighbours
  vtkNew<vtkCausticsPhotonSplatter> Splatter; // 4. irradiance (shared)
  caustics::gl::PhotonPlanes Landed;          // the trace's output, with kernel radii
  caustics::PhotonGrid Grid;                  // the landed photons' grid, for the splatter
  caustics::hcm::StatisticsBuffer Statistics; // where the photons' light went (shared)
};

vtkCausticsImpostorPhotonPass::vtkCausticsImpostorPhotonPass()
  : Internal(new Internals)
{
  auto& s = *this->Internal;
  s.Program->SetName("impostor photon trace");
  const std::string source = std::string(vtkCausticsOptics) + vtkCausticsPhotonBufferCommon +
    vtkCausticsImpostorCommon + vtkCausticsSpecularTrace + vtkCausticsPhotonStatistics +
    vtkCausticsImpostorPhotonTraceCS;
  s.Program->SetComputeSource(source.c_str());
  s.Emitter->SetSplitFresnel(true); // both branches of the first event: no roulette there
  this->SetSpecularShadows(true);   // its photons replace the light the specular actors block
  this->SetRefractionTracing(true); // the base pass's camera view of glass and mirrors
}

vtkCausticsImpostorPhotonPass::~vtkCausticsImpostorPhotonPass() = default;

void vtkCausticsImpostorPhotonPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaximumEvents: " << this->Settings.MaximumEvents << "\n";
  os << indent << "KernelSpacings: " << this->Settings.KernelSpacings << "\n";
  os << indent << "SpreadStretch: " << this->Settings.SpreadStretch << "\n";
  os << indent << "FrameIndex: " << this->FrameIndex << "\n";
  os << indent << "Splatter:\n";
  this->Internal->Splatter->PrintSelf(os, indent.GetNextIndent());
}

vtkCausticsPhotonSplatter* vtkCausticsImpostorPhotonPass::GetSplatter()
{
  return this->Internal->Splatter;
}

void vtkCausticsImpostorPhotonPass::SetReconstruction(int mode)
{
  if (mode != this->Internal->Splatter->GetReconstruction())
  {
    this->Internal->Splatter->SetReconstruction(mode);
    this->Modified();
  }
}

int vtkCausticsImpostorPhotonPass::GetReconstruction()
{
  return this->Internal->Splatter->GetReconstruction();
}

vtkCausticsRenderPass::CausticNeeds vtkCausticsImpostorPhotonPass::GetCausticNeeds()
{
  CausticNeeds needs;
  needs.LitSpecular = true; // a light must reach a specular actor
  return needs;
}

vtkCausticsRenderPass::PhotonStorage vtkCausticsImpostorPhotonPass::GetPhotonStorage()
{
  // Per emitter slot: the landed records and radii (52 B). Beside the grid: the
  // three cube maps of the distance impostors (18 layers of 16 + 8 + 16 B texels)
  // and their caustic store (4 x 4 B per texel: flux per channel, deposits).
  const double r = this->GetDistanceImpostors()->GetResolution();
  return { 52.0, 0.0, 18.0 * r * r * 56.0, false };
}

bool vtkCausticsImpostorPhotonPass::RenderCausticIrradiance(const FrameInputs& in)
{
  bool ok = this->UpdateMaps(in);
  this->Internal->Statistics.Begin(*in.Scene, in.LightBuffers, 1.0); // a photon per texel
  for (int light = 0; ok && light < in.LightBuffers->GetNumberOfLights(); ++light)
  {
    if (!in.LightBuffers->GetView(light).valid)
    {
      continue;
    }
    auto& s = *this->Internal;
    // 6. The caustic store (shared): the landed photons and the light's shadow.
    ok = this->Emit(in, light) && this->Trace(in, light) &&
      this->StoreCaustic(in, light, s.Landed.Records(), s.Grid.Width, s.Grid.Height,
        s.Grid.MaximumPhotonFlux) &&
      this->Spread(in) && this->Splat(in);
  }
  ++this->FrameIndex; // the next frame is a fresh, independent estimate
  return ok;
}

bool vtkCausticsImpostorPhotonPass::UpdateMaps(const FrameInputs& in)
{
  return this->UpdateImpostors(in);
}

bool vtkCausticsImpostorPhotonPass::Emit(const FrameInputs& in, int light)
{
  this->BeginStage("impostor emit");
  const bool ok =
    this->Internal->Emitter->Emit(in.Window, in.LightBuffers, light, in.Geometry, *in.Scene);
  this->EndStage("impostor emit");
  return ok;
}

bool vtkCausticsImpostorPhotonPass::Trace(const FrameInputs& in, int light)
{
  auto& s = *this->Internal;
  const caustics::PhotonGrid& emitted = s.Emitter->GetGrid();
  const caustics::LightView& view = in.LightBuffers->GetView(light);
  const caustics::Light& source = in.Scene->Lights[light];
  const caustics::Camera& camera = in.Scene->View;

  // One landed photon per emitted one: the same grid (caustic triangles join the
  // same neighbours), its records the trace's.
  s.Grid = emitted;
  s.Landed.EnsureWithRadius(in.Window, emitted.Width, emitted.Height); // on a change only
  s.Grid.Emitted = s.Landed.Records();

  this->BeginStage("impostor trace");
  caustics::gl::SetMediumDefine(s.Program, in.MediumGrid); // recompiles only when it changes
  if (!s.Program->Bind(in.Window))
  {
    this->EndStage("impostor trace");
    return false;
  }
  {
    caustics::ssp::TextureUnits units(in.Window);
    s.Program->SetUniformi("emitPosition", units.Bind(emitted.Emitted.Position));
    s.Program->SetUniformi("emitDirection", units.Bind(emitted.Emitted.Direction));
    s.Program->SetUniformi("emitFlux", units.Bind(emitted.Emitted.Flux));
    vtkCausticsGBuffer* seen = in.LightBuffers->GetGBuffer(light);
    s.Program->SetUniformi("lightNormal", units.Bind(seen->GetNormalTexture()));
    s.Program->SetUniformi("lightPosition", units.Bind(seen->GetPositionTexture()));
    this->GetDistanceImpostors()->SetUniforms(s.Program, units);
    in.Geometry->BindMaterials();
    s.Landed.BindImages(0, GL_WRITE_ONLY);
    s.Landed.BindRadiusImage(3, GL_WRITE_ONLY);

    s.Program->SetUniformi("emitResolution", emitted.BranchRows);
    s.Program->SetUniform2i("photonGrid", emitted.Width, emitted.Height);
    s.Program->SetUniformu("frameSeed", Mix(this->FrameIndex ^ 0x5bd1e995u));
    s.Program->SetUniformi("lightType", static_cast<int>(source.type));
    SetVector(s.Program, "lightOrigin", source.position.data());
    SetVector(s.Program, "lightEye", view.eye.data());
    SetVector(s.Program, "lightAxis", view.axis.data());
    SetVector(s.Program, "cameraPosition", camera.position.data());
    const double towards[3] = { camera.focalPoint[0] - camera.position[0],
      camera.focalPoint[1] - camera.position[1], camera.focalPoint[2] - camera.position[2] };
    SetVector(s.Program, "cameraDirection", towards);
    s.Program->SetUniformi("cameraParallel", camera.parallel ? 1 : 0);
    const double* b = in.Scene->Bounds;
    const double low[3] = { b[0], b[2], b[4] }, high[3] = { b[1], b[3], b[5] };
    SetVector(s.Program, "boundsMin", low);
    SetVector(s.Program, "boundsMax", high);
    s.Program->SetUniformf("tolerance", static_cast<float>(1e-5 * in.Scene->Scale()));
    s.Program->SetUniformi("maximumEvents", this->Settings.MaximumEvents);
    s.Program->SetUniformf("spacings", static_cast<float>(this->Settings.KernelSpacings));
    s.Statistics.Bind(s.Program);
    // Glass and mirrors traced as triangles where the camera view traces them.
    vtkCausticsSpecularHierarchy::BindTraced(this->GetTracedSpecularGeometry(*in.Scene), s.Program);
    caustics::gl::SetMediumUniforms(s.Program, *in.Scene, in.MediumGrid);
    s.Program->DispatchCovering2D(emitted.Width, emitted.Height, 8, 8);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
  s.Program->Unbind(in.Window);
  for (unsigned int i = 0; i < 4; ++i)
  {
    glBindImageTexture(i, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  }
  glBindImageTexture(CAUSTICS_IMPOSTOR_CAUSTIC_IMAGE, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32I);
  this->EndStage("impostor trace");
  return true;
}

bool vtkCausticsImpostorPhotonPass::Spread(const FrameInputs& in)
{
  auto& s = *this->Internal;
  this->BeginStage("impostor spread");
  // Whole paths: a neighbour may have taken another branch at a later event.
  const bool ok = s.Spacing->Widen(in.Window, s.Grid, s.Landed.Records(), s.Landed.KernelRadius(),
    this->Settings.KernelSpacings, vtkCausticsPhotonSpacing::MEAN_DISTANCE,
    this->Settings.SpreadStretch);
  this->EndStage("impostor spread");
  return ok;
}

bool vtkCausticsImpostorPhotonPass::Splat(const FrameInputs& in)
{
  auto& s = *this->Internal;
  this->BeginStage("impostor splat");
  const bool ok =
    this->SplatInCameraView(in, s.Splatter, s.Grid, s.Landed.Records(), s.Landed.KernelRadius());
  this->EndStage("impostor splat");
  return ok;
}

void vtkCausticsImpostorPhotonPass::ReleaseTechniqueResources(vtkWindow* w)
{
  auto& s = *this->Internal;
  s.Emitter->ReleaseGraphicsResources(w);
  s.Program->ReleaseGraphicsResources(w);
  s.Spacing->ReleaseGraphicsResources(w);
  s.Splatter->ReleaseGraphicsResources(w);
  s.Landed.Release(w);
  s.Statistics.Release();
}

const caustics::hcm::StatisticsBuffer* vtkCausticsImpostorPhotonPass::GetStatisticsBuffer()
{
  return &this->Internal->Statistics;
}
