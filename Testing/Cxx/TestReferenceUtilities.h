/**
 * Helpers shared by the TestReference*.cxx tests: scene building blocks with VTK
 * actors (so the reference sees scenes through vtkCausticsSceneExtractor, as the GPU
 * passes do), pixel access, and textbook optics written independently of
 * vtkCausticsReferenceCore so that tests never check the reference against itself.
 */
#ifndef TestReferenceUtilities_h
#define TestReferenceUtilities_h

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCylinderSource.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTriangleFilter.h"

#include <cmath>
#include <string>

namespace reftest
{
const double Pi = 3.14159265358979323846;

inline vtkSmartPointer<vtkActor> MakeActor(vtkPolyData* polyData, const char* name)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(polyData);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  vtkCausticsMaterial::SetName(actor, name);
  return actor;
}

/** Diffuse receiver quad at height y covering [-half, half]^2 in x and z, normal +y. */
inline vtkSmartPointer<vtkActor> Floor(double half, double y = 0.0, double albedo = 0.8)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-half, y, half);
  plane->SetPoint1(half, y, half);
  plane->SetPoint2(-half, y, -half);
  plane->Update();
  auto actor = MakeActor(plane->GetOutput(), "floor");
  actor->GetProperty()->SetColor(albedo, albedo, albedo);
  actor->GetProperty()->SetDiffuse(1.0);
  return actor;
}

/** Directional light travelling along `direction` with irradiance E (W/m^2). */
inline vtkSmartPointer<vtkLight> Directional(double dx, double dy, double dz, double irradiance)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetPosition(-dx, -dy, -dz);
  light->SetFocalPoint(0, 0, 0);
  light->SetIntensity(irradiance);
  return light;
}

inline void SetCamera(vtkRenderer* renderer, const double position[3], const double focal[3],
  const double up[3], double angle)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(position[0], position[1], position[2]);
  camera->SetFocalPoint(focal[0], focal[1], focal[2]);
  camera->SetViewUp(up[0], up[1], up[2]);
  camera->SetViewAngle(angle);
  camera->OrthogonalizeViewUp();
  camera->SetClippingRange(0.1, 100.0);
}

/**
 * The mirror cup (issue 13; TestMirrorCup, TestImpostorPhotonPass): an open silver
 * cylinder (n 0.15, k 3.5), 1 m tall and 1 m in radius, 256 sides, no caps, on a
 * 4 x 4 m floor (VTK's default white), under a sun 30 degrees above it (intensity 1),
 * seen from above (view 0) or obliquely (view 1) through a 40-degree camera.
 */
inline void MirrorCupScene(vtkRenderer* renderer, int view)
{
  vtkNew<vtkPlaneSource> floor;
  floor->SetOrigin(-2, 0, 2);
  floor->SetPoint1(2, 0, 2);
  floor->SetPoint2(-2, 0, -2);
  floor->Update();
  vtkNew<vtkPolyDataMapper> floorMapper;
  floorMapper->SetInputData(floor->GetOutput());
  vtkNew<vtkActor> floorActor;
  floorActor->SetMapper(floorMapper);
  renderer->AddActor(floorActor);
  vtkNew<vtkCylinderSource> wall;
  wall->SetRadius(1.0);
  wall->SetHeight(1.0);
  wall->SetCenter(0, 0.5, 0);
  wall->SetResolution(256);
  wall->CappingOff();
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(wall->GetOutputPort());
  triangles->Update();
  vtkNew<vtkPolyDataMapper> cupMapper;
  cupMapper->SetInputData(triangles->GetOutput());
  vtkNew<vtkActor> cup;
  cup->SetMapper(cupMapper);
  const double n[3] = { 0.15, 0.15, 0.15 }, k[3] = { 3.5, 3.5, 3.5 }; // silver-like
  vtkCausticsMaterial::MakeMirror(cup->GetProperty(), n, k);
  renderer->AddActor(cup);
  vtkNew<vtkLight> sun;
  sun->SetLightTypeToSceneLight();
  sun->SetPositional(false);
  sun->SetFocalPoint(0, 0, 0);
  sun->SetPosition(-std::cos(Pi / 6.0), std::sin(Pi / 6.0), 0);
  sun->SetIntensity(1.0);
  renderer->AddLight(sun);
  vtkCamera* camera = renderer->GetActiveCamera();
  if (view == 0)
  {
    camera->SetPosition(0, 4, 0.01);
  }
  else
  {
    camera->SetPosition(2.5, 3, 2.5);
  }
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 0, -1);
  camera->SetViewAngle(40);
  renderer->ResetCameraClippingRange();
}

/** A renderer of the reference set up for tests: no cache, fixed seed, all cores. */
inline vtkSmartPointer<vtkCausticsReferenceRenderer> MakeReference(
  vtkRenderer* renderer, int width, int height, vtkIdType photons)
{
  auto reference = vtkSmartPointer<vtkCausticsReferenceRenderer>::New();
  reference->SetInputRenderer(renderer);
  reference->SetImageSize(width, height);
  reference->SetPhotonsPerLight(photons);
  reference->UseCacheOff();
  return reference;
}

/** Component c of array `name` at pixel (i, j) (j counted from the bottom). */
inline double At(vtkImageData* image, const char* name, int i, int j, int c = 0)
{
  int dims[3];
  image->GetDimensions(dims);
  return image->GetPointData()->GetArray(name)->GetComponent(
    static_cast<vtkIdType>(j) * dims[0] + i, c);
}

// --- Textbook optics, independent of the reference's own implementation ---

/** Fresnel's sine and tangent laws (unpolarized average) for a refracted ray. */
inline double FresnelLaws(double thetaI, double etaI, double etaT)
{
  if (thetaI < 1e-9)
  {
    const double r = (etaI - etaT) / (etaI + etaT);
    return r * r;
  }
  const double sinT = etaI / etaT * std::sin(thetaI);
  if (sinT >= 1.0)
  {
    return 1.0;
  }
  const double thetaT = std::asin(sinT);
  const double s = std::sin(thetaI - thetaT) / std::sin(thetaI + thetaT);
  const double p = std::tan(thetaI - thetaT) / std::tan(thetaI + thetaT);
  return 0.5 * (s * s + p * p);
}

/**
 * Conductor reflectance in the real-valued form of Born and Wolf (as used by
 * Cook-Torrance): a^2 + b^2 = sqrt((n^2 - k^2 - sin^2)^2 + 4 n^2 k^2).
 */
inline double ConductorLaws(double thetaI, double n, double k)
{
  const double c = std::cos(thetaI), s2 = 1.0 - c * c;
  const double t0 = n * n - k * k - s2;
  const double a2b2 = std::sqrt(t0 * t0 + 4.0 * n * n * k * k);
  const double a = std::sqrt(std::max(0.0, 0.5 * (a2b2 + t0)));
  const double rs = (a2b2 - 2.0 * a * c + c * c) / (a2b2 + 2.0 * a * c + c * c);
  const double tanT = s2 > 0.0 ? s2 / c : 0.0; // sin * tan
  const double rp =
    rs * (a2b2 - 2.0 * a * tanT + tanT * tanT) / (a2b2 + 2.0 * a * tanT + tanT * tanT);
  return 0.5 * (rs + rp);
}
}

#endif
