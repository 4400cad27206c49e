// Screen-space photon tracing in an interactive setting: animated geometry (the
// pool's waves), window resizing, camera motion, several lights, per-stage timers,
// GL objects made once and really released, parameters and PrintSelf.
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsLayeredDepth.h"
#include "vtkCausticsScreenSpaceLineTracer.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
#include "vtkCausticsTimings.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <sstream>
#include <string>

namespace
{
struct Frame
{
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkCausticsScreenSpacePhotonPass> Pass;
  vtkNew<vtkCausticsBuiltinScene> Scene;

  explicit Frame(const char* scene, int size = 128)
  {
    this->Scene->SetSceneName(scene);
    EXPECT_TRUE(this->Scene->Populate(this->Renderer)) << this->Scene->GetLastError();
    this->Renderer->SetPass(this->Pass);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(size, size);
    this->Window->AddRenderer(this->Renderer);
  }
  ~Frame()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }
  /** Renders and returns a copy of the caustic irradiance. */
  vtkSmartPointer<vtkImageData> Caustic()
  {
    this->Window->Render();
    EXPECT_TRUE(this->Pass->GetLastFrameHadCaustics());
    auto image = vtkSmartPointer<vtkImageData>::New();
    EXPECT_TRUE(this->Pass->ReadBuffer("CausticIrradiance", image));
    return image;
  }
};

/** Relative L2 difference of two images' first arrays (all components). */
double Difference(vtkImageData* a, vtkImageData* b)
{
  vtkDataArray* x = a->GetPointData()->GetArray(0);
  vtkDataArray* y = b->GetPointData()->GetArray(0);
  double d = 0.0, n = 0.0;
  for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      d += std::pow(x->GetComponent(i, c) - y->GetComponent(i, c), 2);
      n += std::pow(y->GetComponent(i, c), 2);
    }
  }
  return n > 0.0 ? std::sqrt(d / n) : (d > 0.0 ? 1.0 : 0.0);
}
}

// The waves move: the caustic follows, and equals what a new pass makes of the
// same instant (nothing stale from the previous frame: geometry, layers, maps).
TEST(ScreenSpaceDynamic, FollowsAnimatedGeometry)
{
  Frame animated("pool");
  auto first = animated.Caustic();
  animated.Scene->UpdateTime(0.7);
  auto moved = animated.Caustic();
  const double change = Difference(moved, first);
  Frame fresh("pool");
  fresh.Scene->UpdateTime(0.7);
  const double agreement = Difference(moved, fresh.Caustic());
  std::cout << "pool caustic: changed by " << change
            << " after 0.7 s, differs from a fresh pass by " << agreement << "\n";
  EXPECT_GT(change, 0.3) << "the caustic did not follow the waves";
  // Reached: 0. The same GPU work, at most in another order of atomic appends
  // (float rounding of the splat sums, ~1e-7): 1e-4 leaves room for other GPUs.
  EXPECT_LT(agreement, 1e-4);
}

TEST(ScreenSpaceDynamic, FollowsResizeAndCamera)
{
  Frame f("ball-lens", 128);
  f.Caustic();
  const unsigned int position = f.Pass->GetLayeredDepth()->GetPositionTexture();
  const unsigned int hits = f.Pass->GetLineTracer()->GetHitBuffer();
  // Later frames reuse every GL object (no per-frame allocation).
  f.Caustic();
  EXPECT_EQ(f.Pass->GetLayeredDepth()->GetPositionTexture(), position);
  EXPECT_EQ(f.Pass->GetLineTracer()->GetHitBuffer(), hits);
  // A new size: buffers follow.
  f.Window->SetSize(160, 96);
  auto resized = f.Caustic();
  int dims[3];
  resized->GetDimensions(dims);
  EXPECT_EQ(dims[0], 160);
  EXPECT_EQ(dims[1], 96);
  EXPECT_EQ(f.Pass->GetLayeredDepth()->GetWidth(), 160);
  EXPECT_EQ(f.Pass->GetLayeredDepth()->GetHeight(), 96);
  // The camera moves above the ball, looking down: now view rays through the ball
  // reach the floor under it (depth complexity 3, where it was 2), and the caustic
  // is still there.
  f.Window->SetSize(128, 128);
  f.Renderer->GetActiveCamera()->SetPosition(0.0, 9.0, 0.5);
  f.Renderer->GetActiveCamera()->SetFocalPoint(0.0, 0.0, 0.0);
  f.Renderer->GetActiveCamera()->SetViewUp(0.0, 0.0, -1.0);
  f.Renderer->ResetCameraClippingRange();
  auto side = f.Caustic();
  EXPECT_EQ(f.Pass->GetLayeredDepth()->ReadDepthComplexity(), 3);
  double total = 0.0;
  vtkDataArray* e = side->GetPointData()->GetArray(0);
  for (vtkIdType i = 0; i < e->GetNumberOfTuples(); ++i)
  {
    total += e->GetComponent(i, 0);
  }
  EXPECT_GT(total, 0.0);
}

// Light adds up: the caustic of two lights is the sum of each one's. A light is
// turned "off" with a negligible intensity rather than 0, which the scene snapshot
// would drop: the other light would change its index, hence its Russian roulette.
TEST(ScreenSpaceDynamic, SeveralLightsAddUp)
{
  const double Off = 1e-12; // W/m^2: its caustic is below float resolution of the other's
  Frame f("ball-lens", 128);
  vtkNew<vtkLight> second;
  second->SetLightTypeToSceneLight();
  second->SetPositional(false);
  second->SetPosition(1.0, 2.0, 0.5);
  second->SetFocalPoint(0.0, 0.0, 0.0);
  second->SetIntensity(0.5);
  f.Renderer->AddLight(second);
  vtkLight* first = vtkLight::SafeDownCast(f.Renderer->GetLights()->GetItemAsObject(0));
  auto both = f.Caustic();
  first->SetIntensity(Off);
  auto onlySecond = f.Caustic();
  first->SetIntensity(1.0);
  second->SetIntensity(Off);
  auto onlyFirst = f.Caustic();
  vtkDataArray* sum = onlyFirst->GetPointData()->GetArray(0);
  vtkDataArray* other = onlySecond->GetPointData()->GetArray(0);
  double secondTotal = 0.0;
  for (vtkIdType i = 0; i < sum->GetNumberOfTuples(); ++i)
  {
    secondTotal += other->GetComponent(i, 0);
    for (int c = 0; c < 3; ++c)
    {
      sum->SetComponent(i, c, sum->GetComponent(i, c) + other->GetComponent(i, c));
    }
  }
  EXPECT_GT(secondTotal, 0.0) << "the second light makes a caustic of its own";
  const double difference = Difference(both, onlyFirst);
  std::cout << "two lights against the sum of each: " << difference << "\n";
  // Reached: 1.6e-7 (float sums in another order). Bound: 1e-5.
  EXPECT_LT(difference, 1e-5);
  // Both lights have their own timed stages.
  bool secondLightTimed = false;
  vtkCausticsTimings* timings = f.Pass->GetTimings();
  second->SetIntensity(0.5);
  f.Caustic();
  for (int i = 0; i < timings->GetNumberOfStages(); ++i)
  {
    secondLightTimed = secondLightTimed ||
      (std::string(timings->GetStageName(i)).find("ssp light 1 ") == 0 && timings->GetStageRan(i));
  }
  EXPECT_TRUE(secondLightTimed);
}

TEST(ScreenSpaceDynamic, EveryStageIsTimed)
{
  Frame f("ball-lens", 128);
  f.Pass->GetTimings()->SynchronousOn();
  f.Caustic();
  vtkCausticsTimings* timings = f.Pass->GetTimings();
  const char* expected[] = { "ssp layers depth complexity", "ssp layers depth peeling",
    "refractor layers depth peeling", "ssp emission", "ssp bounce 1 line setup",
    "ssp bounce 1 line tracing", "ssp bounce 1 specular transfer", "ssp bounce 1 splatting",
    "ssp bounce 3 line tracing", "refraction tracing" };
  for (const char* stage : expected)
  {
    EXPECT_GE(timings->GetGPUMilliseconds(stage), 0.0) << stage << " has no GPU time";
  }
}

TEST(ScreenSpaceDynamic, ReleasesAndPrints)
{
  Frame f("ball-lens", 64);
  f.Caustic();
  EXPECT_NE(f.Pass->GetLayeredDepth()->GetPositionTexture(), 0u);
  f.Pass->ReleaseGraphicsResources(f.Window);
  EXPECT_EQ(f.Pass->GetLayeredDepth()->GetPositionTexture(), 0u);
  EXPECT_EQ(f.Pass->GetRefractorLayeredDepth()->GetPositionTexture(), 0u);
  EXPECT_EQ(f.Pass->GetLineTracer()->GetHitBuffer(), 0u);
  // And renders again after a release.
  f.Caustic();
  EXPECT_NE(f.Pass->GetLayeredDepth()->GetPositionTexture(), 0u);

  // Parameters are clamped to their documented ranges.
  f.Pass->SetMaximumNumberOfLayers(100);
  EXPECT_EQ(f.Pass->GetMaximumNumberOfLayers(), 16);
  f.Pass->SetMaximumBounces(0);
  EXPECT_EQ(f.Pass->GetMaximumBounces(), 1);
  f.Pass->SetRelativeIntersectionTolerance(-1.0);
  EXPECT_GT(f.Pass->GetRelativeIntersectionTolerance(), 0.0);
  std::ostringstream print;
  f.Pass->Print(print);
  for (const char* key : { "MaximumNumberOfLayers: 16", "MaximumBounces: 1", "GodRayBlurPixels",
         "RefractionTracing", "SplatRadiusSpacings", "LastTolerance" })
  {
    EXPECT_NE(print.str().find(key), std::string::npos) << key;
  }
}

// One layered depth image per object holds the same surfaces as one for the scene
// (the ball lens's depth complexity is far below the cap): the same first hits,
// the same caustic.
TEST(ScreenSpaceDynamic, PerObjectLayersGiveTheSameCaustic)
{
  Frame f("ball-lens", 128);
  auto scene = f.Caustic();
  f.Pass->PerObjectLayersOn();
  auto objects = f.Caustic();
  EXPECT_EQ(f.Pass->GetLayeredDepth()->GetNumberOfObjects(), 2);
  const double difference = Difference(objects, scene);
  std::cout << "per-object layers against one for the scene: " << difference << "\n";
  // Reached: float rounding of the splat sums (atomic append order). Bound 1e-4.
  EXPECT_LT(difference, 1e-4);
}
