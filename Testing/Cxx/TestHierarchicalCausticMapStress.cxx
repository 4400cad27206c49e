// Numerical stress for the hierarchical caustic map pass: grazing light, an object
// where every photon is totally reflected inside, indices of refraction 1 and 4,
// no photons, an empty scene, degenerate and NaN triangles, scenes scaled by 1e-3
// and 1e4, a light inside the glass, and lights that see no specular actor. Each
// frame must finish with finite numbers, a consistent flux balance, and (where
// physics says so) the right irradiance.
#include "TestHierarchicalCausticMapUtilities.h"

#include "vtkCausticsMaterial.h"
#include "vtkCausticsPhotonBuffer.h"
#include "vtkCausticsSceneData.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkCommand.h"
#include "vtkTestErrorObserver.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

using hcmtest::Array;
using hcmtest::Frame;

namespace
{
/** Checks a frame's caustic buffers and counters; returns light 0's counters. */
vtkCausticsHierarchicalCausticMapPass::Counters CheckFrame(Frame& f, const char* what)
{
  vtkCausticsHierarchicalCausticMapPass::Counters c;
  EXPECT_TRUE(f.Pass->GetLastFrameHadCaustics()) << what;
  auto caustic = f.Buffer("CausticIrradiance");
  EXPECT_NE(caustic, nullptr) << what;
  if (caustic)
  {
    EXPECT_EQ(hcmtest::NonFinite(Array(caustic)), 0) << what;
  }
  for (int level = 0; level < 4 && f.Pass->GetLightTraced(0); ++level)
  {
    vtkNew<vtkImageData> map;
    if (f.Pass->ReadCausticMap(0, level, map))
    {
      EXPECT_EQ(hcmtest::NonFinite(Array(map)), 0) << what << " level " << level;
    }
  }
  if (f.Pass->GetLightTraced(0) && f.Pass->GetCounters(0, c))
  {
    EXPECT_EQ(c.Photons, c.Hits + c.LostInside + c.Escaped + c.Stored) << what;
    EXPECT_EQ(c.Valid, c.Hits) << what;
    const double balance = c.FluxHits + c.FluxLostInside + c.FluxEscaped + c.FluxStored +
      c.FluxInternalReflection + c.FluxAbsorbed;
    // Fixed-point flux sums round each term to 2^-20 of the largest texel flux: a
    // photon with 1 % of it errs by 5e-5 per term (PhotonBuffer.AccountsForEveryWatt).
    EXPECT_NEAR(balance, c.FluxIn, 1e-4 * c.FluxIn + 1e-30) << what;
    EXPECT_TRUE(std::isfinite(c.FluxIn)) << what;
  }
  return c;
}

vtkActor* FindActor(vtkRenderer* renderer, const std::string& name)
{
  vtkActorCollection* actors = renderer->GetActors();
  actors->InitTraversal();
  while (vtkActor* actor = actors->GetNextActor())
  {
    if (vtkCausticsMaterial::GetName(actor) == name)
    {
      return actor;
    }
  }
  return nullptr;
}

void ReplaceLight(vtkRenderer* renderer, vtkLight* light)
{
  renderer->RemoveAllLights();
  renderer->AddLight(light);
}

vtkSmartPointer<vtkLight> Directional(double x, double y, double z)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetPosition(-x, -y, -z);
  light->SetFocalPoint(0, 0, 0);
  light->SetIntensity(1.0);
  return light;
}

/** A flat-shaded glass mesh from faces (each a polygon of points sharing a normal). */
vtkSmartPointer<vtkActor> Glass(
  const std::vector<std::vector<std::array<double, 3>>>& faces, double ior)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  normals->SetName("Normals");
  vtkNew<vtkCellArray> triangles;
  for (const auto& face : faces)
  {
    double a[3], b[3], n[3];
    for (int i = 0; i < 3; ++i)
    {
      a[i] = face[1][i] - face[0][i];
      b[i] = face[2][i] - face[0][i];
    }
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const vtkIdType first = points->GetNumberOfPoints();
    for (const auto& p : face)
    {
      points->InsertNextPoint(p.data());
      normals->InsertNextTuple3(n[0] / length, n[1] / length, n[2] / length);
    }
    for (std::size_t k = 1; k + 1 < face.size(); ++k)
    {
      const vtkIdType triangle[3] = { first, first + static_cast<vtkIdType>(k),
        first + static_cast<vtkIdType>(k) + 1 };
      triangles->InsertNextCell(3, triangle);
    }
  }
  vtkNew<vtkPolyData> polyData;
  polyData->SetPoints(points);
  polyData->SetPolys(triangles);
  polyData->GetPointData()->SetNormals(normals);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(polyData);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  vtkCausticsMaterial::MakeGlass(actor->GetProperty(), ior);
  vtkCausticsMaterial::SetName(actor, "glass");
  return actor;
}
}

TEST(Stress, GrazingLight)
{
  // 89.9 degrees from the vertical: the floor is seen edge-on from the light.
  Frame f("ball-lens", 256);
  const double angle = 89.9 * M_PI / 180.0;
  ReplaceLight(f.Renderer, Directional(std::sin(angle), -std::cos(angle), 0.0));
  f.Render();
  const auto c = CheckFrame(f, "grazing light");
  EXPECT_GT(c.Photons, 0);
}

TEST(Stress, GrazingLightTurnsTheMap)
{
  // A sun exactly parallel to the floor: the light's own view sees the floor
  // edge-on, and a caustic map there drew nothing. The map's view turns about the
  // floor point the light meets until it sees the floor at MinimumMapIncidence;
  // the caustic lands (its accuracy: CausticMapReference.GrazingSun).
  Frame f("ball-lens", 128);
  ReplaceLight(f.Renderer, Directional(1.0, 0.0, 0.0));
  vtkNew<vtkTest::ErrorObserver> warnings;
  f.Pass->GlobalWarningDisplayOn();
  f.Pass->AddObserver(vtkCommand::WarningEvent, warnings);
  const double floorUp[3] = { 0.0, 1.0, 0.0 };
  for (double minimum : { 45.0, 20.0, 0.0 })
  {
    f.Pass->SetMinimumMapIncidence(minimum);
    f.Render();
    const auto c = CheckFrame(f, "light parallel to the floor");
    EXPECT_NEAR(f.Pass->GetReceiverIncidence(0), 0.0, 1e-6);
    const caustics::LightView* view = f.Pass->GetMapView(0);
    ASSERT_NE(view, nullptr);
    // The map looks down at the floor at the minimum angle (0: along the sun).
    EXPECT_NEAR(-vtkMath::Dot(view->axis.data(), floorUp), std::sin(vtkMath::RadiansFromDegrees(minimum)), 1e-9)
      << minimum;
    if (minimum > 0.0)
    {
      // Most of the rest leaves over the floor's far edge or up to the sky.
      EXPECT_GT(c.FluxHits, 0.1 * c.FluxIn) << minimum; // measured 13 %
    }
    else
    {
      EXPECT_LT(c.FluxHits, 0.01 * c.FluxIn); // the paper's view: nothing lands
    }
  }
  EXPECT_FALSE(warnings->GetWarning()) << warnings->GetWarningMessage();
  // 60 degrees above the floor, more than the minimum: the sun's own view.
  f.Pass->SetMinimumMapIncidence(45.0);
  const double e = vtkMath::RadiansFromDegrees(60.0);
  ReplaceLight(f.Renderer, Directional(std::cos(e), -std::sin(e), 0.0));
  f.Render();
  EXPECT_NEAR(f.Pass->GetReceiverIncidence(0), 60.0, 1e-6);
  EXPECT_NEAR(-vtkMath::Dot(f.Pass->GetMapView(0)->axis.data(), floorUp), std::sin(e), 1e-9);
}

TEST(Stress, TotalInternalReflectionOnly)
{
  // A Porro prism: light enters the top face head-on, is totally reflected by
  // both 45-degree faces (45 > 41.8 degrees, the critical angle of glass) and
  // leaves through the top, back up to the sky: nothing may land below it.
  Frame f("ball-lens", 256);
  f.Renderer->RemoveActor(FindActor(f.Renderer, "glass ball"));
  const double h = 2.0, s = 0.5; // the right-angle edge at height h, top face at h + s
  f.Renderer->AddActor(
    Glass({ { { -s, h + s, s }, { s, h + s, s }, { s, h + s, -s }, { -s, h + s, -s } },
            { { -s, h + s, -s }, { 0, h, -s }, { 0, h, s }, { -s, h + s, s } },
            { { s, h + s, s }, { 0, h, s }, { 0, h, -s }, { s, h + s, -s } },
            { { -s, h + s, s }, { 0, h, s }, { s, h + s, s } },
            { { s, h + s, -s }, { 0, h, -s }, { -s, h + s, -s } } },
      1.5));
  f.Render();
  const auto c = CheckFrame(f, "total internal reflection");
  EXPECT_GT(c.Photons, 0);
  // The refracted branch (96 % of the flux) leaves upwards; only the faint
  // Fresnel parts at the top face's exit can come down, never more than 10 %.
  EXPECT_LT(c.FluxHits, 0.1 * c.FluxIn);
}

TEST(Stress, IndicesOneAndFour)
{
  for (double ior : { 1.0, 4.0 })
  {
    Frame f(nullptr, 256);
    f.Scene->SetRefractiveIndex(ior);
    ASSERT_TRUE(f.Scene->Populate(f.Renderer));
    f.Render();
    const auto c = CheckFrame(f, ior == 1.0 ? "IOR 1" : "IOR 4");
    EXPECT_GT(c.Hits, 0);
    if (ior == 1.0)
    {
      // Nothing is reflected: every watt lands (or is lost at the rim).
      EXPECT_NEAR(c.FluxHits / c.FluxIn, 1.0, 0.01);
    }
  }
}

TEST(Stress, NoPhotons)
{
  {
    // One texel of photon buffer.
    Frame f("ball-lens", 1);
    f.Render();
    CheckFrame(f, "one texel");
  }
  {
    // A light without power: no photon stage at all, and no caustics.
    Frame f("ball-lens", 64);
    vtkNew<vtkLight> dark;
    dark->DeepCopy(Directional(0, -1, 0));
    dark->SetIntensity(0.0);
    ReplaceLight(f.Renderer, dark);
    f.Render();
    EXPECT_FALSE(f.Pass->GetLastFrameHadCaustics());
    EXPECT_FALSE(f.Pass->GetLightTraced(0));
  }
}

TEST(Stress, EmptyScene)
{
  Frame f(nullptr, 64);
  f.Renderer->AddLight(Directional(0, -1, 0));
  f.Render();
  EXPECT_FALSE(f.Pass->GetLastFrameHadCaustics());
  EXPECT_EQ(f.Pass->GetNumberOfLights(), 0);
}

TEST(Stress, DegenerateAndNaNTriangles)
{
  Frame f("ball-lens", 256);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // A glass "mesh" of a NaN triangle, a zero-area triangle and a needle.
  f.Renderer->AddActor(Glass({ { { nan, 1.0, 0.0 }, { 1.0, 1.0, 0.0 }, { 0.0, 1.0, 1.0 } },
                               { { 2.0, 1.0, 2.0 }, { 2.0, 1.0, 2.0 }, { 2.0, 1.0, 2.0 } },
                               { { -2.0, 1.0, 2.0 }, { -1.0, 1.0, 2.0 }, { 0.0, 1.0, 2.0 } } },
    1.5));
  f.Render();
  const auto c = CheckFrame(f, "degenerate triangles");
  EXPECT_GT(c.Hits, 0); // the ball still makes its caustic
}

TEST(Stress, ExtremeScales)
{
  // A directional light's caustic irradiance does not depend on the scene's size:
  // the ball lens scaled by 1e-3 and 1e4 (geometry and camera) gives the picture
  // of scale 1.
  vtkSmartPointer<vtkImageData> reference;
  for (double scale : { 1.0, 1e-3, 1e4 })
  {
    Frame f("ball-lens", 256);
    vtkActorCollection* actors = f.Renderer->GetActors();
    actors->InitTraversal();
    while (vtkActor* actor = actors->GetNextActor())
    {
      actor->SetScale(scale);
    }
    vtkCamera* camera = f.Renderer->GetActiveCamera();
    double position[3], focal[3];
    camera->GetPosition(position);
    camera->GetFocalPoint(focal);
    camera->SetPosition(scale * position[0], scale * position[1], scale * position[2]);
    camera->SetFocalPoint(scale * focal[0], scale * focal[1], scale * focal[2]);
    f.Renderer->ResetCameraClippingRange();
    f.Render();
    CheckFrame(f, scale == 1.0 ? "scale 1" : (scale < 1.0 ? "scale 1e-3" : "scale 1e4"));
    auto caustic = f.Buffer("CausticIrradiance");
    ASSERT_NE(caustic, nullptr);
    if (scale == 1.0)
    {
      reference = caustic;
      continue;
    }
    // Every tolerance of the stages is relative to texel sizes or the scene's
    // size; what remains is float rounding of positions (1e-7 relative) moving
    // pixels at silhouettes and kernel edges: 1 %.
    EXPECT_LT(hcmtest::RelativeL2(Array(caustic), Array(reference)), 0.01) << scale;
  }
}

TEST(Stress, LightInsideTheGlass)
{
  // A point light at the ball's centre: the light buffers cover a 150-degree cone
  // from there (vtkCausticsLightBuffers warns); the frame must stay finite.
  auto pointLight = [](double y)
  {
    auto light = vtkSmartPointer<vtkLight>::New();
    light->SetLightTypeToSceneLight();
    light->SetPositional(true);
    light->SetConeAngle(180.0);
    light->SetPosition(0.0, y, 0.0);
    light->SetFocalPoint(0.0, 0.0, 0.0);
    light->SetAttenuationValues(0.0, 0.0, 1.0);
    light->SetIntensity(1.0);
    return light;
  };
  {
    Frame f("ball-lens", 256);
    ReplaceLight(f.Renderer, pointLight(3.0));
    f.Render();
    CheckFrame(f, "light at the centre");
  }
  // 0.1 m above the centre, in a ball of index 1 (the photons start inside and
  // leave it unbent): the floor gets the point light's own irradiance,
  // I cos(theta) / d^2, which checks the units of point lights end to end.
  Frame f(nullptr, 512);
  f.Scene->SetRefractiveIndex(1.0);
  ASSERT_TRUE(f.Scene->Populate(f.Renderer));
  const double height = 3.1;
  ReplaceLight(f.Renderer, pointLight(height));
  f.Render();
  const auto c = CheckFrame(f, "light inside");
  EXPECT_GT(c.Hits, 0);
  auto caustic = f.Buffer("CausticIrradiance");
  auto position = f.Buffer("Position");
  ASSERT_TRUE(caustic && position);
  double sum = 0.0;
  int count = 0;
  for (vtkIdType i = 0; i < caustic->GetNumberOfPoints(); ++i)
  {
    const double x = Array(position)->GetComponent(i, 0);
    const double z = Array(position)->GetComponent(i, 2);
    if (Array(position)->GetComponent(i, 3) >= 0.0 && std::hypot(x, z) < 1.0 &&
      std::abs(Array(position)->GetComponent(i, 1)) < 1e-3)
    {
      const double d2 = x * x + height * height + z * z;
      sum += Array(caustic)->GetComponent(i, 0) / (height / (d2 * std::sqrt(d2)));
      ++count;
    }
  }
  ASSERT_GT(count, 100);
  // Kernel ripple of a regular photon grid (8 % peak to peak with SplatScale 2),
  // averaged over the patch: 2 %.
  EXPECT_NEAR(sum / count, 1.0, 0.02);
}

TEST(Stress, LightsThatSeeNoSpecularActor)
{
  // A spot light aimed away from the ball runs no photon stage.
  Frame f("ball-lens", 128);
  vtkNew<vtkLight> away;
  away->SetLightTypeToSceneLight();
  away->SetPositional(true);
  away->SetPosition(4.0, 1.0, 0.0);
  away->SetFocalPoint(8.0, 0.0, 0.0);
  away->SetConeAngle(20.0);
  away->SetIntensity(5.0);
  ReplaceLight(f.Renderer, away);
  f.Render();
  EXPECT_FALSE(f.Pass->GetLastFrameHadCaustics());
  // Beside a light that does see the ball: only that one is traced, and the
  // picture is that light's alone.
  f.Renderer->AddLight(Directional(0, -1, 0));
  f.Render();
  ASSERT_EQ(f.Pass->GetNumberOfLights(), 2);
  EXPECT_FALSE(f.Pass->GetLightTraced(0));
  EXPECT_TRUE(f.Pass->GetLightTraced(1));
  auto both = f.Buffer("CausticIrradiance");
  away->SwitchOff();
  f.Render();
  auto alone = f.Buffer("CausticIrradiance");
  ASSERT_TRUE(both && alone);
  EXPECT_LT(hcmtest::RelativeL2(Array(both), Array(alone)), 1e-6);
}
