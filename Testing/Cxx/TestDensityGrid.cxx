// Heterogeneous media: caustics::DensityGrid and vtkCausticsMedium::LoadDensity.
// Every .vdb is written here with OpenVDB into a temporary folder (no binary files in
// the repository). Bad input must give one error line naming the problem and keep
// the previous density; good grids must sample as OpenVDB's trilinear interpolation
// of what was written, placed by the medium's matrix and scaled.
#include "vtkCausticsDensityGrid.h"
#include "vtkCausticsMedium.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkTestErrorObserver.h"

#include "TestTechniqueFrame.h"

#include <openvdb/openvdb.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <iostream>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

namespace
{
std::string Folder()
{
  static const std::string folder = []()
  {
    const std::string path = std::string(CAUSTICS_TEST_OUTPUT_DIR) + "/density-grid";
    std::filesystem::create_directories(path);
    openvdb::initialize();
    return path;
  }();
  return folder;
}

std::string Write(const std::string& name, const openvdb::GridPtrVec& grids)
{
  const std::string path = Folder() + "/" + name;
  openvdb::io::File(path).write(grids);
  return path;
}

/** A fog volume of `value` over index box [0, n)^3, voxels of `voxel` m. */
openvdb::FloatGrid::Ptr ConstantBox(float value, int n, double voxel, const char* name = "density")
{
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName(name);
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
  grid->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(n - 1)), value, true);
  return grid;
}

/** Density i (the x index) over [0, n)^3: trilinear interpolation reproduces it exactly. */
openvdb::FloatGrid::Ptr Ramp(int n, double voxel)
{
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
  auto accessor = grid->getAccessor();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        accessor.setValue(openvdb::Coord(i, j, k), static_cast<float>(i));
  return grid;
}

/** Loads and returns the error line, "" on success. */
std::string LoadError(vtkCausticsMedium* medium, const std::string& file, const char* grid)
{
  vtkNew<vtkTest::ErrorObserver> observer;
  const unsigned long tag = medium->AddObserver(vtkCommand::ErrorEvent, observer);
  const bool loaded = medium->LoadDensity(file.c_str(), grid);
  medium->RemoveObserver(tag);
  EXPECT_EQ(loaded, observer->GetErrorMessage().empty()) << observer->GetErrorMessage();
  return observer->GetErrorMessage();
}
}

TEST(DensityGrid, BadFilesGiveOneLineNamingTheProblem)
{
  vtkNew<vtkCausticsMedium> medium;
  const std::string good = Write("good.vdb", { ConstantBox(1.0f, 8, 0.1) });
  ASSERT_EQ(LoadError(medium, good, "density"), "");
  ASSERT_TRUE(medium->HasDensity());

  const std::string text = Folder() + "/text.vdb";
  std::ofstream(text) << "this is not a VDB file\n";
  const std::string truncated = Folder() + "/truncated.vdb";
  {
    std::ifstream in(good, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  auto velocity = openvdb::Vec3SGrid::create();
  velocity->setName("velocity");
  velocity->tree().setValue(openvdb::Coord(1, 2, 3), openvdb::Vec3s(1, 0, 0));
  auto temperature = openvdb::DoubleGrid::create();
  temperature->setName("temperature");
  temperature->tree().setValue(openvdb::Coord(0), 300.0);
  auto empty = openvdb::FloatGrid::create();
  empty->setName("density");
  auto levelSet = openvdb::FloatGrid::create(0.3f);
  levelSet->setName("density");
  levelSet->setGridClass(openvdb::GRID_LEVEL_SET);
  levelSet->tree().setValue(openvdb::Coord(0), -0.1f);
  const std::string several =
    Write("several.vdb", { ConstantBox(1.0f, 4, 0.1, "smoke"), velocity, temperature });
  const std::string emptyFile = Write("empty.vdb", { empty });
  const std::string levelSetFile = Write("level-set.vdb", { levelSet });

  struct Case
  {
    std::string file;
    const char* grid;
    std::string expected;
  };
  const Case cases[] = {
    { Folder() + "/missing.vdb", "density", "missing.vdb': no such file or not readable" },
    { text, "density", "text.vdb' (not a VDB file, or truncated)" },
    { truncated, "density", "truncated.vdb' (not a VDB file, or truncated)" },
    { several, "density",
      "has no grid named 'density' (its grids: 'smoke', 'temperature', 'velocity')" },
    { several, "velocity", "holds vec3s values; a density needs a float scalar grid" },
    { several, "temperature", "holds double values; a density needs a float scalar grid" },
    { emptyFile, "density", "is empty (no active voxel)" },
    { levelSetFile, "density", "is a level set (signed distance), not a density" },
  };
  for (const Case& c : cases)
  {
    const std::string error = LoadError(medium, c.file, c.grid);
    EXPECT_NE(error.find(c.expected), std::string::npos) << "got: " << error;
    EXPECT_NE(error.find("keeping the previous density"), std::string::npos) << error;
    EXPECT_NE(error.find(medium->GetLastError()), std::string::npos) << medium->GetLastError();
    // VTK's "ERROR: In <file>, line <n>" header, then the message: one line.
    std::string message = error.substr(error.find('\n') + 1);
    message.erase(message.find_last_not_of('\n') + 1);
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << error;
    // The old state stays.
    EXPECT_TRUE(medium->HasDensity());
    EXPECT_EQ(std::string(medium->GetDensityFileName()), good);
  }
  std::cout << "e.g.: " << LoadError(medium, several, "density");
  EXPECT_EQ(LoadError(medium, good, "density"), "");
  EXPECT_STREQ(medium->GetLastError(), "");
}

TEST(DensityGrid, NegativeAndNaNVoxelsAreClampedWithOneWarning)
{
  auto grid = ConstantBox(2.0f, 4, 0.1);
  grid->tree().setValue(openvdb::Coord(1, 1, 1), -3.0f);
  grid->tree().setValue(openvdb::Coord(2, 1, 1), std::numeric_limits<float>::quiet_NaN());
  grid->tree().setValue(openvdb::Coord(3, 3, 3), -0.5f);
  const std::string file = Write("negative.vdb", { grid });
  vtkNew<vtkCausticsMedium> medium;
  vtkNew<vtkTest::ErrorObserver> observer;
  medium->AddObserver(vtkCommand::WarningEvent, observer);
  ASSERT_TRUE(medium->LoadDensity(file.c_str()));
  EXPECT_NE(observer->GetWarningMessage().find("3 negative or NaN density values set to 0"),
    std::string::npos)
    << observer->GetWarningMessage();
  auto density = medium->GetDensity();
  ASSERT_TRUE(density);
  EXPECT_DOUBLE_EQ(density->Sample({ { 0.1, 0.1, 0.1 } }), 0.0);
  EXPECT_DOUBLE_EQ(density->Sample({ { 0.2, 0.1, 0.1 } }), 0.0);
  EXPECT_DOUBLE_EQ(density->Sample({ { 0.2, 0.2, 0.2 } }), 2.0);
  EXPECT_DOUBLE_EQ(density->GetMajorant(), 2.0);
  EXPECT_NEAR(density->GetMeanDensity(), 2.0 * 61.0 / 64.0, 1e-12);
}

TEST(DensityGrid, AbsurdScaleIsRefused)
{
  vtkNew<vtkCausticsMedium> medium;
  medium->SetDensityScale(3.0);
  for (double bad : { -1.0, std::numeric_limits<double>::quiet_NaN(),
         std::numeric_limits<double>::infinity(), 2e6 })
  {
    vtkNew<vtkTest::ErrorObserver> observer;
    medium->AddObserver(vtkCommand::ErrorEvent, observer);
    medium->SetDensityScale(bad);
    EXPECT_NE(observer->GetErrorMessage().find("density scale"), std::string::npos) << bad;
    EXPECT_DOUBLE_EQ(medium->GetDensityScale(), 3.0);
    medium->RemoveAllObservers();
  }
  medium->SetDensityScale(1e6);
  EXPECT_DOUBLE_EQ(medium->GetDensityScale(), 1e6);
}

TEST(DensityGrid, ConstantBoxSamplesItsValueTimesTheScale)
{
  const std::string file = Write("constant.vdb", { ConstantBox(0.5f, 20, 0.05) });
  vtkNew<vtkCausticsMedium> medium;
  ASSERT_TRUE(medium->LoadDensity(file.c_str()));
  medium->SetDensityScale(2.0);
  auto grid = medium->GetDensity();
  ASSERT_TRUE(grid);
  EXPECT_EQ(grid, medium->GetDensity()) << "unchanged placement: the same object";
  for (double x : { 0.0, 0.123, 0.5, 0.95 })
  {
    EXPECT_NEAR(grid->Sample({ { x, 0.5, 0.3 } }), 1.0, 1e-6) << x;
  }
  EXPECT_DOUBLE_EQ(grid->Sample({ { 3.0, 0.5, 0.5 } }), 0.0);
  EXPECT_NEAR(grid->Sample({ { 0.975, 0.5, 0.5 } }), 0.5, 1e-6) << "half a voxel beyond: ramp";
  EXPECT_DOUBLE_EQ(grid->GetMajorant(), 1.0);
  EXPECT_DOUBLE_EQ(grid->GetMeanDensity(), 1.0);
  EXPECT_EQ(grid->GetActiveVoxelCount(), 8000);
  double bounds[6];
  grid->GetWorldBounds(bounds);
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_NEAR(bounds[2 * a], -0.05, 1e-12);
    EXPECT_NEAR(bounds[2 * a + 1], 1.0, 1e-12);
  }
  EXPECT_EQ(grid->GetDenseBytes(), 8000u * 4u);
  EXPECT_GT(grid->GetNanoVDBBytes(), 0u);
  EXPECT_NE(grid->GetNanoVDBData(), nullptr);
  std::cout << "20^3 constant box: NanoVDB " << grid->GetNanoVDBBytes() << " bytes, dense "
            << grid->GetDenseBytes() << " bytes\n";
  medium->SetDensityScale(3.0);
  EXPECT_NE(grid, medium->GetDensity()) << "a new scale: a new placement";
  EXPECT_DOUBLE_EQ(medium->GetDensity()->GetMajorant(), 1.5);
  EXPECT_EQ(grid->GetContentHash(), medium->GetDensity()->GetContentHash());
}

TEST(DensityGrid, SparseGridIsSmallAsNanoVDB)
{
  // Two 16^3 clouds 1000 voxels apart: a dense array would hold 10^9 voxels.
  auto grid = ConstantBox(1.0f, 16, 0.1);
  grid->fill(openvdb::CoordBBox(openvdb::Coord(1000), openvdb::Coord(1015)), 0.25f, true);
  const std::string file = Write("sparse.vdb", { grid });
  vtkNew<vtkCausticsMedium> medium;
  ASSERT_TRUE(medium->LoadDensity(file.c_str()));
  auto density = medium->GetDensity();
  EXPECT_EQ(density->GetDenseBytes(), std::size_t(1016) * 1016 * 1016 * 4);
  EXPECT_LT(density->GetNanoVDBBytes(), std::size_t(1) << 20);
  EXPECT_DOUBLE_EQ(density->GetMeanDensity(), 0.625);
  std::cout << "two 16^3 clouds 1000 voxels apart: NanoVDB " << density->GetNanoVDBBytes()
            << " bytes, dense " << density->GetDenseBytes() << " bytes\n";
}

TEST(DensityGrid, LinearRampIsInterpolatedExactly)
{
  const double voxel = 0.1;
  const std::string file = Write("ramp.vdb", { Ramp(16, voxel) });
  vtkNew<vtkCausticsMedium> medium;
  ASSERT_TRUE(medium->LoadDensity(file.c_str()));
  auto grid = medium->GetDensity();
  for (double index : { 1.0, 2.25, 7.5, 13.9 })
  {
    EXPECT_NEAR(grid->Sample({ { index * voxel, 0.73, 0.41 } }), index, 1e-5) << index;
  }
  EXPECT_DOUBLE_EQ(grid->GetMajorant(), 15.0);
  EXPECT_NEAR(grid->GetMeanDensity(), 7.5, 1e-12);
}

TEST(DensityGrid, MatrixPlacesTheGridAfterItsOwnTransform)
{
  const double voxel = 0.1;
  const std::string file = Write("placed-ramp.vdb", { Ramp(16, voxel) });
  vtkNew<vtkCausticsMedium> medium;
  ASSERT_TRUE(medium->LoadDensity(file.c_str()));
  // Turned 90 degrees about z, stretched 2x along the grid's x, moved by (5, -2, 1).
  vtkNew<vtkMatrix4x4> matrix;
  const double elements[16] = { 0, -1, 0, 5, 2, 0, 0, -2, 0, 0, 1, 1, 0, 0, 0, 1 };
  matrix->DeepCopy(elements);
  medium->SetDensityMatrix(matrix);
  auto grid = medium->GetDensity();
  const std::array<double, 3> points[] = { { 0.3, 0.7, 0.2 }, { 1.1, 0.45, 1.3 } };
  for (const auto& p : points)
  {
    const caustics::Vec3 world{ { 5 - p[1], -2 + 2 * p[0], 1 + p[2] } };
    EXPECT_NEAR(grid->Sample(world), p[0] / voxel, 1e-5);
  }
  double bounds[6];
  grid->GetWorldBounds(bounds);
  // Index box [-1, 16] -> file world [-0.1, 1.6] per axis.
  const double expected[6] = { 5 - 1.6, 5 + 0.1, -2 - 0.2, -2 + 3.2, 1 - 0.1, 1 + 1.6 };
  for (int i = 0; i < 6; ++i)
  {
    EXPECT_NEAR(bounds[i], expected[i], 1e-12) << i;
  }
  // Changing the matrix in place is a change of the medium.
  const vtkMTimeType before = medium->GetMTime();
  matrix->SetElement(0, 3, 6.0);
  EXPECT_GT(medium->GetMTime(), before);
  EXPECT_NEAR(medium->GetDensity()->Sample({ { 6 - 0.7, -2 + 0.6, 1.2 } }), 3.0, 1e-5);

  // A singular or projective matrix is ignored with a warning: the file's placement.
  vtkNew<vtkTest::ErrorObserver> observer;
  medium->AddObserver(vtkCommand::WarningEvent, observer);
  for (int bad = 0; bad < 2; ++bad)
  {
    vtkNew<vtkMatrix4x4> wrong;
    wrong->SetElement(bad == 0 ? 0 : 3, bad == 0 ? 0 : 0, bad == 0 ? 0.0 : 0.5);
    medium->SetDensityMatrix(wrong);
    EXPECT_NEAR(medium->GetDensity()->Sample({ { 0.3, 0.7, 0.2 } }), 3.0, 1e-5);
    EXPECT_NE(
      observer->GetWarningMessage().find("not an invertible affine transform"), std::string::npos);
    observer->Clear();
  }
}

TEST(DensityGrid, SnapshotCarriesTheGrid)
{
  const std::string file = Write("snapshot.vdb", { ConstantBox(0.5f, 20, 0.05) });
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkCausticsMedium> medium;
  medium->SetScatteringCoefficient(0.2, 0.4, 0.6);
  medium->SetAbsorptionCoefficient(0.1, 0.0, 0.0);
  vtkCausticsMedium::AttachTo(renderer, medium);
  vtkNew<vtkCausticsSceneExtractor> extractor;
  ASSERT_TRUE(extractor->Update(renderer, 8, 8));
  const caustics::Medium& homogeneous = extractor->GetScene().Participating;
  EXPECT_FALSE(homogeneous.density);
  EXPECT_EQ(homogeneous.MeanSigmaT(), (caustics::Vec3{ { 0.30000000000000004, 0.4, 0.6 } }));

  ASSERT_TRUE(medium->LoadDensity(file.c_str()));
  medium->SetDensityScale(4.0);
  ASSERT_TRUE(extractor->Update(renderer, 8, 8));
  const caustics::Medium& heterogeneous = extractor->GetScene().Participating;
  ASSERT_TRUE(heterogeneous.density);
  EXPECT_EQ(heterogeneous.density, medium->GetDensity());
  EXPECT_DOUBLE_EQ(heterogeneous.MeanDensity(), 2.0);
  EXPECT_DOUBLE_EQ(heterogeneous.MeanSigmaS()[2], 1.2);
  EXPECT_DOUBLE_EQ(heterogeneous.MeanSigmaT()[0], 0.6);
}

namespace
{
/**
 * An image whose density at point (i, j, k) is 1 + i + 2 j + 3 k (linear, so trilinear
 * sampling reproduces it anywhere inside), placed with a non-zero extent start, an
 * origin, anisotropic spacing and a rotation of 90 degrees about y.
 */
vtkSmartPointer<vtkImageData> LinearImage()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetExtent(2, 6, 0, 3, 1, 5);
  image->SetOrigin(1.0, -2.0, 0.5);
  image->SetSpacing(0.1, 0.2, 0.25);
  // Columns are the index axes in world: i -> -z, j -> y, k -> x.
  image->SetDirectionMatrix(0, 0, 1, 0, 1, 0, -1, 0, 0);
  vtkNew<vtkFloatArray> values;
  values->SetName("smoke");
  values->SetNumberOfTuples(image->GetNumberOfPoints());
  vtkIdType id = 0;
  for (int k = 1; k <= 5; ++k)
    for (int j = 0; j <= 3; ++j)
      for (int i = 2; i <= 6; ++i)
        values->SetValue(id++, static_cast<float>(1 + i + 2 * j + 3 * k));
  image->GetPointData()->AddArray(values);
  return image;
}

/** SetDensityData's error line, "" on success. */
std::string DataError(vtkCausticsMedium* medium, vtkImageData* image, const char* array)
{
  vtkNew<vtkTest::ErrorObserver> observer;
  const unsigned long tag = medium->AddObserver(vtkCommand::ErrorEvent, observer);
  const bool set = medium->SetDensityData(image, array);
  medium->RemoveObserver(tag);
  EXPECT_EQ(set, observer->GetErrorMessage().empty());
  return observer->GetErrorMessage();
}
}

// A density from a VTK volume: placed exactly as vtkImageData places its points
// (extent start, origin, spacing, direction), zeros left out of the sparse grid.
TEST(DensityGrid, ImageDataIsPlacedAsVTKPlacesItsPoints)
{
  auto image = LinearImage();
  vtkNew<vtkCausticsMedium> medium;
  ASSERT_EQ(DataError(medium, image, "smoke"), "");
  EXPECT_STREQ(medium->GetDensityFileName(), "");
  EXPECT_STREQ(medium->GetDensityGridName(), "vtkImageData:smoke");
  auto density = medium->GetDensity();
  ASSERT_TRUE(density);
  EXPECT_EQ(density->GetActiveVoxelCount(), 5 * 4 * 5);
  for (const std::array<double, 3>& ijk :
    { std::array<double, 3>{ { 2, 0, 1 } }, { { 6, 3, 5 } }, { { 3.5, 1.25, 2.75 } } })
  {
    double world[3];
    image->TransformContinuousIndexToPhysicalPoint(ijk.data(), world);
    const double expected = 1 + ijk[0] + 2 * ijk[1] + 3 * ijk[2];
    EXPECT_NEAR(density->Sample({ { world[0], world[1], world[2] } }), expected, 1e-4)
      << ijk[0] << " " << ijk[1] << " " << ijk[2];
  }
  double bounds[6];
  density->GetWorldBounds(bounds);
  double first[3], last[3];
  image->TransformIndexToPhysicalPoint(2, 0, 1, first);
  image->TransformIndexToPhysicalPoint(6, 3, 5, last);
  // x comes from k (spacing 0.25), y from j (0.2), z from -i (0.1); one voxel's reach.
  EXPECT_NEAR(bounds[0], std::min(first[0], last[0]) - 0.25, 1e-9);
  EXPECT_NEAR(bounds[3], std::max(first[1], last[1]) + 0.2, 1e-9);
  EXPECT_NEAR(bounds[4], std::min(first[2], last[2]) - 0.1, 1e-9);

  // Zero points are inactive: a sparse shell costs what it holds.
  vtkNew<vtkImageData> sparse;
  sparse->SetDimensions(40, 40, 40);
  vtkNew<vtkFloatArray> shell;
  shell->SetNumberOfTuples(sparse->GetNumberOfPoints());
  shell->Fill(0.0);
  shell->SetValue(sparse->ComputePointId(std::array<int, 3>{ { 20, 20, 20 } }.data()), 2.0f);
  sparse->GetPointData()->SetScalars(shell);
  ASSERT_EQ(DataError(medium, sparse, nullptr), "");
  EXPECT_EQ(medium->GetDensity()->GetActiveVoxelCount(), 1);
  EXPECT_STREQ(medium->GetDensityGridName(), "vtkImageData:scalars");
  // Integer arrays are densities too.
  vtkNew<vtkIntArray> counts;
  counts->SetName("counts");
  counts->SetNumberOfTuples(sparse->GetNumberOfPoints());
  counts->Fill(3);
  sparse->GetPointData()->AddArray(counts);
  ASSERT_EQ(DataError(medium, sparse, "counts"), "");
  EXPECT_DOUBLE_EQ(medium->GetDensity()->GetMajorant(), 3.0);
}

TEST(DensityGrid, BadImageDataGivesOneLineAndKeepsTheDensity)
{
  auto image = LinearImage();
  vtkNew<vtkCausticsMedium> medium;
  ASSERT_EQ(DataError(medium, image, "smoke"), "");
  vtkNew<vtkImageData> zeros;
  zeros->SetDimensions(4, 4, 4);
  vtkNew<vtkFloatArray> none;
  none->SetNumberOfTuples(64);
  none->Fill(0.0);
  zeros->GetPointData()->SetScalars(none);
  vtkNew<vtkImageData> bare;
  bare->SetDimensions(4, 4, 4);
  const struct
  {
    vtkImageData* image;
    const char* array;
    const char* says;
  } cases[] = { { nullptr, nullptr, "needs an image" },
    { image, "missing", "no numeric point array 'missing'" },
    { bare, nullptr, "no point scalars" }, { zeros, nullptr, "is empty (no active voxel)" } };
  for (const auto& bad : cases)
  {
    const std::string error = DataError(medium, bad.image, bad.array);
    EXPECT_NE(error.find(bad.says), std::string::npos) << error;
    EXPECT_NE(error.find("keeping the previous density"), std::string::npos) << error;
    EXPECT_STREQ(medium->GetDensityGridName(), "vtkImageData:smoke");
  }
  // NaN and negative points become 0 with one warning.
  vtkNew<vtkImageData> odd;
  odd->SetDimensions(2, 2, 2);
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfTuples(8);
  values->Fill(1.0);
  values->SetValue(0, std::numeric_limits<float>::quiet_NaN());
  values->SetValue(7, -2.0f);
  odd->GetPointData()->SetScalars(values);
  vtkNew<vtkTest::ErrorObserver> observer;
  medium->AddObserver(vtkCommand::WarningEvent, observer);
  ASSERT_TRUE(medium->SetDensityData(odd));
  EXPECT_NE(observer->GetWarningMessage().find("2 negative or NaN density values set to 0"),
    std::string::npos)
    << observer->GetWarningMessage();
  EXPECT_DOUBLE_EQ(medium->GetDensity()->Sample({ { 0.0, 0.0, 0.0 } }), 0.0);
  EXPECT_DOUBLE_EQ(medium->GetDensity()->Sample({ { 1.0, 0.0, 0.0 } }), 1.0);
}

namespace
{
/** A technique with a stage that takes the mean density (none of the real ones does). */
class MeanDensityPass : public vtkCausticsRenderPass
{
public:
  static MeanDensityPass* New();
  vtkTypeMacro(MeanDensityPass, vtkCausticsRenderPass);

protected:
  MeanDensityPass() = default;
  const char* GetMeanDensityStages() override { return "the test's stage"; }
};
vtkStandardNewMacro(MeanDensityPass);
}

// A stage that takes a grid's mean density instead of following it must say so, once
// per medium change; the GPU techniques follow the grid in every stage and say nothing.
TEST(DensityGrid, MeanDensityStagesWarnOncePerMediumChange)
{
  const std::string file = Write("gpu.vdb", { ConstantBox(1.0f, 8, 1.0) });
  vtkNew<vtkCausticsMedium> medium;
  medium->SetScatteringCoefficient(0.05, 0.05, 0.05);
  ASSERT_TRUE(medium->LoadDensity(file.c_str()));
  vtkNew<vtkTest::ErrorObserver> observer;
  auto warnings = [&]()
  {
    const std::string text = observer->GetWarningMessage();
    observer->Clear();
    return text;
  };
  {
    TechniqueFrame frame("none", 64, 64);
    vtkNew<MeanDensityPass> pass;
    pass->SetLightBufferResolution(64);
    frame.Renderer->SetPass(pass);
    vtkCausticsMedium::AttachTo(frame.Renderer, medium);
    pass->AddObserver(vtkCommand::WarningEvent, observer);
    const std::string expected = std::string(pass->GetClassName()) +
      ": the test's stage does not follow the heterogeneous density yet; using the grid's "
      "mean density (1)";
    frame.Window->Render();
    const std::string first = warnings();
    EXPECT_NE(first.find(expected), std::string::npos) << first;
    frame.Window->Render();
    EXPECT_EQ(warnings().find("heterogeneous"), std::string::npos) << "once, not every frame";
    medium->SetDensityScale(0.5);
    frame.Window->Render();
    EXPECT_NE(warnings().find("using the grid's mean density (0.5)"), std::string::npos);
    medium->RemoveDensity();
    frame.Window->Render();
    EXPECT_EQ(warnings().find("heterogeneous"), std::string::npos);
    frame.Renderer->SetPass(nullptr);
    pass->ReleaseGraphicsResources(frame.Window);
  }
  for (const char* technique : { "screen-space", "caustic-maps" })
  {
    TechniqueFrame frame(technique, 64, 64);
    medium->SetDensityScale(1.0);
    ASSERT_TRUE(medium->LoadDensity(file.c_str()));
    vtkCausticsMedium::AttachTo(frame.Renderer, medium);
    frame.Pass->AddObserver(vtkCommand::WarningEvent, observer);
    frame.Window->Render();
    EXPECT_EQ(warnings().find("mean density"), std::string::npos) << technique;
  }
}

// Issue 14's large-grid stress case: 216^3 (about 10^7) active voxels of varying
// density, so that every leaf is stored (a constant fill would become tiles). It is
// loaded through the user's path (.vdb file), converted to NanoVDB, uploaded and
// rendered by two techniques with no NaN and no hang; memory and times are printed
// (on the GPU the NanoVDB bytes, against a dense copy of the same bounds).
TEST(DensityGrid, TenMillionActiveVoxelsRender)
{
  constexpr int n = 216;
  TechniqueFrame probe("caustic-maps", 64, 64);
  double bounds[6];
  probe.Renderer->ComputeVisiblePropBounds(bounds);
  const double size = std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  auto transform = openvdb::math::Transform::createLinearTransform(size / n);
  transform->postTranslate(openvdb::Vec3d(bounds[0], bounds[2], bounds[4]));
  grid->setTransform(transform);
  {
    auto accessor = grid->getAccessor();
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k)
          accessor.setValue(openvdb::Coord(i, j, k),
            static_cast<float>(0.5 + 0.4 * std::sin(0.3 * i) * std::cos(0.2 * j + 0.1 * k)));
  }
  ASSERT_GE(grid->activeVoxelCount(), 10000000u);
  const std::string file = Write("ten-million.vdb", { grid });
  grid.reset();

  vtkNew<vtkCausticsMedium> medium;
  medium->SetScatteringCoefficient(0.02, 0.02, 0.02);
  medium->SetAbsorptionCoefficient(0.01, 0.01, 0.01);
  const auto start = std::chrono::steady_clock::now();
  ASSERT_TRUE(medium->LoadDensity(file.c_str()));
  const double loadSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  auto density = medium->GetDensity();
  ASSERT_TRUE(density);
  EXPECT_GE(density->GetActiveVoxelCount(), 10000000);
  std::cout << "10^7-voxel grid: " << density->GetActiveVoxelCount() << " active voxels, NanoVDB "
            << density->GetNanoVDBBytes() / 1048576.0 << " MiB on the GPU (dense "
            << density->GetDenseBytes() / 1048576.0 << " MiB), load + conversion " << loadSeconds
            << " s\n";

  for (const char* technique : { "caustic-maps", "screen-space" })
  {
    TechniqueFrame frame(technique, 64, 64);
    frame.Pass->KeepBuffersOn();
    vtkCausticsMedium::AttachTo(frame.Renderer, medium);
    frame.Window->Render(); // the upload
    const auto begin = std::chrono::steady_clock::now();
    vtkSmartPointer<vtkImageData> image = frame.Render("FinalColor");
    const double frameSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    ASSERT_TRUE(image) << technique;
    vtkDataArray* colour = image->GetPointData()->GetArray(0);
    double sum = 0.0;
    for (vtkIdType p = 0; p < colour->GetNumberOfTuples(); ++p)
    {
      for (int c = 0; c < 3; ++c)
      {
        const double v = colour->GetComponent(p, c);
        ASSERT_TRUE(std::isfinite(v)) << technique << " pixel " << p;
        sum += v;
      }
    }
    EXPECT_GT(sum, 0.0) << technique << ": not a black image";
    std::cout << technique << " frame with the 10^7-voxel grid at 64^2: " << frameSeconds
              << " s\n";
  }
}
