// caustics-render: renders a built-in caustics scene, a glTF 2.0 file or a mesh
// with one of the module's techniques, to PNG (display) and EXR (physical layers).
//
//   caustics-render [options] [SCENE | FILE.gltf | FILE.glb | FILE.ply|obj|stl]
//
// Every error is one line on stderr naming the problem, and a non-zero exit:
// 2 for bad arguments, 3 when no OpenGL window can be made, 1 for anything else.
#include "CausticsCommandLine.h"

#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsGLTFImporter.h"
#include "vtkCausticsImageIO.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsMedium.h"
#include "vtkCausticsMeshReader.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCausticsTechniques.h"
#include "vtkCausticsTimings.h"
#include "vtkCausticsWindowFactory.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkLogger.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOutputWindow.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
const char* Usage =
  R"(usage: caustics-render [options] [SCENE | FILE.gltf | FILE.glb | MESH.ply|obj|stl]

Renders caustics with a VTK render pass and writes PREFIX.png (display colour)
and PREFIX.exr (linear HDR layers: R,G,B final colour; direct.*, caustic.*:
irradiance in W/m^2 at each pixel's visible surface before albedo; volume.*:
in-scattered radiance in W/(m^2 sr); mask.Y: 1 where a receiver is visible).

Scene (default: ball-lens):
  SCENE                      built-in: ball-lens, pool, ring, bunny
  FILE.gltf | FILE.glb       glTF 2.0 with KHR_materials_ior/transmission and
                             KHR_lights_punctual (directional intensity = W/m^2,
                             point/spot intensity = W/sr)
  MESH.ply|obj|stl           a mesh placed on a floor under a sun, camera fit
  --role ROLE                mesh role: refractor (default), reflector, receiver
  --ior N                    index of refraction of the scene's refractors, 1..100
  --time SECONDS             animation time (pool waves; glTF animations)
  --camera-index I           glTF camera to use (default 0; -1 = fit the view)

Technique and quality:
  --technique NAME           )"
  "%TECHNIQUES%"
  R"(
  --photons N                photon grid side per light (light-buffer texels), 1..8192;
                             refused first if this OpenGL cannot hold it (llvmpipe:
                             at most 1182 for screen-space, 2048 for caustic-maps)
  --size W[xH]               image size in pixels (default 512x512)
  --frames N                 frames rendered; timings are their median (default 1)

Overrides:
  --light-direction X,Y,Z    direction the first light travels (made directional)
  --light-intensity V        first light: W/m^2 (directional) or W/sr (point/spot),
                             0..1e30
  --camera-position X,Y,Z    --camera-focal X,Y,Z    --camera-up X,Y,Z
                             (the up vector must not be parallel to the view)
  --view-angle DEGREES       vertical field of view, (0, 180)
  --medium SS,SA,G           homogeneous medium: scattering and absorption
                             coefficients in 1/m (0..1e9), Henyey-Greenstein g

Output:
  --output PREFIX            output file prefix (default: caustics)
  --exposure E               multiplier applied before the PNG's 8-bit clamp (default 1)
  --timings                  print per-stage GPU and CPU times (ms, a table)
  --help                     this text

Ground truth:
  --reference                also render the CPU reference (Embree) of the same view
                             to PREFIX-reference.exr: caustic.*, direct.* (W/m^2),
                             volume.* (W/(m^2 sr)), mask.Y; shows its progress
  --reference-photons N      its photons per light, 1..1e10 (default 1e6); implies
                             --reference
  --no-reference-cache       render it even when a cached result exists
)";

struct Options
{
  std::string Scene = "ball-lens";
  std::string Role = "refractor";
  std::string Technique = "best";
  std::string Output = "caustics";
  double Time = 0.0;
  double IOR = 0.0;
  int CameraIndex = 0;
  int Photons = 0;
  int Width = 512, Height = 512;
  int Frames = 1;
  double Exposure = 1.0;
  bool Timings = false;
  bool Reference = false;
  double ReferencePhotons = 1e6;
  bool ReferenceCache = true;
  bool HasLightDirection = false, HasLightIntensity = false;
  std::array<double, 3> LightDirection{ { 0, -1, 0 } };
  double LightIntensity = 1.0;
  bool HasCameraPosition = false, HasCameraFocal = false, HasCameraUp = false;
  std::array<double, 3> CameraPosition{}, CameraFocal{}, CameraUp{};
  double ViewAngle = 0.0;
  bool HasMedium = false;
  std::array<double, 3> Medium{};
};

using caustics_cli::NoWindowError;
using caustics_cli::ParseInteger;
using caustics_cli::ParseNumber;
using caustics_cli::UsageError;

std::array<double, 3> ParseVector(const std::string& option, const std::string& text)
{
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, ','))
  {
    parts.push_back(part);
  }
  if (parts.size() != 3)
  {
    throw UsageError(option + " expects three comma-separated numbers, got '" + text + "'");
  }
  return { { ParseNumber(option, parts[0]), ParseNumber(option, parts[1]),
    ParseNumber(option, parts[2]) } };
}

/** ParseVector, rejecting the zero vector (a direction). */
std::array<double, 3> ParseDirection(const std::string& option, const std::string& text)
{
  const std::array<double, 3> direction = ParseVector(option, text);
  if (vtkMath::Norm(direction.data()) == 0.0)
  {
    throw UsageError(option + " must not be the zero vector");
  }
  return direction;
}

/** A limit for messages: "100", "1e+30". */
std::string Number(double value)
{
  std::ostringstream text;
  text << value;
  return text.str();
}

std::string Lower(std::string text)
{
  std::transform(text.begin(), text.end(), text.begin(), ::tolower);
  return text;
}

/** The handler of an option that sets a string. */
caustics_cli::Arguments::ValueHandler Text(std::string& field)
{
  return [&field](const std::string&, const std::string& value) { field = value; };
}

void DeclareSceneOptions(caustics_cli::Arguments& arguments, Options& options, bool& sceneGiven)
{
  arguments.Value("--scene",
    [&options, &sceneGiven](const std::string&, const std::string& value)
    {
      options.Scene = value;
      sceneGiven = true;
    });
  arguments.Value("--role", Text(options.Role));
  arguments.Value("--ior",
    [&options](const std::string& option, const std::string& value)
    {
      options.IOR = ParseNumber(option, value);
      if (options.IOR < 1.0)
      {
        throw UsageError("--ior must be >= 1 (vacuum), got " + value);
      }
      if (options.IOR > vtkCausticsGLTFImporter::MAX_IOR)
      {
        throw UsageError("--ior must be <= " + Number(vtkCausticsGLTFImporter::MAX_IOR) +
          " (the largest index of refraction supported), got " + value);
      }
    });
  arguments.Value("--time",
    [&options](const std::string& option, const std::string& value)
    { options.Time = ParseNumber(option, value); });
  arguments.Value("--camera-index",
    [&options](const std::string& option, const std::string& value)
    { options.CameraIndex = ParseInteger(option, value, -1, 1 << 20); });
}

void DeclareQualityOptions(caustics_cli::Arguments& arguments, Options& options)
{
  arguments.Value("--technique", Text(options.Technique));
  arguments.Value("--photons",
    [&options](const std::string& option, const std::string& value)
    { options.Photons = ParseInteger(option, value, 1, 8192); });
  arguments.Value("--size",
    [&options](const std::string& option, const std::string& value)
    {
      const auto x = value.find('x');
      options.Width = ParseInteger(option, value.substr(0, x), 1, 16384);
      options.Height = x == std::string::npos ? options.Width
                                              : ParseInteger(option, value.substr(x + 1), 1, 16384);
    });
  arguments.Value("--frames",
    [&options](const std::string& option, const std::string& value)
    { options.Frames = ParseInteger(option, value, 1, 10000); });
}

void DeclareLightAndCameraOptions(caustics_cli::Arguments& arguments, Options& options)
{
  arguments.Value("--light-direction",
    [&options](const std::string& option, const std::string& value)
    {
      options.LightDirection = ParseDirection(option, value);
      options.HasLightDirection = true;
    });
  arguments.Value("--light-intensity",
    [&options](const std::string& option, const std::string& value)
    {
      options.LightIntensity = ParseNumber(option, value);
      if (options.LightIntensity < 0.0)
      {
        throw UsageError("--light-intensity must be >= 0");
      }
      if (options.LightIntensity > vtkCausticsGLTFImporter::MAX_LIGHT_INTENSITY)
      {
        throw UsageError(
          "--light-intensity must be <= " + Number(vtkCausticsGLTFImporter::MAX_LIGHT_INTENSITY) +
          " (the largest the GPU passes represent in float), got " + value);
      }
      options.HasLightIntensity = true;
    });
  arguments.Value("--camera-position",
    [&options](const std::string& option, const std::string& value)
    {
      options.CameraPosition = ParseVector(option, value);
      options.HasCameraPosition = true;
    });
  arguments.Value("--camera-focal",
    [&options](const std::string& option, const std::string& value)
    {
      options.CameraFocal = ParseVector(option, value);
      options.HasCameraFocal = true;
    });
  arguments.Value("--camera-up",
    [&options](const std::string& option, const std::string& value)
    {
      options.CameraUp = ParseDirection(option, value);
      options.HasCameraUp = true;
    });
  arguments.Value("--view-angle",
    [&options](const std::string& option, const std::string& value)
    {
      options.ViewAngle = ParseNumber(option, value);
      if (!(options.ViewAngle > 0.0 && options.ViewAngle < 180.0))
      {
        throw UsageError("--view-angle must lie in (0, 180) degrees");
      }
    });
}

void DeclareMediumAndOutputOptions(caustics_cli::Arguments& arguments, Options& options)
{
  arguments.Value("--medium",
    [&options](const std::string& option, const std::string& value)
    {
      options.Medium = ParseVector(option, value);
      if (options.Medium[0] < 0 || options.Medium[1] < 0 || std::abs(options.Medium[2]) >= 1.0)
      {
        throw UsageError("--medium needs sigma_s >= 0, sigma_a >= 0 (1/m) and |g| < 1");
      }
      const double most = vtkCausticsGLTFImporter::MAX_MEDIUM_COEFFICIENT;
      if (options.Medium[0] > most || options.Medium[1] > most)
      {
        throw UsageError("--medium coefficients must be <= " + Number(most) +
          " per metre (opaque within a nanometre; larger ones overflow float), got " + value);
      }
      options.HasMedium = true;
    });
  arguments.Value("--output", Text(options.Output));
  arguments.Value("--exposure",
    [&options](const std::string& option, const std::string& value)
    {
      options.Exposure = ParseNumber(option, value);
      if (options.Exposure <= 0.0)
      {
        throw UsageError("--exposure must be > 0");
      }
    });
  arguments.Flag("--timings", [&options] { options.Timings = true; });
}

void DeclareReferenceOptions(caustics_cli::Arguments& arguments, Options& options)
{
  arguments.Flag("--reference", [&options] { options.Reference = true; });
  arguments.Value("--reference-photons",
    [&options](const std::string& option, const std::string& value)
    {
      options.ReferencePhotons = caustics_cli::ParseCount(option, value, 1, 1e10);
      options.Reference = true;
    });
  arguments.Flag("--no-reference-cache", [&options] { options.ReferenceCache = false; });
}

/** "A, B, ..., best (default: X)": the techniques --technique takes. */
std::string TechniqueNames(bool withDefault)
{
  std::string names;
  for (const auto& name : vtkCausticsTechniques::GetNames())
  {
    names += name + ", ";
  }
  return names + "best" +
    (withDefault ? std::string(" (default: ") + vtkCausticsTechniques::GetBestName() + ")" : "");
}

Options Parse(int argc, char* argv[], bool& help)
{
  Options options;
  help = false;
  bool sceneGiven = false;
  caustics_cli::Arguments arguments;
  arguments.Flag("--help", [&help] { help = true; });
  arguments.Flag("-h", [&help] { help = true; });
  DeclareSceneOptions(arguments, options, sceneGiven);
  DeclareQualityOptions(arguments, options);
  DeclareLightAndCameraOptions(arguments, options);
  DeclareMediumAndOutputOptions(arguments, options);
  DeclareReferenceOptions(arguments, options);
  for (const auto& scene : arguments.Parse(argc, argv))
  {
    if (sceneGiven)
    {
      throw UsageError("more than one scene given ('" + options.Scene + "' and '" + scene + "')");
    }
    options.Scene = scene;
    sceneGiven = true;
  }
  if (!vtkCausticsTechniques::Create(options.Technique))
  {
    throw UsageError(
      "unknown technique '" + options.Technique + "' (known: " + TechniqueNames(false) + ")");
  }
  return options;
}

/** Places a loaded mesh on a floor under a sun, with a camera that frames both. */
void StageMesh(vtkRenderer* renderer, vtkActor* mesh)
{
  renderer->AddActor(mesh);
  double bounds[6];
  mesh->GetBounds(bounds);
  const double size =
    std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
  const double cx = 0.5 * (bounds[0] + bounds[1]), cz = 0.5 * (bounds[4] + bounds[5]);
  // The floor sits one object-size below the mesh, so a lens focuses onto it.
  const double floorY = bounds[2] - size;
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(cx - 4 * size, floorY, cz + 4 * size);
  plane->SetPoint1(cx + 4 * size, floorY, cz + 4 * size);
  plane->SetPoint2(cx - 4 * size, floorY, cz - 4 * size);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkActor> floor;
  floor->SetMapper(mapper);
  floor->GetProperty()->SetColor(0.8, 0.8, 0.8);
  floor->GetProperty()->SetSpecular(0.0);
  vtkCausticsMaterial::SetName(floor, "floor");
  renderer->AddActor(floor);
  vtkNew<vtkLight> sun;
  sun->SetLightTypeToSceneLight();
  sun->SetPositional(false);
  sun->SetPosition(cx, bounds[3] + size, cz);
  sun->SetFocalPoint(cx, floorY, cz);
  sun->SetIntensity(1.0);
  renderer->AddLight(sun);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(cx, 0.5 * (floorY + bounds[3]), cz);
  camera->SetPosition(cx, bounds[3] + 1.5 * size, cz + 4.5 * size);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(30.0);
  renderer->ResetCameraClippingRange();
}

/** --ior on every refractor: glTF ones too (built-ins and meshes take it when loaded). */
void ApplyRefractiveIndex(vtkRenderer* renderer, double ior)
{
  vtkActorCollection* actors = renderer->GetActors();
  vtkCollectionSimpleIterator it;
  actors->InitTraversal(it);
  while (vtkActor* actor = actors->GetNextActor(it))
  {
    if (vtkCausticsMaterial::Classify(actor) == vtkCausticsMaterial::ROLE_REFRACTOR)
    {
      actor->GetProperty()->SetBaseIOR(ior);
    }
  }
}

void LoadScene(const Options& options, vtkRenderWindow* window, vtkRenderer* renderer,
  vtkCausticsBuiltinScene* builtin)
{
  const std::string extension = Lower(vtksys::SystemTools::GetFilenameLastExtension(options.Scene));
  if (vtkCausticsBuiltinScene::IsSceneName(options.Scene))
  {
    builtin->SetSceneName(options.Scene.c_str());
    builtin->SetTime(options.Time);
    builtin->SetRefractiveIndex(options.IOR);
    if (!builtin->Populate(renderer))
    {
      throw std::runtime_error(builtin->GetLastError());
    }
  }
  else if (extension == ".gltf" || extension == ".glb")
  {
    vtkNew<vtkCausticsGLTFImporter> importer;
    importer->SetFileName(options.Scene.c_str());
    importer->SetRenderWindow(window); // imports into the window's first renderer
    importer->SetCamera(options.CameraIndex);
    if (!importer->Read())
    {
      throw std::runtime_error(importer->GetLastError());
    }
    if (options.Time != 0.0)
    {
      importer->UpdateTimeStep(options.Time);
    }
    if (options.CameraIndex < 0 || importer->GetNumberOfCameras() == 0)
    {
      renderer->ResetCamera();
    }
  }
  else if (vtkCausticsMeshReader::IsSupportedExtension(options.Scene))
  {
    vtkNew<vtkCausticsMeshReader> reader;
    reader->SetFileName(options.Scene.c_str());
    if (!reader->SetRoleFromName(options.Role.c_str()))
    {
      throw UsageError("unknown --role '" + options.Role + "' (refractor, reflector, receiver)");
    }
    if (options.IOR > 0.0)
    {
      reader->SetRefractiveIndex(options.IOR);
    }
    auto actor = reader->CreateActor();
    if (!actor)
    {
      throw std::runtime_error(reader->GetLastError());
    }
    renderer->AutomaticLightCreationOff();
    StageMesh(renderer, actor);
  }
  else if (extension.empty())
  {
    throw UsageError("unknown scene '" + options.Scene +
      "' (built-in: ball-lens, pool, ring, bunny; or a .gltf/.glb/.ply/.obj/.stl file)");
  }
  else
  {
    throw UsageError("cannot read '" + options.Scene + "': unsupported file type '" + extension +
      "' (use .gltf, .glb, .ply, .obj or .stl)");
  }
  if (options.IOR > 0.0)
  {
    ApplyRefractiveIndex(renderer, options.IOR);
  }
}

/**
 * An up vector parallel to the line of sight leaves OrthogonalizeViewUp nothing
 * to work with and gives a blank image: refused, naming the options that set it.
 */
void CheckViewUp(const Options& options, vtkCamera* camera)
{
  double position[3], focal[3], up[3], view[3], side[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  camera->GetViewUp(up);
  vtkMath::Subtract(focal, position, view);
  vtkMath::Cross(view, up, side);
  // sin(angle) > 1e-6, as the glTF importer asks of its cameras.
  if (vtkMath::Norm(side) > 1e-6 * vtkMath::Norm(view) * vtkMath::Norm(up))
  {
    return;
  }
  std::ostringstream message;
  message << "the camera's up vector (" << up[0] << "," << up[1] << "," << up[2]
          << (options.HasCameraUp ? ", from --camera-up" : ", from the scene")
          << ") is parallel to its view direction ("
          << (options.HasCameraPosition || options.HasCameraFocal
                 ? "from --camera-position to --camera-focal"
                 : "the scene's camera")
          << "); give a --camera-up off the line of sight";
  throw UsageError(message.str());
}

void ApplyOverrides(const Options& options, vtkRenderer* renderer)
{
  vtkLight* light = vtkLight::SafeDownCast(renderer->GetLights()->GetItemAsObject(0));
  if ((options.HasLightDirection || options.HasLightIntensity) && !light)
  {
    throw UsageError("the scene has no light to override");
  }
  if (options.HasLightDirection)
  {
    const auto& d = options.LightDirection;
    double focal[3];
    light->GetFocalPoint(focal);
    light->SetPositional(false);
    light->SetTransformMatrix(nullptr);
    light->SetPosition(focal[0] - d[0], focal[1] - d[1], focal[2] - d[2]);
  }
  if (options.HasLightIntensity)
  {
    light->SetIntensity(options.LightIntensity);
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  if (options.HasCameraPosition)
  {
    camera->SetPosition(options.CameraPosition.data());
  }
  if (options.HasCameraFocal)
  {
    camera->SetFocalPoint(options.CameraFocal.data());
  }
  if (options.HasCameraUp)
  {
    camera->SetViewUp(options.CameraUp.data());
  }
  if (options.ViewAngle > 0.0)
  {
    camera->SetViewAngle(options.ViewAngle);
  }
  double position[3], focal[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  if (vtkMath::Distance2BetweenPoints(position, focal) == 0.0)
  {
    throw UsageError("the camera position and focal point coincide");
  }
  CheckViewUp(options, camera);
  camera->OrthogonalizeViewUp();
  renderer->ResetCameraClippingRange();
  if (options.HasMedium)
  {
    vtkNew<vtkCausticsMedium> medium;
    medium->SetScatteringCoefficient(options.Medium[0], options.Medium[0], options.Medium[0]);
    medium->SetAbsorptionCoefficient(options.Medium[1], options.Medium[1], options.Medium[1]);
    medium->SetAnisotropy(options.Medium[2]);
    vtkCausticsMedium::AttachTo(renderer, medium);
  }
}

/** Copies buffer `name` of the pass into `output` as array `as`, if the frame made it. */
bool CopyBuffer(vtkCausticsRenderPass* pass, const char* name, const char* as, vtkImageData* output)
{
  vtkNew<vtkImageData> buffer;
  pass->GlobalWarningDisplayOff();
  const bool ok = pass->ReadBuffer(name, buffer);
  pass->GlobalWarningDisplayOn();
  if (!ok)
  {
    return false;
  }
  vtkDataArray* array = buffer->GetPointData()->GetArray(0);
  array->SetName(as);
  output->GetPointData()->AddArray(array);
  return true;
}

/** The median of the known (non-negative) values; NaN when none is known. */
double Median(std::vector<double> values)
{
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !(v >= 0.0); }),
    values.end());
  if (values.empty())
  {
    return std::nan("");
  }
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/**
 * VTK's messages, kept to one line each: errors are remembered (the run then fails
 * naming the first one), warnings are printed as "caustics-render: warning: ...".
 */

/** Each stage's GPU and CPU times over the frames, in the order the stages first ran. */
struct StageTimes
{
  std::vector<std::string> Order;
  std::map<std::string, std::vector<double>> GPU, CPU;
  std::vector<double> Frames; // wall time of each frame

  void Add(vtkCausticsTimings* timings)
  {
    for (int s = 0; s < timings->GetNumberOfStages(); ++s)
    {
      const std::string name = timings->GetStageName(s);
      if (!timings->GetStageRan(s))
      {
        continue;
      }
      if (!this->GPU.count(name))
      {
        this->Order.push_back(name);
      }
      this->GPU[name].push_back(timings->GetStageGPUMilliseconds(s));
      this->CPU[name].push_back(timings->GetStageCPUMilliseconds(s));
    }
  }
};

vtkSmartPointer<vtkRenderWindow> MakeWindow(const Options& options, std::string& how)
{
  vtkSmartPointer<vtkRenderWindow> window = vtkCausticsWindowFactory::Create(true, &how);
  if (!window)
  {
    throw NoWindowError(how);
  }
  window->SetMultiSamples(0);
  window->SetSize(options.Width, options.Height);
  return window;
}

/** The technique's pass, keeping its buffers for read-back, with synchronous timings. */
vtkSmartPointer<vtkCausticsRenderPass> MakePass(const Options& options)
{
  vtkSmartPointer<vtkCausticsRenderPass> pass = vtkCausticsTechniques::Create(options.Technique);
  pass->KeepBuffersOn();
  pass->ComputeDirectIrradianceOn();
  pass->GetTimings()->SynchronousOn();
  if (options.Photons > 0)
  {
    pass->SetLightBufferResolution(options.Photons);
  }
  return pass;
}

StageTimes RenderFrames(
  const Options& options, vtkRenderWindow* window, vtkCausticsRenderPass* pass)
{
  StageTimes times;
  for (int frame = 0; frame < options.Frames; ++frame)
  {
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    times.Frames.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    times.Add(pass->GetTimings());
  }
  return times;
}

/**
 * The last frame's buffers as arrays of one image, and the EXR layers they become
 * (array name, layer prefix). A frame without a caustic stage gets a zero caustic layer.
 */
vtkSmartPointer<vtkImageData> ReadLayers(const Options& options, vtkCausticsRenderPass* pass,
  std::vector<std::pair<std::string, std::string>>& layers)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(options.Width, options.Height, 1);
  if (!CopyBuffer(pass, "FinalColor", "FinalColor", image))
  {
    throw std::runtime_error("the frame produced no image (see the errors above)");
  }
  layers = { { "FinalColor", "" } };
  if (CopyBuffer(pass, "DirectIrradiance", "DirectIrradiance", image))
  {
    layers.emplace_back("DirectIrradiance", "direct");
  }
  if (!CopyBuffer(pass, "CausticIrradiance", "CausticIrradiance", image))
  {
    // No caustic stage ran (no specular actor or light): the caustic term is zero.
    vtkNew<vtkFloatArray> zero;
    zero->SetName("CausticIrradiance");
    zero->SetNumberOfComponents(3);
    zero->SetNumberOfTuples(static_cast<vtkIdType>(options.Width) * options.Height);
    zero->Fill(0.0);
    image->GetPointData()->AddArray(zero);
  }
  layers.emplace_back("CausticIrradiance", "caustic");
  if (CopyBuffer(pass, "VolumeRadiance", "VolumeRadiance", image))
  {
    layers.emplace_back("VolumeRadiance", "volume");
  }
  if (CopyBuffer(pass, "ReceiverMask", "ReceiverMask", image))
  {
    layers.emplace_back("ReceiverMask", "mask");
  }
  return image;
}

void WriteImages(const Options& options, vtkImageData* image,
  const std::vector<std::pair<std::string, std::string>>& layers)
{
  std::string error;
  const std::string png = options.Output + ".png", exr = options.Output + ".exr";
  if (!vtkCausticsImageIO::WritePNG(image, "FinalColor", png, options.Exposure, false, &error) ||
    !vtkCausticsImageIO::WriteEXR(image, layers, exr, &error))
  {
    throw std::runtime_error(error);
  }
}

void PrintSummary(const Options& options, vtkCausticsRenderPass* pass, const std::string& how)
{
  const auto& scene = pass->GetSceneExtractor()->GetScene();
  std::cout << "caustics-render: " << options.Scene << ", technique "
            << (options.Technique == "best" ? vtkCausticsTechniques::GetBestName()
                                            : options.Technique)
            << ", " << options.Width << "x" << options.Height << ", window " << how << ", "
            << scene.Meshes.size() << " meshes, " << scene.Lights.size() << " light(s)"
            << (pass->GetLastFrameHadCaustics() ? "" : " (no caustic stage needed)") << "\n";
  std::cout << "wrote " << options.Output << ".png and " << options.Output << ".exr\n";
}

/**
 * The per-stage table: one row per stage that ran, columns wide enough for the
 * longest name; "-" where a time is not known (a CPU-only stage has no GPU time).
 */
void PrintTimings(const Options& options, StageTimes& times)
{
  const std::string wall = "whole frame (wall clock)";
  std::size_t width = wall.size();
  for (const auto& name : times.Order)
  {
    width = std::max(width, name.size());
  }
  auto row = [width](const std::string& name, const std::string& gpu, const std::string& cpu)
  {
    std::cout << "  " << std::left << std::setw(static_cast<int>(width)) << name << std::right
              << std::setw(12) << gpu << std::setw(12) << cpu << "\n";
  };
  auto cell = [](double milliseconds)
  {
    std::ostringstream text;
    text << std::fixed << std::setprecision(3) << milliseconds;
    return std::isnan(milliseconds) ? std::string("-") : text.str();
  };
  std::cout << "per-stage time in ms, median of " << options.Frames << " frame(s):\n";
  row("stage", "gpu", "cpu");
  for (const auto& name : times.Order)
  {
    row(name, cell(Median(times.GPU[name])), cell(Median(times.CPU[name])));
  }
  row(wall, "-", cell(Median(times.Frames)));
}

/**
 * --reference: the CPU ground truth of the same view (vtkCausticsReferenceRenderer)
 * to PREFIX-reference.exr, showing its progress while it runs.
 */
void RenderReference(const Options& options, vtkRenderer* renderer)
{
  vtkNew<vtkCausticsReferenceRenderer> reference;
  reference->SetInputRenderer(renderer);
  reference->SetImageSize(options.Width, options.Height);
  reference->SetPhotonsPerLight(static_cast<vtkIdType>(options.ReferencePhotons));
  reference->SetUseCache(options.ReferenceCache);
  std::ostringstream label;
  label << "caustics-render: reference, " << static_cast<long long>(options.ReferencePhotons)
        << " photons per light";
  bool ok = false;
  {
    caustics_cli::ProgressReport progress(reference, label.str());
    ok = reference->Update();
  }
  if (!ok)
  {
    throw std::runtime_error(std::string("the reference failed: ") + reference->GetLastError());
  }
  const std::string exr = options.Output + "-reference.exr";
  std::string error;
  if (!vtkCausticsImageIO::WriteEXR(reference->GetOutput(),
        { { "CausticIrradiance", "caustic" }, { "DirectIrradiance", "direct" },
          { "VolumeRadiance", "volume" }, { "ReceiverMask", "mask" } },
        exr, &error))
  {
    throw std::runtime_error(error);
  }
  std::cout << "wrote " << exr << " (reference, "
            << (reference->GetLoadedFromCache() ? "from its cache" : "rendered") << " in "
            << caustics_cli::FormatSeconds(reference->GetWallTime()) << ")\n";
}

int Run(const Options& options)
{
  std::string how;
  vtkSmartPointer<vtkRenderWindow> window = MakeWindow(options, how);
  vtkNew<vtkOpenGLRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkCausticsBuiltinScene> builtin;
  LoadScene(options, window, renderer, builtin);
  ApplyOverrides(options, renderer);
  vtkSmartPointer<vtkCausticsRenderPass> pass = MakePass(options);
  renderer->SetPass(pass);
  // Refuse a photon grid this OpenGL cannot hold before anything is allocated (the
  // frame checks again with the scene's lights: no outputs then either).
  if (!pass->CheckResources(window))
  {
    throw std::runtime_error(pass->GetResourceError());
  }
  StageTimes times = RenderFrames(options, window, pass);
  if (*pass->GetResourceError())
  {
    throw std::runtime_error(pass->GetResourceError());
  }

  std::vector<std::pair<std::string, std::string>> layers;
  vtkSmartPointer<vtkImageData> image = ReadLayers(options, pass, layers);
  WriteImages(options, image, layers);
  PrintSummary(options, pass, how);
  if (options.Timings)
  {
    PrintTimings(options, times);
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  if (options.Reference)
  {
    RenderReference(options, renderer);
  }
  return 0;
}

/** The usage text with the registered techniques filled in. */
std::string UsageText()
{
  std::string text = Usage;
  text.replace(text.find("%TECHNIQUES%"), 12, "technique: " + TechniqueNames(true));
  return text;
}
}

int main(int argc, char* argv[])
{
  return caustics_cli::RunMain("caustics-render", caustics_cli::LoggedErrors::Fail,
    [&](caustics_cli::OneLineOutputWindow*)
    {
      bool help = false;
      const Options options = Parse(argc, argv, help);
      if (help)
      {
        std::cout << UsageText();
        return 0;
      }
      return Run(options);
    });
}
