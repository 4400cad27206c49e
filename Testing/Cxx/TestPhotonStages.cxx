// The shared photon stages: emission conserves the flux reaching specular
// surfaces (Fresnel R + T = 1) and bends it as Snell says; splats deposit
// exactly each photon's flux as irradiance (W/m^2 integrated over the receiver).
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsPhotonEmitter.h"
#include "vtkCausticsPhotonSplatter.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCausticsSceneGeometry.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace
{
struct BallLens
{
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkCausticsRenderPass> Pass;
  vtkNew<vtkCausticsBuiltinScene> Scene;
  BallLens()
  {
    this->Scene->Populate(this->Renderer);
    this->Renderer->SetPass(this->Pass);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(128, 128);
    this->Window->AddRenderer(this->Renderer);
    this->Pass->SetLightBufferResolution(128);
    this->Window->Render();
  }
  ~BallLens()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }
  vtkOpenGLRenderWindow* GL() { return vtkOpenGLRenderWindow::SafeDownCast(this->Window); }
};

vtkDataArray* Array(vtkImageData* image)
{
  return image->GetPointData()->GetArray(0);
}
}

TEST(PhotonEmitter, ConservesFluxAndRefractsAtNormalIncidence)
{
  BallLens f;
  ASSERT_TRUE(f.Pass->GetLastFrameHadCaustics());
  f.GL()->MakeCurrent();
  vtkNew<vtkCausticsPhotonEmitter> emitter;
  const auto& scene = f.Pass->GetSceneExtractor()->GetScene();
  ASSERT_TRUE(emitter->Emit(f.GL(), f.Pass->GetLightBuffers(), 0, f.Pass->GetGeometry(), scene));
  EXPECT_EQ(emitter->GetGrid().Width, 128);
  EXPECT_EQ(emitter->GetGrid().Height, 256);
  auto position = caustics::gl::ReadTexture(emitter->GetPositionTexture(), "p", 4);
  auto direction = caustics::gl::ReadTexture(emitter->GetDirectionTexture(), "d", 4);
  auto flux = caustics::gl::ReadTexture(emitter->GetFluxTexture(), "f", 4);
  auto lightNormal =
    caustics::gl::ReadTexture(f.Pass->GetLightBuffers()->GetGBuffer(0)->GetNormalTexture(), "n", 4);
  auto lightFlux = caustics::gl::ReadTexture(f.Pass->GetLightBuffers()->GetFluxTexture(0), "lf", 4);

  // Flux on the ball's texels, as the light buffers carry it.
  double onBall = 0.0;
  for (vtkIdType i = 0; i < 128 * 128; ++i)
  {
    if (std::lround(Array(lightNormal)->GetComponent(i, 3)) == 3)
    {
      onBall += Array(lightFlux)->GetComponent(i, 0);
    }
  }
  double emitted = 0.0, refracted = 0.0;
  for (vtkIdType i = 0; i < 128 * 256; ++i)
  {
    if (Array(position)->GetComponent(i, 3) > 0.0)
    {
      emitted += Array(flux)->GetComponent(i, 0);
      refracted += i < 128 * 128 ? Array(flux)->GetComponent(i, 0) : 0.0;
    }
  }
  ASSERT_GT(onBall, 0.0);
  // R + T = 1 photon by photon; only float rounding separates the sums.
  EXPECT_NEAR(emitted / onBall, 1.0, 1e-5);
  // A glass ball in air reflects 4% at normal incidence and more towards the rim:
  // the transmitted share lies between 1 - R(rim) and 1 - R(0) = 0.96.
  EXPECT_LT(refracted / onBall, 0.96);
  EXPECT_GT(refracted / onBall, 0.85);

  // The centre texel meets the ball head-on: straight down into the glass,
  // transmitted flux = (1 - 0.04) x the texel's flux, state "inside" (2).
  const vtkIdType centre = 64 * 128 + 64;
  EXPECT_NEAR(Array(position)->GetComponent(centre, 3), 2.0, 0.0);
  EXPECT_NEAR(Array(direction)->GetComponent(centre, 1), -1.0, 1e-3);
  const double t = 1.0 - std::pow((1.5 - 1.0) / (1.5 + 1.0), 2);
  EXPECT_NEAR(
    Array(flux)->GetComponent(centre, 0) / Array(lightFlux)->GetComponent(centre, 0), t, 2e-3);
  // Off-axis texels bend towards the axis (Snell at the entry): the photon's
  // horizontal direction component points back towards the ball's axis.
  const vtkIdType offAxis = 64 * 128 + 96;
  const double px = Array(position)->GetComponent(offAxis, 0);
  const double dx = Array(direction)->GetComponent(offAxis, 0);
  ASSERT_GT(Array(position)->GetComponent(offAxis, 3), 0.0);
  EXPECT_LT(px * dx, 0.0);
  emitter->ReleaseGraphicsResources(f.Window);
}

TEST(PhotonSplatter, DepositsEachPhotonsFlux)
{
  BallLens f;
  f.GL()->MakeCurrent();
  // A top-down orthographic view of the floor, 256 pixels over 8 m: 1/32 m pixels.
  caustics::SceneData scene = f.Pass->GetSceneExtractor()->GetScene();
  const double half = 4.0;
  const double worldToClip[16] = { 1.0 / half, 0, 0, 0, 0, 0, -1.0 / half, 0, 0, -0.1, 0, 0.5, 0, 0,
    0, 1 }; // x -> x, -z -> y, depth from y
  float matrix[16];
  caustics::gl::ToColumnMajor(worldToClip, matrix);
  vtkNew<vtkCausticsGBuffer> view;
  const int size = 256;
  ASSERT_TRUE(view->Render(
    f.GL(), f.Pass->GetGeometry(), matrix, size, size, vtkCausticsSceneGeometry::RoleBit(1)));

  // Three photons landed on the floor (the photon record layout), radius 0.2 m (6.4 pixels).
  const float hits[3][4] = { { 0.0f, 0.0f, 0.0f, 1.0f }, { 1.0f, 0.0f, 1.0f, 1.0f },
    { -2.0f, 0.0f, 0.5f, 1.0f } };
  const float normals[3][4] = { { 0, 1, 0, 1 }, { 0, 1, 0, 1 }, { 0, 1, 0, 1 } };
  const float fluxes[3][4] = { { 1, 2, 3, 0 }, { 0.5f, 0.5f, 0.5f, 0 }, { 2, 1, 0, 0 } };
  const float radii[3] = { 0.2f, 0.2f, 0.2f };
  caustics::gl::PhotonPlanes landed;
  landed.EnsureWithRadius(f.GL(), 3, 1);
  const caustics::PhotonRecords records = landed.Records();
  glTextureSubImage2D(records.Position->GetHandle(), 0, 0, 0, 3, 1, GL_RGBA, GL_FLOAT, hits);
  glTextureSubImage2D(records.Direction->GetHandle(), 0, 0, 0, 3, 1, GL_RGBA, GL_FLOAT, normals);
  glTextureSubImage2D(records.Flux->GetHandle(), 0, 0, 0, 3, 1, GL_RGBA, GL_FLOAT, fluxes);
  glTextureSubImage2D(landed.KernelRadius()->GetHandle(), 0, 0, 0, 3, 1, GL_RED, GL_FLOAT, radii);

  vtkNew<vtkTextureObject> target;
  caustics::gl::EnsureTexture(target, f.GL(), size, size, GL_RGBA32F);
  vtkNew<vtkOpenGLFramebufferObject> framebuffer;
  vtkOpenGLState* state = f.GL()->GetState();
  state->PushFramebufferBindings();
  framebuffer->SetContext(f.GL());
  framebuffer->Bind();
  framebuffer->AddColorAttachment(0, target);
  framebuffer->ActivateDrawBuffers(1);
  const float zero[4] = { 0, 0, 0, 0 };
  glClearBufferfv(GL_COLOR, 0, zero);
  state->vtkglViewport(0, 0, size, size);
  state->vtkglDisable(GL_SCISSOR_TEST);
  vtkNew<vtkCausticsPhotonSplatter> splatter;
  caustics::PhotonGrid grid; // three hits in one row
  grid.Width = 3;
  grid.Height = grid.BranchRows = 1;
  ASSERT_TRUE(splatter->Splat(f.GL(), grid, records, landed.KernelRadius(), view, matrix));
  state->PopFramebufferBindings();

  auto irradiance = caustics::gl::ReadTexture(target, "E", 4);
  const double pixelArea = std::pow(2.0 * half / size, 2);
  double deposited[3] = { 0, 0, 0 };
  for (vtkIdType i = 0; i < size * size; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      deposited[c] += Array(irradiance)->GetComponent(i, c) * pixelArea;
    }
  }
  // Sum of the kernel over pixel centres approximates its integral (1): the
  // midpoint rule on a 6.4-pixel-radius Epanechnikov kernel errs by ~h^2/r^2/12
  // = 0.2%; allow 1%.
  const double expected[3] = { 3.5, 3.5, 3.5 };
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(deposited[c] / expected[c], 1.0, 0.01) << "channel " << c;
  }
  // The first photon's centre pixel: 2 / (pi r^2) x flux = 15.9 W/m^2 in red.
  double px = (0.0 / half * 0.5 + 0.5) * size, py = (0.0 * 0.5 + 0.5) * size;
  const vtkIdType id = static_cast<vtkIdType>(py) * size + static_cast<vtkIdType>(px);
  EXPECT_NEAR(
    Array(irradiance)->GetComponent(id, 0), 2.0 / (M_PI * 0.04), 0.05 * 2.0 / (M_PI * 0.04));
  splatter->ReleaseGraphicsResources(f.Window);
  view->ReleaseGraphicsResources(f.Window);
  landed.Release(f.Window);
  target->ReleaseGraphicsResources(f.Window);
  framebuffer->ReleaseGraphicsResources(f.Window);
}
