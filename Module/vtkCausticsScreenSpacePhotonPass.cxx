#include "vtkCausticsScreenSpacePhotonPass.h"

#include "vtkCausticsBindings.h" // CAUSTICS_*_BINDING
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsLayeredDepth.h"
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsPhotonBufferUtilities.h" // caustics::hcm::StatisticsBuffer
#include "vtkCausticsPhotonEmitter.h"
#include "vtkCausticsPhotonGrid.h"
#include "vtkCausticsPhotonSpacing.h"
#include "vtkCausticsPhotonSplatter.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsScreenSpaceLineTracer.h"
#include "vtkCausticsScreenSpaceUtilities.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkCausticsSpecularHierarchy.h"
#include "vtkCausticsTimings.h"
#include "vtkCausticsTraceView.h"
#include "vtkCausticsVolumeLines.h"
#include "vtkCausticsVolumeSegmentList.h" // IsNeeded(), VolumeSegmentCapacity
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsOptics.h"
#include "vtkCausticsPhotonStatistics.h"
#include "vtkCausticsScreenSpaceCommon.h"
#include "vtkCausticsScreenSpacePhotonPassInitialCS.h"
#include "vtkCausticsScreenSpacePhotonPassShadowCS.h"
#include "vtkCausticsScreenSpacePhotonPassTransferCS.h"
#include "vtkCausticsScreenSpaceVolumeSegmentsCS.h"
#include "vtkCausticsSpecularTrace.h"
#include "vtkCausticsVolumeLinesCommon.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCausticsScreenSpacePhotonPass);

namespace
{
// Storage-buffer bindings: vtkCausticsBindings.h. Record layouts:
// glsl/vtkCausticsScreenSpaceCommon.glsl.
// Bytes of one SspRay, one SspPayload, one SspHit.
constexpr std::size_t RayBytes = 32;
constexpr std::size_t PayloadBytes = 32;
constexpr std::size_t HitBytes = 32;

/** The "Shadow" array of TraceShadowRays from the traced rays and their hits. */
void WriteShadow(const std::vector<float>& rays, const std::vector<float>& hits,
  const caustics::Light& source, int w, int h, vtkImageData* output)
{
  const int count = w * h;
  output->Initialize();
  output->SetDimensions(w, h, 1);
  vtkNew<vtkFloatArray> shadow;
  shadow->SetName("Shadow");
  shadow->SetNumberOfTuples(count);
  for (int i = 0; i < count; ++i)
  {
    const float* ray = &rays[8 * static_cast<std::size_t>(i)];
    const float t = hits[8 * static_cast<std::size_t>(i) + 3];
    float value = -1.0f;
    if (ray[3] > 0.0f)
    {
      double reach = 1e300; // a point light: occluders beyond it cast no shadow
      if (source.type != caustics::Light::Type::Directional)
      {
        reach = std::sqrt(std::pow(source.position[0] - ray[0], 2) +
          std::pow(source.position[1] - ray[1], 2) + std::pow(source.position[2] - ray[2], 2));
      }
      value = t >= 0.0f && t < reach ? 1.0f : 0.0f;
    }
    shadow->SetValue(i, value);
  }
  output->GetPointData()->AddArray(shadow);
}
}

struct vtkCausticsScreenSpacePhotonPass::Internals
{
  vtkNew<vtkCausticsLayeredDepth> SceneLayers;
  vtkNew<vtkCausticsScreenSpaceLineTracer> Tracer;
  vtkNew<vtkCausticsPhotonEmitter> Emitter;
  vtkNew<vtkCausticsPhotonSplatter> Splatter;
  vtkNew<vtkCausticsVolumeLines> VolumeLines; // god-rays: line-based volume caustics (003)
  vtkNew<vtkCausticsShaderProgram> InitialProgram;
  vtkNew<vtkCausticsShaderProgram> TransferProgram;
  vtkNew<vtkCausticsShaderProgram> ShadowProgram;
  vtkNew<vtkCausticsPhotonSpacing> Spacing;        // radii from the neighbours (shared)
  vtkNew<vtkCausticsShaderProgram> SegmentProgram; // rays -> volume line segments

  // Transfer maps (photon lists) and their counters, ping-ponged between bounces.
  caustics::gl::StorageBuffer Rays[2];
  caustics::gl::StorageBuffer Payloads[2];
  caustics::gl::StorageBuffer Counters[2];
  caustics::hcm::StatisticsBuffer Statistics; // where the photons' light went (shared)
  caustics::gl::StorageBuffer VolumeSegments; // CausticsVolumeSegment per ray
  caustics::gl::VolumeSegmentCapacity VolumeCapacity; // how many of them the stage holds
  int Current = 0;
  int Capacity = 0;
  // Splat records of the photons that ended on receivers this bounce.
  caustics::gl::PhotonPlanes Landed; // with their kernel radii

  // The frame's camera (splats, refraction, god-rays) and the view photons are
  // traced in (the camera's or a fitted one, vtkCausticsTraceView.h).
  float ClipToWorld[16];
  double CameraOrigin[4] = { 0, 0, 0, 1 }; // eye (w = 1) or view direction (w = 0)
  caustics::TraceView Traced;
  vtkCausticsScreenSpaceLineTracer::View View; // the tracer's: the traced view
  bool HasLayers = false;
  bool GodRaysOn = false; // this frame draws god-rays

  std::string Prefix(int light, int lights, int bounce) const
  {
    std::string prefix = "ssp ";
    if (lights > 1)
    {
      prefix += "light " + std::to_string(light) + " ";
    }
    if (bounce > 0)
    {
      prefix += "bounce " + std::to_string(bounce) + " ";
    }
    return prefix;
  }

  void ClearCounter(int which) { this->Counters[which].Clear(); }
};

vtkCausticsScreenSpacePhotonPass::vtkCausticsScreenSpacePhotonPass()
  : Internal(new Internals)
{
  this->SetRefractionTracing(true); // the base pass's camera view of glass (§4)
  this->SetSpecularShadows(true);   // its caustic replaces the light glass and mirrors block
  auto& in = *this->Internal;
  const std::string optics = vtkCausticsOptics;
  const std::string common = vtkCausticsScreenSpaceCommon;
  in.InitialProgram->SetName("ssp first transfer map");
  const std::string statistics = vtkCausticsPhotonStatistics;
  in.InitialProgram->SetComputeSource(
    (common + statistics + vtkCausticsScreenSpacePhotonPassInitialCS).c_str());
  in.InitialProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  in.TransferProgram->SetName("ssp specular transfer");
  in.TransferProgram->SetComputeSource((optics + common + vtkCausticsSpecularTrace + statistics +
    vtkCausticsScreenSpacePhotonPassTransferCS)
                                         .c_str());
  in.ShadowProgram->SetName("ssp shadow rays");
  in.ShadowProgram->SetComputeSource((common + vtkCausticsScreenSpacePhotonPassShadowCS).c_str());
  in.ShadowProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  in.SegmentProgram->SetName("ssp volume segments");
  in.SegmentProgram->SetComputeSource(
    (common + vtkCausticsVolumeLinesCommon + vtkCausticsScreenSpaceVolumeSegmentsCS).c_str());
  in.SegmentProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  for (float& v : in.ClipToWorld)
  {
    v = 0.0f;
  }
}

vtkCausticsScreenSpacePhotonPass::~vtkCausticsScreenSpacePhotonPass()
{
  if (this->Internal->Rays[0].Handle())
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): GL objects leaked");
  }
}

vtkCausticsLayeredDepth* vtkCausticsScreenSpacePhotonPass::GetLayeredDepth()
{
  return this->Internal->SceneLayers;
}
vtkCausticsScreenSpaceLineTracer* vtkCausticsScreenSpacePhotonPass::GetLineTracer()
{
  return this->Internal->Tracer;
}
vtkCausticsPhotonEmitter* vtkCausticsScreenSpacePhotonPass::GetEmitter()
{
  return this->Internal->Emitter;
}
vtkCausticsPhotonSplatter* vtkCausticsScreenSpacePhotonPass::GetSplatter()
{
  return this->Internal->Splatter;
}

vtkCausticsRenderPass::CausticNeeds vtkCausticsScreenSpacePhotonPass::GetCausticNeeds()
{
  CausticNeeds needs;
  needs.LitSpecular = true;
  // Traces find specular actors only in the layered depth image of the view.
  needs.SpecularInView = this->Settings.SkipOffscreenSpecular;
  return needs;
}

vtkCausticsRenderPass::PhotonStorage vtkCausticsScreenSpacePhotonPass::GetPhotonStorage()
{
  // Per photon slot: two transfer maps of rays and payloads, the tracer's line and
  // hit, the landed photon record and its radius. Beside the grid: the scene's and
  // the refractors' layered depth images (28 B per pixel and layer; the second is
  // the base pass's camera-view stage) and the line target (8 B per texel).
  const FrameInputs& f = this->GetFrameInputs();
  const double pixels = static_cast<double>(f.Width) * f.Height;
  const double layers = this->Settings.MaximumNumberOfLayers;
  PhotonStorage storage;
  storage.BytesPerPhoton = 2.0 * (RayBytes + PayloadBytes) + 48.0 + HitBytes + 52.0;
  storage.LargestBufferPerPhoton = 48.0; // the tracer's lines
  storage.FixedBytes =
    2.0 * 28.0 * pixels * layers + 8.0 * this->Settings.RowsPerBatch * std::max(f.Width, f.Height);
  return storage;
}

bool vtkCausticsScreenSpacePhotonPass::RenderLayers(vtkOpenGLRenderWindow* renWin)
{
  const FrameInputs& f = this->GetFrameInputs();
  auto& in = *this->Internal;
  const caustics::SceneData& scene = *f.Scene;
  in.SceneLayers->SetMaximumNumberOfLayers(this->Settings.MaximumNumberOfLayers);
  in.SceneLayers->SetPerObject(this->Settings.PerObjectLayers);
  in.SceneLayers->SetTimings(this->GetTimings(), "ssp layers ");
  in.HasLayers =
    in.SceneLayers->Render(renWin, f.Geometry, scene, in.Traced.WorldToClip, f.Width, f.Height);
  return in.HasLayers;
}

bool vtkCausticsScreenSpacePhotonPass::EmitPhotons(vtkOpenGLRenderWindow* renWin, int light)
{
  const FrameInputs& f = this->GetFrameInputs();
  auto& in = *this->Internal;
  const caustics::SceneData& scene = *f.Scene;
  if (!in.Emitter->Emit(renWin, f.LightBuffers, light, f.Geometry, scene))
  {
    return false;
  }
  const caustics::PhotonGrid& grid = in.Emitter->GetGrid();
  in.Capacity = static_cast<int>(grid.Count());
  for (int k = 0; k < 2; ++k)
  {
    in.Rays[k].Allocate(RayBytes * in.Capacity);
    in.Payloads[k].Allocate(PayloadBytes * in.Capacity);
    in.Counters[k].Allocate(16);
  }
  in.Landed.EnsureWithRadius(renWin, grid.Width, grid.Height);

  // Compact the emitter's grid into the first transfer map.
  in.Current = 0;
  in.ClearCounter(0);
  vtkCausticsShaderProgram* p = in.InitialProgram;
  caustics::gl::SetMediumDefine(p, f.MediumGrid);
  if (!p->Bind(renWin))
  {
    return false;
  }
  const caustics::Light& source = scene.Lights[light];
  caustics::ssp::TextureUnits units(renWin);
  p->SetUniformi("emitPosition", units.Bind(grid.Emitted.Position));
  p->SetUniformi("emitDirection", units.Bind(grid.Emitted.Direction));
  p->SetUniformi("emitFlux", units.Bind(grid.Emitted.Flux));
  p->SetUniformi(
    "lightPosition", units.Bind(f.LightBuffers->GetGBuffer(light)->GetPositionTexture()));
  p->SetUniform2i("grid", grid.Width, grid.Height);
  p->SetUniformi("resolution", grid.BranchRows);
  p->SetUniformi("lightType", static_cast<int>(source.type));
  p->SetUniform3f("lightOrigin", static_cast<float>(source.position[0]),
    static_cast<float>(source.position[1]), static_cast<float>(source.position[2]));
  p->SetUniform3f("lightDirection", static_cast<float>(source.direction[0]),
    static_cast<float>(source.direction[1]), static_cast<float>(source.direction[2]));
  const caustics::Vec3& eye = f.LightBuffers->GetView(light).eye;
  p->SetUniform3f(
    "viewEye", static_cast<float>(eye[0]), static_cast<float>(eye[1]), static_cast<float>(eye[2]));
  caustics::gl::SetMediumUniforms(p, scene, f.MediumGrid);
  in.Rays[0].BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_NEXT_RAY_BINDING);
  in.Payloads[0].BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_NEXT_PAYLOAD_BINDING);
  in.Counters[0].BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_NEXT_COUNTER_BINDING);
  in.Statistics.Bind(p);
  p->DispatchCovering2D(grid.Width, grid.Height, 16, 16);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  p->Unbind(renWin);
  return true;
}

bool vtkCausticsScreenSpacePhotonPass::TracePhotons(
  vtkOpenGLRenderWindow* renWin, int light, int bounce)
{
  const FrameInputs& f = this->GetFrameInputs();
  auto& in = *this->Internal;
  const int c = in.Current;
  return in.Tracer->Trace(renWin, this->Settings, in.View, in.Rays[c].Handle(),
    in.Counters[c].Handle(), in.Capacity,
    in.Prefix(light, f.LightBuffers->GetNumberOfLights(), bounce));
}

bool vtkCausticsScreenSpacePhotonPass::TransferPhotons(
  vtkOpenGLRenderWindow* renWin, int light, int bounce)
{
  const FrameInputs& f = this->GetFrameInputs();
  auto& in = *this->Internal;
  const caustics::SceneData& scene = *f.Scene;
  const int c = in.Current, n = 1 - c;
  in.ClearCounter(n);
  in.Landed.ClearPositions();

  vtkCausticsShaderProgram* p = in.TransferProgram;
  caustics::gl::SetMediumDefine(p, f.MediumGrid);
  if (!p->Bind(renWin))
  {
    return false;
  }
  in.Counters[c].BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_COUNTER_BINDING);
  in.Rays[c].BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_RAY_BINDING);
  in.Payloads[c].BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_PAYLOAD_BINDING);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_HIT_BINDING, in.Tracer->GetHitBuffer());
  in.Rays[n].BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_NEXT_RAY_BINDING);
  in.Payloads[n].BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_NEXT_PAYLOAD_BINDING);
  in.Counters[n].BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_NEXT_COUNTER_BINDING);
  in.Statistics.Bind(p);
  f.Geometry->BindMaterials();
  in.Landed.BindImages(0, GL_WRITE_ONLY);
  in.Landed.BindRadiusImage(3, GL_WRITE_ONLY);
  p->SetUniformi("capacity", in.Capacity);
  p->SetUniformi("gridWidth", in.Emitter->GetGrid().Width);
  p->SetUniformi("maxEvents", this->Settings.MaximumBounces);
  p->SetUniformMatrix4("worldToClip", f.WorldToClip);
  p->SetUniformMatrix4("clipToWorld", in.ClipToWorld);
  p->SetUniform2f("viewport", static_cast<float>(f.Width), static_cast<float>(f.Height));
  const float origin[4] = { static_cast<float>(in.CameraOrigin[0]),
    static_cast<float>(in.CameraOrigin[1]), static_cast<float>(in.CameraOrigin[2]),
    static_cast<float>(in.CameraOrigin[3]) };
  p->SetUniform4f("viewOrigin", origin);
  p->SetUniformf("splatRadius", static_cast<float>(this->Settings.SplatRadius));
  p->SetUniformf("splatRadiusPixels", static_cast<float>(this->Settings.SplatRadiusPixels));
  caustics::gl::SetMediumUniforms(p, scene, f.MediumGrid);
  p->SetUniformu(
    "seed", 0x9e3779b9u * static_cast<unsigned int>(bounce + 1) + static_cast<unsigned int>(light));
  // Glass and mirrors traced as triangles where the camera view traces them.
  vtkCausticsSpecularHierarchy::BindTraced(this->GetTracedSpecularGeometry(scene), p);
  p->SetUniformf("tolerance", static_cast<float>(1e-5 * scene.Scale()));
  // Inside traced glass, interfaces within one bounce, up to the reference's 8 events
  // a path (vtkCausticsReferenceRenderer::MaxBounces).
  p->SetUniformi("maxPathEvents", 8);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, in.Tracer->GetArgumentBuffer());
  glDispatchComputeIndirect(0);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT |
    GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  for (GLuint unit = 0; unit < 4; ++unit)
  {
    glBindImageTexture(unit, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, unit < 3 ? GL_RGBA32F : GL_R32F);
  }
  p->Unbind(renWin);
  return true;
}

bool vtkCausticsScreenSpacePhotonPass::SplatPhotons(
  vtkOpenGLRenderWindow* renWin, int light, int bounce)
{
  const FrameInputs& f = this->GetFrameInputs();
  auto& in = *this->Internal;
  const caustics::PhotonGrid& grid = in.Emitter->GetGrid();
  // Radii from the neighbours' spacing (shared, vtkCausticsPhotonSpacing): this bounce's
  // landed photons are all the records hold, so neighbours took the same number of events.
  if (this->Settings.SplatRadius <= 0.0 &&
    !in.Spacing->Widen(renWin, grid, in.Landed.Records(), in.Landed.KernelRadius(),
      this->Settings.SplatRadiusSpacings, vtkCausticsPhotonSpacing::AREA))
  {
    return false;
  }
  // The caustic store (shared): this bounce's landed photons, the light's shadow once.
  if (!this->StoreCaustic(f, light, in.Landed.Records(), grid.Width, grid.Height,
        grid.MaximumPhotonFlux, bounce == 1))
  {
    return false;
  }
  // Into the caustic framebuffer the base pass bound (each stage restores it).
  in.Splatter->SetReconstruction(this->Settings.Reconstruction);
  return this->SplatInCameraView(
    f, in.Splatter, grid, in.Landed.Records(), in.Landed.KernelRadius());
}

bool vtkCausticsScreenSpacePhotonPass::DrawGodRays(vtkOpenGLRenderWindow* renWin, int, int)
{
  const FrameInputs& f = this->GetFrameInputs();
  auto& in = *this->Internal;
  // The stage's view, built as for every technique (the frame's camera of PrepareView).
  caustics::TraceView camera;
  std::copy(in.ClipToWorld, in.ClipToWorld + 16, camera.ClipToWorld);
  std::copy(in.CameraOrigin, in.CameraOrigin + 4, camera.ViewOrigin);
  const vtkCausticsVolumeLines::View view = caustics::gl::VolumeSegmentList::MakeView(*f.Scene,
    camera, f.Width, f.Height,
    { f.WorldToClip, f.MediumGrid, f.CameraOpticalDepth, f.CameraGBuffer, f.RefractiveGBuffer,
      f.Geometry, f.EyeMaterial });
  // One segment per traced ray: the stage's optical depths for all of them, or, where
  // this OpenGL cannot hold them at VolumeSubSegments, what it holds and one warning.
  const int capacity = in.VolumeCapacity.Choose(renWin, this, in.Capacity,
    vtkCausticsVolumeLines::PiecesFor(
      f.MediumGrid && f.MediumGrid->HasGrid(), this->Settings.VolumeSubSegments),
    "one per photon slot of a bounce, LightBufferResolution^2 per branch", "LightBufferResolution");
  return this->WriteVolumeSegments(renWin) &&
    in.VolumeLines->Draw(renWin, view,
      { in.VolumeSegments.Handle(), in.Tracer->GetArgumentBuffer(), 3, capacity },
      this->Settings.VolumeSubSegments);
}

bool vtkCausticsScreenSpacePhotonPass::WriteVolumeSegments(vtkOpenGLRenderWindow* renWin)
{
  // This bounce's traced rays, lines and hits in the volume lines' neutral layout; the
  // ray count stays on the GPU (word 3 of the tracer's arguments).
  auto& in = *this->Internal;
  in.VolumeSegments.Allocate(static_cast<std::size_t>(vtkCausticsVolumeLines::SegmentBytes) *
      static_cast<std::size_t>(in.Capacity),
    caustics::gl::StorageBuffer::Usage::Copy);
  vtkCausticsShaderProgram* p = in.SegmentProgram;
  if (!p->Bind(renWin))
  {
    return false;
  }
  // Whether the medium fills the refractors: a ray inside one draws its line or not.
  const FrameInputs& f = this->GetFrameInputs();
  caustics::gl::SetMediumUniforms(p, *f.Scene, f.MediumGrid);
  const int c = in.Current;
  in.Rays[c].BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_RAY_BINDING);
  in.Payloads[c].BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_PAYLOAD_BINDING);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_LINE_BINDING, in.Tracer->GetLineBuffer());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_HIT_BINDING, in.Tracer->GetHitBuffer());
  glBindBufferBase(
    GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_ARGUMENT_BINDING, in.Tracer->GetArgumentBuffer());
  in.VolumeSegments.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_VOLUME_SEGMENT_BINDING);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, in.Tracer->GetArgumentBuffer());
  glDispatchComputeIndirect(0);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  p->Unbind(renWin);
  return true;
}

void vtkCausticsScreenSpacePhotonPass::PrepareView(const FrameInputs& f)
{
  auto& in = *this->Internal;
  const caustics::SceneData& scene = *f.Scene;
  const caustics::TraceView camera =
    caustics::ChooseTraceView(scene, caustics::TraceViewMode::Camera, f.Width, f.Height);
  std::copy(camera.ClipToWorld, camera.ClipToWorld + 16, in.ClipToWorld);
  std::copy(camera.ViewOrigin, camera.ViewOrigin + 4, in.CameraOrigin);
  // Photons are traced where the specular surfaces they can meet are: those the
  // photon frusta are aimed at (see vtkCausticsTraceView.h).
  double specular[6];
  const bool aimed = this->PhotonFocus(f, specular);
  in.Traced = caustics::ChooseTraceView(scene,
    static_cast<caustics::TraceViewMode>(this->Settings.TraceView), f.Width, f.Height,
    aimed ? specular : nullptr);
  this->LastTraceViewFitted = in.Traced.Fitted;
  // The automatic view fits where the camera's misses a specular actor; the paper's
  // camera view then lets photons pass it unbent. Said once, when it starts.
  const bool missed = !in.Traced.Fitted && !caustics::FrustumHoldsSpecular(scene);
  if (missed && !this->LastTraceViewMissedSpecular)
  {
    vtkWarningMacro(<< "photons are traced in the camera's view (TraceView camera) and a "
                       "reflector or refractor lies outside it: light passing it is not "
                       "bent, so the caustic depends on the framing; TraceView automatic "
                       "traces in a fitted view there");
  }
  this->LastTraceViewMissedSpecular = missed;
  in.View.Layers = in.SceneLayers;
  in.View.WorldToClip = in.Traced.WorldToClip;
  std::copy(scene.Bounds, scene.Bounds + 6, in.View.Bounds);
  std::copy(in.Traced.ViewOrigin, in.Traced.ViewOrigin + 4, in.View.ViewOrigin);
  this->LastTolerance = this->Settings.Tolerance(caustics::VisibleScale(scene, aimed ? specular : nullptr));
  in.View.Tolerance = this->LastTolerance;
  in.Tracer->SetTimings(this->GetTimings());
}

bool vtkCausticsScreenSpacePhotonPass::PhotonFocus(const FrameInputs& f, double box[6]) const
{
  const caustics::SceneData& scene = *f.Scene;
  bool any = false;
  const int lights = std::min(f.LightBuffers->GetNumberOfLights(), static_cast<int>(scene.Lights.size()));
  for (int light = 0; light < lights; ++light)
  {
    const caustics::LightView& view = f.LightBuffers->GetView(light);
    if (!view.valid || !caustics::LightReachesSpecular(scene.Lights[light], scene.SpecularBounds))
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      box[2 * k] = any ? std::min(box[2 * k], view.focus[2 * k]) : view.focus[2 * k];
      box[2 * k + 1] = any ? std::max(box[2 * k + 1], view.focus[2 * k + 1]) : view.focus[2 * k + 1];
    }
    any = true;
  }
  return any;
}

bool vtkCausticsScreenSpacePhotonPass::TraceLight(const FrameInputs& f, int light, bool godRays)
{
  auto& in = *this->Internal;
  vtkOpenGLRenderWindow* renWin = f.Window;
  const int lights = f.LightBuffers->GetNumberOfLights();
  const std::string prefix = in.Prefix(light, lights, 0);
  this->StartStage((prefix + "emission").c_str());
  bool ok = this->EmitPhotons(renWin, light);
  this->StopStage((prefix + "emission").c_str());
  for (int bounce = 1; ok && bounce <= this->Settings.MaximumBounces; ++bounce)
  {
    const std::string stage = in.Prefix(light, lights, bounce);
    ok = this->TracePhotons(renWin, light, bounce);
    if (ok && godRays)
    {
      this->StartStage((stage + "god-rays").c_str());
      ok = this->DrawGodRays(renWin, light, bounce);
      this->StopStage((stage + "god-rays").c_str());
    }
    this->StartStage((stage + "specular transfer").c_str());
    ok = ok && this->TransferPhotons(renWin, light, bounce);
    this->StopStage((stage + "specular transfer").c_str());
    this->StartStage((stage + "splatting").c_str());
    ok = ok && this->SplatPhotons(renWin, light, bounce);
    this->StopStage((stage + "splatting").c_str());
    in.Current = 1 - in.Current;
  }
  return ok;
}

bool vtkCausticsScreenSpacePhotonPass::RenderCausticIrradiance(const FrameInputs& f)
{
  auto& in = *this->Internal;
  const caustics::SceneData& scene = *f.Scene;
  in.GodRaysOn = false;
  // The frame's camera and tolerance, for every stage.
  this->PrepareView(f);

  // 1. Layered depth image of the scene (and of the refractors, for §4).
  if (!this->RenderLayers(f.Window))
  {
    return false;
  }
  in.GodRaysOn = this->Settings.GodRays && caustics::gl::VolumeSegmentList::IsNeeded(scene);
  if (in.GodRaysOn)
  {
    in.VolumeLines->Begin(f.Window, f.Width, f.Height);
  }

  // 2-6. Per light: emit, then trace, transfer and splat bounce after bounce; where
  // the photons' light goes is counted in one set of counters for every light.
  in.Statistics.Begin(scene, f.LightBuffers, 1.0); // one photon per emitter texel
  bool ok = true;
  const int lights = f.LightBuffers->GetNumberOfLights();
  for (int light = 0; ok && light < lights; ++light)
  {
    if (caustics::LightReachesSpecular(scene.Lights[light], scene.SpecularBounds))
    {
      ok = this->TraceLight(f, light, in.GodRaysOn);
    }
  }
  return ok;
}

const caustics::hcm::StatisticsBuffer* vtkCausticsScreenSpacePhotonPass::GetStatisticsBuffer()
{
  return &this->Internal->Statistics;
}

bool vtkCausticsScreenSpacePhotonPass::RenderVolumeRadiance(
  const FrameInputs& f, vtkTextureObject* target)
{
  // The god-rays drawn bounce after bounce, blurred (§3.2).
  if (!this->Internal->GodRaysOn)
  {
    return false;
  }
  this->StartStage("ssp god-ray blur");
  const bool ok =
    this->Internal->VolumeLines->Finish(f.Window, this->Settings.GodRayBlurPixels, target);
  this->StopStage("ssp god-ray blur");
  return ok;
}

double vtkCausticsScreenSpacePhotonPass::GetViewTolerance(double sceneScale)
{
  return this->Settings.Tolerance(sceneScale);
}

bool vtkCausticsScreenSpacePhotonPass::TraceShadowRays(int light, vtkImageData* output)
{
  const FrameInputs& f = this->GetFrameInputs();
  auto& in = *this->Internal;
  vtkOpenGLRenderWindow* renWin = this->GetLastWindow();
  const caustics::SceneData& scene = *f.Scene;
  if (!output || !renWin || !this->GetLastFrameHadCaustics() || !in.HasLayers)
  {
    vtkErrorMacro(<< "TraceShadowRays needs an output and a last frame that traced photons");
    return false;
  }
  if (light < 0 || light >= static_cast<int>(scene.Lights.size()))
  {
    vtkErrorMacro(<< "TraceShadowRays: no light " << light << " (the scene has "
                  << scene.Lights.size() << ")");
    return false;
  }
  renWin->MakeCurrent();
  const int w = f.Width, h = f.Height, count = w * h;
  in.Rays[0].Allocate(RayBytes * count);
  in.Counters[0].Allocate(16);
  const GLuint total = static_cast<GLuint>(count);
  glNamedBufferSubData(in.Counters[0].Handle(), 0, 4, &total);
  vtkCausticsShaderProgram* p = in.ShadowProgram;
  if (!p->Bind(renWin))
  {
    return false;
  }
  const caustics::Light& source = scene.Lights[light];
  {
    caustics::ssp::TextureUnits units(renWin);
    p->SetUniformi("gPosition", units.Bind(f.CameraGBuffer->GetPositionTexture()));
    p->SetUniformi("gNormal", units.Bind(f.CameraGBuffer->GetNormalTexture()));
    p->SetUniform2i("size", w, h);
    p->SetUniformi("lightType", static_cast<int>(source.type));
    p->SetUniform3f("lightOrigin", static_cast<float>(source.position[0]),
      static_cast<float>(source.position[1]), static_cast<float>(source.position[2]));
    p->SetUniform3f("lightDirection", static_cast<float>(source.direction[0]),
      static_cast<float>(source.direction[1]), static_cast<float>(source.direction[2]));
    in.Rays[0].BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_NEXT_RAY_BINDING);
    p->DispatchCovering2D(w, h, 16, 16);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  p->Unbind(renWin);
  const bool timed = this->GetTimings()->GetEnabled();
  this->GetTimings()->EnabledOff();
  const bool ok = in.Tracer->Trace(renWin, this->Settings, in.View, in.Rays[0].Handle(),
    in.Counters[0].Handle(), count, "ssp shadow ");
  this->GetTimings()->SetEnabled(timed);
  if (!ok)
  {
    return false;
  }
  std::vector<float> rays(static_cast<std::size_t>(count) * 8);
  std::vector<float> hits(static_cast<std::size_t>(count) * 8);
  glGetNamedBufferSubData(in.Rays[0].Handle(), 0, rays.size() * 4, rays.data());
  glGetNamedBufferSubData(in.Tracer->GetHitBuffer(), 0, hits.size() * 4, hits.data());
  WriteShadow(rays, hits, source, w, h, output);
  // The next frame rebuilds its transfer maps: nothing else to restore.
  return true;
}

void vtkCausticsScreenSpacePhotonPass::ReleaseTechniqueResources(vtkWindow* w)
{
  auto& in = *this->Internal;
  in.SceneLayers->ReleaseGraphicsResources(w);
  in.Tracer->ReleaseGraphicsResources(w);
  in.Emitter->ReleaseGraphicsResources(w);
  in.Splatter->ReleaseGraphicsResources(w);
  in.VolumeLines->ReleaseGraphicsResources(w);
  in.SegmentProgram->ReleaseGraphicsResources(w);
  in.VolumeSegments.Release();
  in.VolumeCapacity.Release();
  in.InitialProgram->ReleaseGraphicsResources(w);
  in.TransferProgram->ReleaseGraphicsResources(w);
  in.ShadowProgram->ReleaseGraphicsResources(w);
  in.Spacing->ReleaseGraphicsResources(w);
  for (int k = 0; k < 2; ++k)
  {
    in.Rays[k].Release();
    in.Payloads[k].Release();
    in.Counters[k].Release();
  }
  in.Statistics.Release();
  in.Landed.Release(w);
  in.Capacity = 0;
  in.HasLayers = false;
}

void vtkCausticsScreenSpacePhotonPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaximumNumberOfLayers: " << this->Settings.MaximumNumberOfLayers << "\n";
  os << indent << "PerObjectLayers: " << this->Settings.PerObjectLayers << "\n";
  os << indent << "MaximumBounces: " << this->Settings.MaximumBounces << "\n";
  os << indent << "IntersectionTolerance: " << this->Settings.IntersectionTolerance
     << " m (0: relative)\n";
  os << indent << "RelativeIntersectionTolerance: " << this->Settings.RelativeIntersectionTolerance
     << " of the scene's diagonal\n";
  os << indent << "LastTolerance: " << this->LastTolerance << " m\n";
  os << indent << "TraceView: " << this->Settings.TraceView
     << " (last frame: " << (this->LastTraceViewFitted ? "fitted" : "camera")
     << (this->LastTraceViewMissedSpecular ? ", a specular actor outside it" : "") << ")\n";
  os << indent << "MinimumLineLength: " << this->Settings.MinimumLineLength << " fragments\n";
  os << indent << "RowsPerBatch: " << this->Settings.RowsPerBatch << "\n";
  os << indent << "SplatRadius: " << this->Settings.SplatRadius << " m (0: in pixel footprints)\n";
  os << indent << "SplatRadiusPixels: " << this->Settings.SplatRadiusPixels << "\n";
  os << indent << "SplatRadiusSpacings: " << this->Settings.SplatRadiusSpacings << "\n";
  os << indent << "Reconstruction: "
     << (this->Settings.Reconstruction == RECONSTRUCTION_TRIANGLES ? "triangles" : "splats") << "\n";
  os << indent << "GodRays: " << this->Settings.GodRays << "\n";
  os << indent << "GodRayBlurPixels: " << this->Settings.GodRayBlurPixels << "\n";
  os << indent << "VolumeSubSegments: " << this->Settings.VolumeSubSegments << "\n";
  os << indent << "SkipOffscreenSpecular: " << this->Settings.SkipOffscreenSpecular << "\n";
  os << indent << "Photon capacity (last frame): " << this->Internal->Capacity << "\n";
}
