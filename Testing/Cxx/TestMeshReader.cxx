// Mesh files (.ply, .obj, .stl) through vtkCausticsMeshReader: round trips,
// actors with caustics roles, and clear errors on bad files.
#include "vtkCausticsMaterial.h"
#include "vtkCausticsMeshReader.h"
#include "vtkCausticsSceneExtractor.h"

#include "vtkActor.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkStringOutputWindow.h"
#include "vtksys/SystemTools.hxx"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>

namespace
{
const std::string DataDir = CAUSTICS_TEST_DATA_DIR;
const std::string OutputDir = std::string(CAUSTICS_TEST_OUTPUT_DIR) + "/TestMeshReader";

std::string WriteFile(const std::string& name, const std::string& contents)
{
  vtksys::SystemTools::MakeDirectory(OutputDir);
  const std::string path = OutputDir + "/" + name;
  std::ofstream file(path, std::ios::binary);
  file << contents;
  return path;
}

std::string ReadFile(const std::string& path)
{
  std::ifstream file(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

/** A binary STL: 80-byte header, declared triangle count, then `written` triangles. */
std::string BinarySTL(std::uint32_t declared, std::uint32_t written)
{
  std::string bytes(80, ' ');
  bytes.replace(0, 10, "binary stl");
  for (int i = 0; i < 4; ++i)
  {
    bytes.push_back(static_cast<char>((declared >> (8 * i)) & 0xff));
  }
  for (std::uint32_t t = 0; t < written; ++t)
  {
    // normal, three vertices (a triangle shifted along x per t), attribute count
    const float values[12] = { 0, 0, 1, float(t), 0, 0, float(t) + 1, 0, 0, float(t), 1, 0 };
    char record[50] = {};
    std::memcpy(record, values, sizeof(values)); // x86 and ARM hosts are little-endian, as STL
    bytes.append(record, 50);
  }
  return bytes;
}

/** Collects VTK's error output so that tests can check it and the log stays readable. */
class MeshReaderTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Previous = vtkOutputWindow::GetInstance();
    vtkOutputWindow::SetInstance(this->Messages);
  }
  void TearDown() override { vtkOutputWindow::SetInstance(this->Previous); }

  /** Reads `path`, expects failure, returns the error (also checked on VTK's output). */
  std::string ExpectFailure(const std::string& path)
  {
    vtkNew<vtkCausticsMeshReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    const std::string error = reader->GetLastError();
    EXPECT_FALSE(error.empty()) << path;
    EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0) << path;
    EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
    EXPECT_NE(this->Messages->GetOutput().find(error), std::string::npos)
      << "reported through vtkErrorMacro: " << error;
    EXPECT_EQ(reader->CreateActor(), nullptr) << path;
    return error;
  }

  vtkNew<vtkStringOutputWindow> Messages;
  vtkSmartPointer<vtkOutputWindow> Previous;
};

bool Contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}
}

TEST_F(MeshReaderTest, ReadsBunnyPly)
{
  vtkNew<vtkCausticsMeshReader> reader;
  const std::string path = DataDir + "/bunny.ply";
  reader->SetFileName(path.c_str());
  reader->Update();
  EXPECT_STREQ(reader->GetLastError(), "");
  // Counts from Data/README.md (the file's header says the same).
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 1839);
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPolys(), 3674);
}

TEST_F(MeshReaderTest, ReadsObjWithAnyExtensionCase)
{
  // A quad and a triangle sharing vertices 1 and 2.
  const std::string path = WriteFile(
    "shape.OBJ", "# test\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 -1 0\nf 1 2 3 4\nf 2 1 5\n");
  EXPECT_TRUE(vtkCausticsMeshReader::IsSupportedExtension(path));
  vtkNew<vtkCausticsMeshReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  EXPECT_STREQ(reader->GetLastError(), "");
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 5);
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPolys(), 2);
  double bounds[6];
  reader->GetOutput()->GetBounds(bounds);
  EXPECT_EQ(bounds[2], -1.0);
  EXPECT_EQ(bounds[3], 1.0);
}

TEST_F(MeshReaderTest, ReadsAsciiAndBinaryStl)
{
  // Two facets sharing an edge: vtkSTLReader merges coincident points.
  const std::string ascii = WriteFile("square.stl",
    "solid square\n"
    "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\n"
    "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\n"
    "endsolid square\n");
  vtkNew<vtkCausticsMeshReader> reader;
  reader->SetFileName(ascii.c_str());
  reader->Update();
  EXPECT_STREQ(reader->GetLastError(), "");
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 4);
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPolys(), 2);

  const std::string binary = WriteFile("strip.Stl", BinarySTL(3, 3));
  reader->SetFileName(binary.c_str());
  reader->Update();
  EXPECT_STREQ(reader->GetLastError(), "");
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPolys(), 3);
  double bounds[6];
  reader->GetOutput()->GetBounds(bounds);
  EXPECT_EQ(bounds[1], 3.0); // the last triangle reaches x = 2 + 1
}

TEST_F(MeshReaderTest, CreatesActorsWithCausticsRoles)
{
  vtkNew<vtkCausticsMeshReader> reader;
  const std::string path = DataDir + "/bunny.ply";
  reader->SetFileName(path.c_str());

  ASSERT_TRUE(reader->SetRoleFromName("refractor"));
  reader->SetRefractiveIndex(1.5);
  auto glass = reader->CreateActor();
  ASSERT_NE(glass, nullptr) << reader->GetLastError();
  auto material = vtkCausticsMaterial::Describe(glass);
  EXPECT_EQ(material.role, caustics::Role::Refractor);
  EXPECT_EQ(material.ior, 1.5);
  EXPECT_EQ(vtkCausticsMaterial::GetName(glass), "bunny.ply");

  ASSERT_TRUE(reader->SetRoleFromName("mirror"));
  reader->SetColor(0.9, 0.9, 0.9);
  auto mirror = reader->CreateActor();
  ASSERT_NE(mirror, nullptr) << reader->GetLastError();
  material = vtkCausticsMaterial::Describe(mirror);
  EXPECT_EQ(material.role, caustics::Role::Reflector);
  // The complex IOR derived from F0 = 0.9 reproduces that reflectance; the closed-form
  // inversion rounds a few times (~1e-15), 1e-9 is the bound TestScene uses for it too.
  const double n = material.metalN[0], k = material.metalK[0];
  EXPECT_NEAR(((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k), 0.9, 1e-9);

  ASSERT_TRUE(reader->SetRoleFromName("receiver"));
  reader->SetColor(0.5, 0.25, 0.125);
  auto wall = reader->CreateActor();
  ASSERT_NE(wall, nullptr) << reader->GetLastError();
  material = vtkCausticsMaterial::Describe(wall);
  EXPECT_EQ(material.role, caustics::Role::Receiver);
  EXPECT_EQ(material.albedo[1], 0.25);

  // What the caustics stages see: the whole bunny as one refractor.
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(glass);
  vtkNew<vtkCausticsSceneExtractor> extractor;
  ASSERT_TRUE(extractor->Update(renderer, 64, 64));
  EXPECT_EQ(extractor->GetNumberOfMeshesWithRole(vtkCausticsMaterial::ROLE_REFRACTOR), 1);
  EXPECT_EQ(extractor->GetNumberOfTriangles(), 3674);
}

TEST_F(MeshReaderTest, RejectsMissingUnknownAndEmptyFiles)
{
  const std::string missing = OutputDir + "/does-not-exist.ply";
  std::string error = this->ExpectFailure(missing);
  EXPECT_TRUE(Contains(error, missing + ": no such file")) << error;

  error = this->ExpectFailure(WriteFile("mesh.xyz", "1 2 3\n"));
  EXPECT_TRUE(Contains(error, "unknown mesh extension '.xyz'")) << error;

  error = this->ExpectFailure(WriteFile("empty.obj", ""));
  EXPECT_TRUE(Contains(error, "empty.obj: the file is empty")) << error;

  error = this->ExpectFailure(WriteFile("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"));
  EXPECT_TRUE(Contains(error, "points.obj: no triangles")) << error;

  // vtkOBJReader would read these coordinates as 0.
  error = this->ExpectFailure(WriteFile("nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_TRUE(Contains(error, "nan.obj: line 2: vertex coordinate 'nan' is not a finite number"))
    << error;
  error = this->ExpectFailure(WriteFile("typo.obj", "v 0 0 0\nv 1 0 0\nv 0 1.0.0 0\nf 1 2 3\n"));
  EXPECT_TRUE(Contains(error, "line 3: vertex coordinate '1.0.0'")) << error;

  error = this->ExpectFailure(WriteFile("garbage.stl", "garbage\nmore garbage\n"));
  EXPECT_TRUE(Contains(error, "garbage.stl: VTK's vtkSTLReader failed")) << error;

  error = this->ExpectFailure(WriteFile("garbage.ply", "hello\n"));
  EXPECT_TRUE(Contains(error, "garbage.ply: not a PLY file")) << error;
}

TEST_F(MeshReaderTest, RejectsFacesWithMissingVertices)
{
  // vtkOBJReader and vtkPLYReader both accept these and return invalid point ids.
  std::string error =
    this->ExpectFailure(WriteFile("badface.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"));
  EXPECT_TRUE(Contains(error, "refers to vertex 7 (1-based), but the file has 3 vertices"))
    << error;

  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                             "property float y\nproperty float z\nelement face 1\n"
                             "property list uchar int vertex_indices\nend_header\n";
  error = this->ExpectFailure(WriteFile("badface.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n"));
  EXPECT_TRUE(Contains(error, "face 0 refers to vertex 9, but the file has 3 vertices")) << error;
}

TEST_F(MeshReaderTest, RejectsTruncatedFiles)
{
  // VTK 9.1's vtkPLYReader crashes (invalid free) on these; the reader must not.
  const std::string bunny = ReadFile(DataDir + "/bunny.ply");
  ASSERT_GT(bunny.size(), 1000u);
  std::string error =
    this->ExpectFailure(WriteFile("half-bunny.ply", bunny.substr(0, bunny.size() / 2)));
  EXPECT_TRUE(Contains(error, "the file ends inside element 'vertex'") ||
    Contains(error, "the file ends inside element 'face'"))
    << error;
  EXPECT_TRUE(Contains(error, "truncated")) << error;

  std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                       "property float x\nproperty float y\nproperty float z\nelement face 1\n"
                       "property list uchar int vertex_indices\nend_header\n";
  const float vertices[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
  binary.append(reinterpret_cast<const char*>(vertices), sizeof(vertices));
  binary.push_back(3);
  const std::int32_t indices[2] = { 0, 1 }; // the third index is missing
  binary.append(reinterpret_cast<const char*>(indices), sizeof(indices));
  error = this->ExpectFailure(WriteFile("cut.ply", binary));
  EXPECT_TRUE(Contains(error, "the file ends inside element 'face' 0 of 1")) << error;

  // vtkSTLReader silently returns the triangles that are there.
  error = this->ExpectFailure(WriteFile("cut.stl", BinarySTL(5, 2)));
  EXPECT_TRUE(Contains(error, "declares 5 triangles but holds only 2")) << error;
}

TEST_F(MeshReaderTest, RejectsAbsurdMaterialParameters)
{
  vtkNew<vtkCausticsMeshReader> reader;
  const std::string path = DataDir + "/bunny.ply";
  reader->SetFileName(path.c_str());
  EXPECT_FALSE(reader->SetRoleFromName("plastic"));
  EXPECT_TRUE(Contains(reader->GetLastError(), "unknown role 'plastic'"));
  EXPECT_EQ(reader->GetRole(), vtkCausticsMaterial::ROLE_RECEIVER);

  reader->SetRole(7);
  EXPECT_EQ(reader->CreateActor(), nullptr);
  EXPECT_TRUE(Contains(reader->GetLastError(), "role 7")) << reader->GetLastError();
  reader->SetRole(vtkCausticsMaterial::ROLE_REFRACTOR);

  for (double ior : { 0.5, std::numeric_limits<double>::quiet_NaN() })
  {
    reader->SetRefractiveIndex(ior);
    EXPECT_EQ(reader->CreateActor(), nullptr);
    EXPECT_TRUE(Contains(reader->GetLastError(), "must be finite and >= 1"))
      << reader->GetLastError();
  }
  reader->SetRefractiveIndex(1.33);
  reader->SetColor(1.5, 0.0, 0.0);
  EXPECT_EQ(reader->CreateActor(), nullptr);
  EXPECT_TRUE(Contains(reader->GetLastError(), "outside [0, 1]")) << reader->GetLastError();

  // The earlier parameter errors do not stick once the parameters are fixed.
  reader->SetColor(1.0, 1.0, 1.0);
  auto actor = reader->CreateActor();
  ASSERT_NE(actor, nullptr) << reader->GetLastError();
  EXPECT_EQ(vtkCausticsMaterial::Describe(actor).ior, 1.33);
  EXPECT_STREQ(reader->GetLastError(), "");
}
