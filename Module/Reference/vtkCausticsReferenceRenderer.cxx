#include "vtkCausticsReferenceRenderer.h"

#include "vtkCausticsDensityGrid.h"
#include "vtkCausticsImageIO.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtksys/SystemTools.hxx"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <random>
#include <sstream>
#include <thread>

vtkStandardNewMacro(vtkCausticsReferenceRenderer);

namespace
{
// Bump whenever a change alters the reference's results: old cache files then miss.
const char* const ReferenceVersion = "caustics-reference-5";

/** The point-data arrays of the output, with their components (also the EXR layers). */
struct OutputArray
{
  const char* name;
  int components;
  bool optional = false; ///< absent from cache files written without it: zeros
};
const OutputArray OutputArrays[] = { { "CausticIrradiance", 3 }, { "DirectIrradiance", 3 },
  { "VolumeRadiance", 3 }, { "AirlightRadiance", 3 }, { "VolumeCausticRadiance", 3 },
  { "Transmittance", 3 }, { "Position", 3 }, { "Normal", 3 }, { "Albedo", 3 },
  { "ReceiverMask", 1 }, { "PixelArea", 1 },
  // Cache entries of renders without specular samples (their keys leave the samples
  // out) may predate these two.
  { "SpecularColor", 3, true }, { "SpecularMask", 1, true } };

/** 128-bit hash of the inputs: FNV-1a 64 and a SplitMix-based 64, over the same bytes. */
class Hasher
{
public:
  void Bytes(const void* data, std::size_t size)
  {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i)
    {
      this->A = (this->A ^ bytes[i]) * 0x100000001b3ULL;
      this->Word = (this->Word << 8) | bytes[i];
      if (++this->Filled == 8)
      {
        this->Flush();
      }
    }
  }
  template <typename T>
  void Value(const T& value)
  {
    this->Bytes(&value, sizeof(T));
  }
  template <typename T>
  void Vector(const std::vector<T>& values)
  {
    this->Value(values.size());
    this->Bytes(values.data(), values.size() * sizeof(T));
  }
  void String(const std::string& text)
  {
    this->Value(text.size());
    this->Bytes(text.data(), text.size());
  }
  std::string Hex()
  {
    this->Flush();
    std::ostringstream out;
    out << std::hex << std::setfill('0') << std::setw(16) << this->A << std::setw(16) << this->B;
    return out.str();
  }

private:
  static std::uint64_t Mix(std::uint64_t z)
  {
    z ^= z >> 30;
    z *= 0xbf58476d1ce4e5b9ULL;
    z ^= z >> 27;
    z *= 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  void Flush()
  {
    this->B =
      Mix(this->B ^ this->Word ^ (std::uint64_t(this->Filled) << 56)) + 0x9e3779b97f4a7c15ULL;
    this->Word = 0;
    this->Filled = 0;
  }
  std::uint64_t A = 0xcbf29ce484222325ULL;
  std::uint64_t B = 0x243f6a8885a308d3ULL;
  std::uint64_t Word = 0;
  int Filled = 0;
};

void WriteVec3(std::ostream& out, const caustics::Vec3& v)
{
  out << ' ' << v[0] << ' ' << v[1] << ' ' << v[2];
}

bool ReadVec3(std::istream& in, caustics::Vec3& v)
{
  return static_cast<bool>(in >> v[0] >> v[1] >> v[2]);
}

/** True when a cached image has the requested size and every output array. */
bool HasOutputArrays(vtkImageData* image, const int size[2])
{
  int dims[3] = { 0, 0, 0 };
  if (image)
  {
    image->GetDimensions(dims);
  }
  bool valid = image && dims[0] == size[0] && dims[1] == size[1];
  for (const OutputArray& entry : OutputArrays)
  {
    vtkDataArray* array = valid ? image->GetPointData()->GetArray(entry.name) : nullptr;
    valid = valid &&
      (array ? array->GetNumberOfComponents() == entry.components : entry.optional);
  }
  return valid;
}

bool ReadLightStatistics(std::istream& in, caustics::ReferenceLightStatistics& s)
{
  std::string word;
  return (in >> word) && word == "light" &&
    (in >> s.photonsEmitted >> s.photonsDeposited >> s.emissionMeasure) &&
    ReadVec3(in, s.emitted) && ReadVec3(in, s.direct) && ReadVec3(in, s.deposited) &&
    ReadVec3(in, s.escaped) && ReadVec3(in, s.absorbed) && ReadVec3(in, s.bounceLimit) &&
    ReadVec3(in, s.roulette);
}

/**
 * The statistics sidecar of a cache entry (a small text file next to the image);
 * false unless it is complete and belongs to this version and key.
 */
bool ReadStatistics(
  const std::string& path, const std::string& key, caustics::ReferenceStatistics& statistics)
{
  std::ifstream in(path);
  std::string word, version, storedKey;
  std::size_t lights = 0, events = 0;
  bool valid = (in >> word >> version) && word == "version" && version == ReferenceVersion &&
    (in >> word >> storedKey) && word == "key" && storedKey == key && (in >> word >> lights) &&
    word == "lights" && lights < 100000;
  for (std::size_t l = 0; valid && l < lights; ++l)
  {
    caustics::ReferenceLightStatistics s;
    valid = ReadLightStatistics(in, s);
    statistics.lights.push_back(s);
  }
  valid = valid && (in >> word >> events) && word == "events" && events <= 65;
  for (std::size_t k = 0; valid && k < events; ++k)
  {
    caustics::Vec3 v;
    valid = ReadVec3(in, v);
    statistics.depositedByEvents.push_back(v);
  }
  return valid && (in >> word >> statistics.beams) && word == "beams" && (in >> word) &&
    word == "seconds" &&
    (in >> statistics.photonSeconds >> statistics.viewSeconds >> statistics.volumeSeconds >>
      statistics.totalSeconds);
}

/** Writes the statistics sidecar ReadStatistics() reads; false when writing fails. */
bool WriteStatistics(
  const std::string& path, const std::string& key, const caustics::ReferenceStatistics& statistics)
{
  std::ofstream out(path);
  out << std::setprecision(17);
  out << "version " << ReferenceVersion << "\nkey " << key << "\nlights "
      << statistics.lights.size() << "\n";
  for (const auto& s : statistics.lights)
  {
    out << "light " << s.photonsEmitted << ' ' << s.photonsDeposited << ' ' << s.emissionMeasure;
    for (const auto* v :
      { &s.emitted, &s.direct, &s.deposited, &s.escaped, &s.absorbed, &s.bounceLimit, &s.roulette })
    {
      WriteVec3(out, *v);
    }
    out << "\n";
  }
  out << "events " << statistics.depositedByEvents.size() << "\n";
  for (const auto& v : statistics.depositedByEvents)
  {
    WriteVec3(out, v);
    out << "\n";
  }
  out << "beams " << statistics.beams << "\nseconds " << statistics.photonSeconds << ' '
      << statistics.viewSeconds << ' ' << statistics.volumeSeconds << ' ' << statistics.totalSeconds
      << "\n";
  out.close();
  return static_cast<bool>(out);
}
}

struct vtkCausticsReferenceRenderer::Internals
{
  caustics::SceneData Scene;
  bool HasSceneInput = false;
  caustics::ReferenceTracer Tracer;
  caustics::ReferenceStatistics Statistics;
};

vtkCausticsReferenceRenderer::vtkCausticsReferenceRenderer()
  : Extractor(vtkSmartPointer<vtkCausticsSceneExtractor>::New())
  , Output(vtkSmartPointer<vtkImageData>::New())
  , Internal(new Internals)
{
  // The user's cache, not a path compiled in: the library stays relocatable.
  const char* variable = vtksys::SystemTools::GetEnv("CAUSTICS_REFERENCE_CACHE");
  const char* xdg = vtksys::SystemTools::GetEnv("XDG_CACHE_HOME");
  const char* home = vtksys::SystemTools::GetEnv("HOME");
  if (variable && *variable)
  {
    this->CacheDirectory = variable;
  }
  else if (xdg && *xdg)
  {
    this->CacheDirectory = std::string(xdg) + "/vtkcaustics/reference";
  }
  else if (home && *home)
  {
    this->CacheDirectory = std::string(home) + "/.cache/vtkcaustics/reference";
  }
}

vtkCausticsReferenceRenderer::~vtkCausticsReferenceRenderer() = default;

const char* vtkCausticsReferenceRenderer::GetVersion()
{
  return ReferenceVersion;
}

void vtkCausticsReferenceRenderer::SetInputRenderer(vtkRenderer* renderer)
{
  if (this->InputRenderer == renderer && !this->Internal->HasSceneInput)
  {
    return;
  }
  this->InputRenderer = renderer;
  this->Internal->HasSceneInput = false;
  this->Modified();
}

vtkRenderer* vtkCausticsReferenceRenderer::GetInputRenderer()
{
  return this->InputRenderer;
}

void vtkCausticsReferenceRenderer::SetScene(const caustics::SceneData& scene)
{
  this->Internal->Scene = scene;
  this->Internal->HasSceneInput = true;
  this->InputRenderer = nullptr;
  this->ImageSize[0] = scene.View.width;
  this->ImageSize[1] = scene.View.height;
  this->Modified();
}

const caustics::SceneData& vtkCausticsReferenceRenderer::GetScene() const
{
  return this->Internal->HasSceneInput ? this->Internal->Scene : this->Extractor->GetScene();
}

vtkImageData* vtkCausticsReferenceRenderer::GetOutput()
{
  return this->Output;
}

const caustics::ReferenceStatistics& vtkCausticsReferenceRenderer::GetStatistics() const
{
  return this->Internal->Statistics;
}

const std::vector<caustics::ReferencePhoton>& vtkCausticsReferenceRenderer::GetPhotons() const
{
  return this->Internal->Tracer.GetPhotons();
}

const std::vector<caustics::ReferenceBeam>& vtkCausticsReferenceRenderer::GetBeams() const
{
  return this->Internal->Tracer.GetBeams();
}

vtkIdType vtkCausticsReferenceRenderer::GetNumberOfPhotonsEmitted() const
{
  vtkIdType count = 0;
  for (const auto& light : this->Internal->Statistics.lights)
  {
    count += light.photonsEmitted;
  }
  return count;
}

vtkIdType vtkCausticsReferenceRenderer::GetNumberOfPhotonsDeposited() const
{
  vtkIdType count = 0;
  for (const auto& light : this->Internal->Statistics.lights)
  {
    count += light.photonsDeposited;
  }
  return count;
}

vtkIdType vtkCausticsReferenceRenderer::GetNumberOfBeams() const
{
  return this->Internal->Statistics.beams;
}

void vtkCausticsReferenceRenderer::GetEmittedFlux(int light, double rgb[3]) const
{
  const auto& lights = this->Internal->Statistics.lights;
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = light >= 0 && light < static_cast<int>(lights.size()) ? lights[light].emitted[c] : 0.0;
  }
}

void vtkCausticsReferenceRenderer::GetDepositedFlux(int light, double rgb[3]) const
{
  const auto& lights = this->Internal->Statistics.lights;
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] =
      light >= 0 && light < static_cast<int>(lights.size()) ? lights[light].deposited[c] : 0.0;
  }
}

caustics::ReferenceSettings vtkCausticsReferenceRenderer::GetSettings() const
{
  caustics::ReferenceSettings settings;
  settings.photonsPerLight = this->PhotonsPerLight;
  settings.volumePhotonsPerLight = this->VolumePhotonsPerLight;
  settings.maxBounces = this->MaxBounces;
  settings.seed = this->Seed;
  settings.threads = this->NumberOfThreads;
  settings.kernelRadius = this->KernelRadius;
  settings.kernelRadiusPixels = this->KernelRadiusPixels;
  settings.kernelNormalCosine = this->KernelNormalCosine;
  settings.pixelFootprint = this->PixelFootprintEstimate;
  settings.rouletteThreshold = this->RouletteThreshold;
  settings.rayMarchStep = this->RayMarchStep;
  settings.volumeKernelRadiusPixels = this->VolumeKernelRadiusPixels;
  settings.cameraSeesRefractors = this->CameraSeesRefractors;
  settings.specularSamples = this->SpecularSamples;
  if (this->InputRenderer && !this->Internal->HasSceneInput)
  {
    const double* background = this->InputRenderer->GetBackground();
    settings.background = { { background[0], background[1], background[2] } };
  }
  return settings;
}

std::string vtkCausticsReferenceRenderer::ComputeCacheKey(
  const caustics::SceneData& scene, const caustics::ReferenceSettings& settings)
{
  Hasher hash;
  hash.String(ReferenceVersion);
  // Everything that changes the result; not the thread count (results do not depend
  // on it), not mesh names, actor pointers or versions.
  hash.Value(settings.photonsPerLight);
  hash.Value(scene.Participating.enabled ? settings.volumePhotonsPerLight : std::int64_t(0));
  hash.Value(settings.maxBounces);
  hash.Value(settings.seed);
  hash.Value(settings.kernelRadius);
  hash.Value(settings.kernelRadiusPixels);
  hash.Value(settings.kernelNormalCosine);
  hash.Value(settings.rouletteThreshold);
  hash.Value(settings.rayMarchStep);
  hash.Value(settings.volumeKernelRadiusPixels);
  hash.Value(settings.cameraSeesRefractors ? 1 : 0);
  if (settings.pixelFootprint)
  {
    // Only then, as below: the kernel's keys stay those of earlier versions.
    hash.String("pixel footprint");
  }
  if (settings.specularSamples > 0)
  {
    // Only then: the keys of renders without them stay those of earlier versions.
    hash.Value(settings.specularSamples);
    hash.Value(settings.background);
  }
  hash.Value(scene.Meshes.size());
  for (const auto& mesh : scene.Meshes)
  {
    const caustics::Material& m = scene.Materials.at(mesh.material);
    hash.Value(static_cast<int>(m.role));
    hash.Value(m.albedo);
    hash.Value(m.ior);
    hash.Value(m.roughness);
    hash.Value(m.metalN);
    hash.Value(m.metalK);
    hash.Value(m.attenuation);
    hash.Vector(mesh.positions);
    hash.Vector(mesh.normals);
    hash.Vector(mesh.indices);
  }
  hash.Value(scene.Lights.size());
  for (const auto& light : scene.Lights)
  {
    hash.Value(static_cast<int>(light.type));
    hash.Value(light.position);
    hash.Value(light.direction);
    hash.Value(light.radiometric);
    hash.Value(light.cosOuter);
    hash.Value(light.cosInner);
  }
  const caustics::Camera& view = scene.View;
  hash.Value(view.width);
  hash.Value(view.height);
  hash.Bytes(view.worldToClip, sizeof(view.worldToClip));
  hash.Bytes(view.clipToWorld, sizeof(view.clipToWorld));
  const caustics::Medium& medium = scene.Participating;
  hash.Value(medium.enabled);
  if (medium.enabled)
  {
    hash.Value(medium.sigmaS);
    hash.Value(medium.sigmaA);
    hash.Value(medium.g);
    if (medium.fillsRefractors)
    {
      hash.Value(1); // only then: the keys of media in air are those of before
    }
  }
  // A density grid: its voxels' values (hashed once when loaded), scale and placement.
  // Nothing is added without one, so homogeneous keys are those of before grids.
  if (medium.enabled && medium.density)
  {
    const caustics::DensityGrid& density = *medium.density;
    hash.Value(density.GetContentHash());
    hash.Value(density.GetScale());
    hash.Bytes(density.GetMatrix(), 16 * sizeof(double));
  }
  return hash.Hex();
}

bool vtkCausticsReferenceRenderer::Fail(const std::string& message)
{
  this->LastError = message;
  this->Output->Initialize();
  this->Internal->Statistics = caustics::ReferenceStatistics();
  this->Internal->Tracer.ReleasePhotons();
  vtkErrorMacro(<< message);
  return false;
}

bool vtkCausticsReferenceRenderer::CheckSettings()
{
  if (this->ImageSize[0] < 1 || this->ImageSize[1] < 1 || this->ImageSize[0] > 16384 ||
    this->ImageSize[1] > 16384)
  {
    return this->Fail("image size " + std::to_string(this->ImageSize[0]) + " x " +
      std::to_string(this->ImageSize[1]) + " must lie within 1 ... 16384 pixels per side");
  }
  const struct
  {
    const char* name;
    double value;
  } values[] = { { "KernelRadius", this->KernelRadius },
    { "KernelRadiusPixels", this->KernelRadiusPixels },
    { "KernelNormalCosine", this->KernelNormalCosine },
    { "RouletteThreshold", this->RouletteThreshold }, { "RayMarchStep", this->RayMarchStep },
    { "VolumeKernelRadiusPixels", this->VolumeKernelRadiusPixels } };
  for (const auto& entry : values)
  {
    // The clamp macros let NaN through.
    if (!std::isfinite(entry.value))
    {
      return this->Fail(std::string(entry.name) + " is not a finite number");
    }
  }
  return true;
}

bool vtkCausticsReferenceRenderer::AcquireScene()
{
  if (this->Internal->HasSceneInput)
  {
    caustics::Camera& view = this->Internal->Scene.View;
    if (view.width != this->ImageSize[0] || view.height != this->ImageSize[1])
    {
      // Pixel rays depend on the aspect ratio only through the clip transform.
      const double given = static_cast<double>(view.width) / view.height;
      const double wanted = static_cast<double>(this->ImageSize[0]) / this->ImageSize[1];
      if (view.width <= 0 || view.height <= 0 || std::abs(given - wanted) > 1e-9 * wanted)
      {
        return this->Fail("image size " + std::to_string(this->ImageSize[0]) + " x " +
          std::to_string(this->ImageSize[1]) +
          " does not have the aspect ratio of the scene's camera (" + std::to_string(view.width) +
          " x " + std::to_string(view.height) + ")");
      }
      view.width = this->ImageSize[0];
      view.height = this->ImageSize[1];
    }
    return true;
  }
  if (!this->InputRenderer)
  {
    return this->Fail("no input: call SetInputRenderer() or SetScene() before Update()");
  }
  if (!this->Extractor->Update(this->InputRenderer, this->ImageSize[0], this->ImageSize[1]))
  {
    return this->Fail("the scene could not be extracted from the renderer (no active camera?)");
  }
  return true;
}

bool vtkCausticsReferenceRenderer::Update()
{
  const auto start = std::chrono::steady_clock::now();
  this->LastError.clear();
  this->LoadedFromCache = false;
  this->CacheFile.clear();
  if (!this->CheckSettings() || !this->AcquireScene())
  {
    return false;
  }
  const caustics::SceneData& scene = this->GetScene();
  const std::string problem = caustics::ValidateReferenceScene(scene);
  if (!problem.empty())
  {
    return this->Fail("bad scene: " + problem);
  }
  const caustics::ReferenceSettings settings = this->GetSettings();
  if (!this->CheckWorkload(scene, settings))
  {
    return false;
  }
  std::string key;
  if (this->UseCache && !this->CacheDirectory.empty())
  {
    key = ComputeCacheKey(scene, settings);
    this->CacheFile = this->CacheDirectory + "/reference-" + key + ".exr";
    this->LoadedFromCache = this->LoadFromCache(key);
  }
  if (!this->LoadedFromCache)
  {
    if (!this->Render(scene, settings))
    {
      return false;
    }
    if (!key.empty())
    {
      this->StoreInCache(key);
    }
  }
  this->WallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

bool vtkCausticsReferenceRenderer::CheckWorkload(
  const caustics::SceneData& scene, const caustics::ReferenceSettings& settings)
{
  if (scene.HasSpecular && !scene.Lights.empty() && settings.photonsPerLight <= 0)
  {
    return this->Fail("PhotonsPerLight is 0: the scene has specular objects and lights, "
                      "so its caustics cannot be estimated");
  }
  if (scene.HasSpecular && !scene.Lights.empty() && scene.Participating.enabled &&
    settings.volumePhotonsPerLight <= 0)
  {
    return this->Fail("VolumePhotonsPerLight is 0: the scene has a medium, specular objects "
                      "and lights, so its volume caustics cannot be estimated");
  }
  if ((settings.photonsPerLight + settings.volumePhotonsPerLight) *
      static_cast<double>(scene.Lights.size()) >
    4e9)
  {
    return this->Fail("PhotonsPerLight x lights exceeds 4e9 photons (about 270 GB of deposits)");
  }
  if (settings.rayMarchStep > 0.0 && scene.Participating.enabled &&
    scene.Scale() / settings.rayMarchStep > 1e5)
  {
    return this->Fail("RayMarchStep " + std::to_string(settings.rayMarchStep) +
      " m is too small for a scene of " + std::to_string(scene.Scale()) +
      " m (more than 1e5 steps per ray)");
  }
  return true;
}

bool vtkCausticsReferenceRenderer::Render(
  const caustics::SceneData& scene, const caustics::ReferenceSettings& settings)
{
  caustics::ReferenceImage image;
  std::string error;
  double progress = 0.0;
  this->InvokeEvent(vtkCommand::ProgressEvent, &progress);
  const bool ok = this->Internal->Tracer.Render(
    scene, settings, image, this->Internal->Statistics,
    [this](double value)
    {
      double fraction = value;
      this->InvokeEvent(vtkCommand::ProgressEvent, &fraction);
    },
    error);
  if (!ok)
  {
    return this->Fail(error);
  }
  this->MakeOutput(image);
  return true;
}

void vtkCausticsReferenceRenderer::MakeOutput(const caustics::ReferenceImage& image)
{
  auto output = vtkSmartPointer<vtkImageData>::New();
  output->SetDimensions(image.width, image.height, 1);
  const vtkIdType pixels = static_cast<vtkIdType>(image.width) * image.height;
  auto add = [&](const char* name, int components, const std::vector<float>& values)
  {
    vtkNew<vtkFloatArray> array;
    array->SetName(name);
    array->SetNumberOfComponents(components);
    array->SetNumberOfTuples(pixels);
    std::copy(values.begin(), values.end(), array->GetPointer(0));
    output->GetPointData()->AddArray(array);
  };
  std::vector<float> volume(image.airlight.size());
  for (std::size_t k = 0; k < volume.size(); ++k)
  {
    volume[k] = image.airlight[k] + image.volumeCaustic[k];
  }
  add("CausticIrradiance", 3, image.caustic);
  add("DirectIrradiance", 3, image.direct);
  add("VolumeRadiance", 3, volume);
  add("AirlightRadiance", 3, image.airlight);
  add("VolumeCausticRadiance", 3, image.volumeCaustic);
  add("Transmittance", 3, image.transmittance);
  add("Position", 3, image.position);
  add("Normal", 3, image.normal);
  add("Albedo", 3, image.albedo);
  add("ReceiverMask", 1, image.mask);
  add("PixelArea", 1, image.pixelArea);
  add("SpecularColor", 3, image.specular);
  add("SpecularMask", 1, image.specularMask);
  this->Output->ShallowCopy(output);
}

bool vtkCausticsReferenceRenderer::LoadFromCache(const std::string& key)
{
  const std::string exr = this->CacheFile;
  const std::string sidecar = this->CacheDirectory + "/reference-" + key + ".txt";
  if (!vtksys::SystemTools::FileExists(exr, true) ||
    !vtksys::SystemTools::FileExists(sidecar, true))
  {
    return false;
  }
  std::string error;
  vtkSmartPointer<vtkImageData> image = vtkCausticsImageIO::ReadEXR(exr, &error);
  caustics::ReferenceStatistics statistics;
  if (!HasOutputArrays(image, this->ImageSize) || !ReadStatistics(sidecar, key, statistics))
  {
    vtkWarningMacro(<< "ignoring unreadable cache entry " << exr
                    << (error.empty() ? std::string() : ": " + error));
    return false;
  }
  auto output = vtkSmartPointer<vtkImageData>::New();
  output->SetDimensions(this->ImageSize[0], this->ImageSize[1], 1);
  for (const OutputArray& entry : OutputArrays)
  {
    vtkDataArray* array = image->GetPointData()->GetArray(entry.name);
    if (!array)
    {
      vtkNew<vtkFloatArray> zeros; // an optional array the entry predates
      zeros->SetName(entry.name);
      zeros->SetNumberOfComponents(entry.components);
      zeros->SetNumberOfTuples(static_cast<vtkIdType>(this->ImageSize[0]) * this->ImageSize[1]);
      zeros->Fill(0.0);
      output->GetPointData()->AddArray(zeros);
      continue;
    }
    output->GetPointData()->AddArray(array);
  }
  this->Output->ShallowCopy(output);
  this->Internal->Statistics = statistics;
  this->Internal->Tracer.ReleasePhotons();
  return true;
}

void vtkCausticsReferenceRenderer::StoreInCache(const std::string& key)
{
  if (!vtksys::SystemTools::MakeDirectory(this->CacheDirectory))
  {
    vtkWarningMacro(<< "cannot create the cache directory " << this->CacheDirectory
                    << "; the result is not cached");
    return;
  }
  // Write under unique temporary names, then rename: concurrent tests may render
  // the same scene, and a reader must never see a half-written file.
  std::random_device device;
  std::ostringstream unique;
  unique << std::hex << device() << device();
  const std::string base = this->CacheDirectory + "/reference-" + key;
  const std::string exrTemp = base + "." + unique.str() + ".tmp.exr";
  const std::string textTemp = base + "." + unique.str() + ".tmp.txt";
  std::vector<std::pair<std::string, std::string>> layers;
  for (const OutputArray& entry : OutputArrays)
  {
    layers.emplace_back(entry.name, entry.name);
  }
  std::string error;
  bool ok = vtkCausticsImageIO::WriteEXR(this->Output, layers, exrTemp, &error);
  if (ok && !WriteStatistics(textTemp, key, this->Internal->Statistics))
  {
    ok = false;
    error = "cannot write " + textTemp;
  }
  // The statistics go first: a reader needs both and checks the image last.
  ok = ok && std::rename(textTemp.c_str(), (base + ".txt").c_str()) == 0 &&
    std::rename(exrTemp.c_str(), (base + ".exr").c_str()) == 0;
  if (!ok)
  {
    std::remove(exrTemp.c_str());
    std::remove(textTemp.c_str());
    vtkWarningMacro(<< "the result could not be cached in " << this->CacheDirectory
                    << (error.empty() ? std::string() : ": " + error));
  }
}

void vtkCausticsReferenceRenderer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Input: "
     << (this->Internal->HasSceneInput ? "scene snapshot"
                                       : (this->InputRenderer ? "renderer" : "(none)"))
     << "\n";
  os << indent << "ImageSize: " << this->ImageSize[0] << " x " << this->ImageSize[1] << "\n";
  os << indent << "PhotonsPerLight: " << this->PhotonsPerLight << "\n";
  os << indent << "VolumePhotonsPerLight: " << this->VolumePhotonsPerLight << "\n";
  os << indent << "MaxBounces: " << this->MaxBounces << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << " (0 = all cores)\n";
  os << indent << "KernelRadius: " << this->KernelRadius << " m (0 = from pixels)\n";
  os << indent << "KernelRadiusPixels: " << this->KernelRadiusPixels << "\n";
  os << indent << "PixelFootprintEstimate: " << (this->PixelFootprintEstimate ? "on" : "off")
     << "\n";
  os << indent << "KernelNormalCosine: " << this->KernelNormalCosine << "\n";
  os << indent << "RouletteThreshold: " << this->RouletteThreshold << "\n";
  os << indent << "RayMarchStep: " << this->RayMarchStep << " m (0 = scene size / 256)\n";
  os << indent << "VolumeKernelRadiusPixels: " << this->VolumeKernelRadiusPixels << "\n";
  os << indent << "CameraSeesRefractors: " << this->CameraSeesRefractors << "\n";
  os << indent << "SpecularSamples: " << this->SpecularSamples << "\n";
  os << indent << "UseCache: " << (this->UseCache ? "on" : "off") << "\n";
  os << indent << "CacheDirectory: " << this->CacheDirectory << "\n";
  os << indent << "Version: " << ReferenceVersion << "\n";
  os << indent << "LastError: " << this->LastError << "\n";
  os << indent << "LoadedFromCache: " << (this->LoadedFromCache ? "yes" : "no") << "\n";
  os << indent << "PhotonsEmitted: " << this->GetNumberOfPhotonsEmitted() << "\n";
  os << indent << "PhotonsDeposited: " << this->GetNumberOfPhotonsDeposited() << "\n";
  os << indent << "Beams: " << this->GetNumberOfBeams() << "\n";
  const auto& lights = this->Internal->Statistics.lights;
  for (std::size_t l = 0; l < lights.size(); ++l)
  {
    os << indent << "Light " << l << ": emitted " << lights[l].emitted[0] << ' '
       << lights[l].emitted[1] << ' ' << lights[l].emitted[2] << " W, deposited "
       << lights[l].deposited[0] << ' ' << lights[l].deposited[1] << ' ' << lights[l].deposited[2]
       << " W\n";
  }
  os << indent << "WallTime: " << this->WallTime << " s\n";
}
