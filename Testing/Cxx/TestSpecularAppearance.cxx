// What the camera sees on glass and mirrors (issue 13, "Specular surfaces look right
// in every technique"): the shared camera-view stage's colour (the pass's
// "TechniqueColor", VTK's display units) against the reference renderer's camera
// paths ("SpecularColor": 256 paths per pixel, Fresnel-chosen reflection or
// refraction, ending on a receiver with albedo x (direct + caustic irradiance) or
// on the background), on the pixels whose first visible surface is specular, at
// 128 x 128 pixels and 256 x 256 photons. With 256 paths the reference's own noise
// is 3.6 % on the ball lens (7.3 % with the 64 paths these tests first took, which
// added about 2.5 points to the ball's figures; the ring's and the pool's errors are
// the stage's own and moved by less than 0.1 point).
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsScreenSpaceRefraction.h"
#include "vtkCausticsTechniques.h"
#include "vtkCausticsTimings.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

namespace
{
constexpr int Size = 128;

/** A plane actor: corner `origin`, edges to `p1` and `p2` (normal (p1 - o) x (p2 - o)). */
vtkSmartPointer<vtkActor> Plane(
  const double origin[3], const double p1[3], const double p2[3], int resolution)
{
  vtkNew<vtkPlaneSource> source;
  source->SetOrigin(origin[0], origin[1], origin[2]);
  source->SetPoint1(p1[0], p1[1], p1[2]);
  source->SetPoint2(p2[0], p2[1], p2[2]);
  source->SetResolution(resolution, resolution);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

/**
 * An open water sheet (index 1.33, flat, y = 1, normal up) 6 m wide over a 2 m floor,
 * lit from above by a directional light: a camera can stand beside it, beyond its edge.
 */
void PopulateWideSheet(vtkRenderer* renderer)
{
  const double floorCorner[3] = { -1.0, 0.0, 1.0 }, floorRight[3] = { 1.0, 0.0, 1.0 },
               floorBack[3] = { -1.0, 0.0, -1.0 };
  auto floor = Plane(floorCorner, floorRight, floorBack, 8);
  floor->GetProperty()->SetColor(0.8, 0.8, 0.8);
  renderer->AddActor(floor);
  const double sheetCorner[3] = { -3.0, 1.0, 3.0 }, sheetRight[3] = { 3.0, 1.0, 3.0 },
               sheetBack[3] = { -3.0, 1.0, -3.0 };
  auto sheet = Plane(sheetCorner, sheetRight, sheetBack, 32);
  vtkCausticsMaterial::MakeGlass(sheet->GetProperty(), 1.33);
  renderer->AddActor(sheet);
  vtkNew<vtkLight> sun;
  sun->SetLightTypeToSceneLight();
  sun->SetPositional(false);
  sun->SetPosition(0.3, 1.0, 0.2);
  sun->SetFocalPoint(0.0, 0.0, 0.0);
  renderer->AddLight(sun);
}

/**
 * Relative L2 of the technique's colour against the reference's on specular pixels, on
 * the built-in scene `sceneName` or, with `populate`, on the scene it adds (`sceneName`
 * then only names it in the output).
 */
double SpecularError(const std::string& sceneName, const std::string& technique,
  int method = vtkCausticsRenderPass::SCREEN_SPACE, const double* eye = nullptr,
  const double* focal = nullptr, const double* up = nullptr,
  void (*populate)(vtkRenderer*) = nullptr, bool internalReflections = true, int size = Size,
  int exact = -1)
{
  vtkNew<vtkOpenGLRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkCausticsBuiltinScene> scene;
  if (populate)
  {
    populate(renderer);
  }
  else
  {
    scene->SetSceneName(sceneName.c_str());
    EXPECT_TRUE(scene->Populate(renderer));
  }
  if (eye)
  {
    // From `eye` towards `focal` (default: down at the floor's caustic at the origin).
    const double origin[3] = { 0.0, 0.0, 0.0 }, south[3] = { 0.0, 0.0, -1.0 };
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(eye);
    camera->SetFocalPoint(focal ? focal : origin);
    camera->SetViewUp(up ? up : south);
    camera->SetViewAngle(60.0);
    camera->SetClippingRange(0.01, 20.0);
  }
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(size, size);
  window->AddRenderer(renderer);
  vtkNew<vtkCausticsReferenceRenderer> reference;
  reference->SetInputRenderer(renderer);
  reference->SetImageSize(size, size);
  reference->SetPhotonsPerLight(1000000);
  reference->SetSpecularSamples(256);
  EXPECT_TRUE(reference->Update()) << reference->GetLastError();
  vtkDataArray* truth = reference->GetOutput()->GetPointData()->GetArray("SpecularColor");
  vtkDataArray* specular = reference->GetOutput()->GetPointData()->GetArray("SpecularMask");

  vtkSmartPointer<vtkCausticsRenderPass> pass = vtkCausticsTechniques::Create(technique);
  pass->SetLightBufferResolution(256);
  pass->SetCameraViewMethod(method);
  // On unless asked: these bounds are the stage's best (the default is off for speed).
  pass->GetScreenSpaceRefraction()->SetInternalReflections(internalReflections);
  if (exact >= 0)
  {
    pass->GetScreenSpaceRefraction()->SetExactSpecularGeometry(exact);
  }
  pass->KeepBuffersOn();
  pass->GetTimings()->SynchronousOn();
  renderer->SetPass(pass);
  window->Render();
  // The maps' cost, once (the second frame makes none), and the camera view's, per frame.
  const double maps = pass->GetTimings()->GetGPUMilliseconds("distance impostors");
  window->Render();
  const double view = pass->GetTimings()->GetGPUMilliseconds("refraction tracing");
  vtkNew<vtkImageData> color;
  EXPECT_TRUE(pass->ReadBuffer("TechniqueColor", color));
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  vtkDataArray* shown = color->GetPointData()->GetArray(0);
  if (!truth || !specular || !shown)
  {
    ADD_FAILURE() << "missing arrays";
    return 1.0;
  }
  double difference = 0.0, norm = 0.0;
  int pixels = 0;
  for (vtkIdType p = 0; p < static_cast<vtkIdType>(size) * size; ++p)
  {
    // Where the reference's first surface is specular and the stage drew it.
    if (specular->GetComponent(p, 0) == 0.0 || shown->GetComponent(p, 3) < 0.5)
    {
      continue;
    }
    ++pixels;
    for (int c = 0; c < 3; ++c)
    {
      const double e = shown->GetComponent(p, c) - truth->GetComponent(p, c);
      difference += e * e;
      norm += truth->GetComponent(p, c) * truth->GetComponent(p, c);
    }
  }
  EXPECT_GT(pixels, 500) << sceneName;
  const double error = norm > 0.0 ? std::sqrt(difference / norm) : 1.0;
  const char* methods[] = { "screen-space view", "impostor view", "screen-space + impostor view" };
  std::cout << sceneName << ", " << technique << ", " << methods[method] << ": " << pixels
            << " specular pixels, relative L2 " << 100.0 * error << " %; camera view " << view
            << " ms a frame, maps " << maps << " ms once\n";
  return error;
}
}

// Measured (relative L2): ball lens 27.0 % (screen-space; 27.8 % against the 64-path
// reference, 28.4 % before the reflected branch at the glass's exit was followed),
// ring 23.8 % (screen-space) and 23.9 % (caustic maps; 33.1 % and 33.7 % while a ray
// leaving the wall's foot took the wall's own pixel for its hit; 67.8 % while floors
// seen in a mirror kept VTK's unshadowed colour), pool 30.4 % (screen-space; 37.1 %
// with caustic maps); bounds just above.
// The issue's 10 % is not reached: rays that leave the screen see the background (the
// ball's top rim, the pool's near edge), the ring's foot (h < 0.1 m: 15 % of its
// pixels, 60 % of its squared error) and the pool's near strip of water (16 % of its
// pixels, 40 %) (docs/accuracy.md, "Glass and mirrors against the reference's camera
// paths"; scripts/specular-error-map.py).
// Since the shadow test keeps a wall's foot in its shadow and the stage traces the
// ring's and the water's triangles (docs/accuracy.md, "Contact shadows" and "Glass and
// mirrors traced as triangles"): ring 17.6 % (screen-space) and 18.5 % (caustic maps),
// pool 29.9 %; with 8 interfaces a path (the default since then) the ring's further
// mirror-to-mirror bounces leave the screen, where this view alone sees the
// background: 18.9 and 19.5 %. Since a hit on a surface the camera sees is shaded
// bilinearly from the pixels around its projection (ShadeAt: the nearest pixel
// shifted the pool's tiles by up to half a pixel): ring 17.8 and 18.1 %, pool 25.6 %.
// Since a ray leaving a mirror that ends at the scene's box on nothing is marched two
// pixel footprints further (next to the ring's foot it crosses the floor at the box's
// bottom, where the march's last sample projected onto the wall): ring 12.9 and 13.4 %.
// Since the reference's estimate holds up to a receiver's end (docs/reference.md), the
// pool's floor along its walls, seen through the water, counts the light the splats
// lose there: pool 25.6 -> 26.3 %. Since the splats keep their flux at a receiver's
// end and along the image's border (docs/accuracy.md): pool 25.8 %; since the
// first-hit reduction tests the receivers around the row's hit, 25.7 %. Bounds just
// above.
TEST(SpecularAppearance, MatchesTheReferencesCameraPaths)
{
  EXPECT_LT(SpecularError("ball-lens", "screen-space"), 0.275);
  EXPECT_LT(SpecularError("ring", "screen-space"), 0.132);
  EXPECT_LT(SpecularError("ring", "caustic-maps"), 0.137);
  EXPECT_LT(SpecularError("pool", "screen-space"), 0.262);
}

// The same with the distance impostors (paper 004, docs/technique-distance-impostors.md),
// alone and behind the screen-space march (BOTH). Measured (relative L2):
// DISTANCE_IMPOSTORS ball lens 8.4 % (10.8 % against the 64-path reference; 11.5 %
// before the reflected branch at the glass's exit was followed: the ball showed 3.4 %
// less light than the reference), ring 21.6 % (25.2 % before the wall's foot saw the
// floor; 27.0 % before the ring's wall saw itself through REFLECTOR_SURFACE), pool
// 28.3 %, bunny 55.4 % (57.1 % against 64 paths; 58.0 % before Hit() skipped the start
// of rays starting behind the map's surface); BOTH ball lens 11.2 % (13.1 % against 64
// paths), ring 23.8 % (33.1 %), pool 30.4 %. Bounds just above.
// The impostor view's ring and pool with the caustic store, which the screen-space
// photons fill since it became a shared stage (the floor the ring's wall hides and
// the pool's near wall, seen only in the mirror or through the water, with their
// caustic and shadow): ring 19.5 % (21.6 % with the store empty), pool 28.0 % (28.3 %;
// 27.3 % before the store's coarse level, which CameraBesideTheWaterSheet needs).
// Since the maps' radiance takes the lights' shadows from the shadow maps and the store
// holds the photons alone (nothing to cancel): pool 22.6 %, ring 20.15 % (its map hits
// 6 % too bright on average: the photons' adaptive windows spread light into the
// shadow, which the store's own shadow samples used to spread back; not verified
// further). Bounds 0.205 and 0.23, just above.
// Since the combined view hands the impostors the rays its march finds passing behind
// a surface (CombinedViewWhereTheMarchPassesBehindASurface): BOTH pool 30.4 -> 22.6 %
// (as the impostor view), ring 23.8 -> 23.2 %; and since a march that ends, on nothing,
// within the pixels it starts in goes to the impostors too (a ray from the ring's foot
// crosses the floor within the wall's own pixel, where the march takes it for leaving
// the wall, and saw the background): ring 20.4 %. Bounds 0.23 and 0.21.
// Since the shadow test keeps the ring's floor at the wall's foot in the wall's shadow
// (it was lit for a few centimetres, and the wall showed it): ring 13.5 % (impostors)
// and 14.4 % (both); tracing the ring's triangles, 13.5 and 13.4 %. Pool 22.0 % both.
// Shaded bilinearly where the camera sees the hit (ShadeAt): ring 12.0 and 11.8 %, pool
// 17.9 and 17.9 %. Since the contact shadow needs the receiver behind the occluder's
// lit side (no shadow on the floor before a lit wall's foot), the ring's impostor view
// 12.2 %; since the march of a ray leaving a mirror goes two pixel footprints past the
// scene's box, the ring's combined view 9.7 %; with the caustic store's shadow edges
// kept (ImpostorCausticIrradiance), the pool 17.8 and 17.9 %. Since the reference's
// estimate holds up to a receiver's end (docs/reference.md; the floor along the pool's
// walls): pool 18.4 and 18.4 %; since the splats keep their flux there and along the
// image's border (docs/accuracy.md), 17.8 and 17.8 %; since the first-hit reduction
// tests the receivers around the row's hit, 17.6 and 17.7 %. Bounds just above.
// The issue's 10 % is reached on the ball by the impostor view; the combined view's
// screen-space march sees the background where its rays leave the screen (the ball's
// top rim). The ring's foot, the pool's near strip of water seen at grazing angles,
// the bunny's concavities hidden from its centre carry the rest (docs/accuracy.md).
// (Both tests with InternalReflections on; the default, off, in DefaultView below.)
TEST(SpecularAppearance, DistanceImpostors)
{
  const int impostors = vtkCausticsRenderPass::DISTANCE_IMPOSTORS;
  const int both = vtkCausticsRenderPass::BOTH;
  EXPECT_LT(SpecularError("ball-lens", "screen-space", impostors), 0.09);
  EXPECT_LT(SpecularError("ball-lens", "screen-space", both), 0.115);
  EXPECT_LT(SpecularError("ring", "screen-space", impostors), 0.124);
  EXPECT_LT(SpecularError("ring", "screen-space", both), 0.1);
  EXPECT_LT(SpecularError("pool", "screen-space", impostors), 0.181);
  EXPECT_LT(SpecularError("pool", "screen-space", both), 0.181);
  // The impostors' own refractor map (ExactSpecularGeometryOnConcaveGlass traces the
  // bunny's triangles, the default for a concave object).
  EXPECT_LT(SpecularError("bunny", "screen-space", impostors, nullptr, nullptr, nullptr, nullptr,
              true, Size, vtkCausticsScreenSpaceRefraction::EXACT_OFF),
    0.56);
}

// The glass bunny's triangles traced (vtkCausticsSpecularHierarchy), the default for a
// specular object that is not a convex solid, against finding its surfaces in the
// layered depth image and the refractor map, with 8 interfaces a path (the reference's;
// the default since 2026-12-05). Relative L2, 128 x 128, combined view (impostor view):
// its own camera 42.5 % (42.5 %) against 72.0 % (54.3 %) with the layers; from
// (-0.8, 1.5, 1.8) towards (0, 0.5, 0), 60 degrees, 28.3 % (28.3 %) against 105.8 %
// (50.5 %). With 4 interfaces the traced paths ended dark inside the bunny (57.5 % on its
// own camera). Shaded bilinearly where the camera sees the hit (ShadeAt): 39.2 % (39.2 %)
// and 22.6 %; since the screen-space photons cross the bunny as triangles too (the
// caustics seen through it): 38.2 % (38.1 %) and 21.6 %. Bounds just above; the layers
// (which also turn the photons' triangles off) must stay measurably worse (a trace that
// stops working fails the test).
TEST(SpecularAppearance, ExactSpecularGeometryOnConcaveGlass)
{
  const int both = vtkCausticsRenderPass::BOTH;
  const int layers = vtkCausticsScreenSpaceRefraction::EXACT_OFF;
  const double up[3] = { 0.0, 1.0, 0.0 };
  const double eye[3] = { -0.8, 1.5, 1.8 }, focal[3] = { 0.0, 0.5, 0.0 };
  EXPECT_LT(SpecularError("bunny", "screen-space", both), 0.385);
  EXPECT_LT(SpecularError("bunny", "screen-space", vtkCausticsRenderPass::DISTANCE_IMPOSTORS),
    0.385);
  EXPECT_LT(SpecularError("bunny", "screen-space", both, eye, focal, up), 0.22);
  EXPECT_GT(SpecularError("bunny", "screen-space", both, nullptr, nullptr, nullptr, nullptr, true,
              Size, layers),
    0.65);
  EXPECT_GT(
    SpecularError("bunny", "screen-space", both, eye, focal, up, nullptr, true, Size, layers), 0.9);
  vtkNew<vtkCausticsScreenSpaceRefraction> stage;
  EXPECT_EQ(stage->GetExactSpecularGeometry(), vtkCausticsScreenSpaceRefraction::EXACT_AUTOMATIC);
}

// The glass's internal reflections, on by default: the ball lens seen from beside and
// from below, where much of what its glass shows has been reflected inside it once. With
// them off (the default until 2026-12-05, for speed) the glass was 22 and 34 % too dark
// on average; the default camera, looking down on the ball, hardly shows it (both view
// 11.8 % off, 11.2 % on). Relative L2, combined view, 60 degrees: beside 11.7 % (off:
// 31.7 %), below 16.1 % (off: 47.4 %). Bounds just above; with the branch off the test
// asserts the loss it measures (a branch that stops working fails it).
TEST(SpecularAppearance, InternalReflectionsLightGlassSeenFromBesideAndBelow)
{
  const int both = vtkCausticsRenderPass::BOTH;
  const double up[3] = { 0.0, 1.0, 0.0 };
  const double beside[3] = { 6.0, 1.0, 0.0 }, besideFocal[3] = { 0.0, 2.0, 0.0 };
  const double below[3] = { 0.0, 0.5, 4.0 }, belowFocal[3] = { 0.0, 2.5, 0.0 };
  const double on[2] = {
    SpecularError("ball-lens", "screen-space", both, beside, besideFocal, up, nullptr, true),
    SpecularError("ball-lens", "screen-space", both, below, belowFocal, up, nullptr, true)
  };
  const double off[2] = {
    SpecularError("ball-lens", "screen-space", both, beside, besideFocal, up, nullptr, false),
    SpecularError("ball-lens", "screen-space", both, below, belowFocal, up, nullptr, false)
  };
  EXPECT_LT(on[0], 0.12);
  EXPECT_LT(on[1], 0.165);
  EXPECT_GT(off[0], 0.3);
  EXPECT_GT(off[1], 0.45);
  vtkNew<vtkCausticsScreenSpaceRefraction> stage;
  EXPECT_TRUE(stage->GetInternalReflections()) << "the default";
}

// The default camera view (internal reflections on) on the ball lens. Measured:
// screen-space view 27.0 %, impostors 8.4 %, both 11.2 % (with internal reflections
// off, the default until 2026-12-05: 27.6, 9.2 and 11.8 %); bounds just above.
TEST(SpecularAppearance, DefaultView)
{
  const int methods[3] = { vtkCausticsRenderPass::SCREEN_SPACE,
    vtkCausticsRenderPass::DISTANCE_IMPOSTORS, vtkCausticsRenderPass::BOTH };
  const double bounds[3] = { 0.275, 0.09, 0.115 };
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_LT(SpecularError("ball-lens", "screen-space", methods[k]), bounds[k]);
  }
}

// The same at the issue's 256 x 256 pixels, default settings: the impostor view 8.1 %
// and the combined view (the default) 6.3 %, the issue's 10 % (with
// internal reflections off: the impostor view 8.9 % and the combined view 7.3 %; the
// screen-space view 26.8 %; the reference's own noise 3.7 %). The ring's mirror wall
// and the bunny are not reached at this size either (scripts/specular-error-map.py
// with SPECULAR_MAP_SIZE=256). Bounds just above.
TEST(SpecularAppearance, DefaultViewAtTheIssuesSize)
{
  EXPECT_LT(SpecularError("ball-lens", "screen-space", vtkCausticsRenderPass::DISTANCE_IMPOSTORS,
              nullptr, nullptr, nullptr, nullptr, true, 256),
    0.085);
  EXPECT_LT(SpecularError("ball-lens", "screen-space", vtkCausticsRenderPass::BOTH, nullptr,
              nullptr, nullptr, nullptr, true, 256),
    0.066);
}

// A camera inside the ball lens's glass (n = 1.5, centre (0, 3, 0), radius 1), off its
// centre: every pixel sees the floor through the glass's inner surface, where light
// leaves the glass (index 1.5 into 1), bent away from the normal. The stage knows the
// eye's medium from the refractors' winding number at the eye. Before, it took that
// surface as an entry from air, and so did the reference (it turned every first hit's
// normal to the camera), which hid the error: against the corrected reference the old
// stage is 60.4 % (screen-space view) and 46.1 % (impostor view). Reached: 16.9 % and
// 7.2 % (17.0 % and 7.5 % against the 64-path reference;
// scripts/camera-inside-glass.py prints them and writes the images); the
// screen-space view's rays that leave the screen see the background. Bounds just above.
TEST(SpecularAppearance, CameraInsideTheGlass)
{
  const double eye[3] = { 0.35, 3.4, 0.25 };
  EXPECT_LT(
    SpecularError("ball-lens", "screen-space", vtkCausticsRenderPass::SCREEN_SPACE, eye), 0.17);
  EXPECT_LT(
    SpecularError("ball-lens", "screen-space", vtkCausticsRenderPass::DISTANCE_IMPOSTORS, eye),
    0.062);
}

// A camera under the pool's open water sheet (index 1.33, one surface at y ~ 1, its
// normal up, the water below it), looking up at it obliquely: inside Snell's window
// the walls above the water and the sky (the background), outside it the floor by
// total internal reflection. The reference leaves the water there (the ray meets the
// sheet's back side); the sheet has no winding number of 1 anywhere, so the stage
// took it as an entry from air (89.6 %, screen-space view; 88.1 %, impostor view)
// until each pixel read the eye's medium from the side of the first refractor surface
// it sees. Reached: 70.4 % and 44.6 % (scripts/camera-inside-glass.py --scene pool
// prints the same and writes the images). The screen-space view's reflected rays head
// down to a floor behind the camera, out of the view: they see the background (the
// view's mean is 36 % under the reference's; the impostors' 4 % over it). The
// impostor view follows the floor's tiles in the waves but blurs their reflection.
// Since the water's triangles are traced (a sheet is not a convex solid) and hits the
// camera sees are shaded bilinearly: 69.5 % and 27.4 %; with the caustic store's shadow
// edges kept (ImpostorCausticIrradiance), 27.1 %. Bounds just above.
TEST(SpecularAppearance, CameraUnderTheWaterSheet)
{
  const double eye[3] = { 0.5, 0.4, 0.8 }, focal[3] = { -0.4, 1.0, -0.6 },
               up[3] = { 0.0, 1.0, 0.0 };
  EXPECT_LT(
    SpecularError("pool", "screen-space", vtkCausticsRenderPass::SCREEN_SPACE, eye, focal, up),
    0.70);
  EXPECT_LT(SpecularError(
              "pool", "screen-space", vtkCausticsRenderPass::DISTANCE_IMPOSTORS, eye, focal, up),
    0.275);
}

// A second framing, not designed around: low, near a corner, looking across the pool
// at the far wall's waterline, mostly total internal reflection at grazing angles.
// Measured, not bounded: 88.8 % before and 77.8 % after (screen-space view), 88.1 %
// and 70.3 % (impostor view); 72.2 % and 56.5 % since the water's triangles are traced
// and hits the camera sees are shaded bilinearly (2026-12-05).
TEST(SpecularAppearance, DISABLED_CameraUnderTheWaterSheetAcross)
{
  const double eye[3] = { -1.4, 0.25, -1.2 }, focal[3] = { 1.5, 1.1, 1.0 },
               up[3] = { 0.0, 1.0, 0.0 };
  SpecularError("pool", "screen-space", vtkCausticsRenderPass::SCREEN_SPACE, eye, focal, up);
  SpecularError("pool", "screen-space", vtkCausticsRenderPass::DISTANCE_IMPOSTORS, eye, focal, up);
}

// A camera beside an open sheet, beyond its edge (PopulateWideSheet: the sheet spans
// x in [-3, 3]; the eye at x = 4). Below the sheet's plane it sees the sheet's back
// side: the reference leaves the water there, and so does the stage, though no water
// is modelled around the eye (the rule reads the sheet's facing, not a volume). Before
// the per-pixel rule: 86.2 % (screen-space view) and 85.6 % (impostor view); reached:
// 22.8 % and 14.4 %. Above the plane it sees the front, an entry from air, unchanged by
// the rule: 15.4 % and 17.5 % (16.6 % and 18.7 % against the 64-path reference). With
// the caustic store filled by the screen-space photons, the impostor view gives 14.7 %
// below and 16.7 % above (18.7 % and 26.0 % when the store was read through its fine
// window alone: a few thousand photons and shadow samples over 65 536 floor texels).
// Since the photons are aimed at the part of the sheet whose light the camera sees
// (vtkCausticsLightBuffers FOCUS_SEEN: x -0.94 to 1.31, z -1.13 to 1.31 of the 6 m
// sheet), about 12 times as many land on the floor, enough for the store's fine window
// (CausticSamples 8), where the photons' flux and the shadow samples' negative flux,
// two lattices aliasing with the texels, cancel to the sheet's (T - 1) E plus that
// noise: 16.7 % below and 19.1 % above in the impostor view (the screen-space view
// is unchanged). More samples per window trade it against the ring's sharp caustic
// (CausticSamples 24: 15.5 %, 17.5 %, ring 19.9 %; 48: 14.9 %, 16.8 %, ring 20.0 %).
// With the shadow out of the store (the maps' radiance shadowed by the shadow maps, the
// store holding the photons alone): 15.6 % and 18.2 %. Since the sheet's triangles are
// traced and hits the camera sees are shaded bilinearly: below 21.4 % (screen-space)
// and 13.2 % (impostors), above 15.2 % and 18.1 %. Since the reference's estimate holds
// up to a receiver's end (docs/reference.md): below 22.7 % and 15.8 %, above 21.7 % and
// 17.2 %. The 2 m floor, seen through the sheet from 4 m, is a band a few pixels tall
// in the camera's own view, where the screen-space photons splat: their kernels reach
// past its edges on most of its pixels (the reference used to lose that light too).
// Since the splats keep their flux at a receiver's end (docs/accuracy.md, "Kernels at a
// receiver's end"): below 23.1 % and 15.6 %, above 23.8 % and 18.8 %. Above got worse:
// the screen-space photons do not fall as the world-space ones do along the floor's
// edges. On the same floor and sheet seen from the same place
// (scripts/kernel-ends.py, scene "sheet"), their last row at the floor's near edge read
// 0.99 of the reference with no correction, and the one at its far edge 0.66, where
// cascaded and impostor photons read 0.77 and 0.79 at the near edge and 0.95 and 0.91
// at the far: the near edge's light the screen-space splats did not lose is now
// divided by its kernels' share. Bounds just above.
TEST(SpecularAppearance, CameraBesideTheWaterSheet)
{
  const int screen = vtkCausticsRenderPass::SCREEN_SPACE;
  const int impostors = vtkCausticsRenderPass::DISTANCE_IMPOSTORS;
  const double up[3] = { 0.0, 1.0, 0.0 };
  const double below[3] = { 4.0, 0.6, 0.3 }, towardsTheSheet[3] = { 1.0, 1.0, 0.0 };
  EXPECT_LT(SpecularError("sheet, beside below", "screen-space", screen, below, towardsTheSheet, up,
              PopulateWideSheet),
    0.235);
  EXPECT_LT(SpecularError("sheet, beside below", "screen-space", impostors, below, towardsTheSheet,
              up, PopulateWideSheet),
    0.159);
  const double above[3] = { 4.0, 1.6, 0.3 }, origin[3] = { 0.0, 0.0, 0.0 };
  EXPECT_LT(SpecularError(
              "sheet, beside above", "screen-space", screen, above, origin, up, PopulateWideSheet),
    0.242);
  EXPECT_LT(SpecularError("sheet, beside above", "screen-space", impostors, above, origin, up,
              PopulateWideSheet),
    0.192);
}

// The combined view (the default) on framings no other test has, where the screen-space
// march passes behind what the camera sees: in the pool's water, rays head for the
// near wall's inner face, hidden behind its top and outer face; inside the ring, rays
// the far wall sends back head for the floor the near wall hides. The march took the
// hidden surface's occluder for the hit (a wall's top, or the mirror's outer face met
// from behind): the pool's water showed a tenth of its light. It now hands such rays
// to the impostors, as it does rays that leave the view, and the caustic store is read
// over the pixel's footprint (a focus seen in the ring's convex outer wall read its
// peak: one pixel at 12 times the reference's). Relative L2, default settings, 128^2,
// 60 degrees; before (scripts/specular-error-map.py --methods 2 --view-angle 60
// --camera EYE:FOCAL, the same framings): 97.3 %, 59.7 %, 38.3 %, 65.0 %; reached:
// 43.0 %, 32.7 %, 22.4 %, 26.1 %; since the shadow test keeps the ring's floor at the
// wall's foot in its shadow, the water's and the ring's triangles are traced and hits
// the camera sees are shaded bilinearly (2026-12-05): 42.7 %, 30.3 %, 12.2 %, 20.5 %;
// since the caustic store's coarse cells no longer carry a lit floor's light into the
// shadow beside it (ImpostorCausticIrradiance): 41.3 %, 30.3 %, 11.3 %, 18.8 %.
// Bounds just above. What is left on the pool is grazing water 19 % too bright in both
// views (not looked into).
TEST(SpecularAppearance, CombinedViewWhereTheMarchPassesBehindASurface)
{
  const int both = vtkCausticsRenderPass::BOTH;
  const double up[3] = { 0.0, 1.0, 0.0 };
  struct Framing
  {
    const char* scene;
    double eye[3], focal[3];
    double bound;
  };
  const Framing framings[] = {
    { "pool", { -5.0, 2.5, 1.0 }, { 0.0, 0.5, 0.0 }, 0.42 },
    { "pool", { 4.0, 3.5, -4.0 }, { 0.0, 0.5, 0.0 }, 0.31 },
    { "ring", { 3.0, 1.0, -2.0 }, { 0.0, 0.3, 0.0 }, 0.118 },
    { "ring", { -1.5, 1.2, 2.8 }, { 0.3, 0.3, -0.2 }, 0.195 },
  };
  for (const Framing& f : framings)
  {
    EXPECT_LT(SpecularError(f.scene, "screen-space", both, f.eye, f.focal, up),
      f.bound)
      << f.scene << " from " << f.eye[0] << ", " << f.eye[1] << ", " << f.eye[2];
  }
}
