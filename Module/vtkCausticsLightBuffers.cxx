#include "vtkCausticsLightBuffers.h"

#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsFullScreenVS.h"
#include "vtkCausticsLightFluxFS.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <vector>

vtkStandardNewMacro(vtkCausticsLightBuffers);

namespace
{
struct PerLight
{
  vtkSmartPointer<vtkCausticsGBuffer> GBuffer = vtkSmartPointer<vtkCausticsGBuffer>::New();
  vtkSmartPointer<vtkTextureObject> Flux = vtkSmartPointer<vtkTextureObject>::New();
  vtkSmartPointer<vtkOpenGLFramebufferObject> FluxFramebuffer =
    vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
  caustics::LightView View;
};

/** The flux shader's view of one light: its frustum and its emission. */
void SetFluxUniforms(vtkCausticsShaderProgram* program, const caustics::Light& source,
  const caustics::LightView& view, int resolution)
{
  program->SetUniformi("perspective", view.perspective ? 1 : 0);
  program->SetUniform2f(
    "halfExtent", static_cast<float>(view.halfExtent), static_cast<float>(view.HalfExtentUp()));
  program->SetUniform2f(
    "resolution", static_cast<float>(resolution), static_cast<float>(resolution));
  program->SetUniform3f("radiometric", static_cast<float>(source.radiometric[0]),
    static_cast<float>(source.radiometric[1]), static_cast<float>(source.radiometric[2]));
  program->SetUniform3f("viewAxis", static_cast<float>(view.axis[0]),
    static_cast<float>(view.axis[1]), static_cast<float>(view.axis[2]));
  program->SetUniform3f("viewRight", static_cast<float>(view.right[0]),
    static_cast<float>(view.right[1]), static_cast<float>(view.right[2]));
  program->SetUniform3f("viewUp", static_cast<float>(view.up[0]), static_cast<float>(view.up[1]),
    static_cast<float>(view.up[2]));
  program->SetUniformi("isSpot", source.type == caustics::Light::Type::Spot ? 1 : 0);
  program->SetUniform3f("spotAxis", static_cast<float>(source.direction[0]),
    static_cast<float>(source.direction[1]), static_cast<float>(source.direction[2]));
  program->SetUniformf("cosOuter", static_cast<float>(source.cosOuter));
  program->SetUniformf("cosInner", static_cast<float>(source.cosInner));
}

/**
 * Everything the buffers are a function of: the window and the geometry object,
 * the settings, every mesh as drawn (caustics::gl::AppendMeshesKey), the lights,
 * materials and medium as the caustic irradiance sees them
 * (caustics::gl::LightFieldSignature) with the albedo the G-buffer stores besides,
 * and per light the view computed from it and the scene's bounds. Equal keys give
 * equal buffers.
 */
std::vector<std::uint64_t> ContentKey(const vtkOpenGLRenderWindow* renWin,
  const vtkCausticsSceneGeometry* geometry, const caustics::SceneData& scene,
  const std::vector<caustics::LightView>& views, const std::vector<std::uint64_t>& settings)
{
  std::vector<std::uint64_t> key = settings;
  key.push_back(reinterpret_cast<std::uintptr_t>(renWin));
  key.push_back(reinterpret_cast<std::uintptr_t>(geometry));
  caustics::gl::AppendMeshesKey(key, scene);
  const std::vector<double> lightField = caustics::gl::LightFieldSignature(scene);
  caustics::gl::AppendKey(key, lightField.data(), static_cast<int>(lightField.size()));
  for (const caustics::Material& m : scene.Materials)
  {
    caustics::gl::AppendKey(key, m.albedo.data(), 3);
  }
  key.push_back(views.size());
  for (const caustics::LightView& v : views)
  {
    key.push_back(
      static_cast<std::uint64_t>(v.valid) << 1 | static_cast<std::uint64_t>(v.perspective));
    const double values[] = { v.eye[0], v.eye[1], v.eye[2], v.axis[0], v.axis[1], v.axis[2],
      v.right[0], v.right[1], v.right[2], v.up[0], v.up[1], v.up[2], v.halfExtent, v.aspect,
      v.nearPlane, v.farPlane };
    caustics::gl::AppendKey(key, values, static_cast<int>(std::size(values)));
    caustics::gl::AppendKey(key, v.worldToClip, 16);
  }
  return key;
}
}

struct vtkCausticsLightBuffers::Internals
{
  std::vector<PerLight> Lights;
  int ActiveLights = 0;
  vtkNew<vtkCausticsShaderProgram> FluxProgram;
  caustics::gl::FullScreenTriangle Triangle;
  caustics::LightView Invalid;
  std::vector<std::uint64_t> Key; // ContentKey() of the buffers held; empty: none
  std::vector<std::uint64_t> ViewsKey;   // what the Views were computed from
  std::vector<caustics::LightView> Views; // the last ComputeViews()
  bool Reused = false;            // the last Render() kept the buffers held

  void SetNumberOfLights(vtkOpenGLRenderWindow* renWin, int count);
  bool RenderFlux(
    vtkOpenGLRenderWindow* renWin, const caustics::Light& source, PerLight& light, int resolution);
};

/** Keeps one PerLight per light; lights that went away give their GL objects back. */
void vtkCausticsLightBuffers::Internals::SetNumberOfLights(vtkOpenGLRenderWindow* renWin, int count)
{
  if (static_cast<int>(this->Lights.size()) < count)
  {
    this->Lights.resize(count);
  }
  for (int i = count; i < static_cast<int>(this->Lights.size()); ++i)
  {
    this->Lights[i].GBuffer->ReleaseGraphicsResources(renWin);
    this->Lights[i].Flux->ReleaseGraphicsResources(renWin);
    this->Lights[i].FluxFramebuffer->ReleaseGraphicsResources(renWin);
  }
  this->Lights.resize(count);
  this->ActiveLights = count;
}

/** Draws the flux leaving the light through each texel of its frustum. */
bool vtkCausticsLightBuffers::Internals::RenderFlux(
  vtkOpenGLRenderWindow* renWin, const caustics::Light& source, PerLight& light, int resolution)
{
  vtkOpenGLState* state = renWin->GetState();
  const bool resized =
    caustics::gl::EnsureTexture(light.Flux, renWin, resolution, resolution, GL_RGBA32F);
  state->PushFramebufferBindings();
  light.FluxFramebuffer->SetContext(renWin);
  light.FluxFramebuffer->Bind();
  if (resized || light.FluxFramebuffer->GetNumberOfColorAttachments() != 1)
  {
    light.FluxFramebuffer->AddColorAttachment(0, light.Flux);
  }
  light.FluxFramebuffer->ActivateDrawBuffers(1);
  vtkOpenGLState::ScopedglViewport viewport(state);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  // Stages draw whole off-screen targets: VTK may leave a scissor box set.
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglViewport(0, 0, resolution, resolution);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_BLEND);
  vtkCausticsShaderProgram* program = this->FluxProgram;
  const bool ok = program->Bind(renWin);
  if (ok)
  {
    SetFluxUniforms(program, source, light.View, resolution);
    this->Triangle.Draw();
    program->Unbind(renWin);
  }
  state->PopFramebufferBindings();
  return ok;
}

vtkCausticsLightBuffers::vtkCausticsLightBuffers()
  : Internal(new Internals)
{
  this->Internal->FluxProgram->SetName("light flux");
  this->Internal->FluxProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  this->Internal->FluxProgram->SetVertexSource(vtkCausticsFullScreenVS);
  this->Internal->FluxProgram->SetFragmentSource(vtkCausticsLightFluxFS);
}

vtkCausticsLightBuffers::~vtkCausticsLightBuffers() = default;

bool vtkCausticsLightBuffers::Render(vtkOpenGLRenderWindow* renWin,
  vtkCausticsSceneGeometry* geometry, const caustics::SceneData& scene)
{
  auto& in = *this->Internal;
  const int count = static_cast<int>(scene.Lights.size());
  std::vector<caustics::LightView> views = this->ComputeViews(scene);
  for (caustics::LightView& view : views)
  {
    caustics::OffsetLightView(view, this->GridOffset[0], this->GridOffset[1], this->Resolution);
  }
  // Nothing the buffers depend on changed: they are still right (no GL work at all).
  std::vector<std::uint64_t> key = ContentKey(renWin, geometry, scene, views,
    { static_cast<std::uint64_t>(this->Resolution), static_cast<std::uint64_t>(this->Focus),
      static_cast<std::uint64_t>(this->ShadowMapsOnly) });
  in.Reused = this->ReuseUnchanged && key == in.Key;
  if (in.Reused)
  {
    return true;
  }
  in.Key.clear(); // until this Render() succeeds
  in.SetNumberOfLights(renWin, count);
  const int resolution = this->Resolution;
  bool ok = true;
  for (int i = 0; i < count; ++i)
  {
    PerLight& light = in.Lights[i];
    light.View = views[i];
    light.GBuffer->SetReuseUnchanged(this->ReuseUnchanged);
    light.GBuffer->SetAlbedo(!this->ShadowMapsOnly);
    float worldToClip[16];
    caustics::gl::ToColumnMajor(light.View.worldToClip, worldToClip);
    ok = light.GBuffer->Render(renWin, geometry, worldToClip, resolution, resolution,
           vtkCausticsSceneGeometry::AllRoles) &&
      ok;
    if (!this->ShadowMapsOnly)
    {
      ok = in.RenderFlux(renWin, scene.Lights[i], light, resolution) && ok;
    }
    else
    {
      light.Flux->ReleaseGraphicsResources(renWin);
      light.FluxFramebuffer->ReleaseGraphicsResources(renWin);
    }
  }
  if (ok)
  {
    in.Key = std::move(key);
  }
  return ok;
}

std::vector<caustics::LightView> vtkCausticsLightBuffers::ComputeViews(
  const caustics::SceneData& scene)
{
  // The views are a function of these alone; FOCUS_SEEN scans the specular sheets'
  // triangles (caustics::PhotonFocusBounds), so they are kept while none changes.
  auto& in = *this->Internal;
  std::vector<std::uint64_t> key{ static_cast<std::uint64_t>(this->Focus) };
  caustics::gl::AppendMeshesKey(key, scene);
  const std::vector<double> lightField = caustics::gl::LightFieldSignature(scene);
  caustics::gl::AppendKey(key, lightField.data(), static_cast<int>(lightField.size()));
  caustics::gl::AppendKey(key, scene.Bounds, 6);
  if (this->Focus == FOCUS_SEEN)
  {
    const caustics::Camera& camera = scene.View;
    caustics::gl::AppendKey(key, camera.worldToClip, 16);
    caustics::gl::AppendKey(key, camera.position.data(), 3);
    caustics::gl::AppendKey(key, camera.focalPoint.data(), 3);
    key.push_back(camera.parallel);
  }
  if (key == in.ViewsKey)
  {
    return in.Views;
  }
  std::vector<caustics::LightView> views;
  for (int i = 0; i < static_cast<int>(scene.Lights.size()); ++i)
  {
    views.push_back(
      caustics::ComputeLightView(scene, i, static_cast<caustics::LightView::Focus>(this->Focus)));
    // Shadow maps (FOCUS_SCENE) of a lamp inside a room are clamped as a rule; what
    // they miss counts as lit. Photons that are not traced are worth a warning.
    if (views.back().clamped && this->Focus != FOCUS_SCENE)
    {
      vtkWarningMacro(<< "light " << i
                      << " is inside the bounds it must light; its buffers cover only a "
                         "150 degree cone towards the scene's centre");
    }
  }
  in.ViewsKey = std::move(key);
  in.Views = views;
  return views;
}

void vtkCausticsLightBuffers::SetGridOffset(double u, double v)
{
  const double asked[2] = { u, v };
  for (int k = 0; k < 2; ++k)
  {
    // NaN means no offset.
    const double value = std::isnan(asked[k]) ? 0.0 : std::max(-0.5, std::min(0.5, asked[k]));
    if (value != this->GridOffset[k])
    {
      this->GridOffset[k] = value;
      this->Modified();
    }
  }
}

bool vtkCausticsLightBuffers::GetLastRenderReused() const
{
  return this->Internal->Reused;
}

const caustics::LightView& vtkCausticsLightBuffers::GetView(int i) const
{
  const auto& in = *this->Internal;
  return i >= 0 && i < in.ActiveLights ? in.Lights[i].View : in.Invalid;
}

int vtkCausticsLightBuffers::GetNumberOfLights() const
{
  return this->Internal->ActiveLights;
}

vtkCausticsGBuffer* vtkCausticsLightBuffers::GetGBuffer(int i)
{
  auto& in = *this->Internal;
  return i >= 0 && i < in.ActiveLights ? in.Lights[i].GBuffer.GetPointer() : nullptr;
}

vtkTextureObject* vtkCausticsLightBuffers::GetFluxTexture(int i)
{
  auto& in = *this->Internal;
  return !this->ShadowMapsOnly && i >= 0 && i < in.ActiveLights ? in.Lights[i].Flux.GetPointer() : nullptr;
}

void vtkCausticsLightBuffers::ReleaseGraphicsResources(vtkWindow* win)
{
  auto& in = *this->Internal;
  for (PerLight& light : in.Lights)
  {
    light.GBuffer->ReleaseGraphicsResources(win);
    light.Flux->ReleaseGraphicsResources(win);
    light.FluxFramebuffer->ReleaseGraphicsResources(win);
  }
  in.Lights.clear();
  in.ActiveLights = 0;
  in.Key.clear();
  in.Reused = false;
  in.FluxProgram->ReleaseGraphicsResources(win);
  in.Triangle.Release();
}

void vtkCausticsLightBuffers::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Resolution: " << this->Resolution << "\n";
  const char* focus[] = { "specular", "scene", "seen specular" };
  os << indent << "Focus: " << focus[this->Focus] << "\n";
  os << indent << "ShadowMapsOnly: " << this->ShadowMapsOnly << "\n";
  os << indent << "ReuseUnchanged: " << this->ReuseUnchanged << "\n";
  os << indent << "GridOffset: " << this->GridOffset[0] << ", " << this->GridOffset[1] << "\n";
  os << indent << "LastRenderReused: " << this->Internal->Reused << "\n";
  os << indent << "Lights: " << this->Internal->ActiveLights << "\n";
  for (int i = 0; i < this->Internal->ActiveLights; ++i)
  {
    const auto& view = this->Internal->Lights[i].View;
    os << indent.GetNextIndent() << "light " << i << ": "
       << (view.perspective ? "perspective, tan(half angle) " : "orthographic, half width ")
       << view.halfExtent << ", half height " << view.HalfExtentUp() << ", near " << view.nearPlane
       << ", far " << view.farPlane << "\n";
  }
}
