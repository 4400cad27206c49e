// Mesh files (.ply, .obj, .stl) through vtkCausticsMeshReader: round trips,
// actors with caustics roles, and clear errors on bad files.
#include "vtkCausticsMaterial.h"
#include "vtkCausticsMeshReader.h"
#include "vtkCausticsSceneExtractor.h"

#include "vtkActor.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkStringOutputWindow.h"
#include "vtksys/SystemTools.hxx"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
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

/** Three vertices of a triangle in z = 0, as OBJ lines. */
const std::string Triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

/** An ASCII PLY header for `vertices` vertices (x, y, z and, if asked, normals) and `faces` faces.
 */
std::string PlyHeader(int vertices, int faces, bool normals = false)
{
  return "ply\nformat ascii 1.0\nelement vertex " + std::to_string(vertices) +
    "\nproperty float x\nproperty float y\nproperty float z\n" +
    (normals ? "property float nx\nproperty float ny\nproperty float nz\n" : "") + "element face " +
    std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

/** An error line fit for a terminal: short, printable ASCII only. */
void ExpectShortAndPrintable(const std::string& error)
{
  EXPECT_LT(error.size(), 400u) << error.substr(0, 400);
  EXPECT_TRUE(std::all_of(error.begin(), error.end(),
    [](char c)
    { return static_cast<unsigned char>(c) >= 0x20 && static_cast<unsigned char>(c) < 0x7f; }))
    << error.substr(0, 400);
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
  EXPECT_TRUE(Contains(error,
    "badface.obj: line 4: vertex index 7 is out of range: the file has 3 "
    "vertices"))
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

// Issue 18: vtkOBJReader reads out of bounds on an out-of-range normal or texture
// coordinate index (SIGSEGV for a far one, garbage normals for a near one).
TEST_F(MeshReaderTest, RejectsOutOfRangeObjIndicesBeforeVTKReadsThem)
{
  // The issue's file: reaching this line at all means vtkOBJReader did not crash.
  std::string error = this->ExpectFailure(
    WriteFile("far-normal.obj", Triangle + "vn 0 0 1\nf 1//100000000 2//100000000 3//100000000\n"));
  EXPECT_TRUE(Contains(
    error, "far-normal.obj: line 5: normal index 100000000 is out of range: the file has 1 normal"))
    << error;

  error =
    this->ExpectFailure(WriteFile("near-normal.obj", Triangle + "vn 0 0 1\nf 1//1 2//1 3//2\n"));
  EXPECT_TRUE(Contains(error, "near-normal.obj: line 5: normal index 2 is out of range")) << error;

  error =
    this->ExpectFailure(WriteFile("far-texcoord.obj", Triangle + "vt 0 0\nf 1/1 2/99999999 3/1\n"));
  EXPECT_TRUE(Contains(error,
    "line 5: texture coordinate index 99999999 is out of range: the "
    "file has 1 texture coordinate"))
    << error;

  // Relative indices count back from the lines above, as vtkOBJReader resolves them.
  error = this->ExpectFailure(WriteFile("relative.obj", Triangle + "f -1 -2 -4\n"));
  EXPECT_TRUE(Contains(error,
    "relative.obj: line 4: relative vertex index -4 is out of range: only 3 vertices above it"))
    << error;
  error = this->ExpectFailure(
    WriteFile("relative-normal.obj", Triangle + "f 1//-1 2//-1 3//-1\nvn 0 0 1\n"));
  EXPECT_TRUE(Contains(error, "line 4: relative normal index -1 is out of range: only 0 normals"))
    << error;

  // Beyond int (vtkOBJReader's sscanf("%d") would overflow), zero, and not numbers.
  error = this->ExpectFailure(
    WriteFile("overflow.obj", Triangle + "vn 0 0 1\nf 1//1 2//1 3//99999999999999999999\n"));
  EXPECT_TRUE(Contains(error, "line 5: normal index '99999999999999999999' is out of range"))
    << error;
  error = this->ExpectFailure(WriteFile("zero.obj", Triangle + "f 0 1 2\n"));
  EXPECT_TRUE(Contains(error, "line 4: vertex index 0 is invalid (OBJ indices start at 1)"))
    << error;
  error = this->ExpectFailure(WriteFile("words.obj", Triangle + "f 1/a 2 3\n"));
  EXPECT_TRUE(Contains(error, "line 4: texture coordinate index 'a' is not an integer")) << error;
  error = this->ExpectFailure(WriteFile("slashes.obj", Triangle + "f 1/1/1/1 2 3\n"));
  EXPECT_TRUE(Contains(error, "line 4: malformed element vertex '1/1/1/1'")) << error;
  error = this->ExpectFailure(WriteFile("mixed.obj", Triangle + "vn 0 0 1\nf 1//1 2 3\n"));
  EXPECT_TRUE(Contains(error, "line 5: a face gives texture coordinates or normals for some"))
    << error;
  error = this->ExpectFailure(WriteFile("badline.obj", Triangle + "l 1 9\n"));
  EXPECT_TRUE(Contains(error, "line 4: vertex index 9 is out of range: the file has 3 vertices"))
    << error;
  error = this->ExpectFailure(
    WriteFile("material.obj", Triangle + "usemtl " + std::string(150, 'm') + "\nf 1 2 3\n"));
  EXPECT_TRUE(Contains(error, "line 4: name 'mmm")) << error;
  EXPECT_TRUE(Contains(error, "is longer than 99 bytes")) << error;
}

TEST_F(MeshReaderTest, ReadsValidObjIndexForms)
{
  // Relative indices, per-face normals and texture coordinates, a forward
  // reference and a '\' continuation are all valid OBJ.
  const std::string path = WriteFile("forms.obj",
    Triangle +
      "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf -3/-3/-1 -2/-2/-1 -1/-1/-1\n"
      "f 1/1/1 2/2/1 \\\n4/3/1\nv 1 1 0\nf 2/2/1 4/1/1 3/3/1\nl 1 2/1\np -1\n");
  vtkNew<vtkCausticsMeshReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  EXPECT_STREQ(reader->GetLastError(), "");
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPolys(), 3);
  EXPECT_FALSE(Contains(this->Messages->GetOutput(), "dropped")) << this->Messages->GetOutput();

  // vtkOBJReader drops faces without normals when others have them: said, not silent.
  const std::string mixed =
    WriteFile("mixed-faces.obj", Triangle + "v 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 2 4 3\n");
  reader->SetFileName(mixed.c_str());
  reader->Update();
  EXPECT_STREQ(reader->GetLastError(), "");
  EXPECT_TRUE(
    Contains(this->Messages->GetOutput(), "mixed-faces.obj: vtkOBJReader dropped 1 of 2 faces"))
    << this->Messages->GetOutput();
}

// Issue 18: "vn nan" was read as (0, -1, 0) without a word; NaN/Inf positions.
TEST_F(MeshReaderTest, RefusesNonFinitePositionsAndRepairsNonFiniteNormals)
{
  // A bad normal: a warning naming the file and line; the normals are dropped so
  // that they are recomputed from the triangles.
  const std::string path =
    WriteFile("nan-normal.obj", Triangle + "vn 0 0 1\nvn nan 0 1\nf 1//1 2//2 3//1\n");
  vtkNew<vtkCausticsMeshReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  EXPECT_STREQ(reader->GetLastError(), "");
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPolys(), 1);
  EXPECT_EQ(reader->GetOutput()->GetPointData()->GetNormals(), nullptr);
  const std::string messages = this->Messages->GetOutput();
  EXPECT_TRUE(Contains(messages,
    "nan-normal.obj: line 5: normal 'vn nan 0 1' is not three "
    "finite numbers; the file's normals are ignored and recomputed"))
    << messages;

  // The same for a PLY whose reader gives NaN normals.
  const std::string ply = WriteFile(
    "inf-normal.ply", PlyHeader(3, 1, true) + "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 inf 0 1\n3 0 1 2\n");
  reader->SetFileName(ply.c_str());
  reader->Update();
  EXPECT_STREQ(reader->GetLastError(), "");
  EXPECT_EQ(reader->GetOutput()->GetPointData()->GetNormals(), nullptr);
  EXPECT_TRUE(Contains(this->Messages->GetOutput(),
    "inf-normal.ply: vertex 3 (1-based) has a NaN or infinite normal; the file's normals are "
    "ignored and recomputed"))
    << this->Messages->GetOutput();

  // vtkOBJReader attaches 3 normals to 4 vertices when faces use normal i with vertex i.
  const std::string few = WriteFile("few-normals.obj",
    Triangle + "v 1 1 0\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\nf 1//1 2//2 3//3\nf 2 4 3\n");
  reader->SetFileName(few.c_str());
  reader->Update();
  EXPECT_STREQ(reader->GetLastError(), "");
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPolys(), 2);
  EXPECT_EQ(reader->GetOutput()->GetPointData()->GetNormals(), nullptr);
  EXPECT_TRUE(Contains(this->Messages->GetOutput(),
    "few-normals.obj: the file gives 3 normals for 4 vertices; the file's normals are ignored"))
    << this->Messages->GetOutput();

  // Positions: an error, in every format.
  std::string error = this->ExpectFailure(WriteFile("inf.obj", Triangle + "v 1 inf 0\nf 1 2 4\n"));
  EXPECT_TRUE(Contains(error, "inf.obj: line 4: vertex coordinate 'inf' is not a finite number"))
    << error;
  error = this->ExpectFailure(WriteFile("big.obj", Triangle + "v 1e39 0 0\nf 1 2 4\n"));
  EXPECT_TRUE(Contains(error, "line 4: vertex coordinate '1e39' is outside the range of a 32-bit"))
    << error;
  error =
    this->ExpectFailure(WriteFile("nan.ply", PlyHeader(3, 1) + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_TRUE(Contains(error, "nan.ply: vertex 2 (1-based) has a NaN or infinite coordinate"))
    << error;
  std::string stl = BinarySTL(2, 2);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&stl[84 + 50 + 12 + 4], &nan, 4); // second triangle, first vertex, y
  // vtkSTLReader's point merging would convert the NaN to a bucket index: checked first.
  error = this->ExpectFailure(WriteFile("nan.stl", stl));
  EXPECT_TRUE(Contains(error, "nan.stl: triangle 2 has a NaN or infinite vertex coordinate"))
    << error;
  error = this->ExpectFailure(WriteFile("nan-ascii.stl",
    "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 nan 0\nvertex 0 1 0\n"
    "endloop\nendfacet\nendsolid s\n"));
  EXPECT_TRUE(Contains(error, "nan-ascii.stl: line 5: vertex coordinate 'nan' is not a finite"))
    << error;
}

// Issue 18: a truncated ASCII STL reported only "FORWARD_DIRECTION: 0", the last
// line of the executive's dump that came before this reader's error.
TEST_F(MeshReaderTest, ReportsVTKReasonForTruncatedAsciiStl)
{
  const std::string error = this->ExpectFailure(WriteFile(
    "cut-ascii.stl", "solid cut\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"));
  EXPECT_TRUE(Contains(error, "cut-ascii.stl: VTK's vtkSTLReader failed: ")) << error;
  EXPECT_TRUE(Contains(error, "Premature EOF")) << error;
  ExpectShortAndPrintable(error);
  // The reader's own error comes first; VTK's executive dump of the inner reader's
  // failure is not shown.
  const std::string messages = this->Messages->GetOutput();
  EXPECT_FALSE(Contains(messages, "Algorithm vtkSTLReader")) << messages;
  EXPECT_FALSE(Contains(messages.substr(0, messages.find(error)), "FORWARD_DIRECTION")) << messages;
}

// Issue 18: a PLY whose triangles all have zero area was accepted, and rendering
// failed later with "Bad plane coordinate system".
TEST_F(MeshReaderTest, RejectsMeshWithoutTriangleArea)
{
  std::string error = this->ExpectFailure(
    WriteFile("flat.ply", PlyHeader(4, 2) + "0 0 0\n1 1 1\n2 2 2\n0 0 0\n3 0 1 2\n3 0 3 1\n"));
  EXPECT_TRUE(
    Contains(error, "flat.ply: no triangle with non-zero area (all 2 faces are degenerate)"))
    << error;
  error = this->ExpectFailure(WriteFile("point.obj", "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n"));
  EXPECT_TRUE(Contains(error, "point.obj: no triangle with non-zero area")) << error;

  // One good triangle among degenerate ones is enough (the extractor drops the rest).
  const std::string path = WriteFile(
    "mostly-flat.ply", PlyHeader(4, 2) + "0 0 0\n1 1 1\n2 2 2\n0 1 0\n3 0 1 2\n3 0 1 3\n");
  vtkNew<vtkCausticsMeshReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  EXPECT_STREQ(reader->GetLastError(), "");
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPolys(), 2);
}

// Issue 18: a 5 MB one-line OBJ or binary junk was echoed to stderr.
TEST_F(MeshReaderTest, QuotesOnlyShortPrintableExcerpts)
{
  std::string error =
    this->ExpectFailure(WriteFile("one-line.obj", "v " + std::string(5 << 20, '1') + "\n"));
  EXPECT_TRUE(Contains(error, "one-line.obj: line 1 is longer than 262142 bytes")) << error;
  ExpectShortAndPrintable(error);
  // The limit is vtkOBJReader's own: a line just within it reads.
  const std::string longest =
    WriteFile("longest-line.obj", "#" + std::string(262141, 'c') + "\n" + Triangle + "f 1 2 3\n");
  vtkNew<vtkCausticsMeshReader> reader;
  reader->SetFileName(longest.c_str());
  reader->Update();
  EXPECT_STREQ(reader->GetLastError(), "");
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPolys(), 1);

  error =
    this->ExpectFailure(WriteFile("long-word.obj", "v 1 2 " + std::string(100000, 'x') + "\n"));
  EXPECT_TRUE(Contains(error, "line 1: vertex coordinate 'xxx")) << error;
  EXPECT_TRUE(Contains(error, "...' is not a finite number")) << error;
  ExpectShortAndPrintable(error);

  std::string junk;
  for (int i = 0; i < 100000; ++i)
  {
    junk.push_back(static_cast<char>((i * 7919 + i / 13) & 0xff));
  }
  for (const char* name : { "junk.obj", "junk.ply", "junk.stl" })
  {
    error = this->ExpectFailure(WriteFile(name, junk));
    EXPECT_TRUE(Contains(error, name)) << error;
    ExpectShortAndPrintable(error);
  }
  // Text junk goes as far as VTK's ASCII STL parser, whose message quotes it.
  error = this->ExpectFailure(WriteFile(
    "text-junk.stl", "solid " + std::string(3000, 'q') + "\n" + std::string(5000, 'z') + "\n"));
  EXPECT_TRUE(Contains(error, "text-junk.stl: ")) << error;
  ExpectShortAndPrintable(error);
  error = this->ExpectFailure(
    WriteFile("long-header.ply", "ply\nformat ascii 1.0\ncomment " + std::string(10000, 'c')));
  EXPECT_TRUE(Contains(error, "long-header.ply: header line 3 is longer than 4094 bytes")) << error;
  ExpectShortAndPrintable(error);
  // Just past what vtkPLY's 4096-byte line buffer holds with the '\n' and NUL: a
  // 4095-byte line got VTK's vague message before (issue 18).
  for (std::size_t length : { std::size_t(4095), std::size_t(4096) })
  {
    error = this->ExpectFailure(WriteFile("edge-header.ply",
      "ply\nformat ascii 1.0\ncomment " + std::string(length - 8, 'c') +
        "\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
    EXPECT_TRUE(Contains(error, "edge-header.ply: header line 3 is longer than 4094 bytes"))
      << length << ": " << error;
  }
  const std::string messages = this->Messages->GetOutput();
  for (char c : { '1', 'x', 'q', 'z', 'c' })
  {
    EXPECT_FALSE(Contains(messages, std::string(100, c))) << "nothing echoes the file: " << c;
  }
}

// Issue 18: a FIFO or /dev/zero given as a mesh hung the program.
TEST_F(MeshReaderTest, RefusesFilesThatAreNotRegular)
{
  vtksys::SystemTools::MakeDirectory(OutputDir);
  const std::string fifo = OutputDir + "/pipe.obj";
  unlink(fifo.c_str());
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::string error = this->ExpectFailure(fifo);
  EXPECT_TRUE(Contains(error, fifo + ": is a FIFO (named pipe), not a regular file")) << error;
  unlink(fifo.c_str());

  const std::string zero = OutputDir + "/zero.stl";
  unlink(zero.c_str());
  ASSERT_EQ(symlink("/dev/zero", zero.c_str()), 0);
  error = this->ExpectFailure(zero);
  EXPECT_TRUE(Contains(error, zero + ": is a device, not a regular file")) << error;
  unlink(zero.c_str());

  error = this->ExpectFailure(OutputDir);
  EXPECT_TRUE(Contains(error, ": is a folder, not a mesh file")) << error;
}

// Issue 18, found by fuzzing: vtkPLYReader reads an ASCII body one element per
// line, words split at spaces, tabs and carriage returns only, and takes the words
// it needs without counting them; a line with too few words, or a last line
// without a line break, made it read through a null pointer (SIGSEGV).
TEST_F(MeshReaderTest, RefusesPlyLinesThatVTKWouldReadPast)
{
  std::string error = this->ExpectFailure(
    WriteFile("short-line.ply", PlyHeader(3, 1) + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_TRUE(Contains(error,
    "short-line.ply: line 11 (element 'vertex' 1) has 2 values, fewer than its properties need"))
    << error;
  // "\v" separates words for the C library, not for vtkPLY: "0\v0" is one word.
  error =
    this->ExpectFailure(WriteFile("vtab.ply", PlyHeader(3, 1) + "0\v0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_TRUE(Contains(error, "vtab.ply: element 'vertex' 0: '0\\x0b0' is not a number")) << error;
  error = this->ExpectFailure(
    WriteFile("blank-line.ply", PlyHeader(3, 1) + "0 0 0\n\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_TRUE(Contains(error, "line 11 (element 'vertex' 1) has 0 values")) << error;
  error = this->ExpectFailure(
    WriteFile("no-final-newline.ply", PlyHeader(3, 1) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2"));
  EXPECT_TRUE(Contains(
    error, "no-final-newline.ply: line 13 (element 'face' 0) does not end with a line break"))
    << error;
  // Tabs and extra words are fine, as for vtkPLY.
  const std::string path =
    WriteFile("tabs.ply", PlyHeader(3, 1) + "0\t0\t0\n1 0 0 7 8\n0 1 0\n3 0 1 2\n");
  vtkNew<vtkCausticsMeshReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  EXPECT_STREQ(reader->GetLastError(), "");
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPolys(), 1);

  // A NaN index is named as written (converting it to an integer is undefined).
  error = this->ExpectFailure(
    WriteFile("nan-index.ply", PlyHeader(3, 1) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 nan\n"));
  EXPECT_TRUE(Contains(error, "face 0 refers to vertex 'nan', but the file has 3 vertices"))
    << error;
  // Nothing to read per instance: nothing bounds the count.
  error = this->ExpectFailure(WriteFile("empty-element.ply",
    "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n"
    "property float y\nproperty float z\nelement edge 999999999999\nend_header\n"));
  EXPECT_TRUE(Contains(error, "element 'edge' declares 999999999999 instances but no properties"))
    << error;
}

// Issue 18, found by fuzzing: vtkPLYReader takes the file's word for whether a
// property is a list but stores it where it expects its own kind; a face without
// a vertex_indices list crashed it (invalid free), a list where it reads a scalar
// wrote a pointer over a one-byte field.
TEST_F(MeshReaderTest, RefusesPlyPropertiesVTKWouldMisread)
{
  const std::string vertex =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\n";
  const std::string points = "0 0 0\n1 0 0\n0 1 0\n";
  std::string error = this->ExpectFailure(WriteFile("no-indices.ply",
    vertex + "element face 1\nproperty list uchar int vertex_indi1es\nend_header\n" + points +
      "3 0 1 2\n"));
  EXPECT_TRUE(Contains(error, "no-indices.ply: the 'face' element has no vertex_indices list"))
    << error;
  error = this->ExpectFailure(WriteFile("list-intensity.ply",
    vertex +
      "element face 1\nproperty list uchar int vertex_indices\n"
      "property list uchar uchar intensity\nend_header\n" +
      points + "3 0 1 2 1 7\n"));
  EXPECT_TRUE(Contains(
    error, "property 'intensity' of element 'face' must be a scalar, as vtkPLYReader reads it"))
    << error;
  error = this->ExpectFailure(WriteFile("scalar-indices.ply",
    vertex + "element face 1\nproperty int vertex_indices\nend_header\n" + points + "2\n"));
  EXPECT_TRUE(Contains(error, "property 'vertex_indices' of element 'face' must be a list"))
    << error;
  error = this->ExpectFailure(WriteFile("two-vertex-elements.ply",
    vertex + vertex.substr(vertex.find("element")) + "end_header\n" + points + points));
  EXPECT_TRUE(Contains(error, "the header declares element 'vertex' twice")) << error;

  // One format only: a second one made this check and VTK read the body differently.
  error = this->ExpectFailure(WriteFile("two-formats.ply",
    vertex +
      "element face 1\nformat binary_little_endian 1.0\n"
      "property list uchar int vertex_indices\nend_header\n" +
      points + "3 0 1 2\n"));
  EXPECT_TRUE(Contains(error, "two-formats.ply: header line 8 is a second 'format' line")) << error;

  // vtkPLY reads the first word of every header line, even of an empty one.
  error = this->ExpectFailure(WriteFile("blank-header-line.ply",
    vertex + "element face 1\nproperty list uchar int vertex_indices\n\nend_header\n" + points +
      "3 0 1 2\n"));
  EXPECT_TRUE(Contains(error, "blank-header-line.ply: header line 9 is empty")) << error;

  // Names from the header are quoted like any text of the file (found by fuzzing).
  error = this->ExpectFailure(WriteFile("odd-name.ply",
    vertex + "element fac\x97 3\nproperty list uchar int vertex_indices\nend_header\n" + points +
      "3 0 1 2\n"));
  EXPECT_TRUE(Contains(error, "the file ends before element 'fac\\x97' 1 of 3 (truncated?)"))
    << error;
  ExpectShortAndPrintable(error);
}
