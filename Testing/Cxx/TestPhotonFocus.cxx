// caustics::PhotonFocusBounds: the specular surfaces a light's photons are aimed at,
// narrowed to those whose light can reach what the camera sees. Checked on the CPU
// against rays traced exactly from a fine sampling of a wavy water sheet: every
// sample whose refracted light lands where the camera sees the floor must lie in
// the box, and the box must be much smaller than the sheet when the camera frames a
// small part of the floor under it.
#include "TestWaterSheetUtilities.h"
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsMedium.h"
#include "vtkCausticsPhotonFocus.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsSceneExtractor.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using namespace watersheet;
constexpr double FloorHalf = 3.0;

/** The sheet as a glass actor, moved by `offsetX` along x. */
vtkSmartPointer<vtkActor> MakeWater(int resolution, double offsetX = 0.0)
{
  auto actor = MakeActor(watersheet::MakeSheet(resolution));
  actor->SetPosition(offsetX, 0.0, 0.0);
  vtkCausticsMaterial::MakeGlass(actor->GetProperty(), WaterIndex);
  return actor;
}

/** A floor, the water sheet over it and a sun `elevation` degrees up, travelling to +x. */
struct SheetScene
{
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkLight> Sun;
  vtkNew<vtkCausticsSceneExtractor> Extractor;

  explicit SheetScene(double elevation)
  {
    this->Renderer->AddActor(MakeFloor(FloorHalf));
    this->Renderer->AddActor(MakeWater(96));
    const double e = elevation * M_PI / 180.0;
    this->Sun->SetLightTypeToSceneLight();
    this->Sun->SetPositional(false);
    this->Sun->SetFocalPoint(0, 0, 0);
    this->Sun->SetPosition(-std::cos(e), std::sin(e), 0.0);
    this->Renderer->AddLight(this->Sun);
  }

  /** An orthographic camera straight above, framing the 2 m of floor around the origin. */
  void LookDownAtTheFloorsMiddle()
  {
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->ParallelProjectionOn();
    camera->SetPosition(0, 5, 0);
    camera->SetFocalPoint(0, 0, 0);
    camera->SetViewUp(0, 0, -1);
    camera->SetParallelScale(1.0);
    camera->SetClippingRange(1, 10);
  }

  const caustics::SceneData& Extract()
  {
    EXPECT_TRUE(this->Extractor->Update(this->Renderer, 256, 256));
    return this->Extractor->GetScene();
  }
};

/** Clip-space x / w and y / w of world point p under a row-major worldToClip. */
std::array<double, 2> ProjectToClip(const double m[16], const caustics::Vec3& p)
{
  double c[4];
  for (int r = 0; r < 4; ++r)
  {
    c[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
  }
  return { { c[0] / c[3], c[1] / c[3] } };
}

bool Inside(const double box[6], double x, double y, double z, double tolerance)
{
  return x >= box[0] - tolerance && x <= box[1] + tolerance && y >= box[2] - tolerance &&
    y <= box[3] + tolerance && z >= box[4] - tolerance && z <= box[5] + tolerance;
}

/**
 * Traces the sun's light refracted at a fine sampling of the sheet (exact normals, not
 * the mesh's) to the floor. Every sample whose light lands where the camera sees the
 * floor must lie in `box`. Returns how many did (the check is empty without any).
 */
int CheckHoldsTheSeenLight(const caustics::SceneData& scene, double elevation, const double box[6])
{
  const double e = elevation * M_PI / 180.0;
  const double ix = std::cos(e), iy = -std::sin(e);
  int seen = 0, outside = 0;
  const int samples = 1200;
  for (int i = 0; i < samples; ++i)
  {
    const double x = -SheetHalf + 2.0 * SheetHalf * (i + 0.5) / samples;
    const double nx = -Slope(x) / std::sqrt(1.0 + Slope(x) * Slope(x));
    const double ny = 1.0 / std::sqrt(1.0 + Slope(x) * Slope(x));
    const double cosI = -(ix * nx + iy * ny), eta = 1.0 / WaterIndex;
    const double cosT = std::sqrt(std::max(0.0, 1.0 - eta * eta * (1.0 - cosI * cosI)));
    const double tx = eta * ix + (eta * cosI - cosT) * nx, ty = eta * iy + (eta * cosI - cosT) * ny;
    const double landedX = x + Surface(x) * tx / -ty;
    if (std::abs(landedX) > FloorHalf)
    {
      continue; // off the floor: lands nowhere
    }
    for (int k = 0; k < 120; ++k)
    {
      const double z = -SheetHalf + 2.0 * SheetHalf * (k + 0.5) / 120;
      double px, py;
      if (!scene.View.WorldToPixel({ { landedX, 0.0, z } }, px, py) || px < 0.0 || py < 0.0 ||
        px > scene.View.width || py > scene.View.height)
      {
        continue;
      }
      ++seen;
      if (!Inside(box, x, Surface(x), z, 1e-9))
      {
        if (++outside <= 5)
        {
          ADD_FAILURE() << "the sheet at x " << x << ", z " << z << " lights the floor seen at "
                        << landedX << " but lies outside the focus " << box[0] << " " << box[1]
                        << ", " << box[4] << " " << box[5];
        }
      }
    }
  }
  return seen;
}

double AreaXZ(const double box[6])
{
  return (box[1] - box[0]) * (box[5] - box[4]);
}
}

// Looking straight down at 2 m of floor under a 6 m sheet: the photons need only the
// part of the sheet over that floor and up-sun of it, whatever the sun's elevation.
TEST(PhotonFocus, NarrowsToTheSheetWhoseLightTheCameraSees)
{
  for (double elevation : { 90.0, 60.0, 30.0 })
  {
    SheetScene s(elevation);
    s.LookDownAtTheFloorsMiddle();
    const caustics::SceneData& scene = s.Extract();
    double box[6];
    ASSERT_TRUE(caustics::PhotonFocusBounds(scene, 0, box)) << elevation;
    const double* whole = scene.SpecularBounds;
    std::cout << "sun at " << elevation << " degrees: focus x " << box[0] << " to " << box[1]
              << ", z " << box[4] << " to " << box[5] << ": " << AreaXZ(box) / AreaXZ(whole)
              << " of the sheet\n";
    EXPECT_LT(AreaXZ(box), 0.3 * AreaXZ(whole)) << elevation;
    EXPECT_GT(CheckHoldsTheSeenLight(scene, elevation, box), 1000) << elevation;
    // The view the photons are emitted through is aimed at it.
    const caustics::LightView narrow =
      caustics::ComputeLightView(scene, 0, caustics::LightView::Focus::SeenSpecular);
    const caustics::LightView wide =
      caustics::ComputeLightView(scene, 0, caustics::LightView::Focus::Specular);
    ASSERT_TRUE(narrow.valid);
    EXPECT_LT(std::max(narrow.halfExtent, narrow.HalfExtentUp()), 0.6 * wide.halfExtent)
      << elevation;
    // A rectangle around the box's outline across the light: the sheet, met obliquely
    // by a low sun, is narrower across the light than along the crests, and a square
    // would spend texels beside it. It holds every corner of the box.
    EXPECT_GE(narrow.aspect, 1.0 / caustics::LightView::MaximumAspect) << elevation;
    EXPECT_LE(narrow.aspect, caustics::LightView::MaximumAspect) << elevation;
    double across[2] = { 0.0, 0.0 };
    for (int c = 0; c < 8; ++c)
    {
      const caustics::Vec3 corner{ { box[c & 1], box[2 + ((c >> 1) & 1)],
        box[4 + ((c >> 2) & 1)] } };
      const std::array<double, 2> clip = ProjectToClip(narrow.worldToClip, corner);
      for (int k = 0; k < 2; ++k)
      {
        EXPECT_LE(std::abs(clip[k]), 1.0) << elevation << ", corner " << c;
        across[k] = std::max(across[k], std::abs(clip[k]));
      }
    }
    // ...and fills it along both of its sides, where its shape allows.
    EXPECT_GT(std::min(across[0], across[1]),
      elevation < 45.0 ? 0.99 : 0.99 * std::min(narrow.aspect, 1.0 / narrow.aspect))
      << elevation;
    if (elevation < 45.0)
    {
      EXPECT_LT(std::min(narrow.aspect, 1.0 / narrow.aspect), 0.75) << elevation;
    }
    std::cout << "  the light's frustum: half sides " << narrow.halfExtent << " and "
              << narrow.HalfExtentUp() << " m against " << wide.halfExtent
              << " m aimed at the whole sheet (" << wide.TexelArea(256) / narrow.TexelArea(256)
              << " times the photons per m^2)\n";
  }
}

// A perspective camera close to the floor, zoomed in on the caustic at a slant, from
// several azimuths and elevations; and a camera seeing the sheet itself at a grazing
// angle. The light of every sample landing in view stays in the box.
TEST(PhotonFocus, HoldsEveryPathToWhatIsSeenFromAnyCamera)
{
  const double views[][6] = {
    { 0.5, 1.6, 0.8, 0.2, 0.0, 0.1 },   // close over the floor, under the sheet's edge of view
    { -1.5, 0.5, -1.0, 0.5, 0.0, 0.5 }, // under the water, looking along the floor
    { 0.0, 3.0, 5.0, 0.0, 0.0, 0.0 },   // the whole scene, obliquely
    { 4.0, 1.3, 0.0, -2.0, 0.9, 0.0 },  // beside the sheet, grazing it
  };
  for (double elevation : { 80.0, 45.0 })
  {
    for (const auto& v : views)
    {
      SheetScene s(elevation);
      vtkCamera* camera = s.Renderer->GetActiveCamera();
      camera->SetPosition(v[0], v[1], v[2]);
      camera->SetFocalPoint(v[3], v[4], v[5]);
      camera->SetViewUp(0, 1, 0);
      camera->SetViewAngle(25.0);
      camera->SetClippingRange(0.05, 50.0);
      const caustics::SceneData& scene = s.Extract();
      double box[6];
      caustics::PhotonFocusBounds(scene, 0, box);
      CheckHoldsTheSeenLight(scene, elevation, box);
    }
  }
}

// Several specular meshes: each sheet that no other one lights is narrowed on its own.
// A mirror whose light goes nowhere the camera looks adds nothing to the box: beside
// the water, the focus is the one the water alone has. Two mirrors over a floor, one
// throwing the sun onto the floor in view and one sending it to the sky: the box holds
// the first one's light that lands in view (traced exactly) and not the second.
TEST(PhotonFocus, NarrowsEachSheetNoOtherLights)
{
  auto zoomIn = [](vtkRenderer* renderer, double x)
  {
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(x, 1.5, 0.3);
    camera->SetFocalPoint(x, 0.0, 0.0);
    camera->SetViewUp(0, 0, -1);
    camera->SetClippingRange(0.05, 50.0);
  };
  {
    SheetScene alone(60.0);
    zoomIn(alone.Renderer, 0.3);
    double sheet[6];
    ASSERT_TRUE(caustics::PhotonFocusBounds(alone.Extract(), 0, sheet));
    SheetScene s(60.0);
    zoomIn(s.Renderer, 0.3);
    // Beyond the floor's edge, facing up: the sun's reflection leaves up and away.
    const double origin[3] = { 3.5, 0.5, -0.5 }, u[3] = { 1.0, 0.0, 0.0 }, v[3] = { 0.0, 0.0, 1.0 };
    s.Renderer->AddActor(MakeMirror(origin, u, v));
    const caustics::SceneData& scene = s.Extract();
    double box[6];
    ASSERT_TRUE(caustics::PhotonFocusBounds(scene, 0, box));
    for (int k = 0; k < 6; ++k)
    {
      EXPECT_NEAR(box[k], sheet[k], 1e-9) << "beside an idle mirror, bound " << k;
    }
    EXPECT_GT(CheckHoldsTheSeenLight(scene, 60.0, box), 1000);
  }
  {
    vtkNew<vtkRenderer> renderer;
    renderer->AddActor(MakeFloor(FloorHalf));
    // A wall mirror facing the sun, which travels to +x 60 degrees down: its light falls
    // back onto the floor at x 0.63 to 1.33 m.
    const double wallOrigin[3] = { 1.5, 0.3, -1.0 }, wallU[3] = { 0.0, 1.2, 0.0 },
                 wallV[3] = { 0.0, 0.0, 2.0 };
    renderer->AddActor(MakeMirror(wallOrigin, wallU, wallV));
    // A mirror on the floor far up-sun: its light goes to the sky.
    const double padOrigin[3] = { -2.8, 0.2, -0.3 }, padU[3] = { 0.6, 0.0, 0.0 },
                 padV[3] = { 0.0, 0.0, 0.6 };
    renderer->AddActor(MakeMirror(padOrigin, padU, padV));
    vtkNew<vtkLight> sun;
    sun->SetLightTypeToSceneLight();
    sun->SetPositional(false);
    sun->SetFocalPoint(0, 0, 0);
    sun->SetPosition(-std::cos(M_PI / 3.0), std::sin(M_PI / 3.0), 0.0);
    renderer->AddLight(sun);
    zoomIn(renderer, 1.0);
    vtkNew<vtkCausticsSceneExtractor> extractor;
    ASSERT_TRUE(extractor->Update(renderer, 256, 256));
    const caustics::SceneData& scene = extractor->GetScene();
    double box[6];
    ASSERT_TRUE(caustics::PhotonFocusBounds(scene, 0, box));
    std::cout << "two mirrors: focus x " << box[0] << " to " << box[1] << ", y " << box[2]
              << " to " << box[3] << ", z " << box[4] << " to " << box[5] << " (both: x "
              << scene.SpecularBounds[0] << " to " << scene.SpecularBounds[1] << ")\n";
    EXPECT_GT(box[0], -2.2) << "the mirror lighting the sky is left out";
    int seen = 0, outside = 0;
    for (int i = 0; i < 60; ++i)
    {
      const double y = 0.3 + 1.2 * (i + 0.5) / 60;
      const double landedX = 1.5 - y * std::cos(M_PI / 3.0) / std::sin(M_PI / 3.0);
      for (int k = 0; k < 100; ++k)
      {
        const double z = -1.0 + 2.0 * (k + 0.5) / 100;
        double px, py;
        if (!scene.View.WorldToPixel({ { landedX, 0.0, z } }, px, py) || px < 0.0 || py < 0.0 ||
          px > scene.View.width || py > scene.View.height)
        {
          continue;
        }
        ++seen;
        if (!Inside(box, 1.5, y, z, 1e-9) && ++outside <= 5)
        {
          ADD_FAILURE() << "the wall mirror at y " << y << ", z " << z
                        << " lights the floor in view but lies outside the focus";
        }
      }
    }
    EXPECT_GT(seen, 500);
  }
}

// A mirror sheet that a closed ball's light can reach follows that light from anywhere
// in the ball's bounds: kept where it sends it back towards what is seen, left out where
// it sends it to the sky.
TEST(PhotonFocus, FollowsTheLightAMirrorGetsFromAnotherMesh)
{
  auto focusBeside = [](const double origin[3], const double u[3], const double v[3], double box[6])
  {
    vtkNew<vtkRenderer> renderer;
    vtkNew<vtkCausticsBuiltinScene> builtin;
    builtin->SetSceneName("ball-lens"); // glass ball of radius 1 at (0, 3, 0), sun straight down
    EXPECT_TRUE(builtin->Populate(renderer));
    renderer->AddActor(MakeMirror(origin, u, v));
    renderer->GetActiveCamera()->SetViewAngle(12.0);
    renderer->ResetCameraClippingRange();
    vtkNew<vtkCausticsSceneExtractor> extractor;
    EXPECT_TRUE(extractor->Update(renderer, 256, 256));
    return caustics::PhotonFocusBounds(extractor->GetScene(), 0, box);
  };
  // 12 m off, facing up: the sun's light and the ball's both leave it upwards, away.
  const double farOrigin[3] = { 12.0, 0.5, -0.5 }, u[3] = { 1.0, 0.0, 0.0 }, v[3] = { 0.0, 0.0, 1.0 };
  double box[6];
  EXPECT_TRUE(focusBeside(farOrigin, u, v, box));
  EXPECT_NEAR(box[0], -1.0, 0.01) << "only the ball";
  EXPECT_NEAR(box[1], 1.0, 0.01) << "only the ball";
  EXPECT_LT(box[3], 4.01) << "only the ball";
  // Over the ball, 2 m wide: the sun reaches its back only, but the light the ball
  // sends up comes down again onto the ball and the floor.
  const double overOrigin[3] = { -1.0, 5.0, 1.0 }, overU[3] = { 2.0, 0.0, 0.0 },
               overV[3] = { 0.0, 0.0, -2.0 };
  focusBeside(overOrigin, overU, overV, box);
  EXPECT_GE(box[3], 5.0) << "the mirror over the ball is kept";
  EXPECT_LE(box[0], -1.0);
  EXPECT_GE(box[1], 1.0);
}

// Where one specular event does not bound the paths, the focus is every specular
// actor: a closed ball, two sheets one of which lights the other, a participating
// medium, a camera that sees nothing.
TEST(PhotonFocus, KeepsEverySpecularActorWhereItCannotTell)
{
  auto expectWhole = [](const caustics::SceneData& scene, const char* what)
  {
    double box[6];
    EXPECT_FALSE(caustics::PhotonFocusBounds(scene, 0, box)) << what;
    for (int k = 0; k < 6; ++k)
    {
      EXPECT_EQ(box[k], scene.SpecularBounds[k]) << what;
    }
  };
  {
    vtkNew<vtkRenderer> renderer;
    vtkNew<vtkCausticsBuiltinScene> builtin;
    builtin->SetSceneName("ball-lens");
    ASSERT_TRUE(builtin->Populate(renderer));
    vtkNew<vtkCausticsSceneExtractor> extractor;
    ASSERT_TRUE(extractor->Update(renderer, 256, 256));
    expectWhole(extractor->GetScene(), "a closed ball");
  }
  auto zoomIn = [](vtkRenderer* renderer)
  {
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(0.3, 1.5, 0.3);
    camera->SetFocalPoint(0.3, 0.0, 0.0);
    camera->SetViewUp(0, 0, -1);
    camera->SetClippingRange(0.05, 50.0);
  };
  {
    SheetScene s(60.0);
    zoomIn(s.Renderer);
    double box[6];
    EXPECT_TRUE(caustics::PhotonFocusBounds(s.Extract(), 0, box)) << "the sheet alone narrows";
  }
  {
    SheetScene s(60.0);
    zoomIn(s.Renderer);
    auto second = MakeWater(8);
    second->SetPosition(0.0, 0.5, 0.0);
    s.Renderer->AddActor(second);
    expectWhole(s.Extract(), "two sheets, one lighting the other");
  }
  {
    SheetScene s(60.0);
    zoomIn(s.Renderer);
    vtkNew<vtkCausticsMedium> medium;
    medium->SetScatteringCoefficient(0.1, 0.1, 0.1);
    vtkCausticsMedium::AttachTo(s.Renderer, medium);
    expectWhole(s.Extract(), "a medium");
  }
  {
    SheetScene s(60.0);
    vtkCamera* camera = s.Renderer->GetActiveCamera();
    camera->SetPosition(0.0, 20.0, 0.0);
    camera->SetFocalPoint(0.0, 40.0, 0.0);
    camera->SetViewUp(0, 0, -1);
    camera->SetClippingRange(0.05, 10.0);
    expectWhole(s.Extract(), "a camera that sees nothing");
  }
}

// ProgressiveFrames moves the light's texel grid by a sub-texel offset each frame
// (caustics::OffsetLightView): the sun's orthographic view slides across the light by
// that many texels, a spot light's perspective view turns about its eye; both keep
// their size, and the transforms follow. Out-of-range or NaN offsets change nothing.
TEST(LightView, OffsetMovesTheTexelGrid)
{
  for (bool spot : { false, true })
  {
    SCOPED_TRACE(spot ? "spot light" : "sun");
    SheetScene s(60.0);
    if (spot)
    {
      s.Sun->SetPositional(true);
      s.Sun->SetPosition(0.5, 3.0, 0.0);
      s.Sun->SetConeAngle(40.0);
    }
    const caustics::LightView base =
      caustics::ComputeLightView(s.Extract(), 0, caustics::LightView::Focus::Specular);
    ASSERT_TRUE(base.valid);
    ASSERT_EQ(base.perspective, spot);
    caustics::LightView moved = base;
    caustics::OffsetLightView(moved, 0.5, -0.25, 16);
    const double step = 2.0 * base.halfExtent / 16; // one texel (m, or tangent units)
    EXPECT_DOUBLE_EQ(moved.halfExtent, base.halfExtent);
    if (spot)
    {
      const double cosine = base.axis[0] * moved.axis[0] + base.axis[1] * moved.axis[1] +
        base.axis[2] * moved.axis[2];
      EXPECT_NEAR(std::tan(std::acos(std::min(cosine, 1.0))), std::hypot(0.5, 0.25) * step, 1e-9);
      EXPECT_EQ(moved.eye, base.eye);
    }
    else
    {
      const double shift[3] = { moved.eye[0] - base.eye[0], moved.eye[1] - base.eye[1],
        moved.eye[2] - base.eye[2] };
      auto along = [&shift](const caustics::Vec3& d)
      { return shift[0] * d[0] + shift[1] * d[1] + shift[2] * d[2]; };
      EXPECT_NEAR(along(base.right), 0.5 * step, 1e-12);
      EXPECT_NEAR(along(base.up), -0.25 * step, 1e-12);
      EXPECT_NEAR(along(base.axis), 0.0, 1e-12);
    }
    // The moved view's centre lies on its axis: clip (0, 0).
    const caustics::Vec3 ahead{ { moved.eye[0] + 2.0 * moved.axis[0],
      moved.eye[1] + 2.0 * moved.axis[1], moved.eye[2] + 2.0 * moved.axis[2] } };
    const std::array<double, 2> clip = ProjectToClip(moved.worldToClip, ahead);
    EXPECT_NEAR(clip[0], 0.0, 1e-9);
    EXPECT_NEAR(clip[1], 0.0, 1e-9);

    if (!spot)
    {
      // A fitted view whose texels are longer along one side moves by its own texel
      // along each.
      SheetScene low(30.0);
      low.LookDownAtTheFloorsMiddle();
      const caustics::LightView fitted =
        caustics::ComputeLightView(low.Extract(), 0, caustics::LightView::Focus::SeenSpecular);
      ASSERT_TRUE(fitted.valid);
      ASSERT_GT(std::abs(fitted.aspect - 1.0), 0.1);
      caustics::LightView slid = fitted;
      caustics::OffsetLightView(slid, 0.5, -0.25, 16);
      const caustics::Vec3 shift{ { slid.eye[0] - fitted.eye[0], slid.eye[1] - fitted.eye[1],
        slid.eye[2] - fitted.eye[2] } };
      auto along = [&shift](const caustics::Vec3& d)
      { return shift[0] * d[0] + shift[1] * d[1] + shift[2] * d[2]; };
      EXPECT_NEAR(along(fitted.right), 0.5 * 2.0 * fitted.halfExtent / 16, 1e-12);
      EXPECT_NEAR(along(fitted.up), -0.25 * 2.0 * fitted.HalfExtentUp() / 16, 1e-12);
      EXPECT_DOUBLE_EQ(slid.aspect, fitted.aspect);
    }

    for (double bad : { std::nan(""), 0.75, -3.0 })
    {
      caustics::LightView same = base;
      caustics::OffsetLightView(same, bad, 0.0, 16);
      EXPECT_EQ(same.eye, base.eye);
      EXPECT_EQ(same.axis, base.axis);
    }
  }
}

// A caustic map's view of a point light over the ball lens (ComputeReceiverMapView):
// the lamp is inside the bounding sphere of what the camera sees, which gave the widest
// frustum a view takes, 75 degrees off axis. It now fits the receivers in view: every
// corner of their box lies inside it, it is narrower, and where no frustum within 75
// degrees holds them (a lamp low beside the floor) the view stays as it was.
TEST(LightView, ALampsCausticMapFitsTheReceiversInView)
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkCausticsBuiltinScene> builtin;
  ASSERT_TRUE(builtin->Populate(renderer)); // the ball lens: a floor and the ball
  vtkNew<vtkLight> lamp;
  lamp->SetLightTypeToSceneLight();
  lamp->SetPositional(true);
  lamp->SetConeAngle(180.0);
  lamp->SetFocalPoint(0.0, 0.0, 0.0);
  renderer->RemoveAllLights();
  renderer->AddLight(lamp);
  vtkNew<vtkCausticsSceneExtractor> extractor;
  const double widest = std::tan(75.0 * M_PI / 180.0);
  int fitted = 0;
  for (const std::array<double, 3>& at :
    std::vector<std::array<double, 3>>{ { 0.5, 6.0, 0.3 }, { -3.0, 5.0, 2.0 }, { 4.0, 8.0, -4.0 },
      { 0.0, 20.0, 0.0 }, { 1.0, 4.5, -1.0 }, { 5.5, 1.0, 0.0 } })
  {
    SCOPED_TRACE(at[0]);
    lamp->SetPosition(at[0], at[1], at[2]);
    ASSERT_TRUE(extractor->Update(renderer, 256, 256));
    const caustics::SceneData& scene = extractor->GetScene();
    caustics::ReceiverIncidence straight; // not turned towards the floor
    const caustics::LightView map = caustics::ComputeReceiverMapView(scene, 0, straight, 0.0);
    ASSERT_TRUE(map.valid);
    ASSERT_TRUE(map.perspective);
    EXPECT_LE(map.halfExtent, widest * 1.001);
    // The receivers the camera sees: the floor cut by the camera's clip volume.
    double seen[6], floor[6] = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
    caustics::VisibleBounds(scene, seen);
    for (const caustics::Mesh& mesh : scene.Meshes)
    {
      if (caustics::MeshRole(scene, mesh) == caustics::Role::Receiver)
      {
        caustics::GrowBounds(mesh, floor);
      }
    }
    double box[6];
    for (int k = 0; k < 3; ++k)
    {
      box[2 * k] = std::max(seen[2 * k], floor[2 * k]);
      box[2 * k + 1] = std::min(seen[2 * k + 1], floor[2 * k + 1]);
    }
    if (map.clamped)
    {
      // No frustum within 75 degrees holds the floor from beside it.
      EXPECT_LT(at[1], 2.0);
      continue;
    }
    ++fitted;
    for (int c = 0; c < 8; ++c)
    {
      const caustics::Vec3 corner{ { box[c & 1], box[2 + ((c >> 1) & 1)],
        box[4 + ((c >> 2) & 1)] } };
      const std::array<double, 2> clip = ProjectToClip(map.worldToClip, corner);
      EXPECT_LE(std::abs(clip[0]), 1.0) << c;
      EXPECT_LE(std::abs(clip[1]), 1.0) << c;
    }
    std::cout << "lamp at (" << at[0] << ", " << at[1] << ", " << at[2]
              << "): the map's half width tan " << map.halfExtent << "\n";
  }
  EXPECT_EQ(fitted, 5);
}

// caustics::RefractorsInLine: two refractors whose bounding spheres overlap as a light
// sees them (a ball under the ball lens, a ball aside under a slanting sun, any other
// glass seen from a lamp inside one), and not when they stand apart across the light.
TEST(RefractorsInLine, OverlapAsTheLightSeesThem)
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkCausticsBuiltinScene> builtin;
  ASSERT_TRUE(builtin->Populate(renderer)); // the ball lens: radius 1 at (0, 3, 0), sun down
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(0.5);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> second;
  second->SetMapper(mapper);
  vtkCausticsMaterial::MakeGlass(second->GetProperty(), 1.5);
  vtkCausticsMaterial::SetName(second, "second ball");
  renderer->AddActor(second);
  vtkNew<vtkCausticsSceneExtractor> extractor;
  auto inLine = [&](double x, double y, std::string* names = nullptr)
  {
    second->SetPosition(x, y, 0.0);
    EXPECT_TRUE(extractor->Update(renderer, 64, 64));
    const caustics::SceneData& scene = extractor->GetScene();
    int first = -1, next = -1;
    const bool found = caustics::RefractorsInLine(scene, 0, first, next);
    if (found && names)
    {
      *names = scene.Meshes[first].name + " then " + scene.Meshes[next].name;
    }
    return found;
  };
  std::string names;
  EXPECT_TRUE(inLine(0.0, 1.2, &names)) << "under the ball lens";
  EXPECT_EQ(names.find("second ball"), names.size() - std::string("second ball").size())
    << names << ": the ball lens is met first";
  EXPECT_FALSE(inLine(3.5, 0.6)) << "aside, under a vertical sun";
  vtkLight* sun = vtkLight::SafeDownCast(renderer->GetLights()->GetItemAsObject(0));
  ASSERT_NE(sun, nullptr);
  sun->SetPosition(-1.0, 1.0, 0.0); // slanting down towards +x
  sun->SetFocalPoint(0.0, 0.0, 0.0);
  EXPECT_TRUE(inLine(3.5, 0.6)) << "aside, where the slanting sun's rays through the lens go";
  EXPECT_FALSE(inLine(-3.5, 0.6)) << "on the other side";
  sun->SetIntensity(0.0);
  EXPECT_FALSE(inLine(0.0, 1.2)) << "a light without power";
  // A lamp inside the ball lens sees every other glass in line.
  renderer->RemoveAllLights();
  vtkNew<vtkLight> lamp;
  lamp->SetLightTypeToSceneLight();
  lamp->SetPositional(true);
  lamp->SetConeAngle(180.0);
  lamp->SetPosition(0.0, 3.0, 0.0);
  renderer->AddLight(lamp);
  EXPECT_TRUE(inLine(-3.5, 0.6));
}
