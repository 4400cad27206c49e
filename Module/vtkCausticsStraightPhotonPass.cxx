#include "vtkCausticsStraightPhotonPass.h"

#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsPhotonEmitter.h"
#include "vtkCausticsPhotonSplatter.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkCausticsStraightPhotonPassCS.h" // The transport shader
#include "vtkObjectFactory.h"
#include "vtk_glew.h"

vtkStandardNewMacro(vtkCausticsStraightPhotonPass);

struct vtkCausticsStraightPhotonPass::Internals
{
  vtkNew<vtkCausticsPhotonEmitter> Emitter;   // emission (shared)
  vtkNew<vtkCausticsGBuffer> Receivers;       // transport: receivers seen from the light
  vtkNew<vtkCausticsShaderProgram> Program;   // transport: the hit records
  vtkNew<vtkCausticsPhotonSplatter> Splatter; // reconstruction (shared)
  caustics::gl::PhotonPlanes Landed;          // transport's output, with kernel radii
};

vtkCausticsStraightPhotonPass::vtkCausticsStraightPhotonPass()
  : Internal(new Internals)
{
  this->Internal->Program->SetName("straight photon transport");
  this->Internal->Program->SetComputeSource(vtkCausticsStraightPhotonPassCS);
  this->SetSpecularShadows(true); // its photons replace the light the specular actors block
}

vtkCausticsStraightPhotonPass::~vtkCausticsStraightPhotonPass() = default;

vtkCausticsRenderPass::CausticNeeds vtkCausticsStraightPhotonPass::GetCausticNeeds()
{
  return { true, false, true }; // a light must reach a specular actor; early skip allowed
}

vtkCausticsRenderPass::PhotonStorage vtkCausticsStraightPhotonPass::GetPhotonStorage()
{
  return { 52.0 + 14.0, 0.0, 0.0, false }; // landed records and radii; receivers (28 B/texel)
}

bool vtkCausticsStraightPhotonPass::RenderCausticIrradiance(const FrameInputs& in)
{
  auto& s = *this->Internal;
  bool ok = true;
  for (int light = 0; ok && light < in.LightBuffers->GetNumberOfLights(); ++light)
  {
    ok = !in.LightBuffers->GetView(light).valid ||
      (s.Emitter->Emit(in.Window, in.LightBuffers, light, in.Geometry, *in.Scene) &&
        this->Transport(in, light) &&
        this->StoreCaustic(in, light, s.Landed.Records(), s.Emitter->GetGrid().Width,
          s.Emitter->GetGrid().Height, s.Emitter->GetGrid().MaximumPhotonFlux) &&
        this->SplatInCameraView(
          in, s.Splatter, s.Emitter->GetGrid(), s.Landed.Records(), s.Landed.KernelRadius()));
  }
  return ok;
}

bool vtkCausticsStraightPhotonPass::Transport(const FrameInputs& in, int light)
{
  auto& s = *this->Internal;
  const caustics::PhotonGrid& grid = s.Emitter->GetGrid();
  const caustics::LightView& view = in.LightBuffers->GetView(light);
  const int n = grid.BranchRows;
  float lightToClip[16];
  caustics::gl::ToColumnMajor(view.worldToClip, lightToClip);
  const int receiver = vtkCausticsSceneGeometry::RoleBit(1);
  if (!s.Receivers->Render(in.Window, in.Geometry, lightToClip, n, n, receiver) ||
    !s.Program->Bind(in.Window))
  {
    return false;
  }
  // Image units 0-4: the photons and the receivers (normals are RGBA16F); 5-8: the
  // landed photons and their kernel radii.
  vtkTextureObject* images[] = { grid.Emitted.Position, grid.Emitted.Direction, grid.Emitted.Flux,
    s.Receivers->GetPositionTexture(), s.Receivers->GetNormalTexture() };
  for (int i = 0; i < 5; ++i)
  {
    glBindImageTexture(
      i, images[i]->GetHandle(), 0, GL_FALSE, 0, GL_READ_ONLY, i == 4 ? GL_RGBA16F : GL_RGBA32F);
  }
  s.Landed.EnsureWithRadius(in.Window, grid.Width, grid.Height);
  s.Landed.BindImages(5, GL_WRITE_ONLY);
  s.Landed.BindRadiusImage(8, GL_WRITE_ONLY);
  const caustics::Light& source = in.Scene->Lights[light];
  const bool directional = source.type == caustics::Light::Type::Directional;
  const caustics::Vec3& v = directional ? source.direction : source.position;
  const float lightVector[4] = { float(v[0]), float(v[1]), float(v[2]), directional ? 0.f : 1.f };
  s.Program->SetUniform3f("viewEye", float(view.eye[0]), float(view.eye[1]), float(view.eye[2]));
  s.Program->SetUniform2i("grid", grid.Width, grid.Height);
  s.Program->SetUniformi("resolution", n);
  s.Program->SetUniform4f("light", lightVector);
  s.Program->SetUniformf("spacings", 2.0f); // kernel radius in photon spacings
  s.Program->DispatchCovering2D(grid.Width, grid.Height, 16, 16);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  s.Program->Unbind(in.Window);
  return true;
}

void vtkCausticsStraightPhotonPass::ReleaseTechniqueResources(vtkWindow* w)
{
  auto& s = *this->Internal;
  s.Emitter->ReleaseGraphicsResources(w);
  s.Receivers->ReleaseGraphicsResources(w);
  s.Program->ReleaseGraphicsResources(w);
  s.Splatter->ReleaseGraphicsResources(w);
  s.Landed.Release(w);
}
