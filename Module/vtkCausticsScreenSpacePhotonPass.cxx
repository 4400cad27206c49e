#include "vtkCausticsScreenSpacePhotonPass.h"

#include "vtkActor.h"
#include "vtkAssemblyNode.h"
#include "vtkAssemblyPath.h"
#include "vtkCamera.h"
#include "vtkCausticsBindings.h" // CAUSTICS_*_BINDING
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsLayeredDepth.h"
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsPhotonEmitter.h"
#include "vtkCausticsPhotonSplatter.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsScreenSpaceGodRays.h"
#include "vtkCausticsScreenSpaceLineTracer.h"
#include "vtkCausticsScreenSpaceRefraction.h"
#include "vtkCausticsScreenSpaceUtilities.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkCausticsTimings.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtkPropCollection.h"
#include "vtkRenderState.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsOptics.h"
#include "vtkCausticsScreenSpaceCommon.h"
#include "vtkCausticsScreenSpacePhotonPassInitialCS.h"
#include "vtkCausticsScreenSpacePhotonPassRadiusCS.h"
#include "vtkCausticsScreenSpacePhotonPassShadowCS.h"
#include "vtkCausticsScreenSpacePhotonPassTransferCS.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCausticsScreenSpacePhotonPass);

namespace
{
// Bytes of one SspRay, one SspPayload, one SspHit.
constexpr std::size_t RayBytes = 32;
constexpr std::size_t PayloadBytes = 32;
constexpr std::size_t HitBytes = 32;

/** Bounding box of a mesh's vertices. */
std::array<double, 6> MeshBounds(const caustics::Mesh& mesh)
{
  std::array<double, 6> b = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
  for (std::size_t v = 0; v + 2 < mesh.positions.size(); v += 3)
  {
    for (int c = 0; c < 3; ++c)
    {
      b[2 * c] = std::min(b[2 * c], static_cast<double>(mesh.positions[v + c]));
      b[2 * c + 1] = std::max(b[2 * c + 1], static_cast<double>(mesh.positions[v + c]));
    }
  }
  return b;
}

/** True if the box may intersect the clip volume of a row-major world-to-clip matrix. */
bool BoxInFrustum(const std::array<double, 6>& b, const double m[16])
{
  if (b[0] > b[1])
  {
    return false; // no vertex
  }
  // Planes w + s * clip_a >= 0 for a = x, y, z and s = +-1.
  for (int a = 0; a < 3; ++a)
  {
    for (int s = -1; s <= 1; s += 2)
    {
      bool allOutside = true;
      for (int corner = 0; corner < 8 && allOutside; ++corner)
      {
        const double p[3] = { b[(corner & 1) ? 1 : 0], b[(corner & 2) ? 3 : 2],
          b[(corner & 4) ? 5 : 4] };
        double w = m[15], c = m[4 * a + 3];
        for (int k = 0; k < 3; ++k)
        {
          w += m[12 + k] * p[k];
          c += m[4 * a + k] * p[k];
        }
        allOutside = w + s * c < 0.0;
      }
      if (allOutside)
      {
        return false;
      }
    }
  }
  return true;
}
}

struct vtkCausticsScreenSpacePhotonPass::Internals
{
  vtkNew<vtkCausticsLayeredDepth> SceneLayers;
  vtkNew<vtkCausticsLayeredDepth> RefractorLayers;
  vtkNew<vtkCausticsScreenSpaceLineTracer> Tracer;
  vtkNew<vtkCausticsPhotonEmitter> Emitter;
  vtkNew<vtkCausticsPhotonSplatter> Splatter;
  vtkNew<vtkCausticsScreenSpaceGodRays> GodRays;
  vtkNew<vtkCausticsScreenSpaceRefraction> Refraction;
  vtkNew<vtkCausticsShaderProgram> InitialProgram;
  vtkNew<vtkCausticsShaderProgram> TransferProgram;
  vtkNew<vtkCausticsShaderProgram> ShadowProgram;
  vtkNew<vtkCausticsShaderProgram> RadiusProgram;

  // Transfer maps (photon lists) and their counters, ping-ponged between bounces.
  caustics::ssp::Buffer Rays[2];
  caustics::ssp::Buffer Payloads[2];
  caustics::ssp::Buffer Counters[2];
  int Current = 0;
  int Capacity = 0;
  int GridWidth = 0;
  // Splat records of the photons that ended on receivers this bounce.
  vtkNew<vtkTextureObject> SplatPosition;
  vtkNew<vtkTextureObject> SplatNormal;
  vtkNew<vtkTextureObject> SplatFlux;

  // Camera of the frame, for the stages.
  float ClipToWorld[16];
  vtkCausticsScreenSpaceLineTracer::View View;
  bool HasLayers = false;
  bool HasRefractorLayers = false;
  double Background[3] = { 0, 0, 0 }; // the renderer's: what refracted rays see when they leave

  // Per-mesh bounds for the view test, refreshed when a mesh's version changes.
  std::vector<std::pair<unsigned long, std::array<double, 6>>> MeshBounds;

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

  void ClearCounter(int which)
  {
    const GLuint zero = 0;
    glClearNamedBufferData(
      this->Counters[which].Handle, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  }
};

vtkCausticsScreenSpacePhotonPass::vtkCausticsScreenSpacePhotonPass()
  : Internal(new Internals)
{
  auto& in = *this->Internal;
  const std::string optics = vtkCausticsOptics;
  const std::string common = vtkCausticsScreenSpaceCommon;
  in.InitialProgram->SetName("ssp first transfer map");
  in.InitialProgram->SetComputeSource((common + vtkCausticsScreenSpacePhotonPassInitialCS).c_str());
  in.InitialProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  in.TransferProgram->SetName("ssp specular transfer");
  in.TransferProgram->SetComputeSource(
    (optics + common + vtkCausticsScreenSpacePhotonPassTransferCS).c_str());
  in.RadiusProgram->SetName("ssp splat radius");
  in.RadiusProgram->SetComputeSource(vtkCausticsScreenSpacePhotonPassRadiusCS);
  in.RadiusProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  in.ShadowProgram->SetName("ssp shadow rays");
  in.ShadowProgram->SetComputeSource((common + vtkCausticsScreenSpacePhotonPassShadowCS).c_str());
  in.ShadowProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  in.RefractorLayers->SetRoleMask(vtkCausticsSceneGeometry::RoleBit(3));
  for (float& v : in.ClipToWorld)
  {
    v = 0.0f;
  }
}

vtkCausticsScreenSpacePhotonPass::~vtkCausticsScreenSpacePhotonPass()
{
  if (this->Internal->Rays[0].Handle)
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): GL objects leaked");
  }
}

vtkCausticsLayeredDepth* vtkCausticsScreenSpacePhotonPass::GetLayeredDepth()
{
  return this->Internal->SceneLayers;
}
vtkCausticsLayeredDepth* vtkCausticsScreenSpacePhotonPass::GetRefractorLayeredDepth()
{
  return this->Internal->RefractorLayers;
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

void vtkCausticsScreenSpacePhotonPass::Render(const vtkRenderState* s)
{
  vtkRenderer* renderer = s->GetRenderer();
  renderer->GetBackground(this->Internal->Background);
  if (this->ComputeDirectIrradiance || this->KeepBuffers || !this->CannotNeedCaustics(renderer))
  {
    this->Superclass::Render(s);
    return;
  }
  // Nothing can need caustics: plain VTK, without even the scene snapshot (whose
  // cost grows with the scene's triangles), as the base pass's own skip path.
  this->NumberOfRenderedProps = 0;
  this->LastFrameHadCaustics = this->LastFrameHadDirect = this->LastFrameHadBuffers = false;
  this->LastFrameHadTechniqueColor = this->TechniqueWroteVolume = false;
  if (!this->DelegatePass)
  {
    vtkRenderStepsPass* steps = vtkRenderStepsPass::New();
    this->SetDelegatePass(steps);
    steps->Delete();
  }
  this->Timings->BeginFrame();
  this->Timings->StartStage("vtk delegate", false); // CPU only, as the base pass's skip path
  this->DelegatePass->Render(s);
  this->NumberOfRenderedProps += this->DelegatePass->GetNumberOfRenderedProps();
  this->StopStage("vtk delegate");
  this->Timings->EndFrame();
}

bool vtkCausticsScreenSpacePhotonPass::CannotNeedCaustics(vtkRenderer* renderer)
{
  // Specular actors and their world bounds (VTK's own, cached), as the scene
  // snapshot would classify them.
  const double cutoff = this->Extractor->GetRoughnessCutoff();
  std::vector<std::array<double, 6>> specular;
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (!prop->GetVisibility())
    {
      continue;
    }
    prop->InitPathTraversal();
    while (vtkAssemblyPath* path = prop->GetNextPath())
    {
      vtkActor* actor = vtkActor::SafeDownCast(path->GetLastNode()->GetViewProp());
      if (!actor || !actor->GetVisibility() || !actor->GetMapper())
      {
        continue;
      }
      const int role = vtkCausticsMaterial::Classify(actor, cutoff);
      if (role == vtkCausticsMaterial::ROLE_REFLECTOR ||
        role == vtkCausticsMaterial::ROLE_REFRACTOR)
      {
        const double* b = actor->GetBounds();
        if (b && vtkMath::AreBoundsInitialized(b))
        {
          specular.push_back({ b[0], b[1], b[2], b[3], b[4], b[5] });
        }
        else
        {
          return false; // unknown extent: let the snapshot decide
        }
      }
    }
  }
  if (specular.empty())
  {
    return true;
  }
  // Does any light reach them?
  caustics::SceneData scene; // only the fields LightReachesSpecular reads
  for (int c = 0; c < 3; ++c)
  {
    scene.SpecularBounds[2 * c] = VTK_DOUBLE_MAX;
    scene.SpecularBounds[2 * c + 1] = -VTK_DOUBLE_MAX;
    for (const auto& b : specular)
    {
      scene.SpecularBounds[2 * c] = std::min(scene.SpecularBounds[2 * c], b[2 * c]);
      scene.SpecularBounds[2 * c + 1] = std::max(scene.SpecularBounds[2 * c + 1], b[2 * c + 1]);
    }
  }
  bool reached = false;
  vtkLightCollection* lights = renderer->GetLights();
  lights->InitTraversal(it);
  while (vtkLight* light = lights->GetNextLight(it))
  {
    if (!light->GetSwitch() || !(light->GetIntensity() > 0.0))
    {
      continue;
    }
    caustics::Light physical;
    physical.radiometric = { { 1.0, 1.0, 1.0 } };
    double position[3], focal[3], axis[3];
    light->GetTransformedPosition(position);
    light->GetTransformedFocalPoint(focal);
    vtkMath::Subtract(focal, position, axis);
    if (vtkMath::Normalize(axis) == 0.0)
    {
      return false; // degenerate: let the snapshot report it
    }
    physical.position = { { position[0], position[1], position[2] } };
    physical.direction = { { axis[0], axis[1], axis[2] } };
    physical.type = caustics::Light::Type::Directional;
    if (light->GetPositional() && light->GetConeAngle() < 90.0)
    {
      physical.type = caustics::Light::Type::Spot;
      physical.cosOuter = std::cos(vtkMath::RadiansFromDegrees(light->GetConeAngle()));
    }
    reached = reached || caustics::LightReachesSpecular(physical, scene.SpecularBounds);
  }
  if (!reached)
  {
    return true;
  }
  if (!this->SkipOffscreenSpecular)
  {
    return false;
  }
  // Is any of them in the camera's view?
  int width = 0, height = 0, x = 0, y = 0;
  renderer->GetTiledSizeAndOrigin(&width, &height, &x, &y);
  vtkMatrix4x4* matrix = renderer->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
    height > 0 ? static_cast<double>(width) / height : 1.0, -1.0, 1.0);
  for (const auto& b : specular)
  {
    if (BoxInFrustum(b, &matrix->Element[0][0]))
    {
      return false;
    }
  }
  return true;
}

bool vtkCausticsScreenSpacePhotonPass::NeedsCaustics()
{
  if (!this->Superclass::NeedsCaustics())
  {
    return false;
  }
  const caustics::SceneData& scene = this->Extractor->GetScene();
  bool reached = false;
  for (const caustics::Light& light : scene.Lights)
  {
    reached = reached || caustics::LightReachesSpecular(light, scene.SpecularBounds);
  }
  if (!reached)
  {
    return false;
  }
  if (!this->SkipOffscreenSpecular)
  {
    return true;
  }
  // A specular mesh whose bounding box meets the camera's frustum (cached per mesh).
  auto& cache = this->Internal->MeshBounds;
  cache.resize(scene.Meshes.size(), { ~0ul, {} });
  for (std::size_t m = 0; m < scene.Meshes.size(); ++m)
  {
    const caustics::Mesh& mesh = scene.Meshes[m];
    const caustics::Role role = scene.Materials[mesh.material].role;
    if (role != caustics::Role::Reflector && role != caustics::Role::Refractor)
    {
      continue;
    }
    if (cache[m].first != mesh.version)
    {
      cache[m] = { mesh.version, MeshBounds(mesh) };
    }
    if (BoxInFrustum(cache[m].second, scene.View.worldToClip))
    {
      return true;
    }
  }
  return false;
}

bool vtkCausticsScreenSpacePhotonPass::RenderLayers(vtkOpenGLRenderWindow* renWin)
{
  auto& in = *this->Internal;
  const caustics::SceneData& scene = this->Extractor->GetScene();
  in.SceneLayers->SetMaximumNumberOfLayers(this->MaximumNumberOfLayers);
  in.SceneLayers->SetPerObject(this->PerObjectLayers);
  in.SceneLayers->SetTimings(this->Timings, "ssp layers ");
  in.HasLayers = in.SceneLayers->Render(
    renWin, this->Geometry, scene, this->WorldToClip, this->Width, this->Height);
  in.HasRefractorLayers = false;
  if (in.HasLayers && this->RefractionTracing &&
    this->Geometry->GetNumberOfTriangles(vtkCausticsSceneGeometry::RoleBit(3)) > 0)
  {
    in.RefractorLayers->SetMaximumNumberOfLayers(this->MaximumNumberOfLayers);
    in.RefractorLayers->SetTimings(this->Timings, "ssp refractor layers ");
    in.HasRefractorLayers = in.RefractorLayers->Render(
      renWin, this->Geometry, scene, this->WorldToClip, this->Width, this->Height);
  }
  return in.HasLayers;
}

bool vtkCausticsScreenSpacePhotonPass::EmitPhotons(vtkOpenGLRenderWindow* renWin, int light)
{
  auto& in = *this->Internal;
  const caustics::SceneData& scene = this->Extractor->GetScene();
  if (!in.Emitter->Emit(renWin, this->LightBuffers, light, this->Geometry, scene))
  {
    return false;
  }
  const int* grid = in.Emitter->GetGridSize();
  in.GridWidth = grid[0];
  in.Capacity = grid[0] * grid[1];
  for (int k = 0; k < 2; ++k)
  {
    in.Rays[k].Ensure(RayBytes * in.Capacity);
    in.Payloads[k].Ensure(PayloadBytes * in.Capacity);
    in.Counters[k].Ensure(16);
  }
  caustics::gl::EnsureTexture(in.SplatPosition, renWin, grid[0], grid[1], GL_RGBA32F);
  caustics::gl::EnsureTexture(in.SplatNormal, renWin, grid[0], grid[1], GL_RGBA32F);
  caustics::gl::EnsureTexture(in.SplatFlux, renWin, grid[0], grid[1], GL_RGBA32F);

  // Compact the emitter's grid into the first transfer map.
  in.Current = 0;
  in.ClearCounter(0);
  vtkCausticsShaderProgram* p = in.InitialProgram;
  if (!p->Bind(renWin))
  {
    return false;
  }
  const caustics::Light& source = scene.Lights[light];
  const caustics::Medium& medium = scene.Participating;
  caustics::ssp::TextureUnits units(renWin);
  p->SetUniformi("emitPosition", units.Bind(in.Emitter->GetPositionTexture()));
  p->SetUniformi("emitDirection", units.Bind(in.Emitter->GetDirectionTexture()));
  p->SetUniformi("emitFlux", units.Bind(in.Emitter->GetFluxTexture()));
  p->SetUniformi(
    "lightPosition", units.Bind(this->LightBuffers->GetGBuffer(light)->GetPositionTexture()));
  p->SetUniform2i("grid", grid[0], grid[1]);
  p->SetUniformi("resolution", this->LightBuffers->GetResolution());
  p->SetUniformi("lightType", static_cast<int>(source.type));
  p->SetUniform3f("lightOrigin", static_cast<float>(source.position[0]),
    static_cast<float>(source.position[1]), static_cast<float>(source.position[2]));
  p->SetUniform3f("lightDirection", static_cast<float>(source.direction[0]),
    static_cast<float>(source.direction[1]), static_cast<float>(source.direction[2]));
  p->SetUniformi("mediumOn", medium.enabled ? 1 : 0);
  p->SetUniform3f("sigmaT", static_cast<float>(medium.sigmaS[0] + medium.sigmaA[0]),
    static_cast<float>(medium.sigmaS[1] + medium.sigmaA[1]),
    static_cast<float>(medium.sigmaS[2] + medium.sigmaA[2]));
  p->SetUniform3f("boundsMin", static_cast<float>(scene.Bounds[0]),
    static_cast<float>(scene.Bounds[2]), static_cast<float>(scene.Bounds[4]));
  p->SetUniform3f("boundsMax", static_cast<float>(scene.Bounds[1]),
    static_cast<float>(scene.Bounds[3]), static_cast<float>(scene.Bounds[5]));
  in.Rays[0].BindStorage(CAUSTICS_SSP_NEXT_RAY_BINDING);
  in.Payloads[0].BindStorage(CAUSTICS_SSP_NEXT_PAYLOAD_BINDING);
  in.Counters[0].BindStorage(CAUSTICS_SSP_NEXT_COUNTER_BINDING);
  p->DispatchCovering2D(grid[0], grid[1], 16, 16);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  p->Unbind(renWin);
  return true;
}

bool vtkCausticsScreenSpacePhotonPass::TracePhotons(
  vtkOpenGLRenderWindow* renWin, int light, int bounce)
{
  auto& in = *this->Internal;
  const int c = in.Current;
  return in.Tracer->Trace(renWin, in.View, in.Rays[c].Handle, in.Counters[c].Handle, in.Capacity,
    in.Prefix(light, this->LightBuffers->GetNumberOfLights(), bounce));
}

bool vtkCausticsScreenSpacePhotonPass::TransferPhotons(
  vtkOpenGLRenderWindow* renWin, int light, int bounce)
{
  auto& in = *this->Internal;
  const caustics::SceneData& scene = this->Extractor->GetScene();
  const int c = in.Current, n = 1 - c;
  in.ClearCounter(n);
  const float none[4] = { 0, 0, 0, 0 };
  glClearTexImage(in.SplatPosition->GetHandle(), 0, GL_RGBA, GL_FLOAT, none);

  vtkCausticsShaderProgram* p = in.TransferProgram;
  if (!p->Bind(renWin))
  {
    return false;
  }
  in.Counters[c].BindStorage(CAUSTICS_SSP_COUNTER_BINDING);
  in.Rays[c].BindStorage(CAUSTICS_SSP_RAY_BINDING);
  in.Payloads[c].BindStorage(CAUSTICS_SSP_PAYLOAD_BINDING);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_HIT_BINDING, in.Tracer->GetHitBuffer());
  in.Rays[n].BindStorage(CAUSTICS_SSP_NEXT_RAY_BINDING);
  in.Payloads[n].BindStorage(CAUSTICS_SSP_NEXT_PAYLOAD_BINDING);
  in.Counters[n].BindStorage(CAUSTICS_SSP_NEXT_COUNTER_BINDING);
  this->Geometry->BindMaterials();
  glBindImageTexture(0, in.SplatPosition->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glBindImageTexture(1, in.SplatNormal->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glBindImageTexture(2, in.SplatFlux->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  const caustics::Medium& medium = scene.Participating;
  p->SetUniformi("capacity", in.Capacity);
  p->SetUniformi("gridWidth", in.GridWidth);
  p->SetUniformi("maxEvents", this->MaximumBounces);
  p->SetUniformMatrix4("worldToClip", this->WorldToClip);
  p->SetUniformMatrix4("clipToWorld", in.ClipToWorld);
  p->SetUniform2f("viewport", static_cast<float>(this->Width), static_cast<float>(this->Height));
  const float origin[4] = { static_cast<float>(in.View.ViewOrigin[0]),
    static_cast<float>(in.View.ViewOrigin[1]), static_cast<float>(in.View.ViewOrigin[2]),
    static_cast<float>(in.View.ViewOrigin[3]) };
  p->SetUniform4f("viewOrigin", origin);
  p->SetUniformf("splatRadius", static_cast<float>(this->SplatRadius));
  p->SetUniformf("splatRadiusPixels", static_cast<float>(this->SplatRadiusPixels));
  p->SetUniformi("mediumOn", medium.enabled ? 1 : 0);
  p->SetUniform3f("sigmaT", static_cast<float>(medium.sigmaS[0] + medium.sigmaA[0]),
    static_cast<float>(medium.sigmaS[1] + medium.sigmaA[1]),
    static_cast<float>(medium.sigmaS[2] + medium.sigmaA[2]));
  p->SetUniform3f("boundsMin", static_cast<float>(scene.Bounds[0]),
    static_cast<float>(scene.Bounds[2]), static_cast<float>(scene.Bounds[4]));
  p->SetUniform3f("boundsMax", static_cast<float>(scene.Bounds[1]),
    static_cast<float>(scene.Bounds[3]), static_cast<float>(scene.Bounds[5]));
  p->SetUniformu(
    "seed", 0x9e3779b9u * static_cast<unsigned int>(bounce + 1) + static_cast<unsigned int>(light));
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, in.Tracer->GetArgumentBuffer());
  glDispatchComputeIndirect(0);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT |
    GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  for (GLuint unit = 0; unit < 3; ++unit)
  {
    glBindImageTexture(unit, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  }
  p->Unbind(renWin);
  return true;
}

bool vtkCausticsScreenSpacePhotonPass::SplatPhotons(vtkOpenGLRenderWindow* renWin, int, int)
{
  auto& in = *this->Internal;
  const int* grid = in.Emitter->GetGridSize();
  // Radii from the neighbours' spacing (see glsl/vtkCausticsScreenSpacePhotonPassRadiusCS.glsl).
  if (this->SplatRadius <= 0.0 && this->SplatRadiusSpacings > 0.0)
  {
    vtkCausticsShaderProgram* p = in.RadiusProgram;
    if (!p->Bind(renWin))
    {
      return false;
    }
    glBindImageTexture(0, in.SplatPosition->GetHandle(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindImageTexture(1, in.SplatNormal->GetHandle(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    p->SetUniform2i("grid", grid[0], grid[1]);
    p->SetUniformi("branchRows", this->LightBuffers->GetResolution());
    p->SetUniformf("spacings", static_cast<float>(this->SplatRadiusSpacings));
    p->DispatchCovering2D(grid[0], grid[1], 16, 16);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    p->Unbind(renWin);
  }
  // Into the caustic framebuffer the base pass bound (each stage restores it).
  return in.Splatter->Splat(renWin, in.SplatPosition, in.SplatNormal, in.SplatFlux, grid[0],
    grid[1], this->CameraGBuffer, this->WorldToClip);
}

bool vtkCausticsScreenSpacePhotonPass::DrawGodRays(vtkOpenGLRenderWindow* renWin, int, int)
{
  auto& in = *this->Internal;
  const caustics::SceneData& scene = this->Extractor->GetScene();
  vtkCausticsScreenSpaceGodRays::View view;
  view.WorldToClip = this->WorldToClip;
  view.ClipToWorld = in.ClipToWorld;
  view.Width = this->Width;
  view.Height = this->Height;
  std::copy(in.View.ViewOrigin, in.View.ViewOrigin + 4, view.ViewOrigin);
  std::copy(scene.Bounds, scene.Bounds + 6, view.Bounds);
  view.Medium = &scene.Participating;
  view.OpaqueDepth = this->CameraGBuffer->GetDepthTexture();
  view.RefractiveDepth = this->RefractiveGBuffer->GetDepthTexture();
  const int c = in.Current;
  return in.GodRays->Draw(renWin, view, in.Rays[c].Handle, in.Payloads[c].Handle,
    in.Tracer->GetLineBuffer(), in.Tracer->GetHitBuffer(), in.Tracer->GetArgumentBuffer());
}

bool vtkCausticsScreenSpacePhotonPass::RenderCausticIrradiance(vtkOpenGLRenderWindow* renWin)
{
  auto& in = *this->Internal;
  const caustics::SceneData& scene = this->Extractor->GetScene();

  // The frame's camera and tolerance, for every stage.
  const caustics::Camera& camera = scene.View;
  caustics::gl::ToColumnMajor(camera.clipToWorld, in.ClipToWorld);
  in.View.Layers = in.SceneLayers;
  in.View.WorldToClip = this->WorldToClip;
  std::copy(scene.Bounds, scene.Bounds + 6, in.View.Bounds);
  if (camera.parallel)
  {
    double axis[3], length = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      axis[k] = camera.focalPoint[k] - camera.position[k];
      length += axis[k] * axis[k];
    }
    length = std::sqrt(length);
    for (int k = 0; k < 3; ++k)
    {
      in.View.ViewOrigin[k] = length > 0.0 ? axis[k] / length : 0.0;
    }
    in.View.ViewOrigin[3] = 0.0;
  }
  else
  {
    std::copy(camera.position.begin(), camera.position.end(), in.View.ViewOrigin);
    in.View.ViewOrigin[3] = 1.0;
  }
  this->LastTolerance = this->IntersectionTolerance > 0.0
    ? this->IntersectionTolerance
    : this->RelativeIntersectionTolerance * scene.Scale();
  in.Tracer->SetTolerance(this->LastTolerance);
  in.Tracer->SetMinimumLineLength(this->MinimumLineLength);
  in.Tracer->SetRowsPerBatch(this->RowsPerBatch);
  in.Tracer->SetTimings(this->Timings);
  in.GodRays->SetBlurPixels(this->GodRayBlurPixels);

  // 1. Layered depth image of the scene (and of the refractors, for §4).
  if (!this->RenderLayers(renWin))
  {
    return false;
  }
  const caustics::Medium& medium = scene.Participating;
  const bool godRays = this->GodRays && medium.enabled &&
    (medium.sigmaS[0] > 0.0 || medium.sigmaS[1] > 0.0 || medium.sigmaS[2] > 0.0);
  if (godRays)
  {
    in.GodRays->Begin(renWin, this->Width, this->Height);
  }

  // 2-6. Per light: emit, then trace, transfer and splat bounce after bounce.
  bool ok = true;
  const int lights = this->LightBuffers->GetNumberOfLights();
  for (int light = 0; ok && light < lights; ++light)
  {
    if (!caustics::LightReachesSpecular(scene.Lights[light], scene.SpecularBounds))
    {
      continue;
    }
    const std::string prefix = in.Prefix(light, lights, 0);
    this->StartStage((prefix + "emission").c_str());
    ok = this->EmitPhotons(renWin, light);
    this->StopStage((prefix + "emission").c_str());
    for (int bounce = 1; ok && bounce <= this->MaximumBounces; ++bounce)
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
  }
  if (ok && godRays)
  {
    this->StartStage("ssp god-ray blur");
    ok = in.GodRays->Finish(renWin, this->VolumeTexture);
    this->StopStage("ssp god-ray blur");
    this->TechniqueWroteVolume = ok;
  }
  return ok;
}

bool vtkCausticsScreenSpacePhotonPass::RenderTechniqueColor(vtkOpenGLRenderWindow* renWin)
{
  auto& in = *this->Internal;
  if (!this->RefractionTracing || !in.HasRefractorLayers)
  {
    return false;
  }
  // Surfaces seen only through a refractor are shaded from their irradiance.
  if (!this->LastFrameHadDirect)
  {
    this->StartStage("ssp direct irradiance for refraction");
    this->LastFrameHadDirect = this->RenderDirectIrradiance(renWin);
    this->StopStage("ssp direct irradiance for refraction");
  }
  this->StartStage("ssp refraction tracing");
  const caustics::SceneData& scene = this->Extractor->GetScene();
  vtkCausticsScreenSpaceRefraction::Inputs inputs;
  inputs.RefractorLayers = in.RefractorLayers;
  inputs.Opaque = this->CameraGBuffer;
  inputs.Geometry = this->Geometry;
  inputs.DelegateColor = this->DelegateColorTexture;
  inputs.DelegateDepth = this->DelegateDepthTexture;
  inputs.CausticIrradiance = this->CausticTexture;
  inputs.DirectIrradiance = this->LastFrameHadDirect ? this->DirectTexture.GetPointer() : nullptr;
  inputs.WorldToClip = this->WorldToClip;
  inputs.Width = this->Width;
  inputs.Height = this->Height;
  std::copy(in.View.ViewOrigin, in.View.ViewOrigin + 4, inputs.ViewOrigin);
  std::copy(scene.Bounds, scene.Bounds + 6, inputs.Bounds);
  std::copy(in.Background, in.Background + 3, inputs.Background);
  inputs.Tolerance = this->LastTolerance;
  in.Refraction->SetMaximumEvents(std::max(2, this->MaximumBounces + 1));
  const bool ok = in.Refraction->Render(renWin, inputs, this->TechniqueColorTexture);
  this->StopStage("ssp refraction tracing");
  return ok;
}

bool vtkCausticsScreenSpacePhotonPass::TraceShadowRays(int light, vtkImageData* output)
{
  auto& in = *this->Internal;
  vtkOpenGLRenderWindow* renWin = this->LastWindow;
  const caustics::SceneData& scene = this->Extractor->GetScene();
  if (!output || !renWin || !this->LastFrameHadCaustics || !in.HasLayers)
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
  const int w = this->Width, h = this->Height, count = w * h;
  in.Rays[0].Ensure(RayBytes * count);
  in.Counters[0].Ensure(16);
  const GLuint total = static_cast<GLuint>(count);
  glNamedBufferSubData(in.Counters[0].Handle, 0, 4, &total);
  vtkCausticsShaderProgram* p = in.ShadowProgram;
  if (!p->Bind(renWin))
  {
    return false;
  }
  const caustics::Light& source = scene.Lights[light];
  {
    caustics::ssp::TextureUnits units(renWin);
    p->SetUniformi("gPosition", units.Bind(this->CameraGBuffer->GetPositionTexture()));
    p->SetUniformi("gNormal", units.Bind(this->CameraGBuffer->GetNormalTexture()));
    p->SetUniform2i("size", w, h);
    p->SetUniformi("lightType", static_cast<int>(source.type));
    p->SetUniform3f("lightOrigin", static_cast<float>(source.position[0]),
      static_cast<float>(source.position[1]), static_cast<float>(source.position[2]));
    p->SetUniform3f("lightDirection", static_cast<float>(source.direction[0]),
      static_cast<float>(source.direction[1]), static_cast<float>(source.direction[2]));
    in.Rays[0].BindStorage(CAUSTICS_SSP_NEXT_RAY_BINDING);
    p->DispatchCovering2D(w, h, 16, 16);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  p->Unbind(renWin);
  const bool timed = this->Timings->GetEnabled();
  this->Timings->EnabledOff();
  const bool ok = in.Tracer->Trace(
    renWin, in.View, in.Rays[0].Handle, in.Counters[0].Handle, count, "ssp shadow ");
  this->Timings->SetEnabled(timed);
  if (!ok)
  {
    return false;
  }
  std::vector<float> rays(static_cast<std::size_t>(count) * 8);
  std::vector<float> hits(static_cast<std::size_t>(count) * 8);
  glGetNamedBufferSubData(in.Rays[0].Handle, 0, rays.size() * 4, rays.data());
  glGetNamedBufferSubData(in.Tracer->GetHitBuffer(), 0, hits.size() * 4, hits.data());
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
  // The next frame rebuilds its transfer maps: nothing else to restore.
  return true;
}

void vtkCausticsScreenSpacePhotonPass::ReleaseTechniqueResources(vtkWindow* w)
{
  auto& in = *this->Internal;
  in.SceneLayers->ReleaseGraphicsResources(w);
  in.RefractorLayers->ReleaseGraphicsResources(w);
  in.Tracer->ReleaseGraphicsResources(w);
  in.Emitter->ReleaseGraphicsResources(w);
  in.Splatter->ReleaseGraphicsResources(w);
  in.GodRays->ReleaseGraphicsResources(w);
  in.Refraction->ReleaseGraphicsResources(w);
  in.InitialProgram->ReleaseGraphicsResources(w);
  in.TransferProgram->ReleaseGraphicsResources(w);
  in.ShadowProgram->ReleaseGraphicsResources(w);
  in.RadiusProgram->ReleaseGraphicsResources(w);
  for (int k = 0; k < 2; ++k)
  {
    in.Rays[k].Release();
    in.Payloads[k].Release();
    in.Counters[k].Release();
  }
  in.SplatPosition->ReleaseGraphicsResources(w);
  in.SplatNormal->ReleaseGraphicsResources(w);
  in.SplatFlux->ReleaseGraphicsResources(w);
  in.Capacity = in.GridWidth = 0;
  in.HasLayers = in.HasRefractorLayers = false;
}

void vtkCausticsScreenSpacePhotonPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaximumNumberOfLayers: " << this->MaximumNumberOfLayers << "\n";
  os << indent << "PerObjectLayers: " << this->PerObjectLayers << "\n";
  os << indent << "MaximumBounces: " << this->MaximumBounces << "\n";
  os << indent << "IntersectionTolerance: " << this->IntersectionTolerance << " m (0: relative)\n";
  os << indent << "RelativeIntersectionTolerance: " << this->RelativeIntersectionTolerance
     << " of the scene's diagonal\n";
  os << indent << "LastTolerance: " << this->LastTolerance << " m\n";
  os << indent << "MinimumLineLength: " << this->MinimumLineLength << " fragments\n";
  os << indent << "RowsPerBatch: " << this->RowsPerBatch << "\n";
  os << indent << "SplatRadius: " << this->SplatRadius << " m (0: in pixel footprints)\n";
  os << indent << "SplatRadiusPixels: " << this->SplatRadiusPixels << "\n";
  os << indent << "SplatRadiusSpacings: " << this->SplatRadiusSpacings << "\n";
  os << indent << "GodRays: " << this->GodRays << "\n";
  os << indent << "GodRayBlurPixels: " << this->GodRayBlurPixels << "\n";
  os << indent << "RefractionTracing: " << this->RefractionTracing << "\n";
  os << indent << "SkipOffscreenSpecular: " << this->SkipOffscreenSpecular << "\n";
  os << indent << "Photon capacity (last frame): " << this->Internal->Capacity << "\n";
}
