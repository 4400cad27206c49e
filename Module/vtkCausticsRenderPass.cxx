#include "vtkCausticsRenderPass.h"

#include "vtkCausticsPhotonBufferUtilities.h" // caustics::hcm::StatisticsBuffer
#include "vtkCausticsPhotonGrid.h"            // caustics::PhotonStatistics

#include "vtkActor.h"
#include "vtkAssemblyNode.h"
#include "vtkAssemblyPath.h"
#include "vtkCamera.h"
#include "vtkCausticsAirlight.h"
#include "vtkCausticsCameraOpticalDepth.h"
#include "vtkCausticsDensityGrid.h"
#include "vtkCausticsDeviceLimits.h"
#include "vtkCausticsDistanceImpostors.h"
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsLayeredDepth.h"
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsPhotonBufferUtilities.h"
#include "vtkCausticsPhotonSplatter.h"
#include "vtkCausticsProgressiveMean.h"
#include "vtkCausticsSVGFDenoiser.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsScreenSpaceRefraction.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkCausticsSpecularHierarchy.h"
#include "vtkCausticsTimings.h"
#include "vtkCausticsTraceView.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtkPropCollection.h"
#include "vtkRenderState.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsCompositeFS.h"
#include "vtkCausticsDirectIrradianceFS.h"
#include "vtkCausticsFullScreenVS.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkCausticsRenderPass);

namespace
{
/**
 * The material of the closed refractor the eye is in, or -1 (air, an open refractor, or
 * a parallel view): the first refractor whose winding number at the eye is at least one
 * half. Only looked for when the eye is inside the specular actors' bounds, so most
 * frames pay nothing. An open refractor (a water sheet) has no winding number of 1
 * anywhere: where this is -1, the refraction shader takes the eye to be in the medium
 * of the first refractor surface a pixel sees from its back side (the reference's rule
 * at every surface; glsl/vtkCausticsScreenSpaceRefractionFS.glsl), one dot product per
 * pixel and nothing here.
 */
int EyeMaterial(const caustics::SceneData& scene, const double viewOrigin[4])
{
  const double* b = scene.SpecularBounds;
  if (viewOrigin[3] == 0.0 || !(viewOrigin[0] >= b[0] && viewOrigin[0] <= b[1] &&
                                viewOrigin[1] >= b[2] && viewOrigin[1] <= b[3] &&
                                viewOrigin[2] >= b[4] && viewOrigin[2] <= b[5]))
  {
    return -1;
  }
  for (const caustics::Mesh& mesh : scene.Meshes)
  {
    if (scene.Materials[mesh.material].role == caustics::Role::Refractor &&
      caustics::WindingNumber(mesh, viewOrigin) >= 0.5)
    {
      return mesh.material;
    }
  }
  return -1;
}

using Box = std::array<double, 6>;

/** Binds a framebuffer with one colour attachment and clears it to zero. */
void BindAndClear(vtkOpenGLFramebufferObject* framebuffer,
  std::initializer_list<vtkTextureObject*> textures, vtkOpenGLRenderWindow* renWin, bool attach)
{
  framebuffer->SetContext(renWin);
  framebuffer->Bind();
  const unsigned int count = static_cast<unsigned int>(textures.size());
  if (attach || framebuffer->GetNumberOfColorAttachments() != count)
  {
    unsigned int index = 0;
    for (vtkTextureObject* texture : textures)
    {
      framebuffer->AddColorAttachment(index++, texture);
    }
  }
  framebuffer->ActivateDrawBuffers(count);
  const float zero[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  for (unsigned int i = 0; i < count; ++i)
  {
    glClearBufferfv(GL_COLOR, static_cast<GLint>(i), zero);
  }
}

void BindAndClear(vtkOpenGLFramebufferObject* framebuffer, vtkTextureObject* texture,
  vtkOpenGLRenderWindow* renWin, bool attach)
{
  BindAndClear(framebuffer, { texture }, renWin, attach);
}

bool HasPower(const caustics::Light& light)
{
  return light.radiometric[0] > 0 || light.radiometric[1] > 0 || light.radiometric[2] > 0;
}

/** Bounding box of a mesh's vertices. */
Box MeshBounds(const caustics::Mesh& mesh)
{
  Box b = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
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
bool BoxInFrustum(const Box& b, const double m[16])
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

/**
 * Adds the actor's world bounds to `specular` if it is a visible reflector or
 * refractor; false when it is one with no known extent.
 */
bool AddSpecularBounds(vtkActor* actor, double cutoff, std::vector<Box>& specular)
{
  if (!actor || !actor->GetVisibility() || !actor->GetMapper())
  {
    return true;
  }
  const int role = vtkCausticsMaterial::Classify(actor, cutoff);
  if (role != vtkCausticsMaterial::ROLE_REFLECTOR && role != vtkCausticsMaterial::ROLE_REFRACTOR)
  {
    return true;
  }
  const double* b = actor->GetBounds();
  if (!b || !vtkMath::AreBoundsInitialized(b))
  {
    return false; // unknown extent: let the snapshot decide
  }
  specular.push_back({ b[0], b[1], b[2], b[3], b[4], b[5] });
  return true;
}

/**
 * World bounds of the visible specular actors as the snapshot would classify
 * them (VTK's own bounds, cached by VTK). False when one has no known extent.
 */
bool CollectSpecularBounds(vtkRenderer* renderer, double cutoff, std::vector<Box>& specular)
{
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (!prop->GetVisibility())
    {
      continue;
    }
    // A plain actor is its own only path (walking it would allocate the path).
    if (vtkActor* actor = vtkActor::SafeDownCast(prop))
    {
      if (!AddSpecularBounds(actor, cutoff, specular))
      {
        return false;
      }
      continue;
    }
    prop->InitPathTraversal();
    while (vtkAssemblyPath* path = prop->GetNextPath())
    {
      if (!AddSpecularBounds(
            vtkActor::SafeDownCast(path->GetLastNode()->GetViewProp()), cutoff, specular))
      {
        return false;
      }
    }
  }
  return true;
}

/** -1: no VTK light can reach `bounds`, 1: one may, 0: a degenerate light (undecided). */
int VTKLightsReach(vtkRenderer* renderer, const double bounds[6])
{
  vtkCollectionSimpleIterator it;
  vtkLightCollection* lights = renderer->GetLights();
  lights->InitTraversal(it);
  bool reached = false;
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
      return 0; // degenerate: let the snapshot report it
    }
    physical.position = { { position[0], position[1], position[2] } };
    physical.direction = { { axis[0], axis[1], axis[2] } };
    physical.type = caustics::Light::Type::Directional;
    if (light->GetPositional() && light->GetConeAngle() < 90.0)
    {
      physical.type = caustics::Light::Type::Spot;
      physical.cosOuter = std::cos(vtkMath::RadiansFromDegrees(light->GetConeAngle()));
    }
    reached = reached || caustics::LightReachesSpecular(physical, bounds);
  }
  return reached ? 1 : -1;
}
}

struct vtkCausticsRenderPass::Internals
{
  vtkNew<vtkCausticsSceneExtractor> Extractor;
  caustics::hcm::ReceiverBoundsCache ReceiverBounds; // the frame's, kept per mesh version
  vtkNew<vtkCausticsSceneGeometry> Geometry;
  vtkNew<vtkCausticsGBuffer> CameraGBuffer;      // receivers and reflectors
  vtkNew<vtkCausticsGBuffer> RefractiveGBuffer;  // refractors
  vtkNew<vtkCausticsLightBuffers> LightBuffers;  // photon buffers, aimed at specular actors
  vtkNew<vtkCausticsLightBuffers> ShadowBuffers; // shadow maps, aimed at the scene
  // The camera's view of glass and water (RenderTechniqueColor()).
  vtkNew<vtkCausticsLayeredDepth> RefractorLayers;
  vtkNew<vtkCausticsScreenSpaceRefraction> Refraction;
  vtkNew<vtkCausticsDistanceImpostors> Impostors; // CameraViewMethod's cube maps
  vtkNew<vtkTextureObject> CausticTexture;        // RGBA32F, W/m^2
  vtkNew<vtkOpenGLFramebufferObject> CausticFramebuffer;
  vtkNew<vtkCausticsSVGFDenoiser> Denoiser; // denoises CausticTexture in place (Denoise)
  bool PreviousDenoised = false;            // whether the frame before this one was denoised
  std::size_t DenoisedLights = 0;           // lights of the last denoised frame
  std::vector<double> DenoisedLightField; // caustics::gl::LightFieldSignature of the last denoised frame
  std::vector<double> DenoisedOptics;     // the same without placements
  vtkNew<vtkTextureObject> DirectTexture; // RGBA32F, W/m^2
  // RGBA32F: VTK's diffuse shading (albedo 1) that reflectors and refractors block.
  vtkNew<vtkTextureObject> LostShadingTexture;
  vtkNew<vtkOpenGLFramebufferObject> DirectFramebuffer;
  vtkNew<vtkTextureObject> VolumeTexture;         // RGBA32F, W/(m^2 sr)
  vtkNew<vtkTextureObject> TechniqueColorTexture; // RGBA32F, display colour, a = 1: replace
  vtkNew<vtkTextureObject> DelegateColorTexture;
  vtkNew<vtkTextureObject> DelegateDepthTexture;
  vtkNew<vtkOpenGLFramebufferObject> DelegateFramebuffer;
  vtkNew<vtkTextureObject> FinalTexture; // HDR copy of the composite, on request
  vtkNew<vtkOpenGLFramebufferObject> FinalFramebuffer;
  vtkNew<vtkCausticsTimings> Timings;
  vtkNew<vtkCausticsShaderProgram> DirectProgram;
  vtkNew<vtkCausticsShaderProgram> CompositeProgram;
  caustics::gl::FullScreenTriangle Triangle;
  // Per-mesh bounds for the view test, refreshed when a mesh's version changes.
  std::vector<std::pair<unsigned long, Box>> MeshBounds;
  caustics::gl::DeviceLimits Limits; // of LimitsWindow's context, for LimitsBudget
  vtkOpenGLRenderWindow* LimitsWindow = nullptr;
  double LimitsBudget = -1.0;
  double EstimatedBytes = 0.0;       // the last CheckResources()'s estimate of the technique's memory
  std::string ResourceError;         // why the last CheckResources() failed
  std::string ReportedResourceError; // the last one Render() reported (once each)
  std::string ReportedScaleWarning;  // the last scene-scale warning (once each)
  std::string ReportedRefractorsInLine; // the last refractors-in-line warning (once each)
  // The density grid CheckMediumDensity() last warned about (a new one is a new medium).
  std::weak_ptr<const caustics::DensityGrid> ReportedDensity;
  caustics::gl::MediumBuffer MediumGrid; // the density grid on the GPU, for every stage
  vtkNew<vtkCausticsCameraOpticalDepth> CameraOpticalDepth; // its optical depth from the camera
  vtkNew<vtkCausticsAirlight> Airlight; // single scattering of the direct light (volume layer)
  vtkNew<vtkCausticsProgressiveMean> Progressive; // ProgressiveFrames' mean of still frames
  FrameResult Held; // what the frame that completed the mean made (a held frame's result)
};

vtkCausticsRenderPass::vtkCausticsRenderPass()
  : Internal(new Internals)
{
  auto& in = *this->Internal;
  in.ShadowBuffers->SetFocus(vtkCausticsLightBuffers::FOCUS_SCENE);
  in.ShadowBuffers->ShadowMapsOnlyOn(); // positions and normals are all they give
  in.RefractiveGBuffer->AlbedoOff();    // only the opaque G-buffer's albedo is read
  in.DirectProgram->SetName("direct irradiance");
  in.DirectProgram->SetVertexSource(vtkCausticsFullScreenVS);
  in.DirectProgram->SetFragmentSource(vtkCausticsDirectIrradianceFS);
  in.DirectProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  in.CompositeProgram->SetName("caustics composite");
  in.CompositeProgram->SetVertexSource(vtkCausticsFullScreenVS);
  in.CompositeProgram->SetFragmentSource(vtkCausticsCompositeFS);
  in.CompositeProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  // The frame's inputs that never change: the pass's own stages.
  this->Frame.Scene = &in.Extractor->GetScene();
  this->Frame.Geometry = in.Geometry;
  this->Frame.MediumGrid = &in.MediumGrid;
  this->Frame.CameraOpticalDepth = in.CameraOpticalDepth;
  this->Frame.CameraGBuffer = in.CameraGBuffer;
  this->Frame.RefractiveGBuffer = in.RefractiveGBuffer;
  this->Frame.LightBuffers = in.LightBuffers;
  this->Frame.DelegateColor = in.DelegateColorTexture;
  this->Frame.DelegateDepth = in.DelegateDepthTexture;
  this->Frame.CausticIrradiance = in.CausticTexture;
  this->Frame.DirectIrradiance = in.DirectTexture;
}

vtkCausticsRenderPass::~vtkCausticsRenderPass()
{
  if (this->DelegatePass)
  {
    this->DelegatePass->Delete();
    this->DelegatePass = nullptr;
  }
}

vtkCausticsSVGFDenoiser* vtkCausticsRenderPass::GetDenoiser()
{
  return this->Internal->Denoiser;
}

void vtkCausticsRenderPass::ResetDenoiserHistory()
{
  this->Internal->Denoiser->ResetHistory();
}

void vtkCausticsRenderPass::SetRoughnessCutoff(double cutoff)
{
  this->Internal->Extractor->SetRoughnessCutoff(cutoff);
  this->Modified();
}

double vtkCausticsRenderPass::GetRoughnessCutoff()
{
  return this->Internal->Extractor->GetRoughnessCutoff();
}

vtkCausticsTimings* vtkCausticsRenderPass::GetTimings()
{
  return this->Internal->Timings;
}

vtkCausticsSceneExtractor* vtkCausticsRenderPass::GetSceneExtractor()
{
  return this->Internal->Extractor;
}

vtkCausticsSceneGeometry* vtkCausticsRenderPass::GetGeometry()
{
  return this->Internal->Geometry;
}

vtkCausticsGBuffer* vtkCausticsRenderPass::GetCameraGBuffer()
{
  return this->Internal->CameraGBuffer;
}

vtkCausticsGBuffer* vtkCausticsRenderPass::GetRefractiveGBuffer()
{
  return this->Internal->RefractiveGBuffer;
}

vtkCausticsLightBuffers* vtkCausticsRenderPass::GetLightBuffers()
{
  return this->Internal->LightBuffers;
}

vtkCausticsRenderPass::GraphicsMemory vtkCausticsRenderPass::GetGraphicsMemory()
{
  const caustics::gl::GraphicsCounts counts = caustics::gl::CountGraphicsMemory();
  GraphicsMemory memory;
  memory.Textures = counts.Textures;
  memory.TextureBytes = counts.TextureBytes;
  memory.Buffers = counts.Buffers;
  memory.BufferBytes = counts.BufferBytes;
  memory.Framebuffers = counts.Framebuffers;
  return memory;
}

long long vtkCausticsRenderPass::GetGraphicsObjects()
{
  return GetGraphicsMemory().Objects();
}

long long vtkCausticsRenderPass::GetGraphicsBytes()
{
  return GetGraphicsMemory().Bytes();
}

bool vtkCausticsRenderPass::GetLastFrameHadCaustics() const
{
  return this->Result.Caustics;
}

double vtkCausticsRenderPass::GetLastFrameLostLightBound()
{
  caustics::PhotonStatistics statistics;
  return this->GetLastFramePhotonStatistics(statistics) ? statistics.LostShareBound() : -1.0;
}

bool vtkCausticsRenderPass::GetLastFramePhotonStatistics(caustics::PhotonStatistics& statistics)
{
  statistics = caustics::PhotonStatistics();
  const caustics::hcm::StatisticsBuffer* buffer = this->GetStatisticsBuffer();
  if (!buffer || !this->GetLastFrameHadCaustics() || !this->GetLastWindow())
  {
    return false; // no such counters, or no frame that traced photons
  }
  this->GetLastWindow()->MakeCurrent();
  return buffer->Read(statistics);
}

const vtkCausticsRenderPass::FrameInputs& vtkCausticsRenderPass::GetFrameInputs() const
{
  return this->Frame;
}

const vtkCausticsRenderPass::FrameResult& vtkCausticsRenderPass::GetFrameResult() const
{
  return this->Result;
}

vtkOpenGLRenderWindow* vtkCausticsRenderPass::GetLastWindow()
{
  return this->LastWindow;
}

void vtkCausticsRenderPass::StartStage(const char* name)
{
  this->Internal->Timings->StartStage(name);
}

void vtkCausticsRenderPass::StopStage(const char* name)
{
  this->Internal->Timings->StopStage(name);
}

void vtkCausticsRenderPass::BeginStage(const char* name)
{
  if (this->Internal->Timings->GetSynchronous())
  {
    glFinish();
  }
  this->StartStage(name);
}

void vtkCausticsRenderPass::EndStage(const char* name)
{
  if (this->Internal->Timings->GetSynchronous())
  {
    glFinish();
  }
  this->StopStage(name);
}

vtkCausticsRenderPass::CausticNeeds vtkCausticsRenderPass::GetCausticNeeds()
{
  return CausticNeeds(); // a specular actor, a receiver and a light with power
}

bool vtkCausticsRenderPass::NeedsCaustics(const FrameInputs&)
{
  return this->SceneNeedsCaustics(this->GetCausticNeeds());
}

bool vtkCausticsRenderPass::RenderCausticIrradiance(const FrameInputs&)
{
  return true; // no technique: the caustic irradiance stays zero
}

bool vtkCausticsRenderPass::RenderVolumeRadiance(const FrameInputs&, vtkTextureObject*)
{
  return false; // no technique: no volume light
}

vtkCausticsLayeredDepth* vtkCausticsRenderPass::GetRefractorLayeredDepth()
{
  return this->Internal->RefractorLayers;
}

vtkCausticsScreenSpaceRefraction* vtkCausticsRenderPass::GetScreenSpaceRefraction()
{
  return this->Internal->Refraction;
}

vtkCausticsSpecularHierarchy* vtkCausticsRenderPass::GetTracedSpecularGeometry(
  const caustics::SceneData& scene)
{
  vtkCausticsScreenSpaceRefraction* cameraView = this->Internal->Refraction;
  return cameraView->WillTraceSpecularGeometry(scene) ? cameraView->GetSpecularHierarchy()
                                                      : nullptr;
}

vtkCausticsDistanceImpostors* vtkCausticsRenderPass::GetDistanceImpostors()
{
  return this->Internal->Impostors;
}

double vtkCausticsRenderPass::GetViewTolerance(double sceneScale)
{
  return 1e-3 * sceneScale;
}

bool vtkCausticsRenderPass::RenderTechniqueColor(const FrameInputs& f, vtkTextureObject* target)
{
  auto& in = *this->Internal;
  const caustics::SceneData& scene = *f.Scene;
  if (!this->RefractionTracing ||
    f.Geometry->GetNumberOfTriangles(
      vtkCausticsSceneGeometry::RoleBit(2) | vtkCausticsSceneGeometry::RoleBit(3)) == 0)
  {
    return false;
  }
  // 1. The refractors' layered depth image in the camera's view (front and back
  //    faces, every layer a viewing ray may cross; none without refractors: then
  //    only mirrors are traced). Where the stage traces the specular triangles, it
  //    needs the first surface only.
  this->BeginStage("refractor layers");
  in.RefractorLayers->SetRoleMask(vtkCausticsSceneGeometry::RoleBit(3));
  in.RefractorLayers->SetMaximumNumberOfLayers(
    in.Refraction->WillTraceSpecularGeometry(scene) ? 1 : this->RefractorLayers);
  in.RefractorLayers->SetTimings(this->GetTimings(), "refractor layers ");
  const bool layers =
    in.RefractorLayers->Render(f.Window, f.Geometry, scene, f.WorldToClip, f.Width, f.Height);
  this->EndStage("refractor layers");
  if (!layers)
  {
    return false;
  }
  // 2. The distance impostors' cube maps, if the method uses them (only when the
  //    geometry changed: vtkCausticsDistanceImpostors).
  //    Already brought up to date this frame where the caustic store is filled.
  const bool impostors =
    this->CameraViewMethod != SCREEN_SPACE && (this->StoresCaustic || this->UpdateImpostors(f));
  // 3. Surfaces seen only through a refractor are shaded from their irradiance.
  const bool direct = this->EnsureDirectIrradiance("direct irradiance for refraction");
  this->BeginStage("refraction tracing");
  vtkCausticsScreenSpaceRefraction::Inputs inputs;
  inputs.RefractorLayers = in.RefractorLayers;
  inputs.Opaque = f.CameraGBuffer;
  inputs.Geometry = f.Geometry;
  inputs.Scene = &scene;
  inputs.DelegateColor = f.DelegateColor;
  inputs.DelegateDepth = f.DelegateDepth;
  inputs.CausticIrradiance = f.CausticIrradiance;
  inputs.DirectIrradiance = direct ? f.DirectIrradiance : nullptr;
  // What the composite takes off VTK's colour of a receiver, the refraction takes off
  // too: a floor seen in a mirror or through glass is shadowed as seen directly.
  inputs.LostShading =
    direct && this->CorrectsVTKShading() ? in.LostShadingTexture.GetPointer() : nullptr;
  inputs.WorldToClip = f.WorldToClip;
  inputs.Width = f.Width;
  inputs.Height = f.Height;
  const caustics::TraceView camera =
    caustics::ChooseTraceView(scene, caustics::TraceViewMode::Camera, f.Width, f.Height);
  std::copy(camera.ViewOrigin, camera.ViewOrigin + 4, inputs.ViewOrigin);
  inputs.EyeMaterial = f.EyeMaterial;
  std::copy(scene.Bounds, scene.Bounds + 6, inputs.Bounds);
  std::copy(scene.SpecularBounds, scene.SpecularBounds + 6, inputs.SpecularBounds);
  std::copy(f.Background, f.Background + 3, inputs.Background);
  inputs.Tolerance = this->GetViewTolerance(caustics::VisibleScale(scene));
  inputs.Method = impostors ? this->CameraViewMethod : SCREEN_SPACE;
  inputs.Impostors = impostors ? in.Impostors.GetPointer() : nullptr;
  in.Refraction->SetMaximumEvents(this->RefractionEvents);
  const bool ok = in.Refraction->Render(f.Window, inputs, target);
  this->EndStage("refraction tracing");
  return ok;
}

bool vtkCausticsRenderPass::StoreCaustic(const FrameInputs& f, int light,
  const caustics::PhotonRecords& landed, int width, int height, double maximumPhotonFlux,
  bool shadow)
{
  if (!this->StoresCaustic)
  {
    return true;
  }
  this->BeginStage("caustic store");
  // Where the maps' radiance holds the lights' shadows, the store holds the photons alone.
  vtkCausticsDistanceImpostors* impostors = this->Internal->Impostors;
  const bool ok = impostors->StoreCaustic(f.Window, landed, width, height, maximumPhotonFlux,
    f.LightBuffers, light, *f.Scene, shadow && !impostors->GetRadianceShadowed());
  this->EndStage("caustic store");
  return ok;
}

bool vtkCausticsRenderPass::SplatInCameraView(const FrameInputs& in,
  vtkCausticsPhotonSplatter* splatter, const caustics::PhotonGrid& grid,
  const caustics::PhotonRecords& landed, vtkTextureObject* kernelRadius)
{
  splatter->SetReceiverBounds(in.HasReceiverBounds ? in.ReceiverBounds : nullptr);
  return splatter->Splat(in.Window, grid, landed, kernelRadius, in.CameraGBuffer, in.WorldToClip);
}

vtkCausticsDistanceImpostors* vtkCausticsRenderPass::OpenCausticStore(double maximumPhotonFlux)
{
  vtkCausticsDistanceImpostors* impostors = this->Internal->Impostors;
  return this->StoresCaustic && impostors->GetRadianceShadowed() &&
      impostors->OpenCaustic(maximumPhotonFlux)
    ? impostors
    : nullptr;
}

bool vtkCausticsRenderPass::UpdateImpostors(const FrameInputs& f)
{
  auto& in = *this->Internal;
  this->BeginStage("distance impostors");
  // The maps' radiance takes the lights' shadows, specular objects' included, from the
  // direct irradiance stage's shadow maps (drawn here first; that stage keeps them),
  // so that the caustic store holds the photons' light alone: nothing to cancel.
  in.ShadowBuffers->SetResolution(this->ShadowMapResolution);
  this->BeginStage("distance impostors shadow maps");
  const bool shadows = in.ShadowBuffers->Render(f.Window, f.Geometry, *f.Scene);
  this->EndStage("distance impostors shadow maps");
  in.Impostors->SetTimings(this->GetTimings(), "distance impostors ");
  const bool ok = in.Impostors->Update(
    f.Window, f.Geometry, *f.Scene, shadows ? in.ShadowBuffers.GetPointer() : nullptr);
  this->EndStage("distance impostors");
  return ok;
}

void vtkCausticsRenderPass::ReleaseTechniqueResources(vtkWindow*) {}

bool vtkCausticsRenderPass::CannotNeedCaustics(vtkRenderer* renderer, const CausticNeeds& needs)
{
  std::vector<Box> specular;
  if (!CollectSpecularBounds(renderer, this->GetRoughnessCutoff(), specular))
  {
    return false;
  }
  if (specular.empty())
  {
    return true;
  }
  double bounds[6];
  for (int c = 0; c < 3; ++c)
  {
    bounds[2 * c] = VTK_DOUBLE_MAX;
    bounds[2 * c + 1] = -VTK_DOUBLE_MAX;
    for (const Box& b : specular)
    {
      bounds[2 * c] = std::min(bounds[2 * c], b[2 * c]);
      bounds[2 * c + 1] = std::max(bounds[2 * c + 1], b[2 * c + 1]);
    }
  }
  if (needs.LitSpecular)
  {
    const int reach = VTKLightsReach(renderer, bounds);
    if (reach != 1)
    {
      return reach < 0;
    }
  }
  if (!needs.SpecularInView)
  {
    return false;
  }
  // Is any of them in the camera's view?
  int width = 0, height = 0, x = 0, y = 0;
  renderer->GetTiledSizeAndOrigin(&width, &height, &x, &y);
  vtkMatrix4x4* matrix = renderer->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
    height > 0 ? static_cast<double>(width) / height : 1.0, -1.0, 1.0);
  for (const Box& b : specular)
  {
    if (BoxInFrustum(b, &matrix->Element[0][0]))
    {
      return false;
    }
  }
  return true;
}

bool vtkCausticsRenderPass::SceneNeedsCaustics(const CausticNeeds& needs)
{
  const caustics::SceneData& scene = *this->Frame.Scene;
  if (!scene.HasSpecular || scene.Lights.empty())
  {
    return false;
  }
  bool hasReceiver = false, hasPower = false, reached = !needs.LitSpecular;
  for (const auto& material : scene.Materials)
  {
    hasReceiver = hasReceiver || material.role == caustics::Role::Receiver;
  }
  for (const auto& light : scene.Lights)
  {
    hasPower = hasPower || HasPower(light);
    reached = reached || caustics::LightReachesSpecular(light, scene.SpecularBounds);
  }
  if (!hasReceiver || !hasPower || !reached)
  {
    return false;
  }
  if (!needs.SpecularInView)
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

void vtkCausticsRenderPass::BeginFrame(const vtkRenderState* s)
{
  this->NumberOfRenderedProps = 0;
  this->Internal->PreviousDenoised = this->Result.Denoised; // the denoiser's history rule
  this->Result = FrameResult(); // the one place a frame's result starts over
  vtkRenderer* renderer = s->GetRenderer();
  auto* renWin = static_cast<vtkOpenGLRenderWindow*>(renderer->GetRenderWindow());
  this->LastWindow = renWin;
  if (!this->DelegatePass)
  {
    vtkRenderStepsPass* steps = vtkRenderStepsPass::New();
    this->SetDelegatePass(steps);
    steps->Delete();
  }
  FrameInputs& frame = this->Frame;
  frame.Window = renWin;
  frame.Renderer = renderer;
  renderer->GetTiledSizeAndOrigin(&frame.Width, &frame.Height, &frame.Origin[0], &frame.Origin[1]);
  renderer->GetBackground(frame.Background);
  this->Internal->Timings->BeginFrame();
}

bool vtkCausticsRenderPass::PrepareScene(vtkRenderer* renderer)
{
  vtkCausticsSceneExtractor* extractor = this->Internal->Extractor;
  if (!extractor->Update(renderer, this->Frame.Width, this->Frame.Height))
  {
    return false;
  }
  const caustics::SceneData& scene = extractor->GetScene();
  caustics::gl::ToColumnMajor(scene.View.worldToClip, this->Frame.WorldToClip);
  const caustics::Vec3& eye = scene.View.position;
  const double viewOrigin[4] = { eye[0], eye[1], eye[2], scene.View.parallel ? 0.0 : 1.0 };
  this->Frame.EyeMaterial = EyeMaterial(scene, viewOrigin);
  this->Frame.HasReceiverBounds =
    this->Internal->ReceiverBounds.Compute(scene, this->Frame.ReceiverBounds);
  return true;
}

vtkCausticsRenderPass::PhotonStorage vtkCausticsRenderPass::GetPhotonStorage()
{
  return PhotonStorage();
}

const char* vtkCausticsRenderPass::GetResourceError() const
{
  return this->Internal->ResourceError.c_str();
}

bool vtkCausticsRenderPass::CheckResources(vtkRenderWindow* window)
{
  auto* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!renWin)
  {
    this->Internal->ResourceError = "CheckResources needs an OpenGL render window";
    return false;
  }
  renWin->Initialize(); // makes the context if the window has none yet
  const caustics::SceneData* scene = this->Frame.Scene;
  const int lights = scene ? static_cast<int>(scene->Lights.size()) : 1;
  return this->CheckResourcesFor(renWin, std::max(lights, 1));
}

bool vtkCausticsRenderPass::CheckResourcesFor(vtkOpenGLRenderWindow* renWin, int lights)
{
  auto& in = *this->Internal;
  in.ResourceError.clear();
  // The context's limits do not change: queried once per window and budget.
  if (in.LimitsWindow != renWin || in.LimitsBudget != this->MaximumGPUMemory)
  {
    renWin->MakeCurrent();
    in.Limits = caustics::gl::QueryDeviceLimits(this->MaximumGPUMemory);
    in.LimitsWindow = renWin;
    in.LimitsBudget = this->MaximumGPUMemory;
  }
  const caustics::gl::DeviceLimits& limits = in.Limits;
  // The shared stages per photon slot: the emitted photons (3 x RGBA32F) and the
  // light buffers (RGBA32F position and flux, RGBA16F normal, depth: 44 B per
  // texel, two slots per texel), one set per light.
  constexpr double SharedBytesPerPhoton = 48.0 + 22.0;
  const PhotonStorage technique = this->GetPhotonStorage();
  const int n = this->LightBufferResolution;
  const double slots = 2.0 * n * n;
  const double perLight = technique.PerLight ? lights : 1.0;
  const double perSlot = SharedBytesPerPhoton * lights + technique.BytesPerPhoton * perLight;
  const double total = slots * perSlot + technique.FixedBytes * perLight;
  in.EstimatedBytes = total;
  const double largest = slots * technique.LargestBufferPerPhoton;
  const bool tooTall = 2 * n > limits.MaximumTextureSize;
  const bool tooLarge =
    limits.MaximumStorageBlockBytes > 0.0 && largest > limits.MaximumStorageBlockBytes;
  const bool tooMuch = limits.MemoryBudgetBytes > 0.0 && total > limits.MemoryBudgetBytes;
  if (!tooTall && !tooLarge && !tooMuch)
  {
    return true; // every frame that fits ends here, without building a message
  }
  std::ostringstream why;
  why << this->GetClassName() << ": LightBufferResolution " << n;
  if (tooTall)
  {
    why << " needs textures " << 2 * n << " texels high; this OpenGL allows "
        << limits.MaximumTextureSize << ": at most " << limits.MaximumTextureSize / 2;
  }
  else if (tooLarge)
  {
    const int fits = static_cast<int>(
      std::sqrt(limits.MaximumStorageBlockBytes / (2.0 * technique.LargestBufferPerPhoton)));
    why << " needs a " << caustics::gl::FormatBytes(largest)
        << " storage buffer; this OpenGL's shaders see at most "
        << caustics::gl::FormatBytes(limits.MaximumStorageBlockBytes) << ": at most " << fits;
  }
  else
  {
    const double room = limits.MemoryBudgetBytes - technique.FixedBytes * perLight;
    const int fits = room > 0.0 ? static_cast<int>(std::sqrt(room / (2.0 * perSlot))) : 0;
    why << " needs about " << caustics::gl::FormatBytes(total) << " of GPU memory for " << lights
        << " light(s); the budget is " << caustics::gl::FormatBytes(limits.MemoryBudgetBytes)
        << " (" << limits.MemorySource << "): at most " << fits;
  }
  in.ResourceError = why.str();
  return false;
}

double vtkCausticsRenderPass::GetVolumeSegmentBudget() const
{
  const auto& in = *this->Internal;
  if (!in.LimitsWindow || !(in.Limits.MemoryBudgetBytes > 0.0))
  {
    return 0.0; // no budget known: the lists are bounded by the storage block alone
  }
  // What the technique's own buffers leave; at least a byte (a budget, not "none").
  return std::max(in.Limits.MemoryBudgetBytes - in.EstimatedBytes, 1.0);
}

bool vtkCausticsRenderPass::SupportsCaustics(vtkOpenGLRenderWindow* renWin, bool buffers)
{
  int major = 0, minor = 0;
  renWin->GetOpenGLVersion(major, minor);
  const bool supported = major * 10 + minor >= 45;
  if (buffers && !supported)
  {
    vtkErrorMacro(<< "caustics need OpenGL 4.5 (compute shaders, SSBOs); this context is " << major
                  << "." << minor << ": rendering without caustics");
  }
  return supported;
}

void vtkCausticsRenderPass::RenderPlainVTK(const vtkRenderState* s)
{
  // Nothing to add: VTK renders as if the pass were not there (timed on the CPU
  // only: timer queries would cost more than the rest of the pass here).
  this->Internal->Timings->StartStage("vtk delegate", false);
  this->DelegatePass->Render(s);
  this->NumberOfRenderedProps += this->DelegatePass->GetNumberOfRenderedProps();
  this->EndStage("vtk delegate");
  this->Internal->Timings->EndFrame();
}

void vtkCausticsRenderPass::RenderDelegate(const vtkRenderState* s)
{
  auto& in = *this->Internal;
  vtkOpenGLRenderWindow* renWin = this->Frame.Window;
  const int w = this->Frame.Width, h = this->Frame.Height;
  bool resized = caustics::gl::EnsureTexture(in.DelegateColorTexture, renWin, w, h, GL_RGBA32F);
  resized |=
    caustics::gl::EnsureTexture(in.DelegateDepthTexture, renWin, w, h, GL_DEPTH_COMPONENT32F);

  this->PreRender(s);
  in.DelegateFramebuffer->SetContext(renWin);
  in.DelegateFramebuffer->SaveCurrentBindingsAndBuffers();
  in.DelegateFramebuffer->Bind();
  if (resized || in.DelegateFramebuffer->GetNumberOfColorAttachments() != 1)
  {
    in.DelegateFramebuffer->AddColorAttachment(0, in.DelegateColorTexture);
    in.DelegateFramebuffer->AddDepthAttachment(in.DelegateDepthTexture);
  }
  in.DelegateFramebuffer->ActivateDrawBuffers(1);
  in.DelegateFramebuffer->StartNonOrtho(w, h);
  this->DelegatePass->Render(s);
  this->NumberOfRenderedProps += this->DelegatePass->GetNumberOfRenderedProps();
  in.DelegateFramebuffer->UnBind();
  in.DelegateFramebuffer->RestorePreviousBindingsAndBuffers();
  this->PostRender(s);
}

bool vtkCausticsRenderPass::RenderCameraGBuffers()
{
  const FrameInputs& f = this->Frame;
  const int opaque = vtkCausticsSceneGeometry::RoleBit(1) | vtkCausticsSceneGeometry::RoleBit(2);
  const int refractive = vtkCausticsSceneGeometry::RoleBit(3);
  bool ok = f.CameraGBuffer->Render(f.Window, f.Geometry, f.WorldToClip, f.Width, f.Height, opaque);
  ok = f.RefractiveGBuffer->Render(
         f.Window, f.Geometry, f.WorldToClip, f.Width, f.Height, refractive) &&
    ok;
  return ok;
}

bool vtkCausticsRenderPass::RenderLightBuffers()
{
  const FrameInputs& f = this->Frame;
  f.LightBuffers->SetResolution(this->LightBufferResolution);
  return f.LightBuffers->Render(f.Window, f.Geometry, *f.Scene);
}

bool vtkCausticsRenderPass::RenderCaustics()
{
  auto& in = *this->Internal;
  const FrameInputs& f = this->Frame;
  vtkOpenGLState* state = f.Window->GetState();
  const bool resized =
    caustics::gl::EnsureTexture(in.CausticTexture, f.Window, f.Width, f.Height, GL_RGBA32F);
  state->PushFramebufferBindings();
  BindAndClear(in.CausticFramebuffer, in.CausticTexture, f.Window, resized);
  vtkOpenGLState::ScopedglViewport viewport(state);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  state->vtkglViewport(0, 0, f.Width, f.Height);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_BLEND);
  state->vtkglDisable(GL_SCISSOR_TEST);
  // The caustic store (StoreCaustic()): filled by the technique's photons only when
  // the camera view reads map hits; its maps made first (only when the scene changed).
  in.Impostors->ResetCaustic();
  this->StoresCaustic = this->RefractionTracing && this->CameraViewMethod != SCREEN_SPACE &&
    f.Geometry->GetNumberOfTriangles(
      vtkCausticsSceneGeometry::RoleBit(2) | vtkCausticsSceneGeometry::RoleBit(3)) > 0 &&
    this->UpdateImpostors(f);
  const bool ok = this->RenderCausticIrradiance(f);
  this->Result.Volume = ok && this->RenderVolumeRadiance(f, in.VolumeTexture);
  state->PopFramebufferBindings();
  return ok;
}

bool vtkCausticsRenderPass::DenoiseCaustics()
{
  auto& in = *this->Internal;
  const FrameInputs& f = this->Frame;
  // No history across a frame without denoising or a change of the number of lights
  // (the denoiser itself drops it on a resize and, on the GPU, on a camera cut; it
  // follows actors that move, appear or leave, and gives a new one no history).
  if (!in.PreviousDenoised || f.Scene->Lights.size() != in.DenoisedLights)
  {
    in.Denoiser->ResetHistory();
  }
  in.DenoisedLights = f.Scene->Lights.size();
  std::vector<double> lightField = caustics::gl::LightFieldSignature(*f.Scene);
  vtkCausticsSVGFDenoiser::Inputs inputs;
  std::vector<double> optics = caustics::gl::LightFieldSignature(*f.Scene, false);
  inputs.LightChanged = lightField != in.DenoisedLightField;
  inputs.OpticsChanged = optics != in.DenoisedOptics;
  in.DenoisedLightField = std::move(lightField);
  in.DenoisedOptics = std::move(optics);
  inputs.Window = f.Window;
  inputs.Irradiance = in.CausticTexture;
  inputs.PhotonVariance = this->WritesPhotonVariance();
  inputs.GBuffer = f.CameraGBuffer;
  inputs.Camera = &f.Scene->View;
  inputs.Scene = f.Scene;
  inputs.Width = f.Width;
  inputs.Height = f.Height;
  return in.Denoiser->Denoise(inputs);
}

int vtkCausticsRenderPass::BeginProgressiveFrame()
{
  auto& in = *this->Internal;
  const FrameInputs& f = this->Frame;
  const bool averages = this->ProgressiveFrames > 1 && !this->AveragesFramesItself();
  in.Progressive->SetFrames(averages ? this->ProgressiveFrames : 1);
  std::vector<std::uint64_t> key;
  if (averages)
  {
    // Everything the caustic and volume layers depend on: the scene (as the light
    // buffers key it), the camera and viewport, and the settings.
    caustics::gl::AppendMeshesKey(key, *f.Scene);
    const std::vector<double> lightField = caustics::gl::LightFieldSignature(*f.Scene);
    caustics::gl::AppendKey(key, lightField.data(), static_cast<int>(lightField.size()));
    for (const caustics::Material& m : f.Scene->Materials)
    {
      caustics::gl::AppendKey(key, m.albedo.data(), 3);
    }
    key.push_back(reinterpret_cast<std::uintptr_t>(f.Scene->Participating.density.get()));
    const double view[] = { static_cast<double>(f.Width), static_cast<double>(f.Height) };
    caustics::gl::AppendKey(key, view, 2);
    caustics::gl::AppendKey(key, f.WorldToClip, 16);
    key.push_back(reinterpret_cast<std::uintptr_t>(f.Window));
    key.push_back(this->GetMTime());
    for (vtkObject* stage : { static_cast<vtkObject*>(in.Denoiser.GetPointer()),
           static_cast<vtkObject*>(in.Impostors.GetPointer()),
           static_cast<vtkObject*>(in.Refraction.GetPointer()),
           static_cast<vtkObject*>(in.Airlight.GetPointer()),
           static_cast<vtkObject*>(in.CameraOpticalDepth.GetPointer()) })
    {
      key.push_back(stage->GetMTime());
    }
    this->AppendProgressiveKey(key);
  }
  const int frame = in.Progressive->Begin(key);
  double offset[2] = { 0.0, 0.0 };
  vtkCausticsProgressiveMean::GridOffset(std::max(frame, 0), offset);
  if (frame >= 0)
  {
    in.LightBuffers->SetGridOffset(offset[0], offset[1]);
  }
  return frame;
}

int vtkCausticsRenderPass::GetFramesAveraged() const
{
  if (!this->Result.Caustics)
  {
    return 0;
  }
  const int averaged = this->Internal->Progressive->GetFramesAveraged();
  return std::max(averaged, 1);
}

void vtkCausticsRenderPass::ResetProgressive()
{
  this->Internal->Progressive->Reset();
}

void vtkCausticsRenderPass::AppendProgressiveKey(std::vector<std::uint64_t>&) {}

bool vtkCausticsRenderPass::CorrectsVTKShading() const
{
  return this->SpecularShadows || this->Frame.Scene->Participating.enabled;
}

bool vtkCausticsRenderPass::EnsureDirectIrradiance(const char* stage)
{
  if (!this->Result.Direct)
  {
    this->BeginStage(stage);
    this->Result.Direct = this->RenderDirectIrradiance();
    this->EndStage(stage);
  }
  return this->Result.Direct;
}

void vtkCausticsRenderPass::RenderFrame(const vtkRenderState* s, bool caustics)
{
  const FrameInputs& f = this->Frame;
  vtkOpenGLState* state = f.Window->GetState();
  vtkOpenGLState::ScopedglEnableDisable blendSaver(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthSaver(state, GL_DEPTH_TEST);

  this->BeginStage("vtk delegate");
  this->RenderDelegate(s);
  this->EndStage("vtk delegate");

  this->BeginStage("geometry upload");
  bool ok = f.Geometry->Upload(*f.Scene, f.Window);
  this->EndStage("geometry upload");

  this->BeginStage("camera g-buffers");
  ok = this->RenderCameraGBuffers() && ok;
  this->EndStage("camera g-buffers");
  this->Result.Buffers = true;

  // A density grid dims everything the camera sees: integrate it once for the frame.
  if (caustics && ok && f.MediumGrid->HasGrid())
  {
    this->BeginStage("camera optical depth");
    f.CameraOpticalDepth->Build(f.Window, f.Width, f.Height, *f.Scene, f.MediumGrid);
    this->EndStage("camera optical depth");
  }
  else
  {
    f.CameraOpticalDepth->Invalidate();
  }

  // ProgressiveFrames: -1 once a still scene's mean is complete (the textures hold it).
  const int progressive = caustics && ok ? this->BeginProgressiveFrame() : 0;
  if (caustics && ok && progressive < 0)
  {
    const FrameResult& held = this->Internal->Held;
    this->Result.Caustics = true;
    this->Result.Volume = held.Volume;
    this->Result.Denoised = held.Denoised;
  }
  else if (caustics && ok)
  {
    if (this->GetCausticNeeds().LightBuffers)
    {
      this->BeginStage("light buffers");
      ok = this->RenderLightBuffers();
      this->EndStage("light buffers");
    }
    this->BeginStage("caustic irradiance");
    ok = ok && this->RenderCaustics();
    this->EndStage("caustic irradiance");
    this->Result.Caustics = ok;
    if (ok && this->Denoise)
    {
      this->BeginStage("denoise");
      this->Result.Denoised = this->DenoiseCaustics();
      this->EndStage("denoise");
    }
  }
  // The light that reflectors and refractors pass on is the caustic: VTK's direct
  // light where they block it comes off in the composite.
  if (this->ComputeDirectIrradiance || (this->Result.Caustics && this->CorrectsVTKShading()))
  {
    this->EnsureDirectIrradiance("direct irradiance");
  }
  // The medium's own glow: airlight and volume shadows of the direct light, added to
  // the technique's volume caustic (003 §3: the composition is a sum).
  if (this->Result.Caustics && progressive >= 0 && this->Result.Direct &&
    this->Internal->Airlight->IsNeeded(*f.Scene))
  {
    this->BeginStage("airlight");
    this->Result.Volume = this->RenderAirlight() || this->Result.Volume;
    this->EndStage("airlight");
  }
  if (this->Result.Caustics && progressive >= 0 && this->Internal->Progressive->GetFrames() > 1)
  {
    auto& in = *this->Internal;
    this->BeginStage("progressive mean");
    in.Progressive->Add(
      f.Window, in.CausticTexture, this->Result.Volume ? in.VolumeTexture.GetPointer() : nullptr);
    this->EndStage("progressive mean");
    in.Held = this->Result;
  }
  if (this->Result.Caustics)
  {
    this->Result.TechniqueColor =
      this->RenderTechniqueColor(f, this->Internal->TechniqueColorTexture);
  }

  this->BeginStage("composite");
  state->vtkglViewport(f.Origin[0], f.Origin[1], f.Width, f.Height);
  state->vtkglScissor(f.Origin[0], f.Origin[1], f.Width, f.Height);
  this->Composite(false);
  if (this->KeepBuffers)
  {
    this->Composite(true);
  }
  this->EndStage("composite");
  this->Internal->Timings->EndFrame();
}

void vtkCausticsRenderPass::Render(const vtkRenderState* s)
{
  vtkOpenGLClearErrorMacro();
  this->BeginFrame(s);
  vtkRenderer* renderer = s->GetRenderer();
  const bool extraOutputs = this->ComputeDirectIrradiance || this->KeepBuffers;
  const CausticNeeds needs = this->GetCausticNeeds();
  if (!extraOutputs && needs.EarlySkip && this->CannotNeedCaustics(renderer, needs))
  {
    // Nothing can need caustics: plain VTK, without even the scene snapshot (whose
    // cost grows with the scene's triangles).
    this->RenderPlainVTK(s);
    return;
  }
  this->Internal->Timings->StartStage("scene snapshot", false); // CPU work: no timer queries
  const bool sceneOk = this->PrepareScene(renderer);
  this->StopStage("scene snapshot");
  if (sceneOk)
  {
    this->CheckMediumDensity();
  }
  const bool caustics = sceneOk && this->NeedsCaustics(this->Frame);
  if (caustics)
  {
    this->CheckSceneScale();
    this->CheckRefractorsInLine();
  }
  const bool buffers = caustics || extraOutputs;
  if (!sceneOk || !buffers || !this->SupportsCaustics(this->Frame.Window, buffers))
  {
    this->RenderPlainVTK(s);
    return;
  }
  this->RenderFrame(s, caustics && this->FitsTheDevice());
  vtkOpenGLCheckErrorMacro("failed after Render");
}

double vtkCausticsRenderPass::GetLastSceneScaleRatio()
{
  return caustics::VisibleOverSpecular(*this->Frame.Scene);
}

void vtkCausticsRenderPass::CheckSceneScale()
{
  const double limit = this->GetSceneScaleLimit();
  const double ratio = this->GetLastSceneScaleRatio();
  if (!(limit > 0.0) || !(ratio > limit))
  {
    this->Internal->ReportedScaleWarning.clear();
    return;
  }
  std::ostringstream text;
  text.precision(3);
  const double seen = caustics::VisibleScale(*this->Frame.Scene);
  text << "the part of the scene the camera sees is " << ratio
       << " times the size of its reflectors and refractors (" << seen << " m against "
       << seen / ratio << " m, bounding-box diagonals); this technique's caustics lose detail "
       << "beyond " << limit << " times (its resolution follows what the camera sees: "
       << "zoom in on the caustic)";
  // Once per state, not every frame.
  if (text.str() != this->Internal->ReportedScaleWarning)
  {
    this->Internal->ReportedScaleWarning = text.str();
    vtkWarningMacro(<< text.str());
  }
}

void vtkCausticsRenderPass::CheckRefractorsInLine()
{
  const caustics::SceneData& scene = *this->Frame.Scene;
  std::string text;
  for (int i = 0; i < static_cast<int>(scene.Lights.size()) && text.empty() &&
       !this->FollowsLightBetweenRefractors();
       ++i)
  {
    int first, second;
    if (caustics::RefractorsInLine(scene, i, first, second))
    {
      text = "light " + std::to_string(i) + " may pass through the refractor '" +
        scene.Meshes[first].name + "' and then '" + scene.Meshes[second].name +
        "', and this technique follows its photons through one " +
        "refractor only (the second is not in its light's images): the caustic beyond the " +
        "second may be missing or misplaced (the reference and cpu-progressive follow both)";
    }
  }
  // Once per state, not every frame.
  if (text != this->Internal->ReportedRefractorsInLine)
  {
    this->Internal->ReportedRefractorsInLine = text;
    if (!text.empty())
    {
      vtkWarningMacro(<< text);
    }
  }
}

void vtkCausticsRenderPass::CheckMediumDensity()
{
  const caustics::Medium& medium = this->Frame.Scene->Participating;
  const auto& density = medium.density;
  if (!this->Internal->MediumGrid.Update(medium))
  {
    this->Internal->ReportedDensity.reset();
    return;
  }
  const char* meanStages = this->GetMeanDensityStages();
  // Once per medium change (a new load, scale or placement is a new grid object).
  if (meanStages && this->Internal->ReportedDensity.lock() != density)
  {
    this->Internal->ReportedDensity = density;
    vtkWarningMacro(<< this->GetClassName() << ": " << meanStages
                    << " does not follow the heterogeneous density yet; using the grid's "
                       "mean density ("
                    << medium.MeanDensity() << ")");
  }
}

vtkCausticsCameraOpticalDepth* vtkCausticsRenderPass::GetCameraOpticalDepth()
{
  return this->Internal->CameraOpticalDepth;
}

vtkCausticsAirlight* vtkCausticsRenderPass::GetAirlight()
{
  return this->Internal->Airlight;
}

bool vtkCausticsRenderPass::RenderAirlight()
{
  auto& in = *this->Internal;
  const FrameInputs& f = this->Frame;
  vtkCausticsAirlight::Inputs inputs;
  inputs.Window = f.Window;
  inputs.Width = f.Width;
  inputs.Height = f.Height;
  inputs.Scene = f.Scene;
  inputs.Grid = f.MediumGrid;
  inputs.CameraOpticalDepth = f.CameraOpticalDepth;
  inputs.SurfacePositions = f.CameraGBuffer->GetPositionTexture();
  inputs.RefractorPositions = f.RefractiveGBuffer->GetPositionTexture();
  inputs.Shadows = in.ShadowBuffers;
  inputs.ShadowMapResolution = this->ShadowMapResolution;
  // Added to the technique's volume caustic when it wrote one this frame.
  return in.Airlight->Render(inputs, in.VolumeTexture, this->Result.Volume);
}

vtkIdType vtkCausticsRenderPass::GetMediumGridBytes() const
{
  return static_cast<vtkIdType>(this->Internal->MediumGrid.Bytes());
}

vtkIdType vtkCausticsRenderPass::GetMediumDenseBytes() const
{
  const caustics::DensityGrid* grid = this->Internal->MediumGrid.GetGrid();
  return grid ? static_cast<vtkIdType>(grid->GetDenseBytes()) : 0;
}

bool vtkCausticsRenderPass::FitsTheDevice()
{
  const int lights = static_cast<int>(this->Frame.Scene->Lights.size());
  if (this->CheckResourcesFor(this->Frame.Window, std::max(lights, 1)))
  {
    this->Internal->ReportedResourceError.clear();
    return true;
  }
  // Once per cause, not every frame: the frame renders without caustics.
  if (this->Internal->ResourceError != this->Internal->ReportedResourceError)
  {
    this->Internal->ReportedResourceError = this->Internal->ResourceError;
    vtkErrorMacro(<< this->Internal->ResourceError << "; rendering without caustics");
  }
  return false;
}

bool vtkCausticsRenderPass::RenderDirectIrradiance()
{
  auto& in = *this->Internal;
  const FrameInputs& f = this->Frame;
  in.ShadowBuffers->SetResolution(this->ShadowMapResolution);
  if (!in.ShadowBuffers->Render(f.Window, f.Geometry, *f.Scene))
  {
    return false;
  }
  vtkOpenGLState* state = f.Window->GetState();
  bool resized =
    caustics::gl::EnsureTexture(in.DirectTexture, f.Window, f.Width, f.Height, GL_RGBA32F);
  resized |=
    caustics::gl::EnsureTexture(in.LostShadingTexture, f.Window, f.Width, f.Height, GL_RGBA32F);
  state->PushFramebufferBindings();
  BindAndClear(
    in.DirectFramebuffer, { in.DirectTexture, in.LostShadingTexture }, f.Window, resized);
  vtkOpenGLState::ScopedglViewport viewport(state);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglViewport(0, 0, f.Width, f.Height);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglEnable(GL_BLEND);
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  const bool ok = this->DrawDirectIrradiance();
  state->PopFramebufferBindings();
  return ok;
}

bool vtkCausticsRenderPass::DrawDirectIrradiance()
{
  const FrameInputs& f = this->Frame;
  vtkCausticsShaderProgram* program = this->Internal->DirectProgram;
  caustics::gl::SetMediumDefine(program, f.MediumGrid);
  if (!program->Bind(f.Window))
  {
    return false;
  }
  vtkTextureObject* position = f.CameraGBuffer->GetPositionTexture();
  vtkTextureObject* normal = f.CameraGBuffer->GetNormalTexture();
  position->Activate();
  normal->Activate();
  program->SetUniformi("gPosition", position->GetTextureUnit());
  program->SetUniformi("gNormal", normal->GetTextureUnit());
  const caustics::Camera& view = f.Scene->View;
  double direction[3];
  for (int i = 0; i < 3; ++i)
  {
    direction[i] = view.focalPoint[i] - view.position[i];
  }
  const double length = std::sqrt(
    direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
  program->SetUniform3f("cameraPosition", static_cast<float>(view.position[0]),
    static_cast<float>(view.position[1]), static_cast<float>(view.position[2]));
  program->SetUniform3f("cameraDirection", static_cast<float>(direction[0] / length),
    static_cast<float>(direction[1] / length), static_cast<float>(direction[2] / length));
  program->SetUniformi("cameraParallel", view.parallel ? 1 : 0);
  vtkCausticsLightBuffers* shadows = this->Internal->ShadowBuffers;
  for (int i = 0; i < shadows->GetNumberOfLights(); ++i)
  {
    vtkTextureObject* shadow = shadows->GetGBuffer(i)->GetPositionTexture();
    vtkTextureObject* shadowNormal = shadows->GetGBuffer(i)->GetNormalTexture();
    shadow->Activate();
    shadowNormal->Activate();
    program->SetUniformi("shadowPosition", shadow->GetTextureUnit());
    program->SetUniformi("shadowNormal", shadowNormal->GetTextureUnit());
    this->SetDirectLightUniforms(i);
    this->Internal->Triangle.Draw();
    shadowNormal->Deactivate();
    shadow->Deactivate();
  }
  position->Deactivate();
  normal->Deactivate();
  program->Unbind(f.Window);
  return true;
}

void vtkCausticsRenderPass::SetDirectLightUniforms(int i)
{
  vtkCausticsShaderProgram* program = this->Internal->DirectProgram;
  const caustics::Light& light = this->Frame.Scene->Lights[i];
  const caustics::LightView& lightView = this->Internal->ShadowBuffers->GetView(i);
  float matrix[16];
  caustics::gl::ToColumnMajor(lightView.worldToClip, matrix);
  program->SetUniformMatrix4("lightWorldToClip", matrix);
  program->SetUniformi("lightType", static_cast<int>(light.type));
  caustics::gl::SetMediumUniforms(program, *this->Frame.Scene, this->Frame.MediumGrid);
  // Directional lights measure distance along the axis from the view's eye.
  const caustics::Vec3& origin =
    light.type == caustics::Light::Type::Directional ? lightView.eye : light.position;
  program->SetUniform3f("lightPosition", static_cast<float>(origin[0]),
    static_cast<float>(origin[1]), static_cast<float>(origin[2]));
  program->SetUniform3f("lightDirection", static_cast<float>(light.direction[0]),
    static_cast<float>(light.direction[1]), static_cast<float>(light.direction[2]));
  program->SetUniform3f("radiometric", static_cast<float>(light.radiometric[0]),
    static_cast<float>(light.radiometric[1]), static_cast<float>(light.radiometric[2]));
  program->SetUniformf("cosOuter", static_cast<float>(light.cosOuter));
  program->SetUniformf("cosInner", static_cast<float>(light.cosInner));
  program->SetUniform3f("shadingAttenuation", static_cast<float>(light.shadingAttenuation[0]),
    static_cast<float>(light.shadingAttenuation[1]),
    static_cast<float>(light.shadingAttenuation[2]));
  // VTK itself would draw NaN for a NaN exponent; the removal stays finite instead.
  const double exponent = std::isfinite(light.shadingExponent) ? light.shadingExponent : 1.0;
  program->SetUniformf("shadingExponent", static_cast<float>(exponent));
  program->SetUniformf("shadingConeAngle", static_cast<float>(light.shadingConeAngle));
  program->SetUniformi("specularShadows", this->SpecularShadows ? 1 : 0);
  program->SetUniformf(
    "texelWorldSize", static_cast<float>(lightView.TexelWidth(this->ShadowMapResolution)));
}

void vtkCausticsRenderPass::Composite(bool toFinalTexture)
{
  auto& in = *this->Internal;
  const FrameInputs& f = this->Frame;
  vtkCausticsShaderProgram* program = in.CompositeProgram;
  caustics::gl::SetMediumDefine(program, f.MediumGrid);
  f.CameraOpticalDepth->SetDefine(program);
  if (!program->Bind(f.Window))
  {
    return;
  }
  vtkTextureObject* textures[] = { in.DelegateColorTexture, in.DelegateDepthTexture,
    f.CameraGBuffer->GetNormalTexture(), f.CameraGBuffer->GetAlbedoTexture(),
    f.CameraGBuffer->GetDepthTexture(), in.CausticTexture, in.VolumeTexture,
    in.TechniqueColorTexture, in.LostShadingTexture };
  const char* names[] = { "delegateColor", "delegateDepth", "gNormal", "gAlbedo", "gDepth",
    "causticIrradiance", "volumeRadiance", "techniqueColor", "lostShading" };
  const bool hasCaustics = this->Result.Caustics;
  const bool hasVolume = hasCaustics && this->Result.Volume;
  const bool hasTechniqueColor = hasCaustics && this->Result.TechniqueColor;
  const bool hasLostShading = hasCaustics && this->CorrectsVTKShading() && this->Result.Direct;
  const bool hasMedium = hasCaustics && f.Scene->Participating.enabled;
  // An unused sampler would keep the unit it had in an earlier frame, which a sampler of
  // another type (the camera optical-depth volume) may hold now, and GL refuses the draw:
  // unused ones point at VTK's colour, always bound (they are not read).
  for (int i = 0; i < 9; ++i)
  {
    const bool used = i < 2 || (hasCaustics && i < 6) || (hasVolume && i == 6) ||
      (hasTechniqueColor && i == 7) || (hasLostShading && i == 8);
    if (used)
    {
      textures[i]->Activate();
    }
    program->SetUniformi(names[i], textures[used ? i : 0]->GetTextureUnit());
  }
  program->SetUniformi("hasCaustics", hasCaustics ? 1 : 0);
  program->SetUniformi("hasVolume", hasVolume ? 1 : 0);
  program->SetUniformi("hasTechniqueColor", hasTechniqueColor ? 1 : 0);
  program->SetUniformi("hasLostShading", hasLostShading ? 1 : 0);
  program->SetUniformi("hasMedium", hasMedium ? 1 : 0);
  if (hasMedium)
  {
    float clipToWorld[16];
    caustics::gl::ToColumnMajor(f.Scene->View.clipToWorld, clipToWorld);
    program->SetUniformMatrix4("clipToWorld", clipToWorld);
    caustics::gl::SetMediumUniforms(program, *f.Scene, f.MediumGrid);
    f.CameraOpticalDepth->SetUniforms(program);
  }
  // The two depth buffers come from the same triangles and matrix; allow float noise.
  program->SetUniformf("depthTolerance", 2e-6f);
  this->DrawComposite(toFinalTexture);
  f.CameraOpticalDepth->Deactivate();
  for (int i = 0; i < 9; ++i)
  {
    if (textures[i]->GetHandle() && textures[i]->IsBound())
    {
      textures[i]->Deactivate();
    }
  }
  program->Unbind(f.Window);
}

void vtkCausticsRenderPass::DrawComposite(bool toFinalTexture)
{
  auto& in = *this->Internal;
  const FrameInputs& f = this->Frame;
  vtkOpenGLState* state = f.Window->GetState();
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
  state->vtkglDisable(GL_BLEND);
  if (toFinalTexture)
  {
    const bool resized =
      caustics::gl::EnsureTexture(in.FinalTexture, f.Window, f.Width, f.Height, GL_RGBA32F);
    state->PushFramebufferBindings();
    BindAndClear(in.FinalFramebuffer, in.FinalTexture, f.Window, resized);
    vtkOpenGLState::ScopedglViewport viewport(state);
    vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
    state->vtkglDisable(GL_SCISSOR_TEST);
    state->vtkglViewport(0, 0, f.Width, f.Height);
    state->vtkglDisable(GL_DEPTH_TEST);
    in.Triangle.Draw();
    state->PopFramebufferBindings();
  }
  else
  {
    // Into the framebuffer the pass was called with, replacing its depth.
    state->vtkglEnable(GL_DEPTH_TEST);
    state->vtkglDepthFunc(GL_ALWAYS);
    vtkOpenGLState::ScopedglDepthMask depthMask(state);
    state->vtkglDepthMask(GL_TRUE);
    in.Triangle.Draw();
  }
}

/** One readable buffer: a texture of the last frame and when the frame made it. */
struct vtkCausticsRenderPass::BufferEntry
{
  const char* Name;
  int Components;
  bool PerLight; ///< "Name:i" for light i
  vtkTextureObject* (*Texture)(vtkCausticsRenderPass* pass, int light);
  bool (*Available)(vtkCausticsRenderPass* pass);
  int FirstChannel = 0; ///< the texture's first channel read
};

const vtkCausticsRenderPass::BufferEntry* vtkCausticsRenderPass::FindBuffer(const std::string& base)
{
  using Pass = vtkCausticsRenderPass;
  auto always = [](Pass*) { return true; };
  auto caustics = [](Pass* p) { return p->Result.Caustics; };
  // The technique's caustic irradiance before denoising (alpha: CausticsDeposit's).
  auto raw = [](Pass* p, int)
  {
    return p->Result.Denoised ? p->Internal->Denoiser->GetRawTexture()
                              : p->Internal->CausticTexture.Get();
  };
  static const BufferEntry table[] = {
    { "FinalColor", 3, false, [](Pass* p, int) { return p->Internal->FinalTexture.Get(); },
      [](Pass* p) { return p->KeepBuffers; } },
    { "CausticIrradiance", 3, false, [](Pass* p, int) { return p->Internal->CausticTexture.Get(); },
      caustics },
    { "RawCausticIrradiance", 3, false, raw, caustics },
    { "PhotonHalfSetDifference", 1, false, raw,
      [](Pass* p) { return p->Result.Caustics && p->WritesPhotonVariance(); }, 3 },
    { "DirectIrradiance", 3, false, [](Pass* p, int) { return p->Internal->DirectTexture.Get(); },
      [](Pass* p) { return p->Result.Direct; } },
    { "LostShading", 3, false, [](Pass* p, int) { return p->Internal->LostShadingTexture.Get(); },
      [](Pass* p) { return p->Result.Direct; } },
    { "VolumeRadiance", 3, false, [](Pass* p, int) { return p->Internal->VolumeTexture.Get(); },
      [](Pass* p) { return p->Result.Caustics && p->Result.Volume; } },
    { "TechniqueColor", 4, false,
      [](Pass* p, int) { return p->Internal->TechniqueColorTexture.Get(); },
      [](Pass* p) { return p->Result.Caustics && p->Result.TechniqueColor; } },
    { "Position", 4, false,
      [](Pass* p, int) { return p->GetCameraGBuffer()->GetPositionTexture(); }, always },
    { "Normal", 4, false, [](Pass* p, int) { return p->GetCameraGBuffer()->GetNormalTexture(); },
      always },
    { "Albedo", 4, false, [](Pass* p, int) { return p->GetCameraGBuffer()->GetAlbedoTexture(); },
      always },
    { "Depth", 1, false, [](Pass* p, int) { return p->GetCameraGBuffer()->GetDepthTexture(); },
      always },
    { "RefractivePosition", 4, false,
      [](Pass* p, int) { return p->GetRefractiveGBuffer()->GetPositionTexture(); }, always },
    { "RefractiveNormal", 4, false,
      [](Pass* p, int) { return p->GetRefractiveGBuffer()->GetNormalTexture(); }, always },
    { "RefractiveDepth", 1, false,
      [](Pass* p, int) { return p->GetRefractiveGBuffer()->GetDepthTexture(); }, always },
    { "LightPosition", 4, true,
      [](Pass* p, int i) { return p->GetLightBuffers()->GetGBuffer(i)->GetPositionTexture(); },
      caustics },
    { "LightNormal", 4, true,
      [](Pass* p, int i) { return p->GetLightBuffers()->GetGBuffer(i)->GetNormalTexture(); },
      caustics },
    { "LightDepth", 1, true,
      [](Pass* p, int i) { return p->GetLightBuffers()->GetGBuffer(i)->GetDepthTexture(); },
      caustics },
    { "LightFlux", 4, true, [](Pass* p, int i) { return p->GetLightBuffers()->GetFluxTexture(i); },
      caustics },
  };
  for (const BufferEntry& entry : table)
  {
    if (base == entry.Name)
    {
      return &entry;
    }
  }
  return nullptr;
}

bool vtkCausticsRenderPass::ReadBuffer(const char* name, vtkImageData* output)
{
  if (!name || !output)
  {
    vtkErrorMacro(<< "ReadBuffer needs a buffer name and an output image");
    return false;
  }
  vtkOpenGLRenderWindow* renWin = this->LastWindow;
  if (!renWin || !this->Result.Buffers)
  {
    vtkErrorMacro(<< "ReadBuffer('" << name
                  << "'): the last frame made no caustics buffers (nothing needed them; turn "
                     "KeepBuffers on to keep them)");
    return false;
  }
  renWin->MakeCurrent();
  // "Name" or "Name:light".
  const std::string request = name;
  const auto colon = request.find(':');
  const std::string base = request.substr(0, colon);
  int light = -1;
  if (colon != std::string::npos)
  {
    try
    {
      light = std::stoi(request.substr(colon + 1));
    }
    catch (...)
    {
      light = -2;
    }
  }
  if (base == "ReceiverMask")
  {
    return this->ReadReceiverMask(name, output);
  }
  const BufferEntry* entry = FindBuffer(base);
  const bool lightOk = entry &&
    (!entry->PerLight || (light >= 0 && light < this->GetLightBuffers()->GetNumberOfLights()));
  vtkTextureObject* texture =
    lightOk && entry->Available(this) ? entry->Texture(this, light) : nullptr;
  if (!texture || !texture->GetHandle())
  {
    vtkErrorMacro(<< "ReadBuffer: no buffer '" << name
                  << "' in the last frame (unknown name, light index out of range, or a stage "
                     "that did not run)");
    return false;
  }
  auto image = caustics::gl::ReadTexture(texture, name, entry->Components, entry->FirstChannel);
  output->ShallowCopy(image);
  return true;
}

bool vtkCausticsRenderPass::ReadReceiverMask(const char* name, vtkImageData* output)
{
  // Receivers not hidden behind a refractor: where caustic irradiance is defined.
  const FrameInputs& f = this->Frame;
  auto normal = caustics::gl::ReadTexture(f.CameraGBuffer->GetNormalTexture(), "n", 4);
  auto depth = caustics::gl::ReadTexture(f.CameraGBuffer->GetDepthTexture(), "d", 1);
  auto refractive = caustics::gl::ReadTexture(f.RefractiveGBuffer->GetDepthTexture(), "r", 1);
  output->Initialize();
  output->SetDimensions(f.Width, f.Height, 1);
  vtkNew<vtkFloatArray> mask;
  mask->SetName(name);
  mask->SetNumberOfTuples(static_cast<vtkIdType>(f.Width) * f.Height);
  vtkDataArray* n = normal->GetPointData()->GetArray(0);
  vtkDataArray* d = depth->GetPointData()->GetArray(0);
  vtkDataArray* r = refractive->GetPointData()->GetArray(0);
  for (vtkIdType i = 0; i < mask->GetNumberOfTuples(); ++i)
  {
    const bool receiver = std::lround(n->GetComponent(i, 3)) == 1;
    mask->SetValue(i, receiver && d->GetComponent(i, 0) <= r->GetComponent(i, 0) ? 1.0f : 0.0f);
  }
  output->GetPointData()->AddArray(mask);
  return true;
}

void vtkCausticsRenderPass::ReleaseGraphicsResources(vtkWindow* w)
{
  auto& in = *this->Internal;
  // GL names belong to one context: delete ours in the window's own, whichever
  // context the caller left current (else another window's objects of the same
  // names are deleted instead).
  if (auto* renWin = vtkOpenGLRenderWindow::SafeDownCast(w))
  {
    renWin->MakeCurrent();
  }
  this->Superclass::ReleaseGraphicsResources(w);
  this->ReleaseTechniqueResources(w);
  in.LimitsWindow = nullptr; // a later window may reuse the address
  in.Geometry->ReleaseGraphicsResources(w);
  in.MediumGrid.Release();
  in.CameraOpticalDepth->ReleaseGraphicsResources(w);
  in.Airlight->ReleaseGraphicsResources(w);
  in.CameraGBuffer->ReleaseGraphicsResources(w);
  in.RefractiveGBuffer->ReleaseGraphicsResources(w);
  in.LightBuffers->ReleaseGraphicsResources(w);
  in.ShadowBuffers->ReleaseGraphicsResources(w);
  in.RefractorLayers->ReleaseGraphicsResources(w);
  in.Refraction->ReleaseGraphicsResources(w);
  in.Denoiser->ReleaseGraphicsResources(w);
  in.Impostors->ReleaseGraphicsResources(w);
  in.Progressive->ReleaseGraphicsResources(w);
  vtkTextureObject* textures[] = { in.CausticTexture, in.DirectTexture, in.LostShadingTexture,
    in.VolumeTexture, in.DelegateColorTexture, in.DelegateDepthTexture, in.FinalTexture,
    in.TechniqueColorTexture };
  for (vtkTextureObject* texture : textures)
  {
    texture->ReleaseGraphicsResources(w);
  }
  vtkOpenGLFramebufferObject* framebuffers[] = { in.CausticFramebuffer, in.DirectFramebuffer,
    in.DelegateFramebuffer, in.FinalFramebuffer };
  for (vtkOpenGLFramebufferObject* framebuffer : framebuffers)
  {
    framebuffer->ReleaseGraphicsResources(w);
  }
  in.DirectProgram->ReleaseGraphicsResources(w);
  in.CompositeProgram->ReleaseGraphicsResources(w);
  in.Triangle.Release();
  in.Timings->ReleaseGraphicsResources();
  // Nothing of the last frame can be read any more (ReadBuffer, the techniques'
  // queries): they all need the last frame's window.
  this->LastWindow = nullptr;
}

void vtkCausticsRenderPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LightBufferResolution: " << this->LightBufferResolution << "\n";
  os << indent << "ShadowMapResolution: " << this->ShadowMapResolution << "\n";
  os << indent << "ComputeDirectIrradiance: " << this->ComputeDirectIrradiance << "\n";
  os << indent << "KeepBuffers: " << this->KeepBuffers << "\n";
  os << indent << "SpecularShadows: " << this->SpecularShadows << "\n";
  os << indent << "RoughnessCutoff: " << this->GetRoughnessCutoff() << "\n";
  os << indent << "RefractionTracing: " << this->RefractionTracing << "\n";
  os << indent << "RefractionEvents: " << this->RefractionEvents << "\n";
  os << indent << "RefractorLayers: " << this->RefractorLayers << "\n";
  os << indent << "Denoise: " << this->Denoise << "\n";
  os << indent << "ProgressiveFrames: " << this->ProgressiveFrames << "\n";
  os << indent << "Denoiser:\n";
  this->Internal->Denoiser->PrintSelf(os, indent.GetNextIndent());
  os << indent << "CameraViewMethod: " << this->CameraViewMethod << "\n";
  os << indent << "Airlight:\n";
  this->Internal->Airlight->PrintSelf(os, indent.GetNextIndent());
  os << indent << "LastFrameHadCaustics: " << this->Result.Caustics << "\n";
  os << indent << "Size: " << this->Frame.Width << " x " << this->Frame.Height << "\n";
  os << indent << "MediumGridBytes: " << this->GetMediumGridBytes() << " (dense "
     << this->GetMediumDenseBytes() << ")\n";
  os << indent << "Scene:\n";
  this->Internal->Extractor->PrintSelf(os, indent.GetNextIndent());
  os << indent << "Timings:\n" << this->Internal->Timings->GetReport();
}
