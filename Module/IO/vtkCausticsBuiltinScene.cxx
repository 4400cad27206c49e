#include "vtkCausticsBuiltinScene.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsMedium.h"
#include "vtkCausticsMeshReader.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCellArray.h"
#include "vtkCylinderSource.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleKey.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyDataNormals.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtksys/SystemTools.hxx"

#include <cmath>
#include <dlfcn.h> // For dladdr: where this library lives

vtkStandardNewMacro(vtkCausticsBuiltinScene);

namespace
{
// Waves of the pool's water: amplitude (m), wavelength (m), heading (degrees), phase.
struct Wave
{
  double amplitude, wavelength, heading, phase;
};
const Wave PoolWaves[] = { { 0.020, 1.30, 20.0, 0.0 }, { 0.015, 0.90, 75.0, 1.3 },
  { 0.010, 0.60, 140.0, 2.1 }, { 0.008, 0.45, 250.0, 4.0 } };
const double PoolHalfSize = 2.0;
const double PoolWaterLevel = 1.0;
const double PoolWallHeight = 1.5;

vtkSmartPointer<vtkActor> MakeActor(vtkPolyData* polyData, const std::string& name)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(polyData);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  vtkCausticsMaterial::SetName(actor, name);
  return actor;
}

void MakeDiffuse(vtkActor* actor, double r, double g, double b)
{
  vtkProperty* property = actor->GetProperty();
  property->SetColor(r, g, b);
  property->SetDiffuse(1.0);
  property->SetAmbient(0.0);
  property->SetSpecular(0.0);
}

/** A quad from origin spanning the two edge vectors, normals facing `normal`. */
vtkSmartPointer<vtkPolyData> Quad(
  const double origin[3], const double p1[3], const double p2[3], int resolution)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(origin[0], origin[1], origin[2]);
  plane->SetPoint1(p1[0], p1[1], p1[2]);
  plane->SetPoint2(p2[0], p2[1], p2[2]);
  plane->SetResolution(resolution, resolution);
  plane->Update();
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->DeepCopy(plane->GetOutput());
  return output;
}

/** A horizontal floor at height y covering [x0, x1] x [z0, z1], normal +y. */
vtkSmartPointer<vtkPolyData> Floor(double x0, double x1, double z0, double z1, double y)
{
  const double origin[3] = { x0, y, z1 };
  const double p1[3] = { x1, y, z1 };
  const double p2[3] = { x0, y, z0 };
  return Quad(origin, p1, p2, 1);
}

vtkSmartPointer<vtkLight> DirectionalLight(const double direction[3], double irradiance)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetFocalPoint(0, 0, 0);
  light->SetPosition(-direction[0], -direction[1], -direction[2]);
  light->SetColor(1, 1, 1);
  light->SetIntensity(irradiance);
  return light;
}

void SetCamera(vtkRenderer* renderer, const double position[3], const double focal[3], double angle)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(position[0], position[1], position[2]);
  camera->SetFocalPoint(focal[0], focal[1], focal[2]);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(angle);
  camera->OrthogonalizeViewUp();
  renderer->ResetCameraClippingRange();
}
/**
 * The data shipped with the module, found from where this library is loaded:
 * <libdir>/CAUSTICS_DATA_FROM_LIBRARY in an installed prefix, or
 * <build>/lib/../share/vtkcaustics/data in the build tree (copied there at
 * configure time). Empty when neither exists: then CAUSTICS_DATA_DIR or
 * SetDataDirectory() must say where the data is.
 */
std::string DataBesideLibrary()
{
  Dl_info info;
  if (dladdr(reinterpret_cast<void*>(&DataBesideLibrary), &info) == 0 || !info.dli_fname)
  {
    return std::string();
  }
  const std::string libraryDirectory = vtksys::SystemTools::GetFilenamePath(
    vtksys::SystemTools::CollapseFullPath(info.dli_fname));
  for (const char* relative : { CAUSTICS_DATA_FROM_LIBRARY, "../share/vtkcaustics/data" })
  {
    const std::string candidate =
      vtksys::SystemTools::CollapseFullPath(relative, libraryDirectory);
    if (vtksys::SystemTools::FileIsDirectory(candidate))
    {
      return candidate;
    }
  }
  return std::string();
}
}

struct vtkCausticsBuiltinScene::Internals
{
  vtkSmartPointer<vtkPolyData> Water; // pool only: updated in place by UpdateTime()
  int WaterResolution = 0;
};

vtkCausticsBuiltinScene::vtkCausticsBuiltinScene()
  : Internal(new Internals)
{
  this->DataDirectory = DataBesideLibrary();
  if (const char* dir = vtksys::SystemTools::GetEnv("CAUSTICS_DATA_DIR"))
  {
    this->DataDirectory = dir;
  }
}

vtkCausticsBuiltinScene::~vtkCausticsBuiltinScene() = default;

std::vector<std::string> vtkCausticsBuiltinScene::GetSceneNames()
{
  return { "ball-lens", "pool", "ring", "bunny", "underwater", "smoke-lens" };
}

bool vtkCausticsBuiltinScene::IsSceneName(const std::string& name)
{
  for (const auto& known : GetSceneNames())
  {
    if (known == name)
    {
      return true;
    }
  }
  return false;
}

bool vtkCausticsBuiltinScene::IsMediaScene(const std::string& name)
{
  return name == "underwater" || name == "smoke-lens";
}

namespace
{
/** Height field of the pool's water at time t, with analytic normals. */
void FillWater(vtkPolyData* water, int resolution, double time)
{
  vtkPoints* points = water->GetPoints();
  auto* normals = vtkFloatArray::SafeDownCast(water->GetPointData()->GetNormals());
  const double g = 9.81;
  vtkIdType id = 0;
  for (int j = 0; j <= resolution; ++j)
  {
    const double z = -PoolHalfSize + 2.0 * PoolHalfSize * j / resolution;
    for (int i = 0; i <= resolution; ++i, ++id)
    {
      const double x = -PoolHalfSize + 2.0 * PoolHalfSize * i / resolution;
      double height = PoolWaterLevel, dhdx = 0.0, dhdz = 0.0;
      for (const Wave& wave : PoolWaves)
      {
        const double k = 2.0 * vtkMath::Pi() / wave.wavelength;
        const double omega = std::sqrt(g * k); // deep-water dispersion
        const double heading = vtkMath::RadiansFromDegrees(wave.heading);
        const double kx = k * std::cos(heading), kz = k * std::sin(heading);
        const double argument = kx * x + kz * z - omega * time + wave.phase;
        height += wave.amplitude * std::sin(argument);
        dhdx += wave.amplitude * kx * std::cos(argument);
        dhdz += wave.amplitude * kz * std::cos(argument);
      }
      points->SetPoint(id, x, height, z);
      const double length = std::sqrt(dhdx * dhdx + 1.0 + dhdz * dhdz);
      normals->SetTuple3(id, -dhdx / length, 1.0 / length, -dhdz / length);
    }
  }
  points->Modified();
  normals->Modified();
  water->Modified();
}

vtkSmartPointer<vtkPolyData> MakeWater(int resolution, double time)
{
  auto water = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetNumberOfPoints((resolution + 1) * (resolution + 1));
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(points->GetNumberOfPoints());
  normals->SetName("Normals");
  vtkNew<vtkCellArray> triangles;
  for (int j = 0; j < resolution; ++j)
  {
    for (int i = 0; i < resolution; ++i)
    {
      const vtkIdType a = j * (resolution + 1) + i, b = a + 1, c = a + resolution + 1, d = c + 1;
      const vtkIdType t1[3] = { a, c, b }, t2[3] = { b, c, d };
      triangles->InsertNextCell(3, t1);
      triangles->InsertNextCell(3, t2);
    }
  }
  water->SetPoints(points);
  water->SetPolys(triangles);
  water->GetPointData()->SetNormals(normals);
  FillWater(water, resolution, time);
  return water;
}

/** The pool's floor: checker tiles, 0.25 m, as two receivers (per-mesh albedo). */
void AddPoolTiles(vtkRenderer* renderer)
{
  vtkNew<vtkAppendPolyData> light, dark;
  const int tiles = 16;
  const double tile = 2.0 * PoolHalfSize / tiles;
  for (int j = 0; j < tiles; ++j)
  {
    for (int i = 0; i < tiles; ++i)
    {
      const double x0 = -PoolHalfSize + i * tile, z0 = -PoolHalfSize + j * tile;
      ((i + j) % 2 ? dark : light)->AddInputData(Floor(x0, x0 + tile, z0, z0 + tile, 0.0));
    }
  }
  light->Update();
  dark->Update();
  auto lightTiles = MakeActor(light->GetOutput(), "light tiles");
  MakeDiffuse(lightTiles, 0.85, 0.85, 0.85);
  auto darkTiles = MakeActor(dark->GetOutput(), "dark tiles");
  MakeDiffuse(darkTiles, 0.25, 0.45, 0.65);
  renderer->AddActor(lightTiles);
  renderer->AddActor(darkTiles);
}

/** The pool's four walls, one receiver. */
void AddPoolWalls(vtkRenderer* renderer)
{
  vtkNew<vtkAppendPolyData> walls;
  const double h = PoolWallHeight, s = PoolHalfSize;
  const double corners[4][3][3] = { { { -s, 0, -s }, { s, 0, -s }, { -s, h, -s } },
    { { s, 0, s }, { -s, 0, s }, { s, h, s } }, { { -s, 0, s }, { -s, 0, -s }, { -s, h, s } },
    { { s, 0, -s }, { s, 0, s }, { s, h, -s } } };
  for (const auto& wall : corners)
  {
    walls->AddInputData(Quad(wall[0], wall[1], wall[2], 1));
  }
  walls->Update();
  auto wallActor = MakeActor(walls->GetOutput(), "walls");
  MakeDiffuse(wallActor, 0.7, 0.75, 0.8);
  renderer->AddActor(wallActor);
}

/** The bunny scaled to 0.8 m tall, standing centred on the floor, with smooth normals. */
vtkSmartPointer<vtkPolyData> PlaceBunny(vtkPolyData* raw)
{
  double bounds[6];
  raw->GetBounds(bounds);
  const double scale = 0.8 / (bounds[3] - bounds[2]); // 0.8 m tall
  vtkNew<vtkTransform> place;
  place->Translate(0.0, 1e-3, 0.0);
  place->Scale(scale, scale, scale);
  place->Translate(-0.5 * (bounds[0] + bounds[1]), -bounds[2], -0.5 * (bounds[4] + bounds[5]));
  vtkNew<vtkTransformPolyDataFilter> transform;
  transform->SetInputData(raw);
  transform->SetTransform(place);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(transform->GetOutputPort());
  normals->SplittingOff();
  normals->ConsistencyOn();
  normals->AutoOrientNormalsOn();
  normals->Update();
  return normals->GetOutput();
}

/** The bunny's Cornell box, 2 m, open at the front. */
void AddCornellBox(vtkRenderer* renderer)
{
  struct Wall
  {
    const char* name;
    double origin[3], p1[3], p2[3], color[3];
  };
  const Wall walls[] = { { "floor", { -1, 0, 1 }, { 1, 0, 1 }, { -1, 0, -1 },
                           { 0.75, 0.75, 0.75 } },
    { "ceiling", { -1, 2, -1 }, { 1, 2, -1 }, { -1, 2, 1 }, { 0.75, 0.75, 0.75 } },
    { "back wall", { -1, 0, -1 }, { 1, 0, -1 }, { -1, 2, -1 }, { 0.75, 0.75, 0.75 } },
    { "red wall", { -1, 0, 1 }, { -1, 0, -1 }, { -1, 2, 1 }, { 0.63, 0.065, 0.05 } },
    { "green wall", { 1, 0, -1 }, { 1, 0, 1 }, { 1, 2, -1 }, { 0.14, 0.45, 0.091 } } };
  for (const Wall& wall : walls)
  {
    auto actor = MakeActor(Quad(wall.origin, wall.p1, wall.p2, 1), wall.name);
    MakeDiffuse(actor, wall.color[0], wall.color[1], wall.color[2]);
    renderer->AddActor(actor);
  }
}

/** The Cornell box's ceiling spot: 2 W/sr, 50 degree cone, 40 degree inner cone. */
/**
 * A spot light straight down from (0, height, 0): `intensity` W/sr, physical 1/r^2,
 * glTF's falloff between `innerCone` and `cone` (degrees).
 */
vtkSmartPointer<vtkLight> DownwardSpot(double height, double cone, double innerCone, double intensity)
{
  auto spot = vtkSmartPointer<vtkLight>::New();
  spot->SetLightTypeToSceneLight();
  spot->SetPositional(true);
  spot->SetPosition(0.0, height, 0.0);
  spot->SetFocalPoint(0.0, 0.0, 0.0);
  spot->SetConeAngle(cone);
  spot->SetExponent(1.0);
  spot->SetAttenuationValues(0.0, 0.0, 1.0); // physical 1/r^2
  spot->SetColor(1, 1, 1);
  spot->SetIntensity(intensity); // W/sr
  vtkNew<vtkInformation> lightInfo;
  lightInfo->Set(vtkCausticsSceneExtractor::INNER_CONE_ANGLE(), innerCone);
  spot->SetInformation(lightInfo);
  return spot;
}

void AddCeilingSpot(vtkRenderer* renderer)
{
  renderer->AddLight(DownwardSpot(1.95, 50.0, 40.0, 2.0));
}

/**
 * A smooth pseudo-noise in [-1, 1]: a product of sines (no seed, the same everywhere;
 * Testing/CLI/MakeSmokePlume.cxx writes the same plume as a .vdb file).
 */
double Noise(double x, double y, double z, double frequency)
{
  return std::sin(3.1 * frequency * x + 1.7) * std::sin(2.3 * frequency * y + 0.4) *
    std::sin(2.9 * frequency * z + 2.2);
}

/**
 * A density on a regular grid of `voxel` metres over `box` (xmin, xmax, ymin, ymax,
 * zmin, zmax), one value per point from `density(x, y, z)`; zeros stay out of the
 * medium's sparse grid.
 */
template <typename Density>
vtkSmartPointer<vtkImageData> SampleDensity(const double box[6], double voxel, Density density)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  int dimensions[3];
  for (int a = 0; a < 3; ++a)
  {
    dimensions[a] = 1 + static_cast<int>(std::ceil((box[2 * a + 1] - box[2 * a]) / voxel));
  }
  image->SetDimensions(dimensions);
  image->SetOrigin(box[0], box[2], box[4]);
  image->SetSpacing(voxel, voxel, voxel);
  vtkNew<vtkFloatArray> values;
  values->SetName("density");
  values->SetNumberOfTuples(image->GetNumberOfPoints());
  vtkIdType id = 0;
  for (int k = 0; k < dimensions[2]; ++k)
  {
    for (int j = 0; j < dimensions[1]; ++j)
    {
      for (int i = 0; i < dimensions[0]; ++i, ++id)
      {
        values->SetValue(id,
          static_cast<float>(
            density(box[0] + i * voxel, box[2] + j * voxel, box[4] + k * voxel)));
      }
    }
  }
  image->GetPointData()->SetScalars(values);
  return image;
}

/** Attaches `density` as a medium with the given coefficients (1/m per unit density). */
vtkCausticsMedium* AttachMedium(vtkRenderer* renderer, vtkImageData* density,
  const double scattering[3], const double absorption[3], double g)
{
  vtkNew<vtkCausticsMedium> medium;
  medium->SetScatteringCoefficient(scattering[0], scattering[1], scattering[2]);
  medium->SetAbsorptionCoefficient(absorption[0], absorption[1], absorption[2]);
  medium->SetAnisotropy(g);
  medium->SetDensityData(density);
  vtkCausticsMedium::AttachTo(renderer, medium);
  return medium; // the renderer holds it
}

/**
 * The underwater scene's murky water: below the pool's surface, a plankton layer
 * (density peaking at 1, half a metre down, 0.25 m thick) in lumps of a smooth noise,
 * over a faint haze (0.05). Sea water's colours: red absorbed most. The medium fills
 * the water (vtkCausticsMedium::FillsRefractors): the light the waves focus scatters
 * in it, the god rays of a camera under water.
 */
void AttachPlankton(vtkRenderer* renderer)
{
  // Under the deepest trough (the amplitudes sum to 0.053 m) by a voxel more: the
  // grid's last samples and the half voxel around them stay in the water, the air
  // above holds no medium.
  const double top = PoolWaterLevel - 0.06 - 0.05;
  const double box[6] = { -PoolHalfSize, PoolHalfSize, 0.0, top, -PoolHalfSize, PoolHalfSize };
  auto density = SampleDensity(box, 0.05,
    [](double x, double y, double z)
    {
      const double depth = PoolWaterLevel - y - 0.5;
      const double layer = std::exp(-0.5 * depth * depth / (0.25 * 0.25));
      const double lumps = 0.65 + 0.35 * Noise(x, y, z, 1.5);
      return 0.05 + layer * lumps;
    });
  const double scattering[3] = { 0.25, 0.3, 0.3 }, absorption[3] = { 0.3, 0.06, 0.04 };
  AttachMedium(renderer, density, scattering, absorption, 0.6)->FillsRefractorsOn();
}

/**
 * The smoke-lens plume: a lumpy ball of smoke (radius 1.2 m around (0, 1.2, 0)) under
 * the glass ball, density 1 inside a 0.16 m ramp from its noisy surface, thinned by the
 * same noise at twice the frequency.
 */
void AttachPlume(vtkRenderer* renderer)
{
  const double box[6] = { -1.5, 1.5, -0.3, 2.7, -1.5, 1.5 };
  auto density = SampleDensity(box, 0.04,
    [](double x, double y, double z)
    {
      const double r = std::sqrt(x * x + (y - 1.2) * (y - 1.2) + z * z);
      const double inside = 1.2 - 0.12 * Noise(x, y, z, 1.0) - r;
      const double fog = std::min(1.0, std::max(0.0, inside / 0.16));
      return fog * (0.6 + 0.4 * Noise(x, y, z, 2.0));
    });
  const double scattering[3] = { 0.4, 0.4, 0.4 }, absorption[3] = { 0.05, 0.05, 0.05 };
  AttachMedium(renderer, density, scattering, absorption, 0.3);
}
}

bool vtkCausticsBuiltinScene::Populate(vtkRenderer* renderer)
{
  this->LastError.clear();
  this->Internal->Water = nullptr;
  if (!renderer)
  {
    return this->Fail("Populate needs a renderer");
  }
  renderer->RemoveAllViewProps();
  renderer->RemoveAllLights();
  renderer->AutomaticLightCreationOff();
  renderer->SetBackground(0.05, 0.05, 0.06);
  vtkCausticsMedium::AttachTo(renderer, nullptr); // only the media scenes carry one
  if (!this->CheckSettings())
  {
    return false;
  }
  if (this->SceneName == "ball-lens")
  {
    this->AddBallLens(renderer);
  }
  else if (this->SceneName == "pool")
  {
    this->AddPool(renderer);
  }
  else if (this->SceneName == "ring")
  {
    this->AddRing(renderer);
  }
  else if (this->SceneName == "underwater")
  {
    this->AddPool(renderer);
    AttachPlankton(renderer);
    // Under the water, across the light's drift (it travels towards -x, -z) and a
    // little up towards it: the god rays side-on, forward scattering (g = 0.6) seen.
    const double eye[3] = { 1.7, 0.35, -1.7 }, focal[3] = { -1.2, 0.65, 1.2 };
    SetCamera(renderer, eye, focal, 60.0);
  }
  else if (this->SceneName == "smoke-lens")
  {
    this->AddSmokeLens(renderer);
  }
  else
  {
    return this->AddBunny(renderer);
  }
  return true;
}

bool vtkCausticsBuiltinScene::Fail(const std::string& message)
{
  this->LastError = message;
  vtkErrorMacro(<< this->LastError);
  return false;
}

bool vtkCausticsBuiltinScene::CheckSettings()
{
  if (!IsSceneName(this->SceneName))
  {
    return this->Fail(
      "unknown scene '" + this->SceneName +
      "' (known: ball-lens, pool, ring, bunny, underwater, smoke-lens)");
  }
  if (!(this->RefractiveIndex == 0.0 ||
        (this->RefractiveIndex >= 1.0 && std::isfinite(this->RefractiveIndex))))
  {
    return this->Fail("refractive index " + std::to_string(this->RefractiveIndex) +
      " must be 0 (scene default) or a finite value >= 1");
  }
  if (!std::isfinite(this->Time))
  {
    return this->Fail("animation time must be finite");
  }
  return true;
}

double vtkCausticsBuiltinScene::IndexOfRefraction(double sceneDefault) const
{
  return this->RefractiveIndex > 0.0 ? this->RefractiveIndex : sceneDefault;
}

void vtkCausticsBuiltinScene::AddGlassBallOverFloor(vtkRenderer* renderer)
{
  auto floor = MakeActor(Floor(-6, 6, -6, 6, 0.0), "floor");
  MakeDiffuse(floor, 0.8, 0.8, 0.8);
  renderer->AddActor(floor);

  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetCenter(0.0, 3.0, 0.0);
  sphere->SetThetaResolution(static_cast<int>(128 * this->Tessellation));
  sphere->SetPhiResolution(static_cast<int>(64 * this->Tessellation));
  sphere->Update();
  auto ball = MakeActor(sphere->GetOutput(), "glass ball");
  ball->GetProperty()->SetColor(1, 1, 1);
  vtkCausticsMaterial::MakeGlass(ball->GetProperty(), this->IndexOfRefraction(1.5));
  renderer->AddActor(ball);
}

void vtkCausticsBuiltinScene::AddBallLens(vtkRenderer* renderer)
{
  this->AddGlassBallOverFloor(renderer);

  const double down[3] = { 0, -1, 0 };
  renderer->AddLight(DirectionalLight(down, 1.0));
  const double eye[3] = { 0.0, 4.5, 9.0 }, focal[3] = { 0.0, 1.3, 0.0 };
  SetCamera(renderer, eye, focal, 30.0);
}

void vtkCausticsBuiltinScene::AddSmokeLens(vtkRenderer* renderer)
{
  this->AddGlassBallOverFloor(renderer);

  // A spot 4 m above the ball's centre whose cone just covers the ball (asin(1/4) is
  // 14.5 degrees): 16 W/sr give 1 W/m^2 at the ball's top, as the ball lens's sun.
  renderer->AddLight(DownwardSpot(7.0, 16.0, 15.0, 16.0));
  AttachPlume(renderer);

  const double eye[3] = { 0.0, 4.5, 9.0 }, focal[3] = { 0.0, 1.3, 0.0 };
  SetCamera(renderer, eye, focal, 30.0);
}

void vtkCausticsBuiltinScene::AddPool(vtkRenderer* renderer)
{
  AddPoolTiles(renderer);
  AddPoolWalls(renderer);

  this->Internal->WaterResolution = static_cast<int>(128 * this->Tessellation);
  this->Internal->Water = MakeWater(this->Internal->WaterResolution, this->Time);
  auto water = MakeActor(this->Internal->Water, "water");
  water->GetProperty()->SetColor(0.9, 0.95, 1.0);
  vtkCausticsMaterial::MakeGlass(water->GetProperty(), this->IndexOfRefraction(1.33));
  renderer->AddActor(water);

  const double elevation = vtkMath::RadiansFromDegrees(60.0);
  const double sun[3] = { -std::cos(elevation) * 0.8, -std::sin(elevation),
    -std::cos(elevation) * 0.6 };
  renderer->AddLight(DirectionalLight(sun, 1.0));
  const double eye[3] = { 0.0, 5.5, 4.5 }, focal[3] = { 0.0, 0.4, 0.0 };
  SetCamera(renderer, eye, focal, 40.0);
}

void vtkCausticsBuiltinScene::AddRing(vtkRenderer* renderer)
{
  auto floor = MakeActor(Floor(-3, 3, -3, 3, 0.0), "floor");
  MakeDiffuse(floor, 0.8, 0.8, 0.8);
  renderer->AddActor(floor);

  vtkNew<vtkCylinderSource> cylinder;
  cylinder->SetRadius(1.0);
  cylinder->SetHeight(0.6);
  cylinder->SetCenter(0.0, 0.3, 0.0);
  cylinder->SetResolution(static_cast<int>(256 * this->Tessellation));
  cylinder->CappingOff();
  cylinder->Update();
  auto ring = MakeActor(cylinder->GetOutput(), "silver ring");
  ring->GetProperty()->SetColor(0.97, 0.96, 0.91);
  const double silverN[3] = { 0.155, 0.117, 0.138 }, silverK[3] = { 4.83, 3.12, 2.15 };
  vtkCausticsMaterial::MakeMirror(ring->GetProperty(), silverN, silverK);
  renderer->AddActor(ring);

  const double elevation = vtkMath::RadiansFromDegrees(20.0);
  const double light[3] = { -std::cos(elevation), -std::sin(elevation), 0.0 };
  renderer->AddLight(DirectionalLight(light, 1.0));
  const double eye[3] = { 0.0, 4.6, 3.2 }, focal[3] = { 0.0, 0.0, 0.0 };
  SetCamera(renderer, eye, focal, 35.0);
}

bool vtkCausticsBuiltinScene::AddBunny(vtkRenderer* renderer)
{
  const std::string path = this->DataDirectory + "/bunny.ply";
  if (!vtksys::SystemTools::FileExists(path, true))
  {
    return this->Fail("the bunny scene needs " + path +
      " (set the data directory or CAUSTICS_DATA_DIR to the folder holding bunny.ply)");
  }
  // The validating reader: vtkPLYReader alone crashes on a truncated file.
  vtkNew<vtkCausticsMeshReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* raw = reader->GetOutput();
  if (raw->GetNumberOfPolys() == 0)
  {
    return this->Fail(
      *reader->GetLastError() ? std::string(reader->GetLastError()) : path + " holds no triangles");
  }
  auto bunny = MakeActor(PlaceBunny(raw), "glass bunny");
  bunny->GetProperty()->SetColor(1, 1, 1);
  vtkCausticsMaterial::MakeGlass(bunny->GetProperty(), this->IndexOfRefraction(1.5));
  renderer->AddActor(bunny);
  AddCornellBox(renderer);
  AddCeilingSpot(renderer);

  const double eye[3] = { 0.0, 1.0, 4.2 }, focal[3] = { 0.0, 0.95, 0.0 };
  SetCamera(renderer, eye, focal, 37.0);
  return true;
}

void vtkCausticsBuiltinScene::UpdateTime(double time)
{
  if (!std::isfinite(time))
  {
    vtkErrorMacro(<< "animation time must be finite");
    return;
  }
  this->SetTime(time);
  if (this->Internal->Water)
  {
    FillWater(this->Internal->Water, this->Internal->WaterResolution, time);
  }
}

void vtkCausticsBuiltinScene::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SceneName: " << this->SceneName << "\n";
  os << indent << "Time: " << this->Time << " s\n";
  os << indent << "RefractiveIndex: " << this->RefractiveIndex << " (0 = scene default)\n";
  os << indent << "Tessellation: " << this->Tessellation << "\n";
  os << indent << "DataDirectory: " << this->DataDirectory << "\n";
}
