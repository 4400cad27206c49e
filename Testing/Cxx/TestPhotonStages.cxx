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
#include <iostream>
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

namespace
{
/**
 * A top-down orthographic view of the ball lens's floor (12 m square, centred), 256
 * pixels over 8 m (1/32 m pixels) centred at x = `centreX`, and an irradiance target of
 * its size: where the splatter deposits photons that the test puts in the photon record
 * layout.
 */
struct FloorTarget
{
  static constexpr int Size = 256;
  static constexpr double Half = 4.0;
  BallLens& Frame;
  float WorldToClip[16];
  vtkNew<vtkCausticsGBuffer> View;
  vtkNew<vtkTextureObject> Target;
  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  caustics::gl::PhotonPlanes Landed;

  explicit FloorTarget(BallLens& frame, double centreX = 0.0)
    : Frame(frame)
  {
    frame.GL()->MakeCurrent();
    const double worldToClip[16] = { 1.0 / Half, 0, 0, -centreX / Half, 0, 0, -1.0 / Half, 0, 0,
      -0.1, 0, 0.5, 0, 0, 0, 1 }; // x -> x, -z -> y, depth from y
    caustics::gl::ToColumnMajor(worldToClip, this->WorldToClip);
    EXPECT_TRUE(this->View->Render(frame.GL(), frame.Pass->GetGeometry(), this->WorldToClip, Size,
      Size, vtkCausticsSceneGeometry::RoleBit(1)));
    caustics::gl::EnsureTexture(this->Target, frame.GL(), Size, Size, GL_RGBA32F);
  }
  ~FloorTarget()
  {
    this->View->ReleaseGraphicsResources(this->Frame.Window);
    this->Landed.Release(this->Frame.Window);
    this->Target->ReleaseGraphicsResources(this->Frame.Window);
    this->Framebuffer->ReleaseGraphicsResources(this->Frame.Window);
  }

  /** Landed photons (records of the grid's size, flat arrays of 4 floats each) and radii. */
  caustics::PhotonRecords Upload(int width, int height, const std::vector<float>& positions,
    const std::vector<float>& normals, const std::vector<float>& fluxes,
    const std::vector<float>& radii)
  {
    this->Landed.EnsureWithRadius(this->Frame.GL(), width, height);
    const caustics::PhotonRecords records = this->Landed.Records();
    glTextureSubImage2D(records.Position->GetHandle(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT,
      positions.data());
    glTextureSubImage2D(records.Direction->GetHandle(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT,
      normals.data());
    glTextureSubImage2D(
      records.Flux->GetHandle(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, fluxes.data());
    glTextureSubImage2D(this->Landed.KernelRadius()->GetHandle(), 0, 0, 0, width, height, GL_RED,
      GL_FLOAT, radii.data());
    return records;
  }

  /** The irradiance (W/m^2, RGBA) the splatter deposits for the uploaded photons. */
  vtkSmartPointer<vtkImageData> Deposit(
    vtkCausticsPhotonSplatter* splatter, const caustics::PhotonGrid& grid)
  {
    vtkOpenGLState* state = this->Frame.GL()->GetState();
    state->PushFramebufferBindings();
    this->Framebuffer->SetContext(this->Frame.GL());
    this->Framebuffer->Bind();
    this->Framebuffer->AddColorAttachment(0, this->Target);
    this->Framebuffer->ActivateDrawBuffers(1);
    const float zero[4] = { 0, 0, 0, 0 };
    glClearBufferfv(GL_COLOR, 0, zero);
    state->vtkglViewport(0, 0, Size, Size);
    state->vtkglDisable(GL_SCISSOR_TEST);
    EXPECT_TRUE(splatter->Splat(this->Frame.GL(), grid, this->Landed.Records(),
      this->Landed.KernelRadius(), this->View, this->WorldToClip));
    state->PopFramebufferBindings();
    return caustics::gl::ReadTexture(this->Target, "E", 4);
  }

  /** The flux (W) of one channel the image holds: irradiance times the pixels' area. */
  static double Flux(vtkImageData* irradiance, int channel)
  {
    const double pixelArea = std::pow(2.0 * Half / Size, 2);
    double flux = 0.0;
    for (vtkIdType i = 0; i < Size * Size; ++i)
    {
      flux += Array(irradiance)->GetComponent(i, channel) * pixelArea;
    }
    return flux;
  }

  /** Irradiance of one channel at the pixel holding floor point (x, 0, z). */
  static double At(vtkImageData* irradiance, double x, double z, int channel)
  {
    const int px = static_cast<int>((x / Half * 0.5 + 0.5) * Size);
    const int py = static_cast<int>((-z / Half * 0.5 + 0.5) * Size);
    return Array(irradiance)->GetComponent(static_cast<vtkIdType>(py) * Size + px, channel);
  }
};
}

TEST(PhotonSplatter, DepositsEachPhotonsFlux)
{
  BallLens f;
  FloorTarget floor(f);
  // Three photons landed on the floor (the photon record layout), radius 0.2 m (6.4 pixels).
  floor.Upload(3, 1, { 0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 0.0f, 1.0f, 1.0f, -2.0f, 0.0f, 0.5f, 1.0f },
    { 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1 }, { 1, 2, 3, 0, 0.5f, 0.5f, 0.5f, 0, 2, 1, 0, 0 },
    { 0.2f, 0.2f, 0.2f });
  vtkNew<vtkCausticsPhotonSplatter> splatter;
  caustics::PhotonGrid grid; // three hits in one row
  grid.Width = 3;
  grid.Height = grid.BranchRows = 1;
  auto irradiance = floor.Deposit(splatter, grid);
  // Sum of the kernel over pixel centres approximates its integral (1): the
  // midpoint rule on a 6.4-pixel-radius Epanechnikov kernel errs by ~h^2/r^2/12
  // = 0.2%; allow 1%.
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(FloorTarget::Flux(irradiance, c) / 3.5, 1.0, 0.01) << "channel " << c;
  }
  // The first photon's centre pixel: 2 / (pi r^2) x flux = 15.9 W/m^2 in red.
  EXPECT_NEAR(
    FloorTarget::At(irradiance, 0.0, 0.0, 0), 2.0 / (M_PI * 0.04), 0.05 * 2.0 / (M_PI * 0.04));
  splatter->ReleaseGraphicsResources(f.Window);
}

namespace
{
/**
 * A 33 x 33 grid of photons of a directional light (measure 0.01 m^2, 0.02 W each in
 * every channel) landed on the floor at x = X(i), z = 0.1 j - 1.6, facing up: a
 * lattice of 0.1 m where X is uniform, so its caustic triangles carry 2 W/m^2.
 */
struct Lattice
{
  static constexpr int N = 33;
  static constexpr float PhotonFlux = 0.02f;
  std::vector<float> Positions, Normals, Fluxes, Radii;
  caustics::PhotonGrid Grid;

  template <typename X>
  explicit Lattice(X x)
  {
    for (int j = 0; j < N; ++j)
    {
      for (int i = 0; i < N; ++i)
      {
        const float position[4] = { static_cast<float>(x(i)), 0.0f, 0.1f * j - 1.6f, 1.0f };
        const float normal[4] = { 0, 1, 0, 1 };
        const float flux[4] = { PhotonFlux, PhotonFlux, PhotonFlux, 0.01f };
        this->Positions.insert(this->Positions.end(), position, position + 4);
        this->Normals.insert(this->Normals.end(), normal, normal + 4);
        this->Fluxes.insert(this->Fluxes.end(), flux, flux + 4);
        this->Radii.push_back(0.15f);
      }
    }
    this->Grid.Width = this->Grid.Height = this->Grid.BranchRows = N;
    this->Grid.LightType = 0;
  }
  float* Position(int i, int j) { return &this->Positions[4 * (j * N + i)]; }
  caustics::PhotonRecords Upload(FloorTarget& floor)
  {
    return floor.Upload(N, N, this->Positions, this->Normals, this->Fluxes, this->Radii);
  }
};
}

// Caustic triangles deposit the exact irradiance of the piecewise-linear map from
// the grid to the receiver, box-filtered over the pixels, and every photon's whole
// flux, whether its triangles carry it or, where they are broken, its splat.
TEST(PhotonSplatter, CausticTrianglesDepositTheMappedIrradiance)
{
  BallLens f;
  FloorTarget floor(f);
  vtkNew<vtkCausticsPhotonSplatter> splatter;
  splatter->SetReconstructionToTriangles();
  const double total = Lattice::N * Lattice::N * Lattice::PhotonFlux;

  // A uniform lattice: 2 W/m^2 everywhere inside it (pixels of 1/32 m, unaligned
  // with the 0.1 m lattice: only the box filter gives the exact value).
  Lattice uniform([](int i) { return 0.1 * i - 1.6; });
  uniform.Upload(floor);
  auto irradiance = floor.Deposit(splatter, uniform.Grid);
  EXPECT_NEAR(FloorTarget::Flux(irradiance, 0) / total, 1.0, 0.005);
  for (double x : { -1.23, -0.5, 0.0, 0.71, 1.37 })
  {
    for (double z : { -1.31, 0.02, 0.93 })
    {
      EXPECT_NEAR(FloorTarget::At(irradiance, x, z, 0), 2.0, 0.01) << "at " << x << ", " << z;
    }
  }

  // Columns 16 to 20 squeezed four times (0.025 m apart): 8 W/m^2 over the 0.1 m
  // band, with edges as sharp as the pixels (a splat would spread it over its radius).
  Lattice squeezed([](int i) {
    return i <= 16 ? 0.1 * i - 1.6 : (i <= 20 ? 0.025 * (i - 16) : 0.1 * (i - 20) + 0.1);
  });
  squeezed.Upload(floor);
  irradiance = floor.Deposit(splatter, squeezed.Grid);
  EXPECT_NEAR(FloorTarget::Flux(irradiance, 0) / total, 1.0, 0.005);
  EXPECT_NEAR(FloorTarget::At(irradiance, 0.05, 0.3, 0), 8.0, 0.04);
  EXPECT_NEAR(FloorTarget::At(irradiance, -0.05, 0.3, 0), 2.0, 0.01);
  EXPECT_NEAR(FloorTarget::At(irradiance, 0.15, 0.3, 0), 2.0, 0.01);

  // Broken triangles: a photon that did not land, one that landed 3 m away (beyond
  // 8 spacings: another path) and one on a surface 0.3 m higher. Their neighbours
  // splat what their triangles do not carry; the flux of the landed photons stays.
  Lattice broken([](int i) { return 0.1 * i - 1.6; });
  broken.Position(10, 10)[3] = 0.0f;
  broken.Position(20, 20)[0] += 3.0f;
  broken.Position(25, 5)[1] += 0.3f;
  broken.Upload(floor);
  irradiance = floor.Deposit(splatter, broken.Grid);
  // Lost: the photon that did not land, and the one off the floor (no receiver on
  // its tangent plane); the one moved 3 m splats all of its flux.
  EXPECT_NEAR(
    FloorTarget::Flux(irradiance, 0) / (total - 2 * Lattice::PhotonFlux), 1.0, 0.01);
  EXPECT_NEAR(FloorTarget::At(irradiance, 0.7, -0.4, 0), 2.0, 0.01); // far from all three
  splatter->ReleaseGraphicsResources(f.Window);
}

namespace
{
// Photons of 0.005 W on a 0.05 m lattice of the floor (2 W/m^2), x from -0.975 to
// 5.975 and z from -4.975 to 4.975, kernels of 0.15 m, uploaded into `floor`.
caustics::PhotonGrid UploadEvenLattice(FloorTarget& floor)
{
  const int columns = 140, rows = 200;
  std::vector<float> positions, normals, fluxes, radii;
  for (int j = 0; j < rows; ++j)
  {
    for (int i = 0; i < columns; ++i)
    {
      const float position[4] = { 0.05f * i - 0.975f, 0.0f, 0.05f * j - 4.975f, 1.0f };
      const float normal[4] = { 0, 1, 0, 1 };
      const float flux[4] = { 0.005f, 0.005f, 0.005f, 0.0025f };
      positions.insert(positions.end(), position, position + 4);
      normals.insert(normals.end(), normal, normal + 4);
      fluxes.insert(fluxes.end(), flux, flux + 4);
      radii.push_back(0.15f);
    }
  }
  floor.Upload(columns, rows, positions, normals, fluxes, radii);
  caustics::PhotonGrid grid;
  grid.Width = columns;
  grid.Height = grid.BranchRows = rows;
  return grid;
}

// The mean irradiance (red) over pixel columns [x0, x1) and rows [y0, y1).
double MeanRed(vtkImageData* irradiance, int x0, int x1, int y0, int y1)
{
  double sum = 0.0;
  for (int y = y0; y < y1; ++y)
  {
    for (int x = x0; x < x1; ++x)
    {
      sum += Array(irradiance)->GetComponent(static_cast<vtkIdType>(y) * FloorTarget::Size + x, 0);
    }
  }
  return sum / ((x1 - x0) * (y1 - y0));
}
}

// Each pixel's kernels keep their flux where the receiver ends inside them and where
// the view's border cuts them (vtkCausticsPhotonSplatter, KeepFluxAtReceiverEnds and the
// guard band; docs/accuracy.md): photons of 0.005 W on a 0.05 m lattice (2 W/m^2),
// kernels of 0.15 m (4.8 pixels), up to the floor's end at x = 6, in a view of x from 2
// to 10 and z from -4 to 4 (the floor runs on past its top, bottom and left borders).
TEST(PhotonSplatter, KernelsKeepTheirFluxAtAReceiversEndAndAtTheViewsBorder)
{
  BallLens f;
  FloorTarget floor(f, 6.0);
  const caustics::PhotonGrid grid = UploadEvenLattice(floor);
  const int size = FloorTarget::Size;
  // Pixel column 127 is the floor's last (x 5.969 to 6.0); 128 on, nothing.
  vtkNew<vtkCausticsPhotonSplatter> splatter;
  auto kept = floor.Deposit(splatter, grid);
  const double inside = MeanRed(kept, 40, 100, 64, 192);
  std::cout << "inside " << inside << ", the floor's last columns "
            << MeanRed(kept, 124, 125, 64, 192) << " " << MeanRed(kept, 125, 126, 64, 192) << " "
            << MeanRed(kept, 126, 127, 64, 192) << " " << MeanRed(kept, 127, 128, 64, 192)
            << ", the view's top, bottom rows and left column " << MeanRed(kept, 40, 100, 0, 1)
            << " " << MeanRed(kept, 40, 100, size - 1, size) << " " << MeanRed(kept, 0, 1, 64, 192)
            << " W/m^2\n";
  EXPECT_NEAR(inside, 2.0, 0.02);
  EXPECT_NEAR(MeanRed(kept, 127, 128, 64, 192), 2.0, 0.1) << "the floor's last column";
  EXPECT_NEAR(MeanRed(kept, 124, 127, 64, 192), 2.0, 0.06) << "the three before it";
  EXPECT_EQ(MeanRed(kept, 128, size, 0, size), 0.0) << "no light past the floor's end";
  EXPECT_NEAR(MeanRed(kept, 40, 100, 0, 1), 2.0, 0.06) << "the view's top row";
  EXPECT_NEAR(MeanRed(kept, 40, 100, size - 1, size), 2.0, 0.06) << "the view's bottom row";
  EXPECT_NEAR(MeanRed(kept, 0, 1, 64, 192), 2.0, 0.06) << "the view's left column";
  // Without the share, the last column keeps about half (the disc's half past the
  // end holds no photons); the border rows keep theirs (the guard band).
  splatter->KeepFluxAtReceiverEndsOff();
  auto lost = floor.Deposit(splatter, grid);
  std::cout << "without the share, the floor's last column " << MeanRed(lost, 127, 128, 64, 192)
            << " W/m^2\n";
  EXPECT_LT(MeanRed(lost, 127, 128, 64, 192), 0.6 * 2.0);
  EXPECT_NEAR(MeanRed(lost, 40, 100, 0, 1), 2.0, 0.06);
  splatter->ReleaseGraphicsResources(f.Window);
}

// A receiver that ends just past the view's border: the view of x from -2.05 to 5.95
// (the floor ends at x = 6, 1.6 pixels past its right border), the lattice above.
// The image cannot show the end, the receivers' bounds can: with them the border
// columns keep their flux; without them (the image's rule alone: the floor is taken
// to go on) they lose the kernel's part past x = 6.
TEST(PhotonSplatter, KernelsKeepTheirFluxAtAnEndPastTheViewsBorder)
{
  BallLens f;
  FloorTarget floor(f, 1.95);
  const caustics::PhotonGrid grid = UploadEvenLattice(floor);
  const int size = FloorTarget::Size;
  vtkNew<vtkCausticsPhotonSplatter> splatter;
  const double bounds[6] = { -6, 6, 0, 0, -6, 6 }; // the ball lens's floor
  splatter->SetReceiverBounds(bounds);
  auto bounded = floor.Deposit(splatter, grid);
  splatter->SetReceiverBounds(nullptr);
  auto unbounded = floor.Deposit(splatter, grid);
  std::cout << "the view's last columns, with the receivers' bounds "
            << MeanRed(bounded, size - 4, size - 3, 64, 192) << " "
            << MeanRed(bounded, size - 3, size - 2, 64, 192) << " "
            << MeanRed(bounded, size - 2, size - 1, 64, 192) << " "
            << MeanRed(bounded, size - 1, size, 64, 192) << ", without "
            << MeanRed(unbounded, size - 4, size - 3, 64, 192) << " "
            << MeanRed(unbounded, size - 3, size - 2, 64, 192) << " "
            << MeanRed(unbounded, size - 2, size - 1, 64, 192) << " "
            << MeanRed(unbounded, size - 1, size, 64, 192) << " W/m^2\n";
  EXPECT_NEAR(MeanRed(bounded, 40, 100, 64, 192), 2.0, 0.02) << "inside";
  EXPECT_NEAR(MeanRed(bounded, size - 1, size, 64, 192), 2.0, 0.06) << "the view's last column";
  EXPECT_NEAR(MeanRed(bounded, size - 4, size - 1, 64, 192), 2.0, 0.06) << "the three before it";
  EXPECT_LT(MeanRed(unbounded, size - 1, size, 64, 192), 0.9 * 2.0) << "the image alone";
  EXPECT_NEAR(MeanRed(unbounded, 40, 100, 64, 192), 2.0, 0.02);
  splatter->ReleaseGraphicsResources(f.Window);
}
