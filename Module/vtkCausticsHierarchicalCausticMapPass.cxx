#include "vtkCausticsHierarchicalCausticMapPass.h"

#include "vtkCausticsCausticMap.h"
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsPhotonBuffer.h"
#include "vtkCausticsPhotonBufferHierarchy.h"
#include "vtkCausticsPhotonEmitter.h"
#include "vtkCausticsPhotonGrid.h"
#include "vtkCausticsPhotonSplatter.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsTimings.h"
#include "vtkCausticsVolumeSegmentList.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCausticsHierarchicalCausticMapPass);

namespace
{
/** Everything one light owns: its photon buffer, its gather lists, its caustic map. */
struct PerLight
{
  vtkNew<vtkCausticsPhotonEmitter> Emitter;
  vtkNew<vtkCausticsPhotonBuffer> Photons;
  vtkNew<vtkCausticsPhotonBufferHierarchy> Hierarchy;
  vtkNew<vtkCausticsCausticMap> Map;
  vtkNew<vtkCausticsCausticMap> HiddenMap; // receivers behind Map's (HiddenReceivers)
  caustics::LightView MapView;
  bool Traced = false;
  // This frame's caustic store of the photons no receiver layer landed, or null.
  vtkCausticsDistanceImpostors* Store = nullptr;
  // Where the light meets the receivers beyond the specular actors, and what it
  // was found for (the light and the meshes' versions).
  caustics::ReceiverIncidence Incidence;
  std::string IncidenceKey;
  // What the receivers and refractor faces seen from the light were drawn for
  // (LayersKey()); empty: not drawn.
  std::string LayersKey;

  void Release(vtkWindow* w)
  {
    this->Emitter->ReleaseGraphicsResources(w);
    this->Photons->ReleaseGraphicsResources(w);
    this->Hierarchy->ReleaseGraphicsResources(w);
    this->Map->ReleaseGraphicsResources(w);
    this->HiddenMap->ReleaseGraphicsResources(w);
    this->Traced = false;
    this->Store = nullptr;
    this->IncidenceKey.clear();
    this->LayersKey.clear();
  }
};

}

struct vtkCausticsHierarchicalCausticMapPass::Internals
{
  std::vector<std::unique_ptr<PerLight>> Lights;
  vtkNew<vtkCausticsPhotonSplatter> Triangles;    // RECONSTRUCTION_TRIANGLES (shared stage)
  caustics::gl::VolumeSegmentList VolumeSegments; // photon pieces in air -> volume caustics
};

vtkCausticsHierarchicalCausticMapPass::vtkCausticsHierarchicalCausticMapPass()
  : Internal(new Internals)
{
  this->Internal->VolumeSegments.SetOwner(this); // it warns when its segments cannot all fit
  this->SetRefractionTracing(true); // the base pass's camera view of glass
  this->SetSpecularShadows(true);   // its caustic replaces the light glass and mirrors block
}

vtkCausticsHierarchicalCausticMapPass::~vtkCausticsHierarchicalCausticMapPass() = default;

int vtkCausticsHierarchicalCausticMapPass::GetNumberOfLights() const
{
  return static_cast<int>(this->Internal->Lights.size());
}

bool vtkCausticsHierarchicalCausticMapPass::GetLightTraced(int i) const
{
  return this->GetLastFrameHadCaustics() && i >= 0 && i < this->GetNumberOfLights() &&
    this->Internal->Lights[i]->Traced;
}

vtkCausticsPhotonBuffer* vtkCausticsHierarchicalCausticMapPass::GetPhotonBuffer(int i)
{
  return i >= 0 && i < this->GetNumberOfLights() ? this->Internal->Lights[i]->Photons.GetPointer()
                                                 : nullptr;
}

vtkCausticsPhotonBufferHierarchy* vtkCausticsHierarchicalCausticMapPass::GetHierarchy(int i)
{
  return i >= 0 && i < this->GetNumberOfLights() ? this->Internal->Lights[i]->Hierarchy.GetPointer()
                                                 : nullptr;
}

vtkCausticsCausticMap* vtkCausticsHierarchicalCausticMapPass::GetCausticMap(int i)
{
  return i >= 0 && i < this->GetNumberOfLights() ? this->Internal->Lights[i]->Map.GetPointer()
                                                 : nullptr;
}

vtkCausticsRenderPass::PhotonStorage vtkCausticsHierarchicalCausticMapPass::GetPhotonStorage()
{
  // Per photon slot: the landed records and radius (52 B), the trace's work lists
  // (8 B), the hierarchy's nodes (40 B per node, a third of the slots), traversal
  // list (4 B per node and photon) and splat lists (4 B x 4 map levels), and the
  // refractors' front and back layers seen from the light (28 B per texel, two
  // slots per texel). Beside the grid: the caustic map's levels (RGBA32F) and its
  // receiver G-buffer (28 B per texel). All of it once per light.
  const double map = static_cast<double>(this->Settings.CausticMapResolution);
  PhotonStorage storage;
  storage.BytesPerPhoton = 52.0 + 8.0 + 40.0 / 3.0 + 4.0 * 4.0 / 3.0 + 16.0 + 28.0;
  storage.LargestBufferPerPhoton = 16.0; // the splat lists
  storage.FixedBytes = map * map * (16.0 * 4.0 / 3.0 + 28.0);
  storage.PerLight = true;
  return storage;
}

vtkCausticsRenderPass::CausticNeeds vtkCausticsHierarchicalCausticMapPass::GetCausticNeeds()
{
  CausticNeeds needs;
  needs.LitSpecular = true;
  return needs;
}

namespace
{
/** What FindReceiverIncidence() depends on: the light, every mesh's version and the focus. */
std::string IncidenceKey(const caustics::SceneData& scene, int index, const double* focus)
{
  const caustics::Light& light = scene.Lights[index];
  std::ostringstream key;
  key.precision(17);
  key << static_cast<int>(light.type) << ' ' << light.position[0] << ' ' << light.position[1] << ' '
      << light.position[2] << ' ' << light.direction[0] << ' ' << light.direction[1] << ' '
      << light.direction[2];
  for (const caustics::Mesh& mesh : scene.Meshes)
  {
    key << ' ' << mesh.version;
  }
  for (int k = 0; focus && k < 6; ++k)
  {
    key << ' ' << focus[k];
  }
  return key.str();
}
}

namespace
{
/**
 * What the map's receiver G-buffers and the refractors' faces from the light are a
 * function of: the two views, the sizes, and per mesh its version (renewed when its
 * triangles or matrix change) and material.
 */
std::string LayersKey(const caustics::SceneData& scene, const caustics::LightView& photonView,
  const caustics::LightView& mapView, int gridWidth, const caustics::CausticMapSettings& settings,
  const void* geometry)
{
  std::ostringstream key;
  key.precision(17);
  key << geometry << ' ' << gridWidth << ' ' << settings.CausticMapResolution << ' '
      << settings.NumberOfLevels() << ' ' << settings.HiddenReceivers;
  for (const caustics::LightView* view : { &photonView, &mapView })
  {
    key << " | " << view->light << ' ' << view->perspective << ' ' << view->valid << ' '
        << view->clamped << ' ' << view->halfExtent << ' ' << view->aspect << ' ' << view->nearPlane
        << ' ' << view->farPlane;
    for (const caustics::Vec3* v : { &view->eye, &view->axis, &view->right, &view->up })
    {
      key << ' ' << (*v)[0] << ' ' << (*v)[1] << ' ' << (*v)[2];
    }
    for (double m : view->worldToClip)
    {
      key << ' ' << m;
    }
  }
  for (const caustics::Mesh& mesh : scene.Meshes)
  {
    // The whole material: a G-buffer may hold more of it than the role.
    const caustics::Material& m = scene.Materials[mesh.material];
    key << " | " << mesh.version << ' ' << mesh.material << ' ' << static_cast<int>(m.role) << ' '
        << m.ior << ' ' << m.roughness;
    for (const caustics::Vec3* v : { &m.albedo, &m.metalN, &m.metalK, &m.attenuation })
    {
      key << ' ' << (*v)[0] << ' ' << (*v)[1] << ' ' << (*v)[2];
    }
  }
  return key.str();
}
}

void vtkCausticsHierarchicalCausticMapPass::PrepareLights(vtkOpenGLRenderWindow* renWin)
{
  const caustics::SceneData& scene = *this->GetFrameInputs().Scene;
  auto& lights = this->Internal->Lights;
  const std::size_t count = scene.Lights.size();
  // Lights that went away give their GL objects back.
  for (std::size_t i = count; i < lights.size(); ++i)
  {
    lights[i]->Release(renWin);
  }
  lights.resize(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    if (!lights[i])
    {
      lights[i].reset(new PerLight);
    }
    PerLight& light = *lights[i];
    const int index = static_cast<int>(i);
    // The map's view: the light's, on what the camera sees, turned towards
    // receivers the light grazes (found by a CPU scan of the receivers, redone
    // only when the light or the meshes change).
    // The light's ray is followed from the centre of what its photons are aimed at
    // (the photon frustum's focus): a mirror far off, whose light reaches nothing in
    // view, must not move it onto another receiver.
    const double* focus = index < this->GetLightBuffers()->GetNumberOfLights() &&
        this->GetLightBuffers()->GetView(index).valid
      ? this->GetLightBuffers()->GetView(index).focus
      : nullptr;
    std::string key = IncidenceKey(scene, index, focus);
    if (key != light.IncidenceKey)
    {
      light.IncidenceKey = std::move(key);
      light.Incidence = caustics::FindReceiverIncidence(scene, index, focus);
    }
    light.MapView = caustics::ComputeReceiverMapView(
      scene, index, light.Incidence, this->Settings.MinimumMapIncidence, focus);
    light.Traced = index < this->GetLightBuffers()->GetNumberOfLights() &&
      this->GetLightBuffers()->GetView(index).valid && light.MapView.valid && scene.HasSpecular &&
      caustics::LightReachesSpecular(scene.Lights[i], scene.SpecularBounds);
  }
}

double vtkCausticsHierarchicalCausticMapPass::GetReceiverIncidence(int i) const
{
  const auto& lights = this->Internal->Lights;
  return i >= 0 && i < static_cast<int>(lights.size()) && lights[i] ? lights[i]->Incidence.angle
                                                                    : 90.0;
}

const caustics::LightView* vtkCausticsHierarchicalCausticMapPass::GetMapView(int i) const
{
  const auto& lights = this->Internal->Lights;
  return i >= 0 && i < static_cast<int>(lights.size()) && lights[i] ? &lights[i]->MapView : nullptr;
}

bool vtkCausticsHierarchicalCausticMapPass::RenderPhotonBuffers(vtkOpenGLRenderWindow* renWin)
{
  const caustics::SceneData& scene = *this->GetFrameInputs().Scene;
  bool ok = true;
  for (std::size_t i = 0; i < this->Internal->Lights.size(); ++i)
  {
    PerLight& light = *this->Internal->Lights[i];
    light.Store = nullptr;
    if (!light.Traced)
    {
      continue;
    }
    const int index = static_cast<int>(i);
    const caustics::LightView& photonView = this->GetLightBuffers()->GetView(index);
    // Photons after the first specular interaction (the shared stage, whose one
    // knob is the technique's).
    light.Emitter->SetSplitFresnel(this->Settings.SplitFresnel);
    this->BeginStage("hcm emit");
    light.Traced =
      light.Emitter->Emit(renWin, this->GetLightBuffers(), index, this->GetGeometry(), scene);
    this->EndStage("hcm emit");
    const caustics::PhotonGrid& grid = light.Emitter->GetGrid();
    // The receivers the caustic map sees, and the refractors' faces from the light
    // (kept while the views and the meshes are unchanged: nothing else draws there).
    this->BeginStage("hcm light layers");
    std::string layersKey =
      LayersKey(scene, photonView, light.MapView, grid.Width, this->Settings, this->GetGeometry());
    const bool hidden = this->Settings.HiddenReceivers;
    light.Traced = light.Traced &&
      (layersKey == light.LayersKey ||
        (light.Map->RenderReceivers(renWin, this->Settings, this->GetGeometry(), light.MapView) &&
          (!hidden ||
            light.HiddenMap->RenderReceivers(
              renWin, this->Settings, this->GetGeometry(), light.MapView, light.Map)) &&
          light.Photons->RenderLayers(renWin, this->GetGeometry(), photonView, grid)));
    light.LayersKey = light.Traced ? std::move(layersKey) : std::string();
    this->EndStage("hcm light layers");
    // Where each photon lands.
    this->BeginStage("hcm trace");
    light.Photons->SetHiddenReceivers(hidden ? light.HiddenMap->GetReceivers(0) : nullptr);
    // Concave glass traced as triangles, where the camera view traces it.
    light.Photons->SetTracedSpecularGeometry(this->GetTracedSpecularGeometry(scene));
    // Photons that no receiver layer of the map's view lands go to the caustic store
    // (one light: with more, the store at a receiver one light's map sees would also
    // hold that light's landed photons, which its map already shows).
    light.Store =
      this->Internal->Lights.size() == 1 ? this->OpenCausticStore(grid.MaximumPhotonFlux) : nullptr;
    light.Photons->SetCausticStore(light.Store);
    light.Traced = light.Traced &&
      light.Photons->Trace(renWin, this->Settings, this->GetGeometry(), scene, grid, photonView,
        light.MapView, light.Map->GetReceivers(0), this->GetFrameInputs().MediumGrid,
        &this->Internal->VolumeSegments);
    this->EndStage("hcm trace");
    // The caustic store (shared): the landed photons and the light's shadow.
    light.Traced = light.Traced &&
      this->StoreCaustic(this->GetFrameInputs(), index, light.Photons->GetLanded(), grid.Width,
        grid.Height, grid.MaximumPhotonFlux);
    ok = ok && light.Traced;
    if (light.Traced && this->Internal->VolumeSegments.IsOn())
    {
      ok = this->DrawVolumeLines(this->GetFrameInputs()) && ok;
    }
  }
  return ok;
}

bool vtkCausticsHierarchicalCausticMapPass::DrawVolumeLines(const FrameInputs& in)
{
  this->BeginStage("hcm volume lines");
  const bool ok = this->Internal->VolumeSegments.Draw(in.Window,
    { in.WorldToClip, in.MediumGrid, in.CameraOpticalDepth, in.CameraGBuffer,
      in.RefractiveGBuffer, in.Geometry, in.EyeMaterial },
    this->Settings.VolumeSubSegments);
  this->EndStage("hcm volume lines");
  return ok;
}

bool vtkCausticsHierarchicalCausticMapPass::RenderVolumeRadiance(
  const FrameInputs& in, vtkTextureObject* target)
{
  if (!this->Internal->VolumeSegments.IsOn())
  {
    return false; // no scattering medium: no volume stage
  }
  this->BeginStage("hcm volume blur");
  const bool ok =
    this->Internal->VolumeSegments.Finish(in.Window, this->Settings.VolumeBlurPixels, target);
  this->EndStage("hcm volume blur");
  return ok;
}

bool vtkCausticsHierarchicalCausticMapPass::GatherCausticMaps(vtkOpenGLRenderWindow* renWin)
{
  const caustics::SceneData& scene = *this->GetFrameInputs().Scene;
  bool ok = true;
  for (std::size_t i = 0; i < this->Internal->Lights.size(); ++i)
  {
    PerLight& light = *this->Internal->Lights[i];
    if (!light.Traced)
    {
      continue;
    }
    const caustics::PhotonGrid& grid = light.Emitter->GetGrid();
    this->BeginStage("hcm traversal");
    const bool gathered =
      light.Hierarchy->Gather(renWin, this->Settings, grid, light.Photons->GetLanded(),
        light.MapView, static_cast<int>(scene.Lights[i].type), &scene.View);
    this->EndStage("hcm traversal");
    this->BeginStage("hcm splat");
    if (this->Settings.Reconstruction == RECONSTRUCTION_TRIANGLES)
    {
      // The triangles go straight into the camera view at the final render (every
      // landed photon, hidden receivers' too): no map to splat.
      light.Traced = gathered;
      if (light.Store)
      {
        light.Map->ClearIrradiance(renWin);
      }
    }
    else
    {
      light.Traced = gathered &&
        light.Map->Splat(renWin, this->Settings, grid, light.Photons->GetLanded(),
          light.Hierarchy, &scene.View,
          this->Settings.HiddenReceivers ? light.HiddenMap.GetPointer() : nullptr);
    }
    // The photons that landed on hidden receivers, and those whose kernel reaches
    // them, into their own map.
    if (this->Settings.HiddenReceivers && this->Settings.Reconstruction != RECONSTRUCTION_TRIANGLES)
    {
      this->BeginStage("hcm hidden splat");
      light.Traced = light.Traced &&
        light.HiddenMap->Splat(renWin, this->Settings, grid, light.Photons->GetLanded(),
          light.Hierarchy, &scene.View, light.Map, true);
      this->EndStage("hcm hidden splat");
    }
    this->EndStage("hcm splat");
    ok = ok && light.Traced;
  }
  return ok;
}

bool vtkCausticsHierarchicalCausticMapPass::RenderFinal(vtkOpenGLRenderWindow* renWin)
{
  const caustics::Camera& camera = this->GetFrameInputs().Scene->View;
  bool ok = true;
  for (auto& light : this->Internal->Lights)
  {
    if (light->Traced && this->Settings.Reconstruction == RECONSTRUCTION_TRIANGLES)
    {
      // The gather gave every photon its Eq. 2 radius: the splats of the flux the
      // refused triangles leave.
      vtkCausticsPhotonSplatter* triangles = this->Internal->Triangles;
      triangles->SetReconstructionToTriangles();
      ok = this->SplatInCameraView(this->GetFrameInputs(), triangles, light->Emitter->GetGrid(),
             light->Photons->GetLanded(), light->Hierarchy->GetSplatRadiusTexture()) &&
        ok;
    }
    else if (light->Traced)
    {
      ok = light->Map->Apply(renWin, this->GetCameraGBuffer(), camera) && ok;
      if (this->Settings.HiddenReceivers)
      {
        // Drawn only when a photon landed there (the trace sets the draw's count).
        this->BeginStage("hcm hidden final render");
        ok = light->HiddenMap->Apply(renWin, this->GetCameraGBuffer(), camera, light->Map,
               &light->Photons->GetStatisticsBuffer(),
               vtkCausticsPhotonBuffer::GetHiddenDrawOffset()) &&
          ok;
        this->EndStage("hcm hidden final render");
      }
    }
    if (light->Traced && light->Store)
    {
      // The receivers neither map sees: the photons the store took (drawn only then).
      this->BeginStage("hcm store final render");
      ok =
        light->Map->ApplyStore(renWin, this->GetCameraGBuffer(), camera,
          this->Settings.HiddenReceivers ? light->HiddenMap.GetPointer() : nullptr, light->Store,
          light->Photons->GetStatisticsBuffer(), vtkCausticsPhotonBuffer::GetStoreDrawOffset()) &&
        ok;
      this->EndStage("hcm store final render");
    }
  }
  return ok;
}

bool vtkCausticsHierarchicalCausticMapPass::RenderCausticIrradiance(const FrameInputs& in)
{
  vtkOpenGLRenderWindow* renWin = in.Window;
  this->PrepareLights(renWin);
  // A scattering medium: the photons' pieces in air become volume caustics.
  this->Internal->VolumeSegments.Begin(renWin, *in.Scene, in.Width, in.Height);

  this->BeginStage("hcm photon buffer");
  bool ok = this->RenderPhotonBuffers(renWin);
  this->EndStage("hcm photon buffer");

  this->BeginStage("hcm gather");
  ok = this->GatherCausticMaps(renWin) && ok;
  this->EndStage("hcm gather");

  this->BeginStage("hcm final render");
  ok = this->RenderFinal(renWin) && ok;
  this->EndStage("hcm final render");
  vtkOpenGLCheckErrorMacro("failed after the hierarchical caustic map stages");
  return ok;
}

bool vtkCausticsHierarchicalCausticMapPass::GetCounters(int i, Counters& counters)
{
  counters = Counters();
  if (!this->GetLightTraced(i) || !this->GetLastWindow())
  {
    vtkErrorMacro(<< "GetCounters: light " << i << " ran no photon stage in the last frame");
    return false;
  }
  this->GetLastWindow()->MakeCurrent();
  PerLight& light = *this->Internal->Lights[i];
  vtkCausticsPhotonBuffer::Statistics statistics;
  vtkCausticsPhotonBufferHierarchy::Counters gather;
  if (!light.Photons->GetStatistics(statistics) || !light.Hierarchy->GetCounters(gather))
  {
    return false;
  }
  counters.Photons = statistics.Photons;
  counters.Hits = statistics.Hits;
  counters.HiddenHits = statistics.HiddenHits;
  counters.LostInside = statistics.LostInside;
  counters.Escaped = statistics.Escaped;
  counters.Stored = statistics.Stored;
  counters.FluxIn = statistics.FluxIn;
  counters.FluxHits = statistics.FluxHits;
  counters.FluxLostInside = statistics.FluxLostInside;
  counters.FluxEscaped = statistics.FluxEscaped;
  counters.FluxStored = statistics.FluxStored;
  counters.FluxInternalReflection = statistics.FluxInternalReflection;
  counters.FluxAbsorbed = statistics.FluxAbsorbed;
  counters.StartLevel = gather.StartLevel;
  std::copy(gather.Processed, gather.Processed + 16, counters.Processed);
  counters.TotalProcessed = gather.TotalProcessed;
  counters.Valid = gather.Valid;
  counters.Clusters = gather.Clusters;
  counters.ClusteredPhotons = gather.ClusteredPhotons;
  std::copy(gather.Splats, gather.Splats + 4, counters.Splats);
  counters.CoarseSplats = gather.CoarseSplats;
  std::copy(gather.SplatFlux, gather.SplatFlux + 4, counters.SplatFlux);
  counters.CoarseFlux = gather.CoarseFlux;
  counters.CoarseFluxFraction = gather.CoarseFluxFraction;
  counters.DroppedFluxFraction = gather.DroppedFluxFraction;
  return true;
}

bool vtkCausticsHierarchicalCausticMapPass::GetLastFramePhotonStatistics(
  caustics::PhotonStatistics& statistics)
{
  statistics = caustics::PhotonStatistics();
  bool any = false;
  for (int i = 0; i < this->GetNumberOfLights(); ++i)
  {
    vtkCausticsPhotonBuffer::Statistics light;
    if (this->GetLightTraced(i) && this->GetLastWindow())
    {
      this->GetLastWindow()->MakeCurrent();
      if (this->Internal->Lights[i]->Photons->GetStatistics(light))
      {
        statistics += light;
        any = true;
      }
    }
  }
  return any;
}

vtkIdType vtkCausticsHierarchicalCausticMapPass::GetNumberOfProcessedPhotons(int light)
{
  Counters counters;
  return this->GetCounters(light, counters) ? counters.TotalProcessed : 0;
}

vtkIdType vtkCausticsHierarchicalCausticMapPass::GetNumberOfValidPhotons(int light)
{
  Counters counters;
  return this->GetCounters(light, counters) ? counters.Valid : 0;
}

vtkIdType vtkCausticsHierarchicalCausticMapPass::GetNumberOfClusters(int light)
{
  Counters counters;
  return this->GetCounters(light, counters) ? counters.Clusters : 0;
}

vtkIdType vtkCausticsHierarchicalCausticMapPass::GetNumberOfSplats(int light, int level)
{
  Counters counters;
  return this->GetCounters(light, counters) && level >= 0 && level < 4 ? counters.Splats[level] : 0;
}

double vtkCausticsHierarchicalCausticMapPass::GetDroppedFluxFraction(int light)
{
  Counters counters;
  return this->GetCounters(light, counters) ? counters.DroppedFluxFraction : 0.0;
}

bool vtkCausticsHierarchicalCausticMapPass::ReadCausticMap(
  int light, int level, vtkImageData* output)
{
  if (!output || !this->GetLightTraced(light) || !this->GetLastWindow() || level < 0 ||
    level >= this->Internal->Lights[light]->Map->GetNumberOfLevels())
  {
    vtkErrorMacro(<< "ReadCausticMap: no level " << level << " of light " << light
                  << " in the last frame");
    return false;
  }
  this->GetLastWindow()->MakeCurrent();
  auto image = caustics::gl::ReadTexture(
    this->Internal->Lights[light]->Map->GetIrradianceTexture(level), "CausticMap", 3);
  output->ShallowCopy(image);
  return true;
}

bool vtkCausticsHierarchicalCausticMapPass::ReadPhotonBuffer(int light, vtkImageData* output)
{
  if (!output || !this->GetLightTraced(light) || !this->GetLastWindow())
  {
    vtkErrorMacro(<< "ReadPhotonBuffer: light " << light << " has no photon buffer this frame");
    return false;
  }
  this->GetLastWindow()->MakeCurrent();
  const caustics::PhotonRecords landed = this->Internal->Lights[light]->Photons->GetLanded();
  auto position = caustics::gl::ReadTexture(landed.Position, "HitPosition", 4);
  auto normal = caustics::gl::ReadTexture(landed.Direction, "HitNormal", 4);
  auto flux = caustics::gl::ReadTexture(landed.Flux, "HitFlux", 4);
  output->ShallowCopy(position);
  output->GetPointData()->AddArray(normal->GetPointData()->GetArray(0));
  output->GetPointData()->AddArray(flux->GetPointData()->GetArray(0));
  return true;
}

const caustics::gl::VolumeSegmentList* vtkCausticsHierarchicalCausticMapPass::GetVolumeSegmentList()
  const
{
  return &this->Internal->VolumeSegments;
}

void vtkCausticsHierarchicalCausticMapPass::ReleaseTechniqueResources(vtkWindow* w)
{
  for (auto& light : this->Internal->Lights)
  {
    light->Release(w);
  }
  this->Internal->Lights.clear();
  this->Internal->Triangles->ReleaseGraphicsResources(w);
  this->Internal->VolumeSegments.Release(w);
}

void vtkCausticsHierarchicalCausticMapPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const char* gathers[] = { "flat (Wyman & Davis 2006)", "hierarchical (3.1)" };
  const char* clusters[] = { "none", "last level (3.2)", "all levels (3.2)" };
  const char* splats[] = { "constant", "varying, single map", "varying, multi-resolution (3.3)" };
  const caustics::CausticMapSettings& knobs = this->Settings;
  os << indent << "GatherMode: " << gathers[knobs.GatherMode] << "\n";
  os << indent << "ClusterMode: " << clusters[knobs.ClusterMode] << "\n";
  os << indent << "SplatMode: " << splats[knobs.SplatMode] << "\n";
  os << indent
     << "PhotonBufferResolution (LightBufferResolution): " << this->GetLightBufferResolution()
     << "\n";
  os << indent << "CausticMapResolution: " << knobs.CausticMapResolution << "\n";
  os << indent << "TraversalStartResolution: " << knobs.TraversalStartResolution << "\n";
  os << indent << "SplatScale: " << knobs.SplatScale << "\n";
  os << indent << "MaxDistanceFraction: " << knobs.MaxDistanceFraction << "\n";
  os << indent << "ConstantSplatRadius: " << knobs.ConstantSplatRadius << " px\n";
  os << indent << "SplatSizeThreshold: " << knobs.SplatSizeThreshold << " px\n";
  os << indent << "MinimumSplatRadius: " << knobs.MinimumSplatRadius << " px\n";
  os << indent << "MinimumCameraSplatRadius: " << knobs.MinimumCameraSplatRadius
     << " camera pixel footprints\n";
  os << indent << "MaximumSplatRadius: " << knobs.MaximumSplatRadius << " px\n";
  os << indent << "DropCoarseSplats: " << knobs.DropCoarseSplats << "\n";
  os << indent << "MaximumInternalEvents: " << knobs.MaximumInternalEvents << "\n";
  os << indent << "MaximumReflections: " << knobs.MaximumReflections << "\n";
  os << indent << "Reconstruction: "
     << (knobs.Reconstruction == RECONSTRUCTION_TRIANGLES ? "triangles" : "splats") << "\n";
  os << indent << "SplitFresnel: " << knobs.SplitFresnel << "\n";
  os << indent << "HiddenReceivers: " << knobs.HiddenReceivers << "\n";
  os << indent << "MinimumMapIncidence: " << knobs.MinimumMapIncidence << " degrees\n";
  os << indent << "VolumeBlurPixels: " << knobs.VolumeBlurPixels << " px\n";
  os << indent << "VolumeSubSegments: " << knobs.VolumeSubSegments << "\n";
  os << indent << "Lights: " << this->Internal->Lights.size() << "\n";
  for (std::size_t i = 0; i < this->Internal->Lights.size(); ++i)
  {
    os << indent.GetNextIndent() << "light " << i << ": "
       << (this->GetLightTraced(static_cast<int>(i)) ? "traced" : "no photon stage") << "\n";
  }
}
