// The options, scene loading and overrides that caustics-render and caustics-view
// share (CausticsSceneOptions.h).
#include "CausticsSceneOptions.h"

#include "vtkCausticsAirlight.h"
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsCascadedPhotonPass.h"
#include "vtkCausticsDensityGrid.h"
#include "vtkCausticsGLTFImporter.h"
#include "vtkCausticsHierarchicalCausticMapPass.h"
#include "vtkCausticsImpostorPhotonPass.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsMedium.h"
#include "vtkCausticsMeshReader.h"
#include "vtkCausticsPhotonGrid.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
#include "vtkCausticsScreenSpaceRefraction.h"
#include "vtkCausticsTechniques.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace caustics_cli
{
const char* const SceneUsage = R"(Scene (default: ball-lens):
  SCENE                      built-in: ball-lens, pool, ring, bunny, underwater,
                             smoke-lens (the last two in heterogeneous media)
  FILE.gltf | FILE.glb       glTF 2.0 with KHR_materials_ior/transmission and
                             KHR_lights_punctual (directional intensity = W/m^2,
                             point/spot intensity = W/sr)
  MESH.ply|obj|stl           a mesh placed on a floor under a sun, camera fit
  --role ROLE                mesh role: refractor (default), reflector, receiver
  --ior N                    index of refraction of the scene's refractors, 1..100
  --time SECONDS             animation time (pool waves; glTF animations)
  --camera-index I           glTF camera to use (default 0; -1 = fit the view)
)";

const char* const OverridesUsage = R"(Overrides:
  --light-direction X,Y,Z    direction the first light travels (made directional)
  --light-intensity V        first light: W/m^2 (directional) or W/sr (point/spot),
                             0..1e30
  --camera-position X,Y,Z    --camera-focal X,Y,Z    --camera-up X,Y,Z
                             (the up vector must not be parallel to the view)
  --view-angle DEGREES       vertical field of view, (0, 180)
  --medium SS,SA,G           homogeneous medium: scattering and absorption
                             coefficients in 1/m (0..1e9), Henyey-Greenstein g
  --medium FILE.vdb[:GRID]   heterogeneous medium: the density of OpenVDB float
                             grid GRID (default: density); coefficients are then
                             per unit density (default scattering 1, absorption 0)
  --medium-scattering R,G,B  --medium-absorption R,G,B
                             per channel, 1/m per unit density (0..1e9)
  --medium-density-scale S   factor on the grid's densities, 0..1e6 (default 1)
  --medium-g G               Henyey-Greenstein g, (-1, 1)
  --medium-fills-refractors  the medium fills the refractors too (murky water
                             under a water surface); alone, it applies to the
                             scene's own medium
)";

std::string QualityUsage()
{
  return "  --technique NAME           technique: " + TechniqueNames(true) + R"(
  --photons N                photon grid side per light (light-buffer texels), 1..8192;
                             refused first if this OpenGL cannot hold it (llvmpipe:
                             at most 1182 for screen-space, 2048 for caustic-maps)
  --trace-view MODE          screen-space: view photons are traced in: automatic
                             (default: the camera's unless a reflector or refractor
                             is outside it), camera, fitted
  --hidden-starts MODE       cascaded: a photon whose camera-view march starts where
                             the camera does not see: march (default: on behind
                             what the camera sees) or drop (the paper's Fig. 7)
  --reconstruction MODE      screen-space, caustic-maps and impostors: how landed
                             photons become irradiance: splats (default) or
                             triangles (caustic triangles between neighbouring
                             photons; sharp foci, see docs/accuracy.md)
  --god-ray-blur PIXELS      screen-space god-rays: standard deviation of their
                             screen-space Gaussian, 0..16 (default 1.5)
  --volume-sub-segments N    screen-space god-rays in a density grid: pieces each
                             photon segment is split into (0..64, default 8; 0:
                             march the density per fragment, the slow former way)
  --denoise [on|off]         denoise the caustic irradiance over space and time
                             (SVGF, docs/denoising.md) or not; --denoise alone
                             is on (default: the technique's; cascaded: on)
  --progressive N            average the caustic and volume layers over N frames
                             of a still scene and camera, each with new photons
                             (1..4096, default 1: off); any change restarts it,
                             a complete mean is held (docs/architecture.md)
  --camera-view MODE         how glass and mirrors show the scene: screen-space,
                             impostors (distance impostors, paper 004) or both
                             (default: screen-space, impostors where rays leave
                             the view; docs/technique-distance-impostors.md)
  --exact-specular MODE      the camera view traces glass and mirror triangles:
                             off, on, or auto (default: where one is not a convex
                             solid; docs/accuracy.md)
  --refraction-events N      interfaces a camera path through glass and mirrors
                             may cross (2..16, default 8)
  --airlight on|off          a medium's airlight and volume shadows of the direct
                             light (default on; docs/airlight.md)
  --size W[xH]               image size in pixels (default 512x512)
)";
}

Arguments::ValueHandler Text(std::string& field)
{
  return [&field](const std::string&, const std::string& value) { field = value; };
}

namespace
{
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

/**
 * An up vector parallel to the line of sight leaves OrthogonalizeViewUp nothing
 * to work with and gives a blank image: refused, naming the options that set it.
 */
void CheckViewUp(const SceneOptions& options, vtkCamera* camera)
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

void DeclareSourceOptions(Arguments& arguments, SceneOptions& options, bool& sceneGiven)
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

void DeclareQualityOptions(Arguments& arguments, SceneOptions& options)
{
  arguments.Value("--technique", Text(options.Technique));
  arguments.Value("--trace-view",
    [&options](const std::string& option, const std::string& value) {
      options.TraceView = ParseChoice(option, value, { "automatic", "camera", "fitted" });
    });
  arguments.Value("--hidden-starts",
    [&options](const std::string& option, const std::string& value) {
      options.HiddenStarts = ParseChoice(option, value, { "march", "drop" });
    });
  arguments.Value("--reconstruction",
    [&options](const std::string& option, const std::string& value)
    { options.Reconstruction = ParseChoice(option, value, { "splats", "triangles" }); });
  arguments.Value("--volume-sub-segments",
    [&options](const std::string& option, const std::string& value)
    { options.VolumeSubSegments = ParseInteger(option, value, 0, 64); });
  arguments.Value("--god-ray-blur",
    [&options](const std::string& option, const std::string& value)
    {
      options.GodRayBlurPixels = ParseNumber(option, value);
      if (!(options.GodRayBlurPixels >= 0.0 && options.GodRayBlurPixels <= 16.0))
      {
        throw UsageError("--god-ray-blur must lie in [0, 16] pixels");
      }
    });
  arguments.Value("--photons",
    [&options](const std::string& option, const std::string& value)
    { options.Photons = ParseInteger(option, value, 1, 8192); });
  arguments.OptionalChoice("--denoise", { "on", "off" }, "on",
    [&options](const std::string&, const std::string& value) { options.Denoise = value == "on"; });
  arguments.Value("--progressive",
    [&options](const std::string& option, const std::string& value)
    { options.ProgressiveFrames = ParseInteger(option, value, 1, 4096); });
  arguments.Value("--camera-view",
    [&options](const std::string& option, const std::string& value)
    { options.CameraView = ParseChoice(option, value, { "screen-space", "impostors", "both" }); });
  arguments.Value("--exact-specular",
    [&options](const std::string& option, const std::string& value)
    { options.ExactSpecular = ParseChoice(option, value, { "off", "on", "auto" }); });
  arguments.Value("--refraction-events",
    [&options](const std::string& option, const std::string& value)
    { options.RefractionEvents = ParseInteger(option, value, 2, 16); });
  arguments.Value("--airlight",
    [&options](const std::string& option, const std::string& value)
    { options.Airlight = ParseChoice(option, value, { "off", "on" }) == 1; });
  arguments.Value("--size",
    [&options](const std::string& option, const std::string& value)
    {
      const auto x = value.find('x');
      options.Width = ParseInteger(option, value.substr(0, x), 1, 16384);
      options.Height = x == std::string::npos ? options.Width
                                              : ParseInteger(option, value.substr(x + 1), 1, 16384);
    });
}

void DeclareLightAndCameraOptions(Arguments& arguments, SceneOptions& options)
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

/** Coefficients in 1/m: >= 0 and small enough for the GPU's floats. */
void CheckCoefficients(
  const std::string& option, const std::string& value, std::initializer_list<double> coefficients)
{
  const double most = vtkCausticsGLTFImporter::MAX_MEDIUM_COEFFICIENT;
  for (double c : coefficients)
  {
    if (c > most)
    {
      throw UsageError(option + " coefficients must be <= " + Number(most) +
        " per metre (opaque within a nanometre; larger ones overflow float), got " + value);
    }
  }
}

/** --medium FILE.vdb[:GRID]: a value ending in .vdb or holding ".vdb:" names a file. */
bool IsDensityFile(const std::string& value, std::string& file, std::string& grid)
{
  const std::string lower = Lower(value);
  const auto colon = lower.rfind(".vdb:");
  if (colon != std::string::npos)
  {
    file = value.substr(0, colon + 4);
    grid = value.substr(colon + 5);
    return true;
  }
  if (lower.size() > 4 && lower.compare(lower.size() - 4, 4, ".vdb") == 0)
  {
    file = value;
    grid = "density";
    return true;
  }
  return false;
}

double ParseAnisotropy(const std::string& option, const std::string& value)
{
  const double g = ParseNumber(option, value);
  if (!(std::abs(g) < 1.0))
  {
    throw UsageError(option + " must lie in (-1, 1), got " + value);
  }
  return g;
}

void DeclareMediumOptions(Arguments& arguments, SceneOptions& options)
{
  SceneOptions::MediumOptions& medium = options.Medium;
  arguments.Value("--medium",
    [&medium](const std::string& option, const std::string& value)
    {
      medium.Given = true;
      if (IsDensityFile(value, medium.File, medium.Grid))
      {
        if (medium.Grid.empty())
        {
          throw UsageError(option + " " + value + ": the grid name after ':' is empty");
        }
        return;
      }
      // Grey coefficients; with a grid given too, they are per unit density.
      medium.Grey = ParseVector(option, value);
      if (medium.Grey[0] < 0 || medium.Grey[1] < 0 || std::abs(medium.Grey[2]) >= 1.0)
      {
        throw UsageError("--medium needs sigma_s >= 0, sigma_a >= 0 (1/m) and |g| < 1");
      }
      CheckCoefficients(option, value, { medium.Grey[0], medium.Grey[1] });
      medium.HasGrey = true;
    });
  auto coefficients = [&medium](std::array<double, 3>& field, bool& given)
  {
    return [&medium, &field, &given](const std::string& option, const std::string& value)
    {
      field = ParseVector(option, value);
      if (field[0] < 0 || field[1] < 0 || field[2] < 0)
      {
        throw UsageError(option + " needs coefficients >= 0 (1/m per unit density), got " + value);
      }
      CheckCoefficients(option, value, { field[0], field[1], field[2] });
      given = medium.Given = true;
    };
  };
  arguments.Value("--medium-scattering", coefficients(medium.Scattering, medium.HasScattering));
  arguments.Value("--medium-absorption", coefficients(medium.Absorption, medium.HasAbsorption));
  arguments.Value("--medium-g",
    [&medium](const std::string& option, const std::string& value)
    {
      medium.G = ParseAnisotropy(option, value);
      medium.HasG = medium.Given = true;
    });
  arguments.Value("--medium-density-scale",
    [&medium](const std::string& option, const std::string& value)
    {
      medium.DensityScale = ParseNumber(option, value);
      if (!(medium.DensityScale >= 0.0 &&
            medium.DensityScale <= caustics::DensityGrid::MaximumScale))
      {
        throw UsageError(option + " must lie in [0, " +
          Number(caustics::DensityGrid::MaximumScale) + "], got " + value);
      }
      medium.HasDensityScale = medium.Given = true;
    });
  arguments.Flag("--medium-fills-refractors", [&medium] { medium.FillsRefractors = true; });
}
}

void DeclareSceneOptions(Arguments& arguments, SceneOptions& options, bool& sceneGiven)
{
  DeclareSourceOptions(arguments, options, sceneGiven);
  DeclareQualityOptions(arguments, options);
  DeclareLightAndCameraOptions(arguments, options);
  DeclareMediumOptions(arguments, options);
}

void FinishSceneOptions(
  const std::vector<std::string>& positionals, SceneOptions& options, bool sceneGiven)
{
  for (const auto& scene : positionals)
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

void LoadScene(const SceneOptions& options, vtkRenderWindow* window, vtkRenderer* renderer,
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
      "' (built-in: ball-lens, pool, ring, bunny, underwater, smoke-lens; or a "
      ".gltf/.glb/.ply/.obj/.stl file)");
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

namespace
{
/**
 * The medium of the --medium options: --medium SS,SA,G gives grey coefficients, the
 * per-channel options override them; a density grid alone scatters 1 per metre per
 * unit density. A grid that cannot be read throws std::runtime_error with its error line.
 */
vtkSmartPointer<vtkCausticsMedium> MakeMedium(const SceneOptions::MediumOptions& options)
{
  const bool grid = !options.File.empty();
  if (options.HasDensityScale && !grid)
  {
    throw UsageError("--medium-density-scale needs a density grid (--medium FILE.vdb)");
  }
  auto grey = [&](int index, double otherwise)
  {
    const double c = options.HasGrey ? options.Grey[index] : otherwise;
    return std::array<double, 3>{ { c, c, c } };
  };
  const auto scattering = options.HasScattering ? options.Scattering : grey(0, grid ? 1.0 : 0.0);
  const auto absorption = options.HasAbsorption ? options.Absorption : grey(1, 0.0);
  auto medium = vtkSmartPointer<vtkCausticsMedium>::New();
  medium->SetScatteringCoefficient(scattering.data());
  medium->SetAbsorptionCoefficient(absorption.data());
  medium->SetAnisotropy(options.HasG ? options.G : (options.HasGrey ? options.Grey[2] : 0.0));
  medium->SetFillsRefractors(options.FillsRefractors);
  if (grid)
  {
    // The error goes into the exception (one line), not to VTK's output window.
    vtkNew<vtkCallbackCommand> quiet;
    medium->AddObserver(vtkCommand::ErrorEvent, quiet);
    if (!medium->LoadDensity(options.File.c_str(), options.Grid.c_str()))
    {
      throw std::runtime_error(std::string("--medium: ") + medium->GetLastError());
    }
    medium->SetDensityScale(options.DensityScale);
  }
  return medium;
}
}

void ApplyOverrides(const SceneOptions& options, vtkRenderer* renderer)
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
  if (options.Medium.Given)
  {
    vtkCausticsMedium::AttachTo(renderer, MakeMedium(options.Medium));
  }
  else if (options.Medium.FillsRefractors)
  {
    vtkCausticsMedium* medium = vtkCausticsMedium::GetFrom(renderer);
    if (!medium)
    {
      throw UsageError("--medium-fills-refractors: the scene has no medium (give one with --medium)");
    }
    medium->FillsRefractorsOn();
  }
}

std::string TechniqueFor(const SceneOptions& options, vtkRenderer* renderer)
{
  return options.Technique == "best" ? vtkCausticsTechniques::GetBestNameFor(renderer)
                                     : options.Technique;
}

vtkSmartPointer<vtkCausticsRenderPass> MakePass(const SceneOptions& options, vtkRenderer* renderer)
{
  vtkSmartPointer<vtkCausticsRenderPass> pass =
    vtkCausticsTechniques::Create(TechniqueFor(options, renderer));
  if (options.Photons > 0)
  {
    pass->SetLightBufferResolution(options.Photons);
  }
  if (options.Denoise >= 0)
  {
    pass->SetDenoise(options.Denoise == 1); // else the technique's default
  }
  pass->SetProgressiveFrames(options.ProgressiveFrames);
  if (options.CameraView >= 0)
  {
    pass->SetCameraViewMethod(options.CameraView); // the same order as CameraViewMethods
  }
  if (options.RefractionEvents >= 0)
  {
    pass->SetRefractionEvents(options.RefractionEvents);
  }
  if (options.ExactSpecular >= 0)
  {
    // The same order as vtkCausticsScreenSpaceRefraction's EXACT_* values.
    pass->GetScreenSpaceRefraction()->SetExactSpecularGeometry(options.ExactSpecular);
  }
  pass->GetAirlight()->SetEnabled(options.Airlight);
  if (auto* screenSpace = vtkCausticsScreenSpacePhotonPass::SafeDownCast(pass))
  {
    screenSpace->SetTraceView(options.TraceView);
    screenSpace->SetReconstruction(options.Reconstruction);
    if (options.VolumeSubSegments >= 0)
    {
      screenSpace->SetVolumeSubSegments(options.VolumeSubSegments);
    }
    if (options.GodRayBlurPixels >= 0.0)
    {
      screenSpace->SetGodRayBlurPixels(options.GodRayBlurPixels);
    }
  }
  if (auto* maps = vtkCausticsHierarchicalCausticMapPass::SafeDownCast(pass))
  {
    maps->SetReconstruction(options.Reconstruction);
  }
  if (auto* impostors = vtkCausticsImpostorPhotonPass::SafeDownCast(pass))
  {
    impostors->SetReconstruction(options.Reconstruction);
  }
  if (auto* cascaded = vtkCausticsCascadedPhotonPass::SafeDownCast(pass))
  {
    cascaded->SetMarchHiddenStarts(options.HiddenStarts == 0);
  }
  return pass;
}

std::string DescribePhotonLight(
  vtkCausticsRenderPass* pass, const std::string& technique, std::string& warning)
{
  warning.clear();
  caustics::PhotonStatistics photons;
  if (!pass || !pass->GetLastFrameHadCaustics() || !pass->GetLastFramePhotonStatistics(photons) ||
    !(photons.FluxIn > 0.0))
  {
    return std::string();
  }
  auto percent = [](double share)
  {
    std::ostringstream text;
    text << std::fixed << std::setprecision(1) << 100.0 * share << " %";
    return text.str();
  };
  const double in = photons.FluxIn;
  std::ostringstream line;
  line << "photon light (" << photons.Photons << " photons, " << in
       << " W): " << percent((photons.FluxHits + photons.FluxStored) / in) << " landed, "
       << percent(photons.FluxEscaped / in) << " left the views, "
       << percent(photons.FluxLostInside / in) << " lost on paths " << technique
       << " cannot follow";
  if (photons.FluxInternalReflection > 0.0)
  {
    line << ", " << percent(photons.FluxInternalReflection / in)
         << " reflected back inside glass at exits and not followed";
  }
  if (photons.LostShareBound() > 0.1)
  {
    warning = technique + " lost " + percent(photons.FluxLostInside / in) +
      " of its photons' light on paths it cannot follow: up to " +
      percent(photons.LostShareBound()) +
      " of the caustic may be missing (docs/accuracy.md, \"Light a technique cannot follow\")";
  }
  return line.str();
}
}
