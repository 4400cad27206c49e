#include "vtkCausticsScreenSpaceRefraction.h"

#include "vtkCausticsBindings.h" // CAUSTICS_*_BINDING
#include "vtkCausticsDistanceImpostors.h"
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsLayeredDepth.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsScreenSpaceUtilities.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkCausticsSpecularHierarchy.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsFullScreenVS.h"
#include "vtkCausticsImpostorCommon.h"
#include "vtkCausticsOptics.h"
#include "vtkCausticsScreenSpaceCommon.h"
#include "vtkCausticsScreenSpaceRefractionFS.h"
#include "vtkCausticsSpecularTrace.h"

#include <algorithm>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkCausticsScreenSpaceRefraction);

struct vtkCausticsScreenSpaceRefraction::Internals
{
  caustics::ssp::Framebuffer Framebuffer;
  caustics::gl::FullScreenTriangle Triangle;
  vtkNew<vtkCausticsShaderProgram> Program;
  vtkNew<vtkCausticsSpecularHierarchy> Hierarchy;
};

vtkCausticsScreenSpaceRefraction::vtkCausticsScreenSpaceRefraction()
  : Internal(new Internals)
{
  this->Internal->Program->SetName("screen-space refraction");
  this->Internal->Program->SetVertexSource(vtkCausticsFullScreenVS);
  this->Internal->Program->SetFragmentSource((std::string(vtkCausticsOptics) +
    vtkCausticsScreenSpaceCommon + vtkCausticsImpostorCommon + vtkCausticsSpecularTrace +
    vtkCausticsScreenSpaceRefractionFS)
                                               .c_str());
}

vtkCausticsScreenSpaceRefraction::~vtkCausticsScreenSpaceRefraction()
{
  if (this->Internal->Framebuffer.Handle)
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): GL objects leaked");
  }
}

void vtkCausticsScreenSpaceRefraction::ScreenRectangle(
  const float worldToClip[16], const double bounds[6], int width, int height, int rect[4])
{
  rect[0] = rect[1] = rect[2] = rect[3] = 0;
  if (!(bounds[0] <= bounds[1] && bounds[2] <= bounds[3] && bounds[4] <= bounds[5]))
  {
    return; // empty (or NaN) box: no pixel
  }
  double lo[2] = { 1e300, 1e300 }, hi[2] = { -1e300, -1e300 };
  for (int corner = 0; corner < 8; ++corner)
  {
    const double p[3] = { bounds[(corner & 1) ? 1 : 0], bounds[(corner & 2) ? 3 : 2],
      bounds[(corner & 4) ? 5 : 4] };
    double clip[4];
    for (int r = 0; r < 4; ++r)
    {
      clip[r] = worldToClip[12 + r];
      for (int c = 0; c < 3; ++c)
      {
        clip[r] += worldToClip[4 * c + r] * p[c];
      }
    }
    if (!(clip[3] > 1e-12 * (std::abs(clip[0]) + std::abs(clip[1]) + 1.0)))
    {
      rect[2] = width; // a corner at or behind the eye: its projection is unbounded
      rect[3] = height;
      return;
    }
    for (int a = 0; a < 2; ++a)
    {
      lo[a] = std::min(lo[a], clip[a] / clip[3]);
      hi[a] = std::max(hi[a], clip[a] / clip[3]);
    }
  }
  const int size[2] = { width, height };
  int first[2], last[2];
  for (int a = 0; a < 2; ++a)
  {
    // One pixel of margin on each side against rounding; clamped in double first.
    const double from = std::floor((lo[a] * 0.5 + 0.5) * size[a]) - 1.0;
    const double to = std::ceil((hi[a] * 0.5 + 0.5) * size[a]) + 1.0;
    first[a] = static_cast<int>(std::max(0.0, std::min(from, static_cast<double>(size[a]))));
    last[a] = static_cast<int>(std::max(0.0, std::min(to, static_cast<double>(size[a]))));
  }
  rect[0] = first[0];
  rect[1] = first[1];
  rect[2] = std::max(0, last[0] - first[0]);
  rect[3] = std::max(0, last[1] - first[1]);
}

bool vtkCausticsScreenSpaceRefraction::Render(
  vtkOpenGLRenderWindow* renWin, const Inputs& inputs, vtkTextureObject* target)
{
  auto& in = *this->Internal;
  if (!inputs.RefractorLayers || !inputs.Opaque || !inputs.Geometry || !inputs.DelegateColor ||
    !inputs.DelegateDepth || !inputs.CausticIrradiance || !inputs.WorldToClip || !target)
  {
    vtkErrorMacro(<< "refraction tracing needs the refractor layers, the opaque G-buffer, "
                     "VTK's image and the caustic irradiance");
    return false;
  }
  caustics::gl::EnsureTexture(target, renWin, inputs.Width, inputs.Height, GL_RGBA32F);
  vtkOpenGLState* state = renWin->GetState();
  state->PushFramebufferBindings();
  vtkOpenGLState::ScopedglViewport viewport(state);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglScissor scissorBox(state);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_BLEND);
  const GLuint framebuffer = in.Framebuffer.Get();
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, target->GetHandle(), 0);
  glNamedFramebufferDrawBuffer(framebuffer, GL_COLOR_ATTACHMENT0);
  state->vtkglBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  state->vtkglViewport(0, 0, inputs.Width, inputs.Height);
  // Pixels outside the specular objects' rectangle show none of them: alpha 0.
  const float zero[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  glClearTexImage(target->GetHandle(), 0, GL_RGBA, GL_FLOAT, zero);
  int rect[4];
  ScreenRectangle(inputs.WorldToClip, inputs.SpecularBounds, inputs.Width, inputs.Height, rect);
  state->vtkglEnable(GL_SCISSOR_TEST);
  state->vtkglScissor(rect[0], rect[1], rect[2], rect[3]);
  vtkCausticsShaderProgram* p = in.Program;
  const bool exact = inputs.Scene && this->WillTraceSpecularGeometry(*inputs.Scene);
  this->TracedSpecularGeometry = exact;
  const bool ok = rect[2] == 0 || rect[3] == 0 || p->Bind(renWin);
  if (ok && rect[2] > 0 && rect[3] > 0)
  {
    caustics::ssp::TextureUnits units(renWin);
    vtkCausticsLayeredDepth* layers = inputs.RefractorLayers;
    const int layerUnit = units.Bind(layers->GetPositionTexture());
    p->SetUniformi("refractorPosition", layerUnit);
    p->SetUniformi("refractorNormal", units.Bind(layers->GetNormalTexture()));
    p->SetUniformi("gPosition", units.Bind(inputs.Opaque->GetPositionTexture()));
    p->SetUniformi("gNormal", units.Bind(inputs.Opaque->GetNormalTexture()));
    p->SetUniformi("gAlbedo", units.Bind(inputs.Opaque->GetAlbedoTexture()));
    p->SetUniformi("gDepth", units.Bind(inputs.Opaque->GetDepthTexture()));
    p->SetUniformi("delegateColor", units.Bind(inputs.DelegateColor));
    p->SetUniformi("delegateDepth", units.Bind(inputs.DelegateDepth));
    p->SetUniformi("causticIrradiance", units.Bind(inputs.CausticIrradiance));
    const bool direct = inputs.DirectIrradiance && inputs.DirectIrradiance->GetHandle();
    p->SetUniformi(
      "directIrradiance", units.Bind(direct ? inputs.DirectIrradiance : inputs.CausticIrradiance));
    p->SetUniformi("hasDirect", direct ? 1 : 0);
    const bool lost = inputs.LostShading && inputs.LostShading->GetHandle();
    p->SetUniformi(
      "lostShading", units.Bind(lost ? inputs.LostShading : inputs.CausticIrradiance));
    p->SetUniformi("hasLostShading", lost ? 1 : 0);
    glBindBufferBase(
      GL_SHADER_STORAGE_BUFFER, CAUSTICS_LDI_TABLE_BINDING, layers->GetTableBuffer());
    inputs.Geometry->BindMaterials();
    p->SetUniformMatrix4("worldToClip", inputs.WorldToClip);
    p->SetUniform2f(
      "viewport", static_cast<float>(inputs.Width), static_cast<float>(inputs.Height));
    const float origin[4] = { static_cast<float>(inputs.ViewOrigin[0]),
      static_cast<float>(inputs.ViewOrigin[1]), static_cast<float>(inputs.ViewOrigin[2]),
      static_cast<float>(inputs.ViewOrigin[3]) };
    p->SetUniform4f("viewOrigin", origin);
    p->SetUniformi("eyeMaterial", inputs.EyeMaterial);
    p->SetUniform3f("boundsMin", static_cast<float>(inputs.Bounds[0]),
      static_cast<float>(inputs.Bounds[2]), static_cast<float>(inputs.Bounds[4]));
    p->SetUniform3f("boundsMax", static_cast<float>(inputs.Bounds[1]),
      static_cast<float>(inputs.Bounds[3]), static_cast<float>(inputs.Bounds[5]));
    p->SetUniform3f("background", static_cast<float>(inputs.Background[0]),
      static_cast<float>(inputs.Background[1]), static_cast<float>(inputs.Background[2]));
    p->SetUniformi("maxEvents", this->MaximumEvents);
    p->SetUniformi("internalReflections", this->InternalReflections ? 1 : 0);
    vtkCausticsSpecularHierarchy::BindTraced(exact ? in.Hierarchy.GetPointer() : nullptr, p);
    p->SetUniformf("tolerance", static_cast<float>(inputs.Tolerance));
    p->SetUniformf(
      "pixelScale", caustics::ssp::PixelScale(inputs.WorldToClip, inputs.Width, inputs.Height));
    // VTK's depth and the G-buffer's come from the same triangles and matrix (as
    // the composite's test).
    p->SetUniformf("depthTolerance", 2e-6f);
    const bool impostors = inputs.Method != 0 && inputs.Impostors;
    p->SetUniformi("viewMethod", impostors ? inputs.Method : 0);
    if (impostors)
    {
      inputs.Impostors->SetUniforms(p, units);
    }
    else
    {
      vtkCausticsDistanceImpostors::SetAbsentUniforms(p, layerUnit);
    }
    in.Triangle.Draw();
    p->Unbind(renWin);
  }
  state->PopFramebufferBindings();
  return ok;
}

void vtkCausticsScreenSpaceRefraction::ReleaseGraphicsResources(vtkWindow* win)
{
  this->Internal->Framebuffer.Release();
  this->Internal->Triangle.Release();
  this->Internal->Program->ReleaseGraphicsResources(win);
  this->Internal->Hierarchy->ReleaseGraphicsResources(win);
}

bool vtkCausticsScreenSpaceRefraction::WillTraceSpecularGeometry(const caustics::SceneData& scene)
{
  if (this->ExactSpecularGeometry == EXACT_OFF || !this->Internal->Hierarchy->Update(scene))
  {
    return false; // a hierarchy that failed to upload has said why; the layers serve
  }
  return this->ExactSpecularGeometry == EXACT_ON ||
    this->Internal->Hierarchy->GetNumberOfNonConvexMeshes() > 0;
}

vtkCausticsSpecularHierarchy* vtkCausticsScreenSpaceRefraction::GetSpecularHierarchy()
{
  return this->Internal->Hierarchy;
}

void vtkCausticsScreenSpaceRefraction::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaximumEvents: " << this->MaximumEvents << "\n";
  os << indent << "InternalReflections: " << this->InternalReflections << "\n";
  os << indent << "ExactSpecularGeometry: " << this->ExactSpecularGeometry << "\n";
}
