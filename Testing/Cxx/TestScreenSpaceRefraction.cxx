// Screen-space refraction tracing (the base pass's camera-view stage, §4 of
// 000_54cf099eeccf42d9.txt, shared by every technique) against Snell's law: a checkerboard floor under a
// flat water surface (IOR 1.33, 1 m above it) seen obliquely. Every pixel that
// sees the water must show the tile that the analytically refracted viewing ray
// reaches; pixels whose ray lands near a tile edge are not judged. The same
// stage reflects the view in mirrors: a silver wall on the same floor.
#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsScreenSpaceRefraction.h"
#include "vtkCausticsTechniques.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <iostream>

namespace
{
const double Tile = 0.5;  // m
const double Depth = 1.0; // water surface height, m
const double LightAlbedo = 0.9;
const double DarkAlbedo = 0.2;

vtkSmartPointer<vtkActor> Receiver(vtkPolyData* polyData, double albedo)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(polyData);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(albedo, albedo, albedo);
  actor->GetProperty()->SetDiffuse(1.0);
  actor->GetProperty()->SetAmbient(0.0);
  actor->GetProperty()->SetSpecular(0.0);
  return actor;
}

/**
 * The floor point (x, z) that the viewing ray of pixel (i, j) reaches after
 * refracting into the flat water (Snell, normal +y, eta = 1 / 1.33), and where it
 * enters the water (x0, z0). False if it misses the water or the floor.
 */
bool RefractedFloorPoint(
  const caustics::SceneData& scene, int i, int j, double& x, double& z, double& x0, double& z0)
{
  caustics::Vec3 o, d;
  scene.View.PixelRay(i, j, o, d);
  const double s = (Depth - o[1]) / d[1];
  x0 = o[0] + s * d[0];
  z0 = o[2] + s * d[2];
  if (!(s > 0.0) || std::abs(x0) > 2.0 || std::abs(z0) > 2.0)
  {
    return false;
  }
  const double eta = 1.0 / 1.33, cosI = -d[1];
  const double cosT = std::sqrt(1.0 - eta * eta * (1.0 - cosI * cosI));
  const double r[3] = { eta * d[0], eta * d[1] + (eta * cosI - cosT), eta * d[2] };
  const double t = -Depth / r[1];
  x = x0 + t * r[0];
  z = z0 + t * r[2];
  return std::abs(x) < 2.0 && std::abs(z) < 2.0;
}

/** Is floor point (x, z) on a light tile? Sets `edge` when within `margin` of an edge. */
bool LightTile(double x, double z, double margin, bool& edge)
{
  const double u = (x + 2.0) / Tile, v = (z + 2.0) / Tile;
  const double fu = u - std::floor(u), fv = v - std::floor(v);
  edge = std::min(fu, 1.0 - fu) * Tile < margin || std::min(fv, 1.0 - fv) * Tile < margin;
  return (static_cast<int>(std::floor(u)) + static_cast<int>(std::floor(v))) % 2 == 0;
}

/**
 * Whether pixel (i, j), whose viewing ray `floorPoint` maps to the floor, must show a
 * light tile. The lookup is quantized to the pixel where the ray crosses the floor:
 * pixels whose floor point lies within one pixel footprint (the distance to the
 * neighbours' floor points) of a tile edge, or whose neighbours miss, are not judged
 * (false).
 */
bool JudgeTile(const std::function<bool(int, int, double&, double&)>& floorPoint, int i, int j,
  double x, double z, bool& expected)
{
  double xi, zi, xj, zj;
  if (!floorPoint(i + 1, j, xi, zi) || !floorPoint(i, j + 1, xj, zj))
  {
    return false;
  }
  const double footprint = std::max(std::hypot(xi - x, zi - z), std::hypot(xj - x, zj - z));
  bool edge = false;
  expected = LightTile(x, z, footprint, edge);
  return !edge;
}
}

// Glass and water look the same in every technique: the stage belongs to the
// base pass, so each registered surface technique must pass.
class ScreenSpaceRefraction : public testing::TestWithParam<std::string>
{
};

INSTANTIATE_TEST_SUITE_P(EveryTechnique, ScreenSpaceRefraction,
  testing::Values("screen-space", "caustic-maps"),
  [](const testing::TestParamInfo<std::string>& info)
  { return info.param == "screen-space" ? std::string("ScreenSpace") : std::string("CausticMaps"); });

namespace
{
/** The 4 m checkerboard floor (light and dark tiles of Tile m) under a vertical sun. */
void AddCheckerboardUnderSun(vtkRenderer* renderer)
{
  renderer->AutomaticLightCreationOff();
  vtkNew<vtkAppendPolyData> light, dark;
  for (int j = 0; j < 8; ++j)
  {
    for (int i = 0; i < 8; ++i)
    {
      vtkNew<vtkPlaneSource> tile;
      const double x0 = -2.0 + Tile * i, z0 = -2.0 + Tile * j;
      tile->SetOrigin(x0, 0.0, z0 + Tile);
      tile->SetPoint1(x0 + Tile, 0.0, z0 + Tile);
      tile->SetPoint2(x0, 0.0, z0);
      tile->Update();
      ((i + j) % 2 ? dark : light)->AddInputData(tile->GetOutput());
    }
  }
  light->Update();
  dark->Update();
  renderer->AddActor(Receiver(light->GetOutput(), LightAlbedo));
  renderer->AddActor(Receiver(dark->GetOutput(), DarkAlbedo));
  vtkNew<vtkLight> sun;
  sun->SetLightTypeToSceneLight();
  sun->SetPositional(false);
  sun->SetPosition(0.0, 1.0, 0.0);
  sun->SetFocalPoint(0.0, 0.0, 0.0);
  sun->SetIntensity(1.0);
  renderer->AddLight(sun);
}

/** The checkerboard under its sun, rendered by one technique at 256 x 256 pixels. */
struct CheckerboardFrame
{
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkSmartPointer<vtkCausticsRenderPass> Pass;

  explicit CheckerboardFrame(const std::string& technique)
  {
    AddCheckerboardUnderSun(this->Renderer);
    this->Pass = vtkCausticsTechniques::Create(technique);
    this->Renderer->SetPass(this->Pass);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(256, 256);
    this->Window->AddRenderer(this->Renderer);
  }
  ~CheckerboardFrame()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }
  CheckerboardFrame(const CheckerboardFrame&) = delete;
  CheckerboardFrame& operator=(const CheckerboardFrame&) = delete;

  /** Renders from `position` towards `focal`; the technique's colours, null if none. */
  vtkDataArray* Render(const double position[3], const double focal[3], double viewAngle)
  {
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetPosition(position[0], position[1], position[2]);
    camera->SetFocalPoint(focal[0], focal[1], focal[2]);
    camera->SetViewAngle(viewAngle);
    this->Renderer->ResetCameraClippingRange();
    this->Window->Render();
    return this->Pass->ReadBuffer("TechniqueColor", this->Color)
      ? this->Color->GetPointData()->GetArray(0)
      : nullptr;
  }
  const caustics::SceneData& Scene() { return this->Pass->GetSceneExtractor()->GetScene(); }

  vtkNew<vtkImageData> Color;
};
}

TEST_P(ScreenSpaceRefraction, FlatWaterObeysSnell)
{
  CheckerboardFrame f(GetParam());
  vtkNew<vtkPlaneSource> water;
  water->SetOrigin(-2.0, Depth, 2.0);
  water->SetPoint1(2.0, Depth, 2.0);
  water->SetPoint2(-2.0, Depth, -2.0);
  water->SetResolution(16, 16);
  water->Update();
  vtkNew<vtkPolyDataMapper> waterMapper;
  waterMapper->SetInputData(water->GetOutput());
  vtkNew<vtkActor> waterActor;
  waterActor->SetMapper(waterMapper);
  vtkCausticsMaterial::MakeGlass(waterActor->GetProperty(), 1.33);
  f.Renderer->AddActor(waterActor);
  const double eye[3] = { 0.0, 4.0, 4.0 }, focal[3] = { 0.0, 0.0, 0.0 };
  vtkDataArray* rgba = f.Render(eye, focal, 40.0);
  ASSERT_TRUE(f.Pass->GetLastFrameHadCaustics());
  ASSERT_NE(rgba, nullptr);
  const caustics::SceneData& scene = f.Scene();

  // Under flat water the floor gets the sun through one interface: E T(0) with
  // T(0) = 1 - ((1.33 - 1) / 2.33)^2, no direct light (the water shadows it). A
  // light tile shows 0.9 x 0.98 = 0.88, a dark one 0.2 x 0.98 = 0.20 (VTK's
  // display units, x the Fresnel transmittance towards the camera, > 0.9 here):
  // 0.5 separates them with a margin for the reflected background (< 4% x 0.05).
  int judged = 0, wrong = 0, wrongIfStraight = 0, replaced = 0;
  for (int j = 0; j < 256; ++j)
  {
    for (int i = 0; i < 256; ++i)
    {
      const vtkIdType id = static_cast<vtkIdType>(j) * 256 + i;
      if (rgba->GetComponent(id, 3) < 1.0)
      {
        continue;
      }
      ++replaced;
      double x, z, x0, z0;
      if (!RefractedFloorPoint(scene, i, j, x, z, x0, z0))
      {
        continue; // the ray misses the water or lands off the floor
      }
      bool expected = false;
      if (!JudgeTile(
            [&scene](int a, int b, double& u, double& v)
            {
              double u0, v0;
              return RefractedFloorPoint(scene, a, b, u, v, u0, v0);
            },
            i, j, x, z, expected))
      {
        continue;
      }
      // Where the camera ray would land without the water.
      caustics::Vec3 o, d;
      scene.View.PixelRay(i, j, o, d);
      bool straightEdge = false;
      const bool straight =
        LightTile(o[0] - o[1] / d[1] * d[0], o[2] - o[1] / d[1] * d[2], 0.0, straightEdge);
      ++judged;
      const bool seen = rgba->GetComponent(id, 0) > 0.5;
      wrong += seen != expected ? 1 : 0;
      wrongIfStraight += straight != expected ? 1 : 0;
    }
  }
  std::cout << GetParam() << ", refraction: " << replaced << " pixels replaced, " << judged << " judged, " << wrong
            << " show the wrong tile (" << 100.0 * wrong / std::max(judged, 1)
            << " %); without refraction " << wrongIfStraight << "\n";
  ASSERT_GT(judged, 10000);
  // The test can tell: ignoring refraction would get this many wrong.
  EXPECT_GT(wrongIfStraight, judged / 5);
  // Measured: 0 of 33450 (the crossing is refined on the floor's tangent plane).
  // Allow 0.1% for rasterization differences at the pool's rim.
  EXPECT_LE(wrong, judged / 1000);
}

namespace
{
const double MirrorZ = -1.0; // the mirror wall's plane, facing +z
const double MirrorHeight = 2.0;

/**
 * The floor point (x, z) that the viewing ray of pixel (i, j) reaches after the
 * mirror wall (the plane z = MirrorZ, |x| < 2, 0 < y < MirrorHeight) reflects it,
 * and the cosine at the mirror. False if it misses the mirror or the floor.
 */
bool ReflectedFloorPoint(
  const caustics::SceneData& scene, int i, int j, double& x, double& z, double& cosine)
{
  caustics::Vec3 o, d;
  scene.View.PixelRay(i, j, o, d);
  const double s = (MirrorZ - o[2]) / d[2];
  const double hit[3] = { o[0] + s * d[0], o[1] + s * d[1], MirrorZ };
  if (!(s > 0.0) || std::abs(hit[0]) > 2.0 || hit[1] < 0.0 || hit[1] > MirrorHeight)
  {
    return false;
  }
  cosine = std::abs(d[2]);
  // Reflected: z flips. Down to the floor.
  const double t = -hit[1] / d[1];
  x = hit[0] + t * d[0];
  z = hit[2] - t * d[2];
  return d[1] < 0.0 && std::abs(x) < 2.0 && z > MirrorZ && z < 2.0;
}
}

// A mirror shows the scene it reflects (VTK draws a metal without an environment
// as a dark surface): a silver wall standing on the checkerboard, seen obliquely.
// Every pixel that sees the mirror must show the tile that the analytically
// reflected viewing ray reaches, dimmed by silver's reflectance (above 0.9 here).
TEST_P(ScreenSpaceRefraction, FlatMirrorReflectsTheFloor)
{
  CheckerboardFrame f(GetParam());
  vtkNew<vtkPlaneSource> wall;
  wall->SetOrigin(-2.0, 0.0, MirrorZ);
  wall->SetPoint1(2.0, 0.0, MirrorZ);
  wall->SetPoint2(-2.0, MirrorHeight, MirrorZ);
  wall->SetResolution(8, 4);
  wall->Update();
  vtkNew<vtkPolyDataMapper> wallMapper;
  wallMapper->SetInputData(wall->GetOutput());
  vtkNew<vtkActor> mirror;
  mirror->SetMapper(wallMapper);
  const double silverN[3] = { 0.155, 0.117, 0.138 }, silverK[3] = { 4.83, 3.12, 2.15 };
  vtkCausticsMaterial::MakeMirror(mirror->GetProperty(), silverN, silverK);
  f.Renderer->AddActor(mirror);
  const double eye[3] = { 0.7, 2.5, 4.0 }, focal[3] = { 0.0, 0.6, MirrorZ };
  vtkDataArray* rgba = f.Render(eye, focal, 45.0);
  ASSERT_NE(rgba, nullptr);
  const caustics::SceneData& scene = f.Scene();

  int mirrorPixels = 0, judged = 0, wrong = 0, replaced = 0;
  double lowestLight = 1e300;
  for (int j = 0; j < 256; ++j)
  {
    for (int i = 0; i < 256; ++i)
    {
      const vtkIdType id = static_cast<vtkIdType>(j) * 256 + i;
      double x, z, cosine;
      if (!ReflectedFloorPoint(scene, i, j, x, z, cosine))
      {
        continue;
      }
      ++mirrorPixels;
      if (rgba->GetComponent(id, 3) < 1.0)
      {
        continue;
      }
      ++replaced;
      // The reflected floor point must be in the image, where the march finds it.
      double px, py;
      if (!scene.View.WorldToPixel({ { x, 0.0, z } }, px, py) || px < 1.0 || py < 1.0 ||
        px > 255.0 || py > 255.0)
      {
        continue;
      }
      bool expected = false;
      if (!JudgeTile(
            [&scene](int a, int b, double& u, double& v)
            {
              double unused;
              return ReflectedFloorPoint(scene, a, b, u, v, unused);
            },
            i, j, x, z, expected))
      {
        continue;
      }
      ++judged;
      const double seen = rgba->GetComponent(id, 0);
      wrong += (seen > 0.5) != expected ? 1 : 0;
      if (expected)
      {
        lowestLight = std::min(lowestLight, seen);
      }
    }
  }
  std::cout << GetParam() << ", mirror: " << mirrorPixels << " pixels see it, " << replaced
            << " replaced, " << judged << " judged, " << wrong << " show the wrong tile; light tiles at least "
            << lowestLight << "\n";
  ASSERT_GT(judged, 4000); // measured 4503 (the rest: reflected floor out of the image, tile edges)
  // Every pixel that sees the mirror gets the traced colour (none is left to VTK).
  EXPECT_GE(replaced, mirrorPixels * 99 / 100);
  // Measured: 0 wrong. Allow 0.1 % for rasterization at the wall's edges.
  EXPECT_LE(wrong, judged / 1000);
  // A light tile (0.9) through silver (reflectance above 0.9 from 0 to 80 degrees);
  // measured 0.877.
  EXPECT_GT(lowestLight, 0.8);
}

TEST(ScreenSpaceRefractionRectangle, CoversTheProjectedBoxAndNoMore)
{
  // A perspective camera at the origin looking down -z (fovy 90 degrees, near 1, far
  // 100), column-major: x_ndc = x / -z, y_ndc = y / -z.
  const float n = 1.0f, f = 100.0f;
  const float m[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -(f + n) / (f - n), -1, 0, 0,
    -2.0f * f * n / (f - n), 0 };
  int rect[4];
  // x in [-1, 1], y in [0, 1] at depth 2 to 4: the widest at depth 2, x_ndc in
  // [-0.5, 0.5], y_ndc in [0, 0.5]: pixels [50, 150) x [100, 150) of 200 x 200, plus
  // a pixel of margin each side.
  const double box[6] = { -1, 1, 0, 1, -4, -2 };
  vtkCausticsScreenSpaceRefraction::ScreenRectangle(m, box, 200, 200, rect);
  EXPECT_EQ(rect[0], 49);
  EXPECT_EQ(rect[1], 99);
  EXPECT_EQ(rect[2], 102);
  EXPECT_EQ(rect[3], 52);
  // Clamped to the image.
  const double wide[6] = { -10, 10, -10, 10, -4, -2 };
  vtkCausticsScreenSpaceRefraction::ScreenRectangle(m, wide, 200, 100, rect);
  EXPECT_EQ(rect[0], 0);
  EXPECT_EQ(rect[1], 0);
  EXPECT_EQ(rect[2], 200);
  EXPECT_EQ(rect[3], 100);
  // A corner behind the eye: its projection is unbounded, so the whole image.
  const double behind[6] = { -1, 1, -1, 1, -2, 2 };
  vtkCausticsScreenSpaceRefraction::ScreenRectangle(m, behind, 200, 100, rect);
  EXPECT_EQ(rect[2], 200);
  EXPECT_EQ(rect[3], 100);
  // Beside the view, empty or NaN: no pixel.
  const double beside[6] = { 10, 11, 0, 1, -4, -2 };
  vtkCausticsScreenSpaceRefraction::ScreenRectangle(m, beside, 200, 200, rect);
  EXPECT_EQ(rect[2], 0);
  const double empty[6] = { 1, -1, 0, 1, -4, -2 };
  vtkCausticsScreenSpaceRefraction::ScreenRectangle(m, empty, 200, 200, rect);
  EXPECT_EQ(rect[2] * rect[3], 0);
  const double nan[6] = { std::nan(""), 1, 0, 1, -4, -2 };
  vtkCausticsScreenSpaceRefraction::ScreenRectangle(m, nan, 200, 200, rect);
  EXPECT_EQ(rect[2] * rect[3], 0);
}
