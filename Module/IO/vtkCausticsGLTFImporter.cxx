#include "vtkCausticsGLTFImporter.h"

#include "vtkCausticsFileText.h"
#include "vtkCausticsGLTFDocumentChecker.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkEventForwarderCommand.h"
#include "vtkGLTFDocumentLoader.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtksys/SystemTools.hxx"

#include <vtk_jsoncpp.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkCausticsGLTFImporter);

namespace
{
const double Pi = vtkMath::Pi();
const double NaN = std::numeric_limits<double>::quiet_NaN();
/** Deepest nesting of JSON arrays and objects read (jsoncpp's default limit). */
const int MaxJSONDepth = 1000;

void CollectMessages(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* messages = static_cast<std::vector<std::string>*>(clientData);
  std::string message = callData ? static_cast<const char*>(callData) : "";
  // vtkErrorMacro texts look like "ERROR: In file, line N\nClass (0x...): message\n\n".
  const std::size_t object = message.find("): ");
  if (object != std::string::npos)
  {
    message = message.substr(object + 3);
  }
  while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
  {
    message.pop_back();
  }
  std::replace(message.begin(), message.end(), '\n', ' ');
  messages->push_back(message);
}

/** Point (w = 1) or direction (w = 0) through a node's world matrix. */
caustics::Vec3 Transform(vtkMatrix4x4* matrix, double x, double y, double z, double w)
{
  const double in[4] = { x, y, z, w };
  double out[4];
  matrix->MultiplyPoint(in, out);
  return { { out[0], out[1], out[2] } };
}

/** Scales v to unit length; false when it has none (zero, NaN or infinite). */
bool Normalize(caustics::Vec3& v)
{
  const double length = vtkMath::Norm(v.data());
  if (!(length > 0.0) || !std::isfinite(length))
  {
    return false;
  }
  for (double& c : v)
  {
    c /= length;
  }
  return true;
}

/** Pre-order walk of a scene's node trees, children in file order (no recursion: deep trees). */
std::vector<int> SceneNodes(const Json::Value& nodes, const Json::Value& roots)
{
  std::vector<int> order;
  std::vector<int> stack;
  for (Json::ArrayIndex r = roots.size(); r-- > 0;)
  {
    stack.push_back(roots[r].asInt());
  }
  while (!stack.empty())
  {
    const int node = stack.back();
    stack.pop_back();
    order.push_back(node);
    const Json::Value& children = nodes[node]["children"];
    for (Json::ArrayIndex c = children.size(); c-- > 0;)
    {
      stack.push_back(children[c].asInt());
    }
  }
  return order;
}

/**
 * A lower-case-extension path for VTK's loader: the file itself when its extension
 * is already lower case, else a symbolic link (or a copy) in a temporary folder,
 * removed with this object. An empty path when no alias can be made.
 */
class LowerCaseAlias
{
public:
  LowerCaseAlias() = default;
  LowerCaseAlias(const LowerCaseAlias&) = delete;
  LowerCaseAlias& operator=(const LowerCaseAlias&) = delete;
  ~LowerCaseAlias()
  {
    if (!this->Folder.empty())
    {
      std::error_code ignored;
      std::filesystem::remove_all(this->Folder, ignored);
    }
  }

  std::string For(const std::string& path)
  {
    const std::string extension = vtksys::SystemTools::GetFilenameLastExtension(path);
    const std::string lower = vtksys::SystemTools::LowerCase(extension);
    if (extension == lower)
    {
      return path;
    }
    std::error_code error;
    std::string folder =
      (std::filesystem::temp_directory_path(error) / "caustics-gltf-XXXXXX").string();
    if (error || !mkdtemp(&folder[0]))
    {
      return std::string();
    }
    this->Folder = folder;
    const std::filesystem::path alias = std::filesystem::path(folder) / ("scene" + lower);
    const std::filesystem::path target = vtksys::SystemTools::CollapseFullPath(path);
    std::filesystem::create_symlink(target, alias, error);
    if (error)
    {
      error.clear();
      std::filesystem::copy_file(target, alias, error);
    }
    return error ? std::string() : alias.string();
  }

private:
  std::string Folder;
};

/**
 * Drops the images and textures from what VTK's loader will load. The caustics
 * read only a material's constant factors, and VTK 9.1's image loading crashes on
 * a corrupt or truncated PNG or JPEG (and reports "Not a PNG file!" without the
 * file's name), so images are never decoded; the importer warns about textured
 * materials instead.
 */
void SkipImages(vtkGLTFDocumentLoader::Model& model)
{
  model.Images.clear();
  model.Textures.clear();
  for (auto& material : model.Materials)
  {
    for (auto* info : { &material.PbrMetallicRoughness.BaseColorTexture,
           &material.PbrMetallicRoughness.MetallicRoughnessTexture, &material.NormalTexture,
           &material.OcclusionTexture, &material.EmissiveTexture })
    {
      info->Index = -1;
    }
  }
}

/** The first vertex index of a primitive beyond its POSITION count, as a problem; "" if none. */
std::string VertexIndexProblem(vtkPolyData* geometry)
{
  const vtkIdType numPoints = geometry->GetNumberOfPoints();
  for (vtkCellArray* cells :
    { geometry->GetVerts(), geometry->GetLines(), geometry->GetPolys(), geometry->GetStrips() })
  {
    vtkIdType npts = 0;
    const vtkIdType* ids = nullptr;
    for (cells->InitTraversal(); cells->GetNextCell(npts, ids);)
    {
      for (vtkIdType k = 0; k < npts; ++k)
      {
        if (ids[k] < 0 || ids[k] >= numPoints)
        {
          return "vertex index " + std::to_string(ids[k]) + " is out of range: POSITION has " +
            std::to_string(numPoints) + " vertices";
        }
      }
    }
  }
  return std::string();
}

/**
 * The first per-vertex array VTK's loader decoded with fewer or more values than
 * POSITION has vertices, as a problem; "" if none. The checker already refuses
 * attributes of a type glTF does not allow (VTK leaves those empty, and the scene
 * extractor read past an empty normal array); this catches what VTK still drops.
 */
std::string AttributeArrayProblem(vtkPolyData* geometry)
{
  const vtkIdType numPoints = geometry->GetNumberOfPoints();
  vtkPointData* pointData = geometry->GetPointData();
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = pointData->GetAbstractArray(a);
    if (array && array->GetNumberOfTuples() != numPoints)
    {
      return "VTK's loader decoded " + std::to_string(array->GetNumberOfTuples()) +
        " values of vertex attribute " +
        caustics::text::Quote(array->GetName() ? array->GetName() : "(unnamed)") + " for " +
        std::to_string(numPoints) + " vertices";
    }
  }
  return std::string();
}

/**
 * Why node n's world transform cannot be used, or "": it must be finite, and
 * give cameras and directional or spot lights a direction (cameras also an up
 * vector off their axis).
 */
std::string NodeTransformProblem(
  const Json::Value& nodes, const Json::Value& lights, int n, vtkMatrix4x4* world)
{
  if (!world ||
    !std::all_of(
      world->GetData(), world->GetData() + 16, [](double v) { return std::isfinite(v); }))
  {
    return "the world transform is not finite (overflow?)";
  }
  const Json::Value& light = nodes[n]["extensions"]["KHR_lights_punctual"];
  const bool isCamera = nodes[n].isMember("camera");
  const bool aims = isCamera ||
    (light.isMember("light") && lights[light["light"].asInt()]["type"].asString() != "point");
  auto forward = Transform(world, 0, 0, -1, 0);
  auto up = Transform(world, 0, 1, 0, 0);
  bool directed = Normalize(forward);
  if (isCamera && directed && Normalize(up))
  {
    // A view needs an up vector off its axis: sin(angle) > 1e-6, far above
    // rounding, is what OrthogonalizeViewUp can work with (else a blank image).
    caustics::Vec3 side;
    vtkMath::Cross(forward.data(), up.data(), side.data());
    if (!(vtkMath::Norm(side.data()) > 1e-6))
    {
      return "the world transform maps the camera's up axis (+y) onto its view axis (-z): the "
             "up vector is parallel to the view direction";
    }
  }
  else if (isCamera)
  {
    directed = false;
  }
  if (aims && !directed)
  {
    return std::string("the world transform is degenerate (zero scale?), so the ") +
      (isCamera ? "camera" : "light") + " has no direction";
  }
  return std::string();
}
}

struct vtkCausticsGLTFImporter::Internals
{
  struct Source
  {
    int Node, Mesh, Primitive, Material;
  };

  Json::Value Document;   ///< the validated glTF JSON
  std::vector<int> Nodes; ///< nodes of the imported scene, pre-order
  std::map<vtkActor*, Source> Sources;
  std::vector<std::string> LoaderMessages;

  int SceneIndex() const { return this->Document.get("scene", 0).asInt(); }
};

vtkCausticsGLTFImporter::vtkCausticsGLTFImporter()
  : Internal(new Internals)
{
}

vtkCausticsGLTFImporter::~vtkCausticsGLTFImporter() = default;

bool vtkCausticsGLTFImporter::Read()
{
  this->LastError.clear();
  try
  {
    this->Superclass::Read();
  }
  catch (const std::exception& e)
  {
    this->Fail(std::string("unexpected glTF structure (") + e.what() + ")");
  }
  return this->LastError.empty();
}

int vtkCausticsGLTFImporter::Fail(const std::string& problem)
{
  this->LastError = (this->FileName ? std::string(this->FileName) + ": " : std::string()) + problem;
  vtkErrorMacro(<< this->LastError);
  this->Loader = nullptr;
  this->Internal->Sources.clear();
  return 0;
}

void vtkCausticsGLTFImporter::SetCamera(vtkIdType index)
{
  if (this->CameraIndex != index)
  {
    this->CameraIndex = index;
    this->Modified();
  }
}

vtkIdType vtkCausticsGLTFImporter::GetNumberOfCameras()
{
  return this->Loader ? this->Superclass::GetNumberOfCameras() : 0;
}

std::string vtkCausticsGLTFImporter::GetCameraName(vtkIdType index)
{
  return this->Loader ? this->Superclass::GetCameraName(index) : std::string();
}

vtkIdType vtkCausticsGLTFImporter::GetNumberOfAnimations()
{
  return this->Loader ? this->Superclass::GetNumberOfAnimations() : 0;
}

void vtkCausticsGLTFImporter::UpdateTimeStep(double time)
{
  if (this->Loader)
  {
    this->Superclass::UpdateTimeStep(time);
  }
}

bool vtkCausticsGLTFImporter::IsAnimationEnabled(vtkIdType index)
{
  return index >= 0 && index < static_cast<vtkIdType>(this->EnabledAnimations.size()) &&
    this->EnabledAnimations[index];
}

bool vtkCausticsGLTFImporter::GetActorSource(
  vtkActor* actor, int& node, int& mesh, int& primitive, int& material)
{
  const auto it = this->Internal->Sources.find(actor);
  if (it == this->Internal->Sources.end())
  {
    return false;
  }
  node = it->second.Node;
  mesh = it->second.Mesh;
  primitive = it->second.Primitive;
  material = it->second.Material;
  return true;
}

int vtkCausticsGLTFImporter::ImportBegin()
{
  try
  {
    return this->CheckAndLoad();
  }
  catch (const std::exception& e)
  {
    // Last resort: jsoncpp throws on a member of an unexpected JSON type that the
    // checks above do not cover.
    return this->Fail(std::string("unexpected glTF structure (") + e.what() + ")");
  }
}

int vtkCausticsGLTFImporter::CheckAndLoad()
{
  this->Internal->Sources.clear();
  this->Internal->Nodes.clear();
  this->Internal->LoaderMessages.clear();
  this->CameraAspectRatio = 0.0;
  this->Loader = nullptr;
  this->EnabledAnimations.clear();

  // 1. The file, its JSON and what it refers to, before VTK's loader sees it.
  if (!this->FileName || !*this->FileName)
  {
    return this->Fail("no glTF file name given");
  }
  const std::string path = this->FileName;
  std::string contents, json;
  bool binary = false;
  std::size_t binSize = 0;
  if (!this->ReadFile(path, contents) ||
    !this->SplitContainer(path, contents, json, binary, binSize) || !this->ParseJSON(json) ||
    !this->ValidateDocument(path, binary, binSize))
  {
    return 0;
  }
  // 2. VTK's loader, its messages collected so that they name the file.
  // 3. What VTK decoded: vertex indices and world transforms of the scene.
  if (!this->RunLoader(path, binary) || !this->CheckVertexIndices() || !this->CheckSceneNodes())
  {
    return 0;
  }
  this->EnabledAnimations.assign(this->Loader->GetInternalModel()->Animations.size(), false);
  return 1;
}

int vtkCausticsGLTFImporter::ReadFile(const std::string& path, std::string& contents)
{
  if (!vtksys::SystemTools::FileExists(path, true))
  {
    return this->Fail(
      vtksys::SystemTools::FileIsDirectory(path) ? "is a folder, not a glTF file" : "no such file");
  }
  std::ifstream file(path, std::ios::binary);
  std::ostringstream buffer;
  buffer << file.rdbuf();
  if (!file || file.bad())
  {
    return this->Fail("cannot be read (permissions?)");
  }
  contents = buffer.str();
  if (contents.empty())
  {
    return this->Fail("the file is empty");
  }
  return 1;
}

int vtkCausticsGLTFImporter::SplitContainer(const std::string& path, const std::string& contents,
  std::string& json, bool& binary, std::size_t& binSize)
{
  binary = contents.compare(0, 4, "glTF") == 0;
  const std::string extension = vtksys::SystemTools::GetFilenameLastExtension(path);
  const std::string lowerExtension = vtksys::SystemTools::LowerCase(extension);
  if (lowerExtension != ".glb" && lowerExtension != ".gltf")
  {
    return this->Fail(
      "unknown extension " + caustics::gltf::QuotedName(extension) + " (expected .gltf or .glb)");
  }
  if (binary != (lowerExtension == ".glb"))
  {
    // VTK's loader decides between JSON and binary glTF by the extension.
    return this->Fail(binary ? "binary glTF content needs the file extension '.glb'"
                             : "a '.glb' file must start with the binary glTF magic 'glTF'");
  }
  json = contents;
  binSize = 0;
  if (binary)
  {
    const std::string problem = caustics::gltf::SplitBinary(contents, json, binSize);
    if (!problem.empty())
    {
      return this->Fail(problem);
    }
  }
  return 1;
}

int vtkCausticsGLTFImporter::ParseJSON(const std::string& json)
{
  Json::CharReaderBuilder builder;
  builder["collectComments"] = false;
  builder["allowComments"] = false;
  builder["strictRoot"] = true;
  builder["rejectDupKeys"] = true;
  builder["failIfExtra"] = true;
  builder["allowTrailingCommas"] = false; // JSON has none; jsoncpp allows them by default
  // NaN/Infinity (as Python's json module writes them) are parsed so that the
  // error can name the member, instead of a bare syntax error.
  builder["allowSpecialFloats"] = true;
  // jsoncpp's default nesting limit, and VTK's loader's: it throws beyond it.
  builder["stackLimit"] = MaxJSONDepth;
  std::unique_ptr<Json::CharReader> reader(builder.newCharReader());
  std::string errors;
  Json::Value& document = this->Internal->Document;
  document = Json::Value();
  try
  {
    if (!reader->parse(json.data(), json.data() + json.size(), &document, &errors))
    {
      return this->Fail("malformed JSON at " + caustics::gltf::OneLineErrors(errors));
    }
  }
  catch (const std::exception&)
  {
    return this->Fail("malformed JSON: arrays and objects nested more than " +
      std::to_string(MaxJSONDepth) + " levels deep");
  }
  return 1;
}

int vtkCausticsGLTFImporter::ValidateDocument(
  const std::string& path, bool binary, std::size_t binSize)
{
  const Json::Value& document = this->Internal->Document;
  const std::string folder =
    vtksys::SystemTools::GetFilenamePath(vtksys::SystemTools::CollapseFullPath(path));
  const std::string problem = caustics::gltf::CheckDocument(document, folder, binary, binSize);
  if (!problem.empty())
  {
    return this->Fail(problem);
  }
  const vtkIdType cameras = document["cameras"].size();
  if (this->CameraIndex >= cameras && !(this->CameraIndex == 0 && cameras == 0))
  {
    return this->Fail("camera index " + std::to_string(this->CameraIndex) +
      " is out of range: the file has " + caustics::gltf::CountOf(cameras, "camera"));
  }
  return 1;
}

int vtkCausticsGLTFImporter::RunLoader(const std::string& path, bool binary)
{
  this->Textures.clear();
  this->Loader = vtkSmartPointer<vtkGLTFDocumentLoader>::New();
  vtkNew<vtkEventForwarderCommand> forwarder;
  forwarder->SetTarget(this);
  this->Loader->AddObserver(vtkCommand::ProgressEvent, forwarder);
  vtkNew<vtkCallbackCommand> collect;
  collect->SetCallback(CollectMessages);
  collect->SetClientData(&this->Internal->LoaderMessages);
  this->Loader->AddObserver(vtkCommand::ErrorEvent, collect);
  this->Loader->AddObserver(vtkCommand::WarningEvent, collect);
  std::vector<char> glbBuffer;
  const auto& messages = this->Internal->LoaderMessages;
  auto loaderFailed = [&](const char* step)
  {
    return this->Fail(std::string("VTK's glTF loader failed to ") + step +
      (messages.empty()
          ? std::string()
          : ": " + caustics::text::Printable(messages.back(), caustics::text::ReasonLength)));
  };
  // VTK 9.1's loader accepts only the exact extensions ".gltf" and ".glb"; a
  // "scene.GLTF" is read through a lower-case alias. Relative buffer URIs still
  // resolve next to the real file: the model's file name is set back below.
  LowerCaseAlias alias;
  const std::string loaderPath = alias.For(path);
  if (loaderPath.empty())
  {
    return this->Fail("cannot read a file with an upper-case extension (no temporary folder "
                      "for a lower-case alias); rename it to .gltf or .glb");
  }
  if (binary && !this->Loader->LoadFileBuffer(loaderPath, glbBuffer))
  {
    return loaderFailed("read the binary chunk");
  }
  if (!this->Loader->LoadModelMetaDataFromFile(loaderPath))
  {
    return loaderFailed("read the JSON");
  }
  if (loaderPath != path)
  {
    this->Loader->GetInternalModel()->FileName = vtksys::SystemTools::CollapseFullPath(path);
  }
  SkipImages(*this->Loader->GetInternalModel());
  if (!this->Loader->LoadModelData(glbBuffer))
  {
    return loaderFailed("load the buffers");
  }
  if (!this->Loader->BuildModelVTKGeometry())
  {
    return loaderFailed("build the geometry");
  }
  for (const std::string& message : messages)
  {
    // VTK warns about the extensions only this class reads.
    if (!caustics::gltf::MentionsOwnExtension(message))
    {
      vtkWarningMacro(<< path << ": VTK's glTF loader: "
                      << caustics::text::Printable(message, caustics::text::ReasonLength));
    }
  }
  return 1;
}

int vtkCausticsGLTFImporter::CheckVertexIndices()
{
  auto model = this->Loader->GetInternalModel();
  for (std::size_t m = 0; m < model->Meshes.size(); ++m)
  {
    for (std::size_t p = 0; p < model->Meshes[m].Primitives.size(); ++p)
    {
      const std::string where =
        "meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) + "]";
      vtkPolyData* geometry = model->Meshes[m].Primitives[p].Geometry;
      if (!geometry || !geometry->GetPoints())
      {
        return this->Fail(where + ": VTK's loader built no geometry");
      }
      std::string problem = VertexIndexProblem(geometry);
      problem = problem.empty() ? AttributeArrayProblem(geometry) : problem;
      if (!problem.empty())
      {
        return this->Fail(where + ": " + problem);
      }
    }
  }
  return 1;
}

int vtkCausticsGLTFImporter::CheckSceneNodes()
{
  const Json::Value& document = this->Internal->Document;
  const Json::Value& nodes = document["nodes"];
  this->Internal->Nodes =
    SceneNodes(nodes, document["scenes"][this->Internal->SceneIndex()]["nodes"]);
  const Json::Value& lights = document["extensions"]["KHR_lights_punctual"]["lights"];
  auto model = this->Loader->GetInternalModel();
  for (int n : this->Internal->Nodes)
  {
    const std::string problem =
      NodeTransformProblem(nodes, lights, n, model->Nodes[n].GlobalTransform);
    if (!problem.empty())
    {
      return this->Fail("nodes[" + std::to_string(n) + "]: " + problem);
    }
  }
  return 1;
}

namespace
{
/** Sets a vtkProperty from a glTF material object (an empty object is glTF's default material). */
void ApplyMaterial(vtkActor* actor, const Json::Value& material)
{
  const Json::Value& extensions = material["extensions"];
  if (extensions.isMember("KHR_materials_unlit"))
  {
    // Unlit surfaces neither receive nor redirect light; VTK draws them as they are.
    vtkCausticsMaterial::SetRole(actor, vtkCausticsMaterial::ROLE_NONE);
    return;
  }
  const Json::Value& pbr = material["pbrMetallicRoughness"];
  double color[4] = { 1.0, 1.0, 1.0, 1.0 };
  for (Json::ArrayIndex c = 0; c < 4 && pbr.isMember("baseColorFactor"); ++c)
  {
    color[c] = pbr["baseColorFactor"][c].asDouble();
  }
  vtkProperty* property = actor->GetProperty();
  property->SetInterpolationToPBR();
  property->SetColor(color);
  property->SetDiffuse(1.0);
  // Only BLEND makes alpha a coverage; MASK cuts per texel, which caustics ignore.
  property->SetOpacity(material.get("alphaMode", "OPAQUE").asString() == "BLEND" ? color[3] : 1.0);
  property->SetMetallic(pbr.get("metallicFactor", 1.0).asDouble());
  property->SetRoughness(pbr.get("roughnessFactor", 1.0).asDouble());
  property->SetBaseIOR(extensions["KHR_materials_ior"].get("ior", 1.5).asDouble());
  if (extensions.isMember("KHR_materials_transmission"))
  {
    vtkCausticsMaterial::SetTransmission(
      property, extensions["KHR_materials_transmission"].get("transmissionFactor", 0.0).asDouble());
  }
  const Json::Value& volume = extensions["KHR_materials_volume"];
  if (volume.isMember("attenuationDistance"))
  {
    // Beer-Lambert: a ray keeps attenuationColor of its power after
    // attenuationDistance, so sigma = -ln(color) / distance. A zero colour is
    // taken as 1e-6 (opaque after that distance) to keep sigma finite.
    const double distance = volume["attenuationDistance"].asDouble();
    double sigma[3];
    for (Json::ArrayIndex c = 0; c < 3; ++c)
    {
      const double kept = volume.isMember("attenuationColor")
        ? std::max(1e-6, volume["attenuationColor"][c].asDouble())
        : 1.0;
      sigma[c] = -std::log(kept) / distance;
    }
    vtkCausticsMaterial::SetAttenuation(property, sigma);
  }
}

/** Textures a material uses that caustics do not read, for a warning. */
std::string IgnoredTextures(const Json::Value& material)
{
  std::string names;
  auto note = [&names](bool used, const char* name)
  {
    if (used)
    {
      names += (names.empty() ? "" : ", ") + std::string(name);
    }
  };
  const Json::Value& pbr = material["pbrMetallicRoughness"];
  note(pbr.isMember("baseColorTexture"), "baseColorTexture");
  note(pbr.isMember("metallicRoughnessTexture"), "metallicRoughnessTexture");
  note(material["extensions"]["KHR_materials_transmission"].isMember("transmissionTexture"),
    "transmissionTexture");
  return names;
}
}

void vtkCausticsGLTFImporter::ImportActors(vtkRenderer* renderer)
{
  this->Superclass::ImportActors(renderer);
  const Json::Value& document = this->Internal->Document;
  const Json::Value& nodes = document["nodes"];
  const Json::Value& meshes = document["meshes"];
  const Json::Value defaultMaterial(Json::objectValue);
  std::set<int> warned;
  for (const auto& entry : this->Actors)
  {
    const int node = entry.first;
    if (entry.second.empty())
    {
      continue;
    }
    const int mesh = nodes[node]["mesh"].asInt();
    const Json::Value& primitives = meshes[mesh]["primitives"];
    for (std::size_t k = 0; k < entry.second.size(); ++k)
    {
      vtkActor* actor = entry.second[k];
      const Json::Value& primitive = primitives[static_cast<Json::ArrayIndex>(k)];
      const int material = primitive.get("material", -1).asInt();
      const Json::Value& definition =
        material >= 0 ? document["materials"][material] : defaultMaterial;
      ApplyMaterial(actor, definition);
      const std::string ignored = IgnoredTextures(definition);
      if (!ignored.empty() && warned.insert(material).second)
      {
        vtkWarningMacro(<< this->FileName << ": materials[" << material << "] uses " << ignored
                        << "; caustics read only the material's constant factors");
      }

      // Names for messages: the node's, else the mesh's, plus the primitive if several.
      std::string name = nodes[node].get("name", "").asString();
      if (name.empty())
      {
        name = meshes[mesh].get("name", "").asString();
      }
      if (name.empty())
      {
        name = "mesh " + std::to_string(mesh);
      }
      if (primitives.size() > 1)
      {
        name += "[" + std::to_string(k) + "]";
      }
      vtkCausticsMaterial::SetName(actor, name);
      this->Internal->Sources[actor] = { node, mesh, static_cast<int>(k), material };
    }
  }
}

void vtkCausticsGLTFImporter::ImportLights(vtkRenderer* renderer)
{
  // Replaces vtkGLTFImporter::ImportLights: see the class description for what it gets wrong.
  const Json::Value& document = this->Internal->Document;
  const Json::Value& lights = document["extensions"]["KHR_lights_punctual"]["lights"];
  auto model = this->Loader->GetInternalModel();
  for (int n : this->Internal->Nodes)
  {
    const Json::Value& link = document["nodes"][n]["extensions"]["KHR_lights_punctual"];
    if (!link.isMember("light"))
    {
      continue;
    }
    const Json::Value& definition = lights[link["light"].asInt()];
    vtkMatrix4x4* world = model->Nodes[n].GlobalTransform;
    const caustics::Vec3 position = Transform(world, 0, 0, 0, 1);
    caustics::Vec3 direction = Transform(world, 0, 0, -1, 0);
    Normalize(direction); // checked in ImportBegin for directional and spot lights

    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->SetPosition(position.data());
    light->SetFocalPoint(
      position[0] + direction[0], position[1] + direction[1], position[2] + direction[2]);
    double color[3] = { 1.0, 1.0, 1.0 };
    for (Json::ArrayIndex c = 0; c < 3 && definition.isMember("color"); ++c)
    {
      color[c] = definition["color"][c].asDouble();
    }
    light->SetColor(color);
    // Radiometric: W/m^2 (directional) or W/sr (point, spot); see the class description.
    light->SetIntensity(definition.get("intensity", 1.0).asDouble());
    const std::string type = definition["type"].asString();
    if (type == "directional")
    {
      light->SetPositional(false);
    }
    else
    {
      light->SetPositional(true);
      light->SetAttenuationValues(0.0, 0.0, 1.0); // 1/r^2 in VTK's own shading
      if (type == "spot")
      {
        const Json::Value& spot = definition["spot"];
        light->SetConeAngle(
          vtkMath::DegreesFromRadians(spot.get("outerConeAngle", Pi / 4.0).asDouble()));
        vtkNew<vtkInformation> information;
        information->Set(vtkCausticsSceneExtractor::INNER_CONE_ANGLE(),
          vtkMath::DegreesFromRadians(spot.get("innerConeAngle", 0.0).asDouble()));
        light->SetInformation(information);
      }
      else
      {
        // No cone: VTK's surface shading and vtkCausticsSceneExtractor take any
        // angle >= 90 degrees as a point light (VTK's fluid mapper only > 90).
        light->SetConeAngle(180.0);
      }
    }
    renderer->AddLight(light);
  }
}

namespace
{
/**
 * A camera at a node's world transform. glTF cameras have no focal point; VTK
 * rotates about it, so it is put level with the scene's centre (1 m ahead when the
 * scene is behind, or when there is no centre).
 */
vtkSmartPointer<vtkCamera> PlaceCamera(vtkMatrix4x4* world, const double* center)
{
  const caustics::Vec3 position = Transform(world, 0, 0, 0, 1);
  caustics::Vec3 forward = Transform(world, 0, 0, -1, 0);
  caustics::Vec3 up = Transform(world, 0, 1, 0, 0);
  Normalize(forward);
  Normalize(up);
  double distance = 1.0;
  if (center)
  {
    const double toCenter[3] = { center[0] - position[0], center[1] - position[1],
      center[2] - position[2] };
    const double along = vtkMath::Dot(toCenter, forward.data());
    distance = along > 0.0 ? along : distance;
  }
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetPosition(position.data());
  camera->SetFocalPoint(position[0] + distance * forward[0], position[1] + distance * forward[1],
    position[2] + distance * forward[2]);
  camera->SetViewUp(up.data());
  camera->OrthogonalizeViewUp();
  return camera;
}

/**
 * The projection of a glTF camera definition. Returns its aspect ratio (0 when
 * not given) and whether its frustum is infinite (a perspective without zfar).
 */
void SetProjection(
  vtkCamera* camera, const Json::Value& definition, double& aspectRatio, bool& infinite)
{
  infinite = false;
  if (definition["type"].asString() == "perspective")
  {
    const Json::Value& perspective = definition["perspective"];
    camera->SetParallelProjection(false);
    camera->SetViewAngle(vtkMath::DegreesFromRadians(perspective["yfov"].asDouble()));
    const double znear = perspective["znear"].asDouble();
    infinite = !perspective.isMember("zfar");
    camera->SetClippingRange(znear, perspective.get("zfar", 2.0 * znear).asDouble());
    aspectRatio = perspective.get("aspectRatio", 0.0).asDouble();
  }
  else
  {
    const Json::Value& orthographic = definition["orthographic"];
    camera->SetParallelProjection(true);
    camera->SetParallelScale(orthographic["ymag"].asDouble());
    camera->SetClippingRange(orthographic["znear"].asDouble(), orthographic["zfar"].asDouble());
    aspectRatio = orthographic["xmag"].asDouble() / orthographic["ymag"].asDouble();
  }
}
}

void vtkCausticsGLTFImporter::ImportCameras(vtkRenderer* renderer)
{
  // Replaces vtkGLTFImporter::ImportCameras to apply the camera by default, keep
  // the renderer's camera object and give orthographic cameras a focal point.
  const Json::Value& document = this->Internal->Document;
  auto model = this->Loader->GetInternalModel();
  double bounds[6];
  renderer->ComputeVisiblePropBounds(bounds);
  const bool haveBounds = vtkMath::AreBoundsInitialized(bounds);
  const double center[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]) };

  this->Cameras.clear();
  std::map<int, double> aspectRatios;
  std::map<int, bool> infinite;
  for (int n : this->Internal->Nodes)
  {
    const int index = document["nodes"][n].get("camera", -1).asInt();
    if (index < 0 || this->Cameras.count(index))
    {
      continue; // no camera, or placed by an earlier node
    }
    auto camera = PlaceCamera(model->Nodes[n].GlobalTransform, haveBounds ? center : nullptr);
    SetProjection(camera, document["cameras"][index], aspectRatios[index], infinite[index]);
    this->Cameras[index] = camera;
  }

  this->CameraAspectRatio = 0.0;
  if (this->CameraIndex < 0 || document["cameras"].empty())
  {
    return;
  }
  const int index = static_cast<int>(this->CameraIndex);
  const auto it = this->Cameras.find(index);
  if (it == this->Cameras.end())
  {
    vtkWarningMacro(<< this->FileName << ": cameras[" << index
                    << "] is not used by any node of the scene, so it has no position; the "
                       "renderer's camera is kept");
    return;
  }
  vtkCamera* active = renderer->GetActiveCamera();
  active->DeepCopy(it->second);
  if (infinite[index])
  {
    // An infinite glTF frustum: far plane from the scene, near plane from the file.
    const double znear = active->GetClippingRange()[0];
    renderer->ResetCameraClippingRange();
    active->SetClippingRange(znear, std::max(active->GetClippingRange()[1], 2.0 * znear));
  }
  this->CameraAspectRatio = aspectRatios[index];
}

void vtkCausticsGLTFImporter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CameraIndex: " << this->CameraIndex << "\n";
  os << indent << "CameraAspectRatio: " << this->CameraAspectRatio << "\n";
  os << indent << "ImportedActors: " << this->Internal->Sources.size() << "\n";
  os << indent << "LastError: " << (this->LastError.empty() ? "(none)" : this->LastError) << "\n";
}
