#include "StressScene.h"

#include "vtkCausticsMaterial.h"
#include "vtkCausticsMedium.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

namespace stress
{
namespace
{
using Point = std::array<double, 3>;

/** A unit vector, uniform on the sphere. */
Point Direction(Random& random)
{
  const double z = random.Uniform(-1.0, 1.0), phi = random.Uniform(0.0, 2.0 * M_PI);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return { r * std::cos(phi), r * std::sin(phi), z };
}

vtkSmartPointer<vtkPolyData> Sphere(Random& random)
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(random.Integer(4, 24));
  source->SetPhiResolution(random.Integer(3, 16));
  source->SetRadius(1.0);
  source->Update();
  vtkSmartPointer<vtkPolyData> sphere = source->GetOutput();
  sphere->GetPointData()->SetTCoords(nullptr); // Break() adds points: keep arrays whole
  return sphere;
}

vtkSmartPointer<vtkPolyData> Box()
{
  vtkNew<vtkCubeSource> source;
  source->SetXLength(2.0);
  source->SetYLength(2.0);
  source->SetZLength(2.0);
  source->Update();
  vtkSmartPointer<vtkPolyData> box = source->GetOutput();
  box->GetPointData()->SetTCoords(nullptr); // Break() adds points: keep arrays whole
  return box;
}

/** A sphere whose vertices moved by up to 30 % of its radius (normals kept: inconsistent). */
vtkSmartPointer<vtkPolyData> JitteredSphere(Random& random)
{
  auto mesh = Sphere(random);
  vtkPoints* points = mesh->GetPoints();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    const double f = random.Uniform(0.7, 1.3);
    points->SetPoint(i, p[0] * f, p[1] * f, p[2] * f);
  }
  return mesh;
}

/** Random triangles in the unit cube around the origin, one normal per corner. */
vtkSmartPointer<vtkPolyData> TriangleSoup(Random& random)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  normals->SetName("Normals");
  vtkNew<vtkCellArray> cells;
  const int count = random.Integer(1, 40);
  for (int t = 0; t < count; ++t)
  {
    const Point n = Direction(random);
    vtkIdType ids[3];
    for (vtkIdType& id : ids)
    {
      id = points->InsertNextPoint(
        random.Uniform(-1.0, 1.0), random.Uniform(-1.0, 1.0), random.Uniform(-1.0, 1.0));
      normals->InsertNextTuple3(n[0], n[1], n[2]);
    }
    cells->InsertNextCell(3, ids);
  }
  auto soup = vtkSmartPointer<vtkPolyData>::New();
  soup->SetPoints(points);
  soup->SetPolys(cells);
  soup->GetPointData()->SetNormals(normals);
  return soup;
}

/** Adds a zero-area triangle, a triangle with a NaN corner and NaN normals. */
void Break(Random& random, vtkPolyData* mesh, std::ostringstream& text)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  vtkPoints* points = mesh->GetPoints();
  vtkDataArray* normals = mesh->GetPointData()->GetNormals();
  vtkIdType same[3], withNaN[3];
  for (int k = 0; k < 3; ++k)
  {
    same[k] = points->InsertNextPoint(0.1, 0.2, 0.3);
    withNaN[k] = points->InsertNextPoint(k == 1 ? nan : 0.5, 0.5 * k, -0.5);
    if (normals)
    {
      normals->InsertNextTuple3(0.0, 1.0, 0.0);
      normals->InsertNextTuple3(0.0, 1.0, 0.0);
    }
  }
  mesh->GetPolys()->InsertNextCell(3, same);
  mesh->GetPolys()->InsertNextCell(3, withNaN);
  if (normals && random.Chance(0.5))
  {
    normals->SetTuple3(0, nan, nan, nan);
    normals->SetTuple3(normals->GetNumberOfTuples() / 2, nan, 0.0, 1.0);
  }
  mesh->Modified();
  text << "+broken";
}

vtkSmartPointer<vtkActor> Place(
  vtkRenderer* renderer, vtkPolyData* mesh, const Point& centre, double size, Random& random)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(mesh);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->SetPosition(centre[0], centre[1], centre[2]);
  actor->SetScale(size);
  actor->SetOrientation(
    random.Uniform(0.0, 360.0), random.Uniform(0.0, 360.0), random.Uniform(0.0, 360.0));
  actor->GetProperty()->SetAmbient(0.0);
  actor->GetProperty()->SetSpecular(0.0);
  renderer->AddActor(actor);
  return actor;
}

/** One random shape: sphere, box, jittered sphere or triangle soup (the last two rarer). */
vtkSmartPointer<vtkPolyData> Shape(Random& random, std::ostringstream& text)
{
  const double pick = random.Uniform();
  if (pick < 0.4)
  {
    text << "sphere";
    return Sphere(random);
  }
  if (pick < 0.7)
  {
    text << "box";
    return Box();
  }
  if (pick < 0.85)
  {
    text << "blob";
    return JitteredSphere(random);
  }
  text << "soup";
  return TriangleSoup(random);
}

/** Glass (IOR 1 to 4) or mirror objects above the floor; returns their centres. */
std::vector<Point> AddSpecular(
  Random& random, vtkRenderer* renderer, double s, std::ostringstream& text)
{
  std::vector<Point> centres;
  const int count = random.Chance(0.1) ? 0 : random.Integer(1, 3);
  for (int i = 0; i < count; ++i)
  {
    text << " ";
    auto mesh = Shape(random, text);
    if (random.Chance(0.1))
    {
      Break(random, mesh, text);
    }
    const Point centre{ random.Uniform(-2.0, 2.0) * s, random.Uniform(0.5, 3.0) * s,
      random.Uniform(-2.0, 2.0) * s };
    auto actor = Place(renderer, mesh, centre, random.Uniform(0.2, 1.0) * s, random);
    if (random.Chance(0.75))
    {
      const double ior = random.Uniform(1.0, 4.0);
      vtkCausticsMaterial::MakeGlass(actor->GetProperty(), ior);
      text << "(glass " << ior << ")";
    }
    else
    {
      const double n[3] = { 0.155, 0.117, 0.138 }, k[3] = { 4.83, 3.12, 2.15 };
      vtkCausticsMaterial::MakeMirror(actor->GetProperty(), n, k);
      text << "(mirror)";
    }
    centres.push_back(centre);
  }
  return centres;
}

/** A floor (usually) and up to two diffuse shapes standing on it. */
void AddReceivers(Random& random, vtkRenderer* renderer, double s, std::ostringstream& text)
{
  if (random.Chance(0.85))
  {
    vtkNew<vtkPlaneSource> floor;
    floor->SetOrigin(-5.0 * s, 0.0, 5.0 * s);
    floor->SetPoint1(5.0 * s, 0.0, 5.0 * s);
    floor->SetPoint2(-5.0 * s, 0.0, -5.0 * s);
    floor->Update();
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(floor->GetOutput());
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetAmbient(0.0);
    renderer->AddActor(actor);
    text << " floor";
  }
  const int count = random.Integer(0, 2);
  for (int i = 0; i < count; ++i)
  {
    text << " diffuse-";
    auto mesh = Shape(random, text);
    if (random.Chance(0.1))
    {
      Break(random, mesh, text);
    }
    const Point centre{ random.Uniform(-3.0, 3.0) * s, random.Uniform(0.0, 1.0) * s,
      random.Uniform(-3.0, 3.0) * s };
    Place(renderer, mesh, centre, random.Uniform(0.2, 1.5) * s, random);
  }
}

/** One light: directional (some grazing), point or spot (some inside a specular object). */
void AddLight(Random& random, vtkRenderer* renderer, double s, const std::vector<Point>& centres,
  std::ostringstream& text)
{
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetColor(random.Uniform(0.2, 1.0), random.Uniform(0.2, 1.0), random.Uniform(0.2, 1.0));
  const double pick = random.Uniform();
  if (pick < 0.45)
  {
    const bool grazing = random.Chance(0.3);
    const double elevation = (grazing ? random.Uniform(0.01, 1.0) : random.Uniform(5.0, 90.0));
    const double azimuth = random.Uniform(0.0, 2.0 * M_PI), e = elevation * M_PI / 180.0;
    light->SetPositional(false);
    light->SetPosition(
      std::cos(e) * std::cos(azimuth) * s, std::sin(e) * s, std::cos(e) * std::sin(azimuth) * s);
    light->SetFocalPoint(0.0, 0.0, 0.0);
    light->SetIntensity(random.Uniform(0.1, 10.0));
    text << " directional" << (grazing ? "(grazing " : "(") << elevation << " deg)";
    renderer->AddLight(light);
    return;
  }
  const bool inside = !centres.empty() && random.Chance(0.25);
  const Point at = inside ? centres[random.Integer(0, static_cast<int>(centres.size()) - 1)]
                          : Point{ random.Uniform(-3.0, 3.0) * s, random.Uniform(1.0, 6.0) * s,
                              random.Uniform(-3.0, 3.0) * s };
  light->SetPositional(true);
  light->SetPosition(at[0], at[1], at[2]);
  light->SetFocalPoint(
    at[0] + random.Uniform(-1.0, 1.0) * s, at[1] - s, at[2] + random.Uniform(-1.0, 1.0) * s);
  light->SetAttenuationValues(0.0, 0.0, 1.0);
  light->SetIntensity(random.Uniform(0.1, 10.0) * s * s);
  const bool spot = pick > 0.75;
  light->SetConeAngle(spot ? random.Uniform(5.0, 80.0) : 180.0);
  text << (spot ? " spot" : " point") << (inside ? "(inside)" : "");
  renderer->AddLight(light);
}

/** One input a user should not give: NaN, Inf, zero and absurd values. */
void Abuse(
  Random& random, vtkRenderer* renderer, double s, std::ostringstream& text, SceneSummary& summary)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(true);
  light->SetPosition(0.0, 3.0 * s, 0.0);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  light->SetAttenuationValues(0.0, 0.0, 1.0);
  auto actor = Place(renderer, Sphere(random), { 0.0, 1.5 * s, 0.0 }, 0.5 * s, random);
  vtkCausticsMaterial::MakeGlass(actor->GetProperty(), 1.5);
  switch (random.Integer(0, 6))
  {
    case 0:
      light->SetIntensity(nan);
      text << " abuse:light-intensity-NaN";
      summary.VtkShadesNaN = true;
      break;
    case 1:
      light->SetPosition(inf, 3.0 * s, 0.0);
      text << " abuse:light-at-Inf";
      summary.VtkShadesNaN = true;
      break;
    case 2:
      light->SetIntensity(1e30);
      text << " abuse:light-of-1e30-W/sr";
      break;
    case 3:
      actor->GetProperty()->SetBaseIOR(nan);
      text << " abuse:IOR-NaN";
      break;
    case 4:
      actor->SetScale(0.0);
      text << " abuse:scale-0";
      break;
    case 5:
      actor->SetPosition(nan, 0.0, 0.0);
      text << " abuse:actor-at-NaN";
      break;
    default:
      actor->GetProperty()->SetBaseIOR(1e6);
      text << " abuse:IOR-1e6";
      break;
  }
  renderer->AddLight(light);
}

/** Perspective or parallel, from any side, sometimes looking away from everything. */
void SetCamera(Random& random, vtkRenderer* renderer, double s, std::ostringstream& text)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  Point d = Direction(random);
  d[1] = std::abs(d[1]) * (random.Chance(0.9) ? 1.0 : -1.0); // mostly from above
  const double distance = random.Uniform(3.0, 12.0) * s;
  const Point eye{ d[0] * distance, d[1] * distance + 0.5 * s, d[2] * distance };
  const bool away = random.Chance(0.1);
  const double sign = away ? 2.0 : -1.0;
  camera->SetPosition(eye[0], eye[1], eye[2]);
  camera->SetFocalPoint(eye[0] + sign * d[0] * distance, eye[1] + sign * d[1] * distance,
    eye[2] + sign * d[2] * distance);
  camera->SetViewUp(std::abs(d[1]) > 0.99 ? 1.0 : 0.0, std::abs(d[1]) > 0.99 ? 0.0 : 1.0, 0.0);
  camera->OrthogonalizeViewUp();
  const bool parallel = random.Chance(0.3);
  camera->SetParallelProjection(parallel);
  camera->SetParallelScale(random.Uniform(1.0, 6.0) * s);
  camera->SetViewAngle(random.Uniform(10.0, 100.0));
  renderer->ResetCameraClippingRange();
  text << (parallel ? " parallel" : " perspective") << (away ? "-away" : "");
}
}

SceneSummary MakeScene(std::uint64_t seed, vtkRenderer* renderer)
{
  Random random(seed);
  SceneSummary summary;
  std::ostringstream text;
  text.precision(3);
  summary.Scale = std::pow(10.0, random.Uniform(-3.0, 4.0));
  summary.Width = random.Integer(48, 128);
  summary.Height = random.Integer(48, 128);
  const int photons[] = { 16, 32, 48, 64 };
  summary.Photons = photons[random.Integer(0, 3)];
  const double s = summary.Scale;
  text << "scale " << s << ", " << summary.Width << "x" << summary.Height << " px, "
       << summary.Photons << "^2 photons:";
  renderer->AutomaticLightCreationOff();
  if (random.Chance(0.04))
  {
    text << " empty";
  }
  else
  {
    const std::vector<Point> centres = AddSpecular(random, renderer, s, text);
    AddReceivers(random, renderer, s, text);
    const int lights = random.Chance(0.08) ? 0 : random.Integer(1, 3);
    for (int i = 0; i < lights; ++i)
    {
      AddLight(random, renderer, s, centres, text);
    }
  }
  if (random.Chance(0.08))
  {
    Abuse(random, renderer, s, text, summary);
  }
  if (random.Chance(0.1))
  {
    vtkNew<vtkCausticsMedium> medium;
    medium->SetScatteringCoefficient(
      random.Uniform(0.0, 0.3) / s, random.Uniform(0.0, 0.3) / s, random.Uniform(0.0, 0.3) / s);
    medium->SetAbsorptionCoefficient(random.Uniform(0.0, 0.1) / s, 0.0, 0.0);
    vtkCausticsMedium::AttachTo(renderer, medium);
    text << " medium";
  }
  SetCamera(random, renderer, s, text);
  if (random.Chance(0.03))
  {
    // More photons than llvmpipe's storage blocks hold for the screen-space and
    // caustic-map techniques: they must refuse the frame in one line.
    summary.Photons = 8192;
    text << " abuse:8192^2-photons";
  }
  summary.Text = text.str();
  return summary;
}
}
