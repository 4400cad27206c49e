// glTF 2.0 scenes through vtkCausticsGLTFImporter: materials and their caustics
// roles, physical lights under transformed parent nodes, cameras, names, and one
// clear error per kind of bad file. The test writes its own small glTF files
// (JSON with base64 data-URI buffers) with jsoncpp.
#include "vtkCausticsGLTFImporter.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsSceneExtractor.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkStringOutputWindow.h"
#include "vtksys/Base64.h"
#include "vtksys/SystemTools.hxx"

#include <vtk_jsoncpp.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace
{
const std::string OutputDir = std::string(CAUSTICS_TEST_OUTPUT_DIR) + "/TestGLTFImporter";
const double Pi = vtkMath::Pi();
const double NaN = std::numeric_limits<double>::quiet_NaN();
const double Inf = std::numeric_limits<double>::infinity();

// VTK's glTF loader keeps node translations, rotations and scales as float32, so
// world positions and directions built from them carry ~1e-7 relative error;
// 1e-6 (metres, or unit-vector components) is ten times that for scenes of a few metres.
const double TransformTolerance = 1e-6;

/** Geometry bytes: a 4 m quad (4 vertices, 6 uint16 indices) and a unit triangle (3 vertices). */
std::vector<unsigned char> SceneBuffer(std::uint16_t badIndex = 0)
{
  const float quad[12] = { -2, 0, 2, 2, 0, 2, 2, 0, -2, -2, 0, -2 }; // normal +y
  const std::uint16_t indices[6] = { 0, 1, 2, 0, 2, badIndex ? badIndex : std::uint16_t(3) };
  const float triangle[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
  std::vector<unsigned char> bytes(sizeof(quad) + sizeof(indices) + sizeof(triangle));
  // glTF buffers are little-endian, like the x86 and ARM hosts this test runs on.
  std::memcpy(bytes.data(), quad, sizeof(quad));
  std::memcpy(bytes.data() + 48, indices, sizeof(indices));
  std::memcpy(bytes.data() + 60, triangle, sizeof(triangle));
  return bytes;
}

std::string DataURI(const std::vector<unsigned char>& bytes)
{
  std::vector<unsigned char> text((bytes.size() + 2) / 3 * 4 + 1, 0);
  const std::size_t length = vtksysBase64_Encode(bytes.data(), bytes.size(), text.data(), 0);
  return "data:application/octet-stream;base64," +
    std::string(reinterpret_cast<const char*>(text.data()), length);
}

Json::Value Numbers(std::initializer_list<double> values)
{
  Json::Value array(Json::arrayValue);
  for (double v : values)
  {
    array.append(v);
  }
  return array;
}

/** Quaternion [x, y, z, w] of a rotation by `degrees` about a unit axis. */
Json::Value Rotation(double ax, double ay, double az, double degrees)
{
  const double half = vtkMath::RadiansFromDegrees(degrees) / 2.0;
  return Numbers({ ax * std::sin(half), ay * std::sin(half), az * std::sin(half), std::cos(half) });
}

Json::Value Accessor(int view, int componentType, int count, const char* type)
{
  Json::Value accessor;
  accessor["bufferView"] = view;
  accessor["componentType"] = componentType;
  accessor["count"] = count;
  accessor["type"] = type;
  return accessor;
}

Json::Value Material(
  const char* name, std::initializer_list<double> color, double metallic, double roughness)
{
  Json::Value material;
  material["name"] = name;
  material["pbrMetallicRoughness"]["baseColorFactor"] = Numbers(color);
  material["pbrMetallicRoughness"]["metallicFactor"] = metallic;
  material["pbrMetallicRoughness"]["roughnessFactor"] = roughness;
  return material;
}

/**
 * The test scene. Meshes: "floor" quad (white receiver), "prism" triangle (glass,
 * KHR_materials_ior 1.33, transmission 1, volume), "metals" with two primitives
 * (metal of roughness 0.1 and 0.6), "plain" without material. Lights under
 * transformed parents, a perspective camera under a parent and an orthographic one.
 * Node indices are referred to by the tests and the bad-input variants.
 */
Json::Value SceneDocument()
{
  Json::Value doc;
  doc["asset"]["version"] = "2.0";
  doc["asset"]["generator"] = "TestGLTFImporter";
  doc["extensionsUsed"] = Json::Value(Json::arrayValue);
  for (const char* name : { "KHR_lights_punctual", "KHR_materials_ior",
         "KHR_materials_transmission", "KHR_materials_volume" })
  {
    doc["extensionsUsed"].append(name);
  }

  const auto bytes = SceneBuffer();
  doc["buffers"][0]["byteLength"] = static_cast<int>(bytes.size());
  doc["buffers"][0]["uri"] = DataURI(bytes);
  const int views[3][2] = { { 0, 48 }, { 48, 12 }, { 60, 36 } }; // offset, length
  for (int v = 0; v < 3; ++v)
  {
    doc["bufferViews"][v]["buffer"] = 0;
    doc["bufferViews"][v]["byteOffset"] = views[v][0];
    doc["bufferViews"][v]["byteLength"] = views[v][1];
  }
  doc["accessors"][0] = Accessor(0, 5126, 4, "VEC3");
  doc["accessors"][0]["min"] = Numbers({ -2, 0, -2 });
  doc["accessors"][0]["max"] = Numbers({ 2, 0, 2 });
  doc["accessors"][1] = Accessor(1, 5123, 6, "SCALAR");
  doc["accessors"][2] = Accessor(2, 5126, 3, "VEC3");
  doc["accessors"][2]["min"] = Numbers({ 0, 0, 0 });
  doc["accessors"][2]["max"] = Numbers({ 1, 1, 0 });

  doc["materials"][0] = Material("white", { 0.8, 0.8, 0.8, 1 }, 0.0, 1.0);
  doc["materials"][1] = Material("glass", { 1, 1, 1, 1 }, 0.0, 0.0);
  Json::Value& glass = doc["materials"][1]["extensions"];
  glass["KHR_materials_ior"]["ior"] = 1.33;
  glass["KHR_materials_transmission"]["transmissionFactor"] = 1.0;
  glass["KHR_materials_volume"]["attenuationDistance"] = 2.0;
  glass["KHR_materials_volume"]["attenuationColor"] = Numbers({ 0.5, 1, 1 });
  doc["materials"][2] = Material("polished", { 0.95, 0.64, 0.54, 1 }, 1.0, 0.1);
  doc["materials"][3] = Material("rough", { 0.95, 0.64, 0.54, 1 }, 1.0, 0.6);

  auto primitive = [](int position, int material)
  {
    Json::Value p;
    p["attributes"]["POSITION"] = position;
    if (material >= 0)
    {
      p["material"] = material;
    }
    return p;
  };
  doc["meshes"][0]["name"] = "floor";
  doc["meshes"][0]["primitives"][0] = primitive(0, 0);
  doc["meshes"][0]["primitives"][0]["indices"] = 1;
  doc["meshes"][1]["name"] = "prism";
  doc["meshes"][1]["primitives"][0] = primitive(2, 1);
  doc["meshes"][2]["name"] = "metals";
  doc["meshes"][2]["primitives"][0] = primitive(2, 2);
  doc["meshes"][2]["primitives"][1] = primitive(2, 3);
  doc["meshes"][3]["name"] = "plain";
  doc["meshes"][3]["primitives"][0] = primitive(2, -1);

  Json::Value& lights = doc["extensions"]["KHR_lights_punctual"]["lights"];
  lights[0]["type"] = "point";
  lights[0]["intensity"] = 3.0;
  lights[1]["type"] = "spot";
  lights[1]["intensity"] = 5.0;
  lights[1]["color"] = Numbers({ 1, 0.5, 0.25 });
  lights[1]["range"] = 10.0;
  lights[1]["spot"]["innerConeAngle"] = 0.2;
  lights[1]["spot"]["outerConeAngle"] = 0.5;
  lights[2]["type"] = "directional";
  lights[2]["intensity"] = 2.0;

  doc["cameras"][0]["type"] = "perspective";
  doc["cameras"][0]["perspective"]["yfov"] = 0.8;
  doc["cameras"][0]["perspective"]["aspectRatio"] = 1.5;
  doc["cameras"][0]["perspective"]["znear"] = 0.1;
  doc["cameras"][0]["perspective"]["zfar"] = 50.0;
  doc["cameras"][1]["type"] = "orthographic";
  doc["cameras"][1]["orthographic"]["xmag"] = 3.0;
  doc["cameras"][1]["orthographic"]["ymag"] = 2.0;
  doc["cameras"][1]["orthographic"]["znear"] = 0.01;
  doc["cameras"][1]["orthographic"]["zfar"] = 20.0;

  Json::Value& nodes = doc["nodes"];
  nodes[0]["name"] = "floor";
  nodes[0]["mesh"] = 0;
  nodes[1]["name"] = "glass";
  nodes[1]["mesh"] = 1;
  nodes[1]["translation"] = Numbers({ 0, 1, 0 });
  nodes[2]["mesh"] = 2; // unnamed: actors are named after the mesh
  nodes[3]["name"] = "plain node";
  nodes[3]["mesh"] = 3;
  // Light rig: (x, y, z) -> (0, 2, 0) + 2 * Rz(90)(x, y, z) = (0, 2, 0) + 2 * (-y, x, z).
  nodes[4]["name"] = "rig";
  nodes[4]["translation"] = Numbers({ 0, 2, 0 });
  nodes[4]["rotation"] = Rotation(0, 0, 1, 90);
  nodes[4]["scale"] = Numbers({ 2, 2, 2 });
  nodes[4]["children"] = Numbers({ 5, 6 });
  nodes[5]["name"] = "bulb";
  nodes[5]["translation"] = Numbers({ 1, 0, 0 });
  nodes[5]["extensions"]["KHR_lights_punctual"]["light"] = 0;
  nodes[6]["name"] = "spot";
  nodes[6]["translation"] = Numbers({ 0, 1, 0 });
  nodes[6]["rotation"] = Rotation(1, 0, 0, -90); // local -z -> (0, -1, 0)
  nodes[6]["extensions"]["KHR_lights_punctual"]["light"] = 1;
  // Sun: local -z turned by Rx(-60), then by the parent's Ry(90); see the lights test.
  nodes[7]["name"] = "sky";
  nodes[7]["rotation"] = Rotation(0, 1, 0, 90);
  nodes[7]["translation"] = Numbers({ 5, 5, 5 });
  nodes[7]["children"] = Numbers({ 8 });
  nodes[8]["name"] = "sun";
  nodes[8]["rotation"] = Rotation(1, 0, 0, -60);
  nodes[8]["extensions"]["KHR_lights_punctual"]["light"] = 2;
  nodes[9]["name"] = "eye";
  nodes[9]["translation"] = Numbers({ 0, 1, 5 });
  nodes[9]["camera"] = 0;
  nodes[10]["name"] = "dolly";
  nodes[10]["translation"] = Numbers({ 0, 1, 0 });
  nodes[10]["children"] = Numbers({ 9 });
  nodes[11]["name"] = "top";
  nodes[11]["translation"] = Numbers({ 0, 10, 0 });
  nodes[11]["rotation"] = Rotation(1, 0, 0, -90); // looks down, up = -z
  nodes[11]["camera"] = 1;

  doc["scene"] = 0;
  doc["scenes"][0]["nodes"] = Numbers({ 0, 1, 2, 3, 4, 7, 10, 11 });
  return doc;
}

std::string WriteText(const std::string& name, const std::string& text)
{
  vtksys::SystemTools::MakeDirectory(OutputDir);
  const std::string path = OutputDir + "/" + name;
  std::ofstream file(path, std::ios::binary);
  file << text;
  return path;
}

std::string JSONText(const Json::Value& doc)
{
  Json::StreamWriterBuilder writer;
  writer["indentation"] = " ";
  writer["useSpecialFloats"] = true; // NaN/Infinity as Python's json module writes them
  return Json::writeString(writer, doc);
}

std::string WriteGLTF(const std::string& name, const Json::Value& doc)
{
  return WriteText(name, JSONText(doc));
}

/** A .glb: header, JSON chunk (space padded), BIN chunk (zero padded). */
std::string WriteGLB(const std::string& name, Json::Value doc, std::size_t cut = 0)
{
  const auto bytes = SceneBuffer();
  doc["buffers"][0].removeMember("uri");
  std::string json = JSONText(doc);
  json.resize((json.size() + 3) / 4 * 4, ' ');
  std::string bin(bytes.begin(), bytes.end());
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
  auto u32 = [](std::uint32_t v)
  {
    std::string s(4, '\0');
    for (int i = 0; i < 4; ++i)
    {
      s[i] = static_cast<char>((v >> (8 * i)) & 0xff);
    }
    return s;
  };
  const std::uint32_t total = static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size());
  std::string glb = "glTF" + u32(2) + u32(total) + u32(static_cast<std::uint32_t>(json.size())) +
    "JSON" + json + u32(static_cast<std::uint32_t>(bin.size())) + std::string("BIN\0", 4) + bin;
  if (cut > 0)
  {
    glb.resize(glb.size() - cut);
  }
  return WriteText(name, glb);
}

vtkActor* FindActor(vtkRenderer* renderer, const std::string& name)
{
  vtkActorCollection* actors = renderer->GetActors();
  vtkCollectionSimpleIterator it;
  actors->InitTraversal(it);
  while (vtkActor* actor = actors->GetNextActor(it))
  {
    if (vtkCausticsMaterial::GetName(actor) == name)
    {
      return actor;
    }
  }
  return nullptr;
}

bool Contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

/** Imports into a fresh renderer; VTK's messages go to a string, for the checks. */
class GLTFImporterTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Previous = vtkOutputWindow::GetInstance();
    vtkOutputWindow::SetInstance(this->Messages);
    this->Window->AddRenderer(this->Renderer);
    this->Importer->SetRenderWindow(this->Window);
  }
  void TearDown() override { vtkOutputWindow::SetInstance(this->Previous); }

  bool Import(const std::string& path, vtkIdType camera = 0)
  {
    this->Importer->SetFileName(path.c_str());
    this->Importer->SetCamera(camera);
    return this->Importer->Update();
  }

  /** Imports `path`, expects a failure that leaves the renderer empty; returns the error. */
  std::string ExpectFailure(const std::string& path, vtkIdType camera = 0)
  {
    EXPECT_FALSE(this->Import(path, camera)) << path;
    const std::string error = this->Importer->GetLastError();
    EXPECT_EQ(error.compare(0, path.size() + 2, path + ": "), 0) << "names the file: " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
    EXPECT_NE(this->Messages->GetOutput().find(error), std::string::npos)
      << "reported through vtkErrorMacro: " << error;
    EXPECT_EQ(this->Renderer->GetActors()->GetNumberOfItems(), 0) << error;
    EXPECT_EQ(this->Renderer->GetLights()->GetNumberOfItems(), 0) << error;
    return error;
  }

  vtkNew<vtkStringOutputWindow> Messages;
  vtkSmartPointer<vtkOutputWindow> Previous;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkCausticsGLTFImporter> Importer;
};
}

TEST_F(GLTFImporterTest, MaterialsBecomeCausticsRoles)
{
  ASSERT_TRUE(this->Import(WriteGLTF("scene.gltf", SceneDocument())))
    << this->Importer->GetLastError();
  // Not even VTK's "extension not supported" warnings for the extensions read here.
  EXPECT_EQ(this->Messages->GetOutput(), std::string());
  EXPECT_EQ(this->Renderer->GetActors()->GetNumberOfItems(), 5);

  vtkActor* glass = FindActor(this->Renderer, "glass");
  ASSERT_NE(glass, nullptr);
  auto material = vtkCausticsMaterial::Describe(glass);
  EXPECT_EQ(material.role, caustics::Role::Refractor);
  EXPECT_EQ(material.ior, 1.33); // exactly the file's value
  // KHR_materials_volume: half the red power left after 2 m, sigma = ln 2 / 2 per metre.
  // The importer computes -ln(0.5) / 2: one rounding of log and one of the division
  // apart from ln(2) / 2 = 0.347, i.e. a few 1e-17; 1e-15 bounds that.
  EXPECT_NEAR(material.attenuation[0], std::log(2.0) / 2.0, 1e-15);
  EXPECT_EQ(material.attenuation[1], 0.0);

  vtkActor* floor = FindActor(this->Renderer, "floor");
  ASSERT_NE(floor, nullptr);
  material = vtkCausticsMaterial::Describe(floor);
  EXPECT_EQ(material.role, caustics::Role::Receiver);
  EXPECT_EQ(material.albedo[0], 0.8);
  EXPECT_EQ(floor->GetProperty()->GetInterpolation(), VTK_PBR);

  // Unnamed node: named after its mesh, one actor per primitive.
  vtkActor* polished = FindActor(this->Renderer, "metals[0]");
  vtkActor* rough = FindActor(this->Renderer, "metals[1]");
  ASSERT_NE(polished, nullptr);
  ASSERT_NE(rough, nullptr);
  EXPECT_EQ(polished->GetProperty()->GetRoughness(), 0.1);
  EXPECT_EQ(polished->GetProperty()->GetMetallic(), 1.0);
  EXPECT_EQ(vtkCausticsMaterial::Describe(polished).role, caustics::Role::Reflector);
  EXPECT_EQ(vtkCausticsMaterial::Describe(rough).role, caustics::Role::Receiver);
  int node, mesh, primitive, materialIndex;
  ASSERT_TRUE(this->Importer->GetActorSource(rough, node, mesh, primitive, materialIndex));
  EXPECT_EQ(node, 2);
  EXPECT_EQ(mesh, 2);
  EXPECT_EQ(primitive, 1);
  EXPECT_EQ(materialIndex, 3);

  // No material: glTF's default material (metallic 1, roughness 1), IOR 1.5.
  vtkActor* plain = FindActor(this->Renderer, "plain node");
  ASSERT_NE(plain, nullptr);
  material = vtkCausticsMaterial::Describe(plain);
  EXPECT_EQ(material.role, caustics::Role::Receiver);
  EXPECT_EQ(material.ior, 1.5);
  ASSERT_TRUE(this->Importer->GetActorSource(plain, node, mesh, primitive, materialIndex));
  EXPECT_EQ(materialIndex, -1);
  vtkNew<vtkActor> stranger;
  EXPECT_FALSE(this->Importer->GetActorSource(stranger, node, mesh, primitive, materialIndex));

  // What the caustics stages see: node transforms applied, names kept.
  vtkNew<vtkCausticsSceneExtractor> extractor;
  ASSERT_TRUE(extractor->Update(this->Renderer, 64, 64));
  EXPECT_EQ(extractor->GetNumberOfMeshes(), 5);
  EXPECT_EQ(extractor->GetNumberOfTriangles(), 2 + 1 + 1 + 1 + 1);
  EXPECT_EQ(extractor->GetNumberOfMeshesWithRole(vtkCausticsMaterial::ROLE_REFRACTOR), 1);
  EXPECT_EQ(extractor->GetNumberOfMeshesWithRole(vtkCausticsMaterial::ROLE_REFLECTOR), 1);
  EXPECT_EQ(extractor->GetNumberOfMeshesWithRole(vtkCausticsMaterial::ROLE_RECEIVER), 3);
  const auto& scene = extractor->GetScene();
  for (std::size_t m = 0; m < scene.Meshes.size(); ++m)
  {
    if (scene.Materials[m].role == caustics::Role::Refractor)
    {
      EXPECT_EQ(scene.Meshes[m].name, "glass");
      EXPECT_EQ(scene.Materials[m].ior, 1.33);
    }
  }
  const double* sb = scene.SpecularBounds;
  EXPECT_EQ(sb[2], 0.0); // metals at the origin, glass lifted by 1 m: y in [0, 2]
  EXPECT_EQ(sb[3], 2.0);
}

TEST_F(GLTFImporterTest, LightsArePhysicalAndFollowNodeTransforms)
{
  ASSERT_TRUE(this->Import(WriteGLTF("lights.gltf", SceneDocument())))
    << this->Importer->GetLastError();
  vtkNew<vtkCausticsSceneExtractor> extractor;
  ASSERT_TRUE(extractor->Update(this->Renderer, 64, 64));
  const auto& lights = extractor->GetScene().Lights;
  ASSERT_EQ(lights.size(), 3u);
  auto expectVector = [](const caustics::Vec3& got, double x, double y, double z, const char* what)
  {
    EXPECT_NEAR(got[0], x, TransformTolerance) << what;
    EXPECT_NEAR(got[1], y, TransformTolerance) << what;
    EXPECT_NEAR(got[2], z, TransformTolerance) << what;
  };

  // Point light at rig(1, 0, 0) = (0, 2, 0) + 2 (0, 1, 0); 3 W/sr, white.
  EXPECT_EQ(lights[0].type, caustics::Light::Type::Point);
  expectVector(lights[0].position, 0, 4, 0, "point position");
  EXPECT_EQ(lights[0].radiometric[2], 3.0);

  // Spot at rig(0, 1, 0) = (0, 2, 0) + 2 (-1, 0, 0); its local -z, turned to (0, -1, 0)
  // by its own rotation, turned by the rig to (1, 0, 0). 5 W/sr times its colour.
  EXPECT_EQ(lights[1].type, caustics::Light::Type::Spot);
  expectVector(lights[1].position, -2, 2, 0, "spot position");
  expectVector(lights[1].direction, 1, 0, 0, "spot direction");
  EXPECT_EQ(lights[1].radiometric[0], 5.0);
  EXPECT_EQ(lights[1].radiometric[1], 2.5);
  EXPECT_EQ(lights[1].radiometric[2], 1.25);
  // Cones: radians -> degrees (importer) -> radians -> cosine (extractor), each step
  // one rounding (~1e-16); 1e-14 bounds the sum.
  EXPECT_NEAR(lights[1].cosOuter, std::cos(0.5), 1e-14);
  EXPECT_NEAR(lights[1].cosInner, std::cos(0.2), 1e-14);

  // Sun: Rx(-60) (0, 0, -1) = (0, -sin 60, -cos 60); Ry(90) maps (x, y, z) to (z, y, -x).
  // Directional: 2 W/m^2; the parent's translation does not matter.
  EXPECT_EQ(lights[2].type, caustics::Light::Type::Directional);
  expectVector(lights[2].direction, -0.5, -std::sqrt(3.0) / 2.0, 0, "sun direction");
  EXPECT_EQ(lights[2].radiometric[1], 2.0);

  // VTK's own shading: 1/r^2 falloff, cones in degrees on the vtkLight.
  vtkLightCollection* vtklights = this->Renderer->GetLights();
  vtkCollectionSimpleIterator it;
  vtklights->InitTraversal(it);
  vtkLight* point = vtklights->GetNextLight(it);
  vtkLight* spot = vtklights->GetNextLight(it);
  ASSERT_NE(spot, nullptr);
  for (vtkLight* light : { point, spot })
  {
    EXPECT_EQ(light->GetAttenuationValues()[0], 0.0);
    EXPECT_EQ(light->GetAttenuationValues()[1], 0.0);
    EXPECT_EQ(light->GetAttenuationValues()[2], 1.0);
  }
  EXPECT_GE(point->GetConeAngle(), 90.0); // a point light for VTK's shaders and the extractor
  // The same conversion of the same number: equal to within GoogleTest's 4 ulps.
  EXPECT_DOUBLE_EQ(spot->GetConeAngle(), vtkMath::DegreesFromRadians(0.5));
  ASSERT_NE(spot->GetInformation(), nullptr);
  EXPECT_DOUBLE_EQ(spot->GetInformation()->Get(vtkCausticsSceneExtractor::INNER_CONE_ANGLE()),
    vtkMath::DegreesFromRadians(0.2));
}

TEST_F(GLTFImporterTest, AppliesPerspectiveAndOrthographicCameras)
{
  const std::string path = WriteGLTF("cameras.gltf", SceneDocument());
  ASSERT_TRUE(this->Import(path)) << this->Importer->GetLastError();
  EXPECT_EQ(this->Importer->GetNumberOfCameras(), 2);
  vtkCamera* camera = this->Renderer->GetActiveCamera();
  // "eye" at (0, 1, 5) under "dolly" at (0, 1, 0), looking down -z.
  const double* position = camera->GetPosition();
  EXPECT_NEAR(position[0], 0.0, TransformTolerance);
  EXPECT_NEAR(position[1], 2.0, TransformTolerance);
  EXPECT_NEAR(position[2], 5.0, TransformTolerance);
  EXPECT_NEAR(camera->GetDirectionOfProjection()[2], -1.0, TransformTolerance);
  EXPECT_NEAR(camera->GetViewUp()[1], 1.0, TransformTolerance);
  EXPECT_FALSE(camera->GetParallelProjection());
  EXPECT_DOUBLE_EQ(camera->GetViewAngle(), vtkMath::DegreesFromRadians(0.8));
  EXPECT_EQ(camera->GetClippingRange()[0], 0.1);
  EXPECT_EQ(camera->GetClippingRange()[1], 50.0);
  EXPECT_EQ(this->Importer->GetCameraAspectRatio(), 1.5);

  // The orthographic camera, 10 m above the origin, looking down with -z up.
  vtkNew<vtkRenderer> other;
  vtkNew<vtkRenderWindow> window;
  window->AddRenderer(other);
  vtkNew<vtkCausticsGLTFImporter> importer;
  importer->SetRenderWindow(window);
  importer->SetFileName(path.c_str());
  importer->SetCamera(1);
  ASSERT_TRUE(importer->Update()) << importer->GetLastError();
  camera = other->GetActiveCamera();
  EXPECT_TRUE(camera->GetParallelProjection());
  EXPECT_EQ(camera->GetParallelScale(), 2.0);
  EXPECT_EQ(importer->GetCameraAspectRatio(), 1.5); // xmag / ymag = 3 / 2
  EXPECT_NEAR(camera->GetPosition()[1], 10.0, TransformTolerance);
  EXPECT_NEAR(camera->GetDirectionOfProjection()[1], -1.0, TransformTolerance);
  EXPECT_NEAR(camera->GetViewUp()[2], -1.0, TransformTolerance);
  EXPECT_EQ(camera->GetClippingRange()[0], 0.01);
  EXPECT_EQ(camera->GetClippingRange()[1], 20.0);
  // The focal point lies level with the scene's centre, on the view axis.
  EXPECT_NEAR(camera->GetFocalPoint()[0], 0.0, TransformTolerance);
  EXPECT_GT(camera->GetDistance(), 0.0);

  // -1 keeps the renderer's camera.
  vtkNew<vtkRenderer> kept;
  vtkNew<vtkRenderWindow> keptWindow;
  keptWindow->AddRenderer(kept);
  kept->GetActiveCamera()->SetPosition(7, 8, 9);
  vtkNew<vtkCausticsGLTFImporter> keeper;
  keeper->SetRenderWindow(keptWindow);
  keeper->SetFileName(path.c_str());
  keeper->SetCamera(-1);
  ASSERT_TRUE(keeper->Update()) << keeper->GetLastError();
  EXPECT_EQ(kept->GetActiveCamera()->GetPosition()[0], 7.0);
  EXPECT_EQ(keeper->GetCameraAspectRatio(), 0.0);
  // The file's cameras are still there.
  ASSERT_NE(keeper->GetCamera(1), nullptr);
  EXPECT_TRUE(keeper->GetCamera(1)->GetParallelProjection());
}

TEST_F(GLTFImporterTest, InfinitePerspectiveKeepsItsNearPlane)
{
  Json::Value doc = SceneDocument();
  doc["cameras"][0]["perspective"].removeMember("zfar");
  ASSERT_TRUE(this->Import(WriteGLTF("infinite.gltf", doc))) << this->Importer->GetLastError();
  const double* range = this->Renderer->GetActiveCamera()->GetClippingRange();
  EXPECT_EQ(range[0], 0.1);
  // The far plane comes from the scene: the floor's far corner is sqrt(2^2 + 2^2 + 7^2) away.
  EXPECT_GT(range[1], std::sqrt(4.0 + 4.0 + 49.0));
}

TEST_F(GLTFImporterTest, UnlitAndBlendedMaterialsTakeNoPart)
{
  Json::Value doc = SceneDocument();
  doc["materials"][0]["extensions"]["KHR_materials_unlit"] = Json::Value(Json::objectValue);
  doc["materials"][3]["alphaMode"] = "BLEND";
  doc["materials"][3]["pbrMetallicRoughness"]["baseColorFactor"][3] = 0.5;
  ASSERT_TRUE(this->Import(WriteGLTF("unlit.gltf", doc))) << this->Importer->GetLastError();
  vtkActor* floor = FindActor(this->Renderer, "floor");
  vtkActor* blended = FindActor(this->Renderer, "metals[1]");
  ASSERT_NE(floor, nullptr);
  ASSERT_NE(blended, nullptr);
  EXPECT_EQ(vtkCausticsMaterial::Describe(floor).role, caustics::Role::None);
  EXPECT_EQ(blended->GetProperty()->GetOpacity(), 0.5);
  EXPECT_EQ(vtkCausticsMaterial::Describe(blended).role, caustics::Role::None);
}

TEST_F(GLTFImporterTest, ReadsBinaryGLTF)
{
  ASSERT_TRUE(this->Import(WriteGLB("scene.glb", SceneDocument())))
    << this->Importer->GetLastError();
  EXPECT_EQ(this->Renderer->GetActors()->GetNumberOfItems(), 5);
  EXPECT_EQ(this->Renderer->GetLights()->GetNumberOfItems(), 3);
  vtkActor* glass = FindActor(this->Renderer, "glass");
  ASSERT_NE(glass, nullptr);
  EXPECT_EQ(vtkCausticsMaterial::Describe(glass).ior, 1.33);
}

TEST_F(GLTFImporterTest, SafeBeforeImport)
{
  // vtkGLTFImporter 9.1 dereferences its loader here before any import.
  vtkNew<vtkCausticsGLTFImporter> importer;
  EXPECT_EQ(importer->GetNumberOfCameras(), 0);
  EXPECT_EQ(importer->GetNumberOfAnimations(), 0);
  EXPECT_FALSE(importer->IsAnimationEnabled(0));
  importer->UpdateTimeStep(1.0);
}

TEST_F(GLTFImporterTest, RejectsMissingAndMalformedFiles)
{
  const std::string missing = OutputDir + "/missing.gltf";
  EXPECT_TRUE(Contains(this->ExpectFailure(missing), "no such file"));

  std::string text = JSONText(SceneDocument());
  std::string error =
    this->ExpectFailure(WriteText("truncated.gltf", text.substr(0, text.size() / 2)));
  EXPECT_TRUE(Contains(error, "malformed JSON at line")) << error;

  error = this->ExpectFailure(WriteText("empty.gltf", ""));
  EXPECT_TRUE(Contains(error, "the file is empty")) << error;

  error = this->ExpectFailure(WriteText("scene.obj", text));
  EXPECT_TRUE(Contains(error, "unknown extension '.obj' (expected .gltf or .glb)")) << error;

  error = this->ExpectFailure(WriteText("array.gltf", "[1, 2, 3]"));
  EXPECT_TRUE(Contains(error, "not an object")) << error;

  Json::Value doc = SceneDocument();
  doc["asset"]["version"] = "1.0";
  error = this->ExpectFailure(WriteGLTF("version.gltf", doc));
  EXPECT_TRUE(Contains(error, "asset.version is '1.0'; only glTF 2.x is supported")) << error;

  doc = SceneDocument();
  doc["extensionsRequired"].append("KHR_draco_mesh_compression");
  error = this->ExpectFailure(WriteGLTF("draco.gltf", doc));
  EXPECT_TRUE(Contains(error, "requires extension 'KHR_draco_mesh_compression'")) << error;

  doc = SceneDocument();
  doc.removeMember("scenes");
  doc.removeMember("scene");
  error = this->ExpectFailure(WriteGLTF("noscene.gltf", doc));
  EXPECT_TRUE(Contains(error, "no scenes")) << error;

  // A .glb cut short: the BIN chunk runs past the end.
  error = this->ExpectFailure(WriteGLB("cut.glb", SceneDocument(), 20));
  EXPECT_TRUE(Contains(error, "truncated")) << error;
}

TEST_F(GLTFImporterTest, RejectsOutOfRangeIndices)
{
  Json::Value doc = SceneDocument();
  doc["meshes"][1]["primitives"][0]["material"] = 9;
  std::string error = this->ExpectFailure(WriteGLTF("material.gltf", doc));
  EXPECT_TRUE(Contains(
    error, "meshes[1].primitives[0].material = 9 is out of range: 'materials' has 4 entries"))
    << error;

  doc = SceneDocument();
  doc["nodes"][0]["mesh"] = 7;
  error = this->ExpectFailure(WriteGLTF("mesh.gltf", doc));
  EXPECT_TRUE(Contains(error, "nodes[0].mesh = 7 is out of range: 'meshes' has 4 entries"))
    << error;

  doc = SceneDocument();
  doc["scenes"][0]["nodes"].append(42);
  error = this->ExpectFailure(WriteGLTF("node.gltf", doc));
  EXPECT_TRUE(Contains(error, "scenes[0].nodes[8] = 42 is out of range: 'nodes' has 12 entries"))
    << error;

  doc = SceneDocument();
  doc["nodes"][4]["children"].append(-1);
  error = this->ExpectFailure(WriteGLTF("child.gltf", doc));
  EXPECT_TRUE(Contains(error, "nodes[4].children[2] must be a non-negative integer index"))
    << error;

  doc = SceneDocument();
  doc["nodes"][5]["extensions"]["KHR_lights_punctual"]["light"] = 3;
  error = this->ExpectFailure(WriteGLTF("light.gltf", doc));
  EXPECT_TRUE(Contains(error,
    "nodes[5].extensions.KHR_lights_punctual.light = 3 is out of range: 'lights' has 3 entries"))
    << error;

  doc = SceneDocument();
  doc["accessors"][2]["bufferView"] = 3;
  error = this->ExpectFailure(WriteGLTF("view.gltf", doc));
  EXPECT_TRUE(Contains(error, "accessors[2].bufferView = 3 is out of range")) << error;

  // An index that points past the vertices, inside the (valid) buffer.
  doc = SceneDocument();
  doc["buffers"][0]["uri"] = DataURI(SceneBuffer(9));
  error = this->ExpectFailure(WriteGLTF("vertex.gltf", doc));
  EXPECT_TRUE(Contains(
    error, "meshes[0].primitives[0]: vertex index 9 is out of range: POSITION has 4 vertices"))
    << error;

  // The selected camera must exist.
  error = this->ExpectFailure(WriteGLTF("camera.gltf", SceneDocument()), 5);
  EXPECT_TRUE(Contains(error, "camera index 5 is out of range: the file has 2 cameras")) << error;
}

TEST_F(GLTFImporterTest, RejectsBrokenStructure)
{
  // A cycle crashes VTK 9.1's glTF import (unbounded recursion).
  Json::Value doc = SceneDocument();
  doc["nodes"][6]["children"] = Numbers({ 4 });
  std::string error = this->ExpectFailure(WriteGLTF("cycle.gltf", doc));
  EXPECT_TRUE(Contains(error, "the node hierarchy has a cycle")) << error;

  doc = SceneDocument();
  doc["nodes"][10]["children"] = Numbers({ 9, 5 });
  error = this->ExpectFailure(WriteGLTF("twoparents.gltf", doc));
  EXPECT_TRUE(Contains(error, "node 5 already has a parent (node 4)")) << error;

  // The data URI holds fewer bytes than the buffer claims.
  doc = SceneDocument();
  const std::string uri = doc["buffers"][0]["uri"].asString();
  doc["buffers"][0]["uri"] = uri.substr(0, uri.size() - 16);
  error = this->ExpectFailure(WriteGLTF("shortbuffer.gltf", doc));
  EXPECT_TRUE(Contains(error, "buffers[0].uri holds 84 bytes but byteLength is 96")) << error;

  doc = SceneDocument();
  doc["buffers"][0]["uri"] = "geometry.bin";
  error = this->ExpectFailure(WriteGLTF("nobin.gltf", doc));
  EXPECT_TRUE(Contains(error, "buffers[0].uri 'geometry.bin' not found")) << error;

  doc = SceneDocument();
  doc["accessors"][2]["count"] = 4; // 4 vertices of 12 bytes do not fit in 36
  error = this->ExpectFailure(WriteGLTF("accessor.gltf", doc));
  EXPECT_TRUE(Contains(error, "accessors[2] reads 48 bytes but bufferViews[2] has 36")) << error;
}

TEST_F(GLTFImporterTest, RejectsNonFiniteTransformsAndDegenerateLights)
{
  Json::Value doc = SceneDocument();
  doc["nodes"][1]["translation"][0] = NaN;
  std::string error = this->ExpectFailure(WriteGLTF("nan.gltf", doc));
  EXPECT_TRUE(Contains(error, "nodes[1].translation[0] is not a finite number (NaN or infinity)"))
    << error;

  doc = SceneDocument();
  doc["nodes"][3]["matrix"] = Numbers({ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, Inf, 0, 0, 1 });
  error = this->ExpectFailure(WriteGLTF("inf.gltf", doc));
  EXPECT_TRUE(Contains(error, "nodes[3].matrix[12] is not a finite number")) << error;

  // Finite numbers whose product overflows.
  doc = SceneDocument();
  doc["nodes"][4]["scale"] = Numbers({ 1e300, 1e300, 1e300 });
  doc["nodes"][5]["scale"] = Numbers({ 1e300, 1e300, 1e300 });
  doc["nodes"][5]["translation"] = Numbers({ 1e300, 0, 0 });
  error = this->ExpectFailure(WriteGLTF("overflow.gltf", doc));
  EXPECT_TRUE(Contains(error, "the world transform is not finite")) << error;

  // A sun whose node scale is zero has no direction.
  doc = SceneDocument();
  doc["nodes"][8]["scale"] = Numbers({ 0, 0, 0 });
  error = this->ExpectFailure(WriteGLTF("flat.gltf", doc));
  EXPECT_TRUE(Contains(error,
    "nodes[8]: the world transform is degenerate (zero scale?), so the light has no direction"))
    << error;

  // A camera squashed along y has no up direction.
  doc = SceneDocument();
  doc["nodes"][11]["scale"] = Numbers({ 1, 0, 1 });
  error = this->ExpectFailure(WriteGLTF("flatcamera.gltf", doc));
  EXPECT_TRUE(
    Contains(error, "nodes[11]: the world transform is degenerate (zero scale?), so the camera"))
    << error;

  doc = SceneDocument();
  doc["nodes"][4]["rotation"] = Numbers({ 0, 0, 0, 0 });
  error = this->ExpectFailure(WriteGLTF("quaternion.gltf", doc));
  EXPECT_TRUE(Contains(error, "nodes[4].rotation is not a unit quaternion")) << error;
}

TEST_F(GLTFImporterTest, RejectsAbsurdPhysicalParameters)
{
  Json::Value doc = SceneDocument();
  doc["materials"][1]["extensions"]["KHR_materials_ior"]["ior"] = 0.5;
  std::string error = this->ExpectFailure(WriteGLTF("ior.gltf", doc));
  EXPECT_TRUE(Contains(error, "materials[1].extensions.KHR_materials_ior.ior = 0.5"));
  EXPECT_TRUE(Contains(error,
    "is not a physical index of refraction (it must be finite and >= 1) in material 'glass'"))
    << error;

  doc["materials"][1]["extensions"]["KHR_materials_ior"]["ior"] = Inf;
  error = this->ExpectFailure(WriteGLTF("ior-inf.gltf", doc));
  EXPECT_TRUE(
    Contains(error, "materials[1].extensions.KHR_materials_ior.ior is not a finite number"))
    << error;

  doc = SceneDocument();
  doc["materials"][1]["extensions"]["KHR_materials_transmission"]["transmissionFactor"] = 1.5;
  error = this->ExpectFailure(WriteGLTF("transmission.gltf", doc));
  EXPECT_TRUE(Contains(error, "transmissionFactor = 1.5, but it must be in [0, 1]")) << error;

  doc = SceneDocument();
  doc["extensions"]["KHR_lights_punctual"]["lights"][1]["spot"]["innerConeAngle"] = 0.7;
  error = this->ExpectFailure(WriteGLTF("cone.gltf", doc));
  EXPECT_TRUE(Contains(error, "lights[1].spot.innerConeAngle = 0.7, but it must be in [0, 0.5]"))
    << error;

  doc = SceneDocument();
  doc["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = -3.0;
  error = this->ExpectFailure(WriteGLTF("intensity.gltf", doc));
  EXPECT_TRUE(Contains(error, "lights[0].intensity = -3, but it must be >= 0")) << error;

  doc = SceneDocument();
  doc["cameras"][0]["perspective"]["znear"] = 0.0;
  error = this->ExpectFailure(WriteGLTF("znear.gltf", doc));
  EXPECT_TRUE(Contains(error, "cameras[0].perspective.znear = 0, but it must be > 0")) << error;
}

TEST_F(GLTFImporterTest, RejectsValuesBeyondFloatRange)
{
  // 3.5e38 is finite in double but not in the GPU's float: it used to pass.
  Json::Value doc = SceneDocument();
  doc["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = 3.5e38;
  std::string error = this->ExpectFailure(WriteGLTF("intensity-float.gltf", doc));
  EXPECT_TRUE(Contains(error,
    "lights[0].intensity = 3.5e+38 is beyond the largest intensity the GPU passes represent"))
    << error;

  // An IOR of 1e20 gave NaN pixels in the screen-space refraction.
  doc = SceneDocument();
  doc["materials"][1]["extensions"]["KHR_materials_ior"]["ior"] = 1e20;
  error = this->ExpectFailure(WriteGLTF("ior-huge.gltf", doc));
  EXPECT_TRUE(Contains(error,
    "materials[1].extensions.KHR_materials_ior.ior = 1e+20 is beyond the largest index of "
    "refraction supported (100) in material 'glass'"))
    << error;

  // A tiny attenuation distance gives an attenuation coefficient beyond float.
  doc = SceneDocument();
  doc["materials"][1]["extensions"]["KHR_materials_volume"]["attenuationDistance"] = 1e-300;
  error = this->ExpectFailure(WriteGLTF("attenuation.gltf", doc));
  EXPECT_TRUE(Contains(error, "attenuationDistance = 1e-300, but it must be >= 1e-09")) << error;

  // The limits themselves are accepted.
  doc = SceneDocument();
  doc["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] =
    vtkCausticsGLTFImporter::MAX_LIGHT_INTENSITY;
  doc["materials"][1]["extensions"]["KHR_materials_ior"]["ior"] = vtkCausticsGLTFImporter::MAX_IOR;
  EXPECT_TRUE(this->Import(WriteGLTF("limits.gltf", doc))) << this->Importer->GetLastError();
}

TEST_F(GLTFImporterTest, RejectsCameraUpAlongItsView)
{
  // Column-major: x -> x, y -> -z, z -> +z: the camera looks along -z and its up
  // is -z too, which gave a blank image.
  Json::Value doc = SceneDocument();
  doc["nodes"][9].removeMember("translation");
  doc["nodes"][9]["matrix"] = Numbers({ 1, 0, 0, 0, 0, 0, -1, 0, 0, 0, 1, 0, 0, 1, 5, 1 });
  const std::string error = this->ExpectFailure(WriteGLTF("upalongview.gltf", doc));
  EXPECT_TRUE(Contains(error,
    "nodes[9]: the world transform maps the camera's up axis (+y) "
    "onto its view axis (-z): the up vector is parallel"))
    << error;
}

TEST_F(GLTFImporterTest, ReadsUpperCaseExtensions)
{
  ASSERT_TRUE(this->Import(WriteGLTF("upper.GLTF", SceneDocument())))
    << this->Importer->GetLastError();
  EXPECT_EQ(this->Renderer->GetActors()->GetNumberOfItems(), 5);

  // The buffer in a .bin next to the file: found next to the real file, not the alias.
  Json::Value doc = SceneDocument();
  const auto bytes = SceneBuffer();
  WriteText("upper-buffer.bin", std::string(bytes.begin(), bytes.end()));
  doc["buffers"][0]["uri"] = "upper-buffer.bin";
  vtkNew<vtkRenderer> second;
  this->Window->AddRenderer(second);
  this->Window->RemoveRenderer(this->Renderer);
  ASSERT_TRUE(this->Import(WriteGLTF("upper-external.Gltf", doc)))
    << this->Importer->GetLastError();
  EXPECT_EQ(second->GetActors()->GetNumberOfItems(), 5);

  vtkNew<vtkRenderer> third;
  this->Window->AddRenderer(third);
  this->Window->RemoveRenderer(second);
  ASSERT_TRUE(this->Import(WriteGLB("upper.GLB", SceneDocument())))
    << this->Importer->GetLastError();
  EXPECT_EQ(third->GetActors()->GetNumberOfItems(), 5);
}

TEST_F(GLTFImporterTest, NeverDecodesImages)
{
  // Images: a PNG signature followed by junk, a PNG cut after its signature, and a
  // text file named .png. VTK 9.1 crashed on the first two and printed "Not a PNG
  // file!" without a file name on the third. The caustics read no textures, so
  // the images are not decoded at all; the textured material gets a warning.
  const std::string signature("\x89PNG\r\n\x1a\n", 8);
  auto pngURI = [](const std::string& bytes)
  {
    return "data:image/png;base64," +
      DataURI(std::vector<unsigned char>(bytes.begin(), bytes.end())).substr(37);
  };
  WriteText("garbage.png", "this is not an image\n");
  Json::Value doc = SceneDocument();
  doc["images"][0]["uri"] = pngURI(signature + std::string(64, '\x7f'));
  doc["images"][1]["uri"] = pngURI(signature + std::string("\0\0\0\rIHDR", 8));
  doc["images"][2]["uri"] = "garbage.png";
  for (int t = 0; t < 3; ++t)
  {
    doc["textures"][t]["source"] = t;
  }
  doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 0;
  doc["materials"][2]["pbrMetallicRoughness"]["metallicRoughnessTexture"]["index"] = 1;
  doc["materials"][3]["normalTexture"]["index"] = 2;
  ASSERT_TRUE(this->Import(WriteGLTF("images.gltf", doc))) << this->Importer->GetLastError();
  EXPECT_EQ(this->Renderer->GetActors()->GetNumberOfItems(), 5);
  const std::string messages = this->Messages->GetOutput();
  EXPECT_FALSE(Contains(messages, "Not a PNG")) << messages;
  EXPECT_TRUE(Contains(messages, "images.gltf: materials[0] uses baseColorTexture")) << messages;
}

TEST_F(GLTFImporterTest, RefusesSparseAccessors)
{
  // A valid sparse accessor (zeros with one vertex replaced) used as POSITION:
  // VTK 9.1's loader threw std::bad_array_new_length on it.
  Json::Value doc = SceneDocument();
  Json::Value sparse;
  sparse["componentType"] = 5126;
  sparse["count"] = 3;
  sparse["type"] = "VEC3";
  sparse["sparse"]["count"] = 1;
  sparse["sparse"]["indices"]["bufferView"] = 1;
  sparse["sparse"]["indices"]["componentType"] = 5123;
  sparse["sparse"]["values"]["bufferView"] = 2;
  doc["accessors"][3] = sparse;
  doc["meshes"][3]["primitives"][0]["attributes"]["POSITION"] = 3;
  const std::string error = this->ExpectFailure(WriteGLTF("sparse.gltf", doc));
  EXPECT_TRUE(Contains(error, "accessors[3].sparse: sparse accessors are not supported")) << error;
  EXPECT_FALSE(Contains(error, "bad_array")) << error;
}

namespace
{
/**
 * SceneDocument() with a chain of `depth` nodes, each the only child of the
 * previous one, under a new root of scene 0; the last holds the "plain" mesh.
 */
Json::Value ChainedDocument(int depth)
{
  Json::Value doc = SceneDocument();
  Json::Value& nodes = doc["nodes"];
  const int first = static_cast<int>(nodes.size());
  for (int level = 0; level < depth; ++level)
  {
    Json::Value node(Json::objectValue);
    if (level + 1 < depth)
    {
      node["children"].append(first + level + 1);
    }
    else
    {
      node["mesh"] = 3;
    }
    nodes.append(node);
  }
  doc["scenes"][0]["nodes"].append(first);
  return doc;
}
}

// Issue 18: a node hierarchy 100000 levels deep overflowed the stack in VTK's
// loader, which recurses once per level; the limit is refused in one line.
TEST_F(GLTFImporterTest, RefusesNodeHierarchiesDeeperThanTheLimit)
{
  const int limit = vtkCausticsGLTFImporter::MAX_NODE_DEPTH;
  std::string error = this->ExpectFailure(WriteGLTF("too-deep.gltf", ChainedDocument(limit + 1)));
  EXPECT_TRUE(Contains(error,
    "the node hierarchy is 1001 levels deep (down to nodes[1012]); at most 1000 levels are "
    "supported"))
    << error;

  // The file, generated here rather than checked in (a few MB of JSON).
  error = this->ExpectFailure(WriteGLTF("deep.gltf", ChainedDocument(100000)));
  EXPECT_TRUE(Contains(error, "the node hierarchy is 100000 levels deep (down to nodes[100011])"))
    << error;
}

TEST_F(GLTFImporterTest, ImportsNodeHierarchiesAtTheLimit)
{
  const std::string path =
    WriteGLTF("deepest.gltf", ChainedDocument(vtkCausticsGLTFImporter::MAX_NODE_DEPTH));
  ASSERT_TRUE(this->Import(path)) << this->Importer->GetLastError();
  EXPECT_EQ(this->Renderer->GetActors()->GetNumberOfItems(), 6);
}

// Issue 18, found by fuzzing: an accessor without a bufferView (glTF's accessor
// of zeros) used as indices crashed VTK 9.1's loader (SIGSEGV).
TEST_F(GLTFImporterTest, RefusesAccessorsWithoutBufferView)
{
  Json::Value doc = SceneDocument();
  doc["accessors"][1].removeMember("bufferView");
  const std::string error = this->ExpectFailure(WriteGLTF("zeros.gltf", doc));
  EXPECT_TRUE(
    Contains(error, "accessors[1] has no bufferView: accessors of zeros are not supported"))
    << error;
}

// Issue 18, found by fuzzing: a version string with binary bytes was quoted as
// is, breaking the one-line message (and a long one flooded it). Text from the
// file is quoted at most 60 characters long, bytes outside ASCII as \xNN.
TEST_F(GLTFImporterTest, QuotesOnlyShortPrintableExcerpts)
{
  auto expectShortAndPrintable = [](const std::string& error)
  {
    EXPECT_LT(error.size(), 400u) << error.substr(0, 400);
    for (char c : error)
    {
      ASSERT_TRUE(static_cast<unsigned char>(c) >= 0x20 && static_cast<unsigned char>(c) < 0x7f)
        << error.substr(0, 400);
    }
  };
  // Raw bytes in the JSON string (jsoncpp's writer would escape them).
  Json::Value doc = SceneDocument();
  doc["asset"]["version"] = "VERSION";
  std::string text = JSONText(doc);
  text.replace(text.find("VERSION"), 7, std::string("2\xd4") + "0\x7f" + std::string(5000, 'x'));
  std::string error = this->ExpectFailure(WriteText("binary-version.gltf", text));
  EXPECT_TRUE(Contains(error, "asset.version is '2\\xd40\\x7fxxxx")) << error;
  EXPECT_TRUE(Contains(error, "...'; only glTF 2.x is supported")) << error;
  expectShortAndPrintable(error);

  // A member name from the file in a JSON path.
  doc = SceneDocument();
  doc["meshes"][0]["primitives"][0]["attributes"]["\x01" + std::string(300, 'N')] = 99;
  error = this->ExpectFailure(WriteGLTF("attribute-name.gltf", doc));
  EXPECT_TRUE(Contains(error, "meshes[0].primitives[0].attributes['\\x01NNN")) << error;
  EXPECT_TRUE(Contains(error, "...'] = 99 is out of range")) << error;
  expectShortAndPrintable(error);

  doc = SceneDocument();
  doc["buffers"][0]["uri"] = std::string(3000, 'b') + ".bin";
  error = this->ExpectFailure(WriteGLTF("long-uri.gltf", doc));
  EXPECT_TRUE(Contains(error, "buffers[0].uri 'bbbb")) << error;
  expectShortAndPrintable(error);
}

// Issue 18, found by fuzzing: a NORMAL accessor of unsigned integers was left empty
// by VTK's loader, and the scene snapshot read past the empty array (SIGSEGV).
TEST_F(GLTFImporterTest, RefusesAttributesOfTypesGLTFDoesNotAllow)
{
  Json::Value doc = SceneDocument();
  doc["accessors"][3] = Accessor(0, 5125, 4, "VEC3"); // the quad's bytes as integers
  doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 3;
  std::string error = this->ExpectFailure(WriteGLTF("int-normals.gltf", doc));
  EXPECT_TRUE(Contains(error,
    "meshes[0].primitives[0].attributes.NORMAL must be a VEC3 FLOAT accessor (accessors[3] is "
    "VEC3 of component type 5125)"))
    << error;

  doc["accessors"][3] = Accessor(0, 5126, 4, "VEC3");
  doc["accessors"][3]["normalized"] = "yes";
  error = this->ExpectFailure(WriteGLTF("normalized.gltf", doc));
  EXPECT_TRUE(Contains(error, "accessors[3].normalized must be true or false")) << error;

  // Morph targets hold VEC3 FLOAT displacements, one per vertex.
  doc = SceneDocument();
  doc["accessors"][3] = Accessor(1, 5123, 6, "SCALAR");
  doc["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] = 3;
  error = this->ExpectFailure(WriteGLTF("target.gltf", doc));
  EXPECT_TRUE(
    Contains(error, "meshes[0].primitives[0].targets[0].POSITION must be a VEC3 FLOAT accessor"))
    << error;
  doc["meshes"][0]["primitives"][0]["targets"][0] = 3;
  error = this->ExpectFailure(WriteGLTF("target-number.gltf", doc));
  EXPECT_TRUE(Contains(error, "meshes[0].primitives[0].targets[0] must be a JSON object")) << error;
}

// Issue 18, found by fuzzing: an accessor's max with two numbers for a VEC3 (and a
// trailing comma, which jsoncpp accepts by default) threw std::length_error inside
// VTK's loader, reported only as the importer's last-resort message.
TEST_F(GLTFImporterTest, RefusesBoundsOfTheWrongSize)
{
  Json::Value doc = SceneDocument();
  doc["accessors"][2]["max"] = Numbers({ 1, 1 });
  std::string error = this->ExpectFailure(WriteGLTF("short-max.gltf", doc));
  EXPECT_TRUE(Contains(error, "accessors[2].max must be 3 numbers, finite")) << error;

  std::string text = JSONText(SceneDocument());
  const std::size_t bound = text.find("\"max\"");
  text.insert(text.find(']', bound), ",");
  error = this->ExpectFailure(WriteText("trailing-comma.gltf", text));
  EXPECT_TRUE(Contains(error, "malformed JSON at line")) << error;
}

// Issue 18: JSON nested deeper than jsoncpp's limit made it throw, reported only
// as the importer's last-resort message.
TEST_F(GLTFImporterTest, RefusesJSONNestedTooDeep)
{
  const std::string error =
    this->ExpectFailure(WriteText("nested.gltf", std::string(1200, '[') + std::string(1200, ']')));
  EXPECT_TRUE(
    Contains(error, "malformed JSON: arrays and objects nested more than 1000 levels deep"))
    << error;
}

// Issue 18: VTK 9.1's loader walks the chunks of a .glb by their lengths and
// looped for ever, growing its chunk list until memory ran out, on a partial
// chunk header at the end of the file.
TEST_F(GLTFImporterTest, RefusesBinaryGLTFChunksThatDoNotTileTheFile)
{
  const std::string path = WriteGLB("tail.glb", SceneDocument());
  std::string glb;
  {
    std::ifstream file(path, std::ios::binary);
    glb.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  }
  auto withLength = [](std::string bytes)
  {
    const std::uint32_t length = static_cast<std::uint32_t>(bytes.size());
    for (int i = 0; i < 4; ++i)
    {
      bytes[8 + i] = static_cast<char>((length >> (8 * i)) & 0xff);
    }
    return bytes;
  };
  const std::size_t end = glb.size();
  std::string error =
    this->ExpectFailure(WriteText("partial-header.glb", withLength(glb + std::string(4, '\0'))));
  EXPECT_TRUE(Contains(error,
    "the binary glTF ends inside a chunk header at byte " + std::to_string(end) + " (truncated?)"))
    << error;

  // The header's length must be the file's, not more or less.
  error = this->ExpectFailure(WriteText("long.glb", glb + std::string(8, '\0')));
  EXPECT_TRUE(Contains(error,
    "binary glTF header declares " + std::to_string(end) + " bytes but the file has " +
      std::to_string(end + 8)))
    << error;

  // Chunks are multiples of 4 bytes long, as glTF requires and VTK's walk assumes.
  std::string odd = glb;
  odd[12] = static_cast<char>(odd[12] - 1); // the JSON chunk's length, one short
  error = this->ExpectFailure(WriteText("odd.glb", odd));
  EXPECT_TRUE(Contains(error, "not a multiple of 4 as glTF requires")) << error;
}
