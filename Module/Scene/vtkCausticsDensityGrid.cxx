#include "vtkCausticsDensityGrid.h"

#include <nanovdb/util/OpenToNanoVDB.h> // For nanovdb::openToNanoVDB
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h> // For openvdb::tools::BoxSampler

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <fstream>
#include <limits>
#include <mutex>
#include <sstream>

namespace caustics
{
namespace
{
void Identity(double m[16])
{
  for (int i = 0; i < 16; ++i)
  {
    m[i] = i % 5 == 0 ? 1.0 : 0.0;
  }
}

/** Row-major 4x4 times a point (w = 1, affine). */
openvdb::Vec3d Transform(const double m[16], const openvdb::Vec3d& p)
{
  openvdb::Vec3d out;
  for (int r = 0; r < 3; ++r)
  {
    out[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
  }
  return out;
}

/** Inverse of a row-major affine 4x4 (last row 0 0 0 1); false when singular. */
bool InvertAffine(const double m[16], double inverse[16])
{
  const double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9],
               k = m[10];
  const double det = a * (e * k - f * h) - b * (d * k - f * g) + c * (d * h - e * g);
  if (!(std::abs(det) > 0.0) || !std::isfinite(det))
  {
    return false;
  }
  const double r[9] = { (e * k - f * h) / det, (c * h - b * k) / det, (b * f - c * e) / det,
    (f * g - d * k) / det, (a * k - c * g) / det, (c * d - a * f) / det, (d * h - e * g) / det,
    (b * g - a * h) / det, (a * e - b * d) / det };
  for (int row = 0; row < 3; ++row)
  {
    inverse[4 * row] = r[3 * row];
    inverse[4 * row + 1] = r[3 * row + 1];
    inverse[4 * row + 2] = r[3 * row + 2];
    inverse[4 * row + 3] = -(r[3 * row] * m[3] + r[3 * row + 1] * m[7] + r[3 * row + 2] * m[11]);
  }
  inverse[12] = inverse[13] = inverse[14] = 0.0;
  inverse[15] = 1.0;
  return true;
}

std::uint64_t Mix(std::uint64_t hash, std::uint64_t value)
{
  // SplitMix64's finalizer over the running hash: order-dependent, well spread.
  std::uint64_t z = hash ^ (value + 0x9e3779b97f4a7c15ULL + (hash << 6) + (hash >> 2));
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t Bits(double value)
{
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

std::string ListGrids(openvdb::io::File& file)
{
  std::string names;
  for (auto name = file.beginName(); name != file.endName(); ++name)
  {
    names += (names.empty() ? "'" : ", '") + name.gridName() + "'";
  }
  return names.empty() ? "none" : names;
}
}

struct DensityGrid::Voxels
{
  openvdb::FloatGrid::Ptr Grid;
  nanovdb::GridHandle<nanovdb::HostBuffer> Nano;
  std::string FileName, GridName;
  openvdb::CoordBBox ActiveBox;
  double Maximum = 0.0, Mean = 0.0;
  double MinimumActive = 0.0; ///< smallest active value
  bool Dense = false;         ///< every voxel of ActiveBox is active
  std::int64_t ActiveVoxels = 0;
  std::uint64_t Hash = 0;
};

DensityGrid::DensityGrid()
{
  Identity(this->Matrix);
  Identity(this->InverseMatrix);
}

DensityGrid::~DensityGrid() = default;

std::shared_ptr<const DensityGrid> DensityGrid::Load(const std::string& fileName,
  const std::string& gridName, std::string& error, std::string& warning)
{
  static std::once_flag initialized;
  std::call_once(initialized, []() { openvdb::initialize(); });
  error.clear();
  warning.clear();
  const std::string where = "VDB file '" + fileName + "'";
  if (!std::ifstream(fileName, std::ios::binary).good())
  {
    error = "cannot open " + where + ": no such file or not readable";
    return nullptr;
  }
  openvdb::GridBase::Ptr base;
  try
  {
    openvdb::io::File file(fileName);
    file.open(false); // no delayed loading: the whole grid is read (and checked) now
    if (!file.hasGrid(gridName))
    {
      error = where + " has no grid named '" + gridName + "' (its grids: " + ListGrids(file) + ")";
      return nullptr;
    }
    base = file.readGrid(gridName);
    file.close();
  }
  catch (const openvdb::Exception& e)
  {
    error = "cannot read " + where + " (not a VDB file, or truncated): " + e.what();
    return nullptr;
  }
  catch (const std::exception& e)
  {
    error = "cannot read " + where + " (not a VDB file, or truncated): " + e.what();
    return nullptr;
  }
  const std::string named = "grid '" + gridName + "' of " + where;
  if (!base || !base->isType<openvdb::FloatGrid>())
  {
    error = named + " holds " + (base ? base->valueType() : std::string("nothing")) +
      " values; a density needs a float scalar grid";
    return nullptr;
  }
  if (base->getGridClass() == openvdb::GRID_LEVEL_SET)
  {
    error = named +
      " is a level set (signed distance), not a density: convert it to a fog "
      "volume first (openvdb::tools::sdfToFogVolume)";
    return nullptr;
  }
  return FromGrid(openvdb::gridPtrCast<openvdb::FloatGrid>(base), fileName, gridName, named,
    error, warning);
}

std::shared_ptr<const DensityGrid> DensityGrid::FromGrid(std::shared_ptr<void> gridPointer,
  const std::string& fileName, const std::string& gridName, const std::string& named,
  std::string& error, std::string& warning)
{
  auto floatGrid = std::static_pointer_cast<openvdb::FloatGrid>(gridPointer);
  auto voxels = std::make_shared<Voxels>();
  voxels->Grid = floatGrid;
  voxels->FileName = fileName;
  voxels->GridName = gridName;
  openvdb::FloatGrid& grid = *voxels->Grid;
  if (grid.activeVoxelCount() == 0)
  {
    error = named + " is empty (no active voxel)";
    return nullptr;
  }

  // A density is >= 0: negative and NaN values (and background) become 0.
  std::int64_t clamped = 0;
  const float background = grid.background();
  if (!(background >= 0.0f) || !std::isfinite(background))
  {
    grid.tree().root().setBackground(0.0f, true);
    ++clamped;
  }
  double sum = 0.0, maximum = std::max(0.0, static_cast<double>(grid.background()));
  double minimum = std::numeric_limits<double>::infinity();
  std::uint64_t hash = 0;
  for (auto value = grid.beginValueOn(); value; ++value)
  {
    float v = *value;
    if (!(v >= 0.0f) || !std::isfinite(v))
    {
      value.setValue(0.0f);
      clamped += static_cast<std::int64_t>(value.getVoxelCount());
      v = 0.0f;
    }
    sum += static_cast<double>(v) * static_cast<double>(value.getVoxelCount());
    maximum = std::max(maximum, static_cast<double>(v));
    minimum = std::min(minimum, static_cast<double>(v));
    const openvdb::Coord c = value.getCoord();
    hash =
      Mix(Mix(Mix(Mix(hash, static_cast<std::uint32_t>(c.x())), static_cast<std::uint32_t>(c.y())),
            static_cast<std::uint32_t>(c.z())),
        Bits(v));
  }
  for (const openvdb::Vec3d& corner : { openvdb::Vec3d(0, 0, 0), openvdb::Vec3d(1, 0, 0),
         openvdb::Vec3d(0, 1, 0), openvdb::Vec3d(0, 0, 1) })
  {
    const openvdb::Vec3d world = grid.indexToWorld(corner);
    hash = Mix(Mix(Mix(hash, Bits(world[0])), Bits(world[1])), Bits(world[2]));
  }
  if (clamped > 0)
  {
    std::ostringstream text;
    text << named << ": " << clamped << " negative or NaN density values set to 0";
    warning = text.str();
  }
  voxels->ActiveVoxels = static_cast<std::int64_t>(grid.activeVoxelCount());
  voxels->ActiveBox = grid.evalActiveVoxelBoundingBox();
  voxels->Maximum = maximum;
  voxels->MinimumActive = minimum;
  voxels->Dense = grid.transform().isLinear() &&
    static_cast<openvdb::Index64>(voxels->ActiveVoxels) == voxels->ActiveBox.volume();
  voxels->Mean = sum / static_cast<double>(voxels->ActiveVoxels);
  voxels->Hash = hash;
  try
  {
    voxels->Nano = nanovdb::openToNanoVDB(grid);
  }
  catch (const std::exception& e)
  {
    error = "cannot convert " + named + " to NanoVDB: " + e.what();
    return nullptr;
  }
  std::shared_ptr<DensityGrid> result(new DensityGrid);
  result->Shared = voxels;
  return result;
}

std::shared_ptr<const DensityGrid> DensityGrid::FromDense(const float* values, const int dimensions[3],
  const double indexToWorld[16], const std::string& name, std::string& error, std::string& warning)
{
  static std::once_flag initialized;
  std::call_once(initialized, []() { openvdb::initialize(); });
  error.clear();
  warning.clear();
  const std::string named = "density '" + name + "'";
  if (!values || !dimensions)
  {
    error = named + " has no values";
    return nullptr;
  }
  double voxels = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    if (dimensions[a] < 1)
    {
      error = named + " has a dimension < 1";
      return nullptr;
    }
    voxels *= dimensions[a];
  }
  if (voxels > MaximumDenseVoxels)
  {
    std::ostringstream text;
    text << named << " has " << voxels << " voxels, more than the " << MaximumDenseVoxels
         << " a dense density may have (write a sparse .vdb instead)";
    error = text.str();
    return nullptr;
  }
  // OpenVDB maps row vectors (p' = p M): the transpose of the column-vector matrix given.
  openvdb::math::Mat4d map;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      map(c, r) = indexToWorld ? indexToWorld[4 * r + c] : (r == c ? 1.0 : 0.0);
      if (!std::isfinite(map(c, r)))
      {
        error = named + " has a non-finite index-to-world transform";
        return nullptr;
      }
    }
  }
  const double determinant = map.getMat3().det();
  if (!(std::abs(determinant) > 1e-300) || map(0, 3) != 0.0 || map(1, 3) != 0.0 ||
    map(2, 3) != 0.0 || map(3, 3) != 1.0)
  {
    error = named + " has an index-to-world transform that is not affine and invertible";
    return nullptr;
  }
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(map));
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->setName(name);
  // Zero voxels stay inactive: what a fog volume's sparse tree leaves out. NaN and
  // negative values are kept active here so that FromGrid() counts and clears them.
  auto accessor = grid->getAccessor();
  const std::size_t nx = static_cast<std::size_t>(dimensions[0]);
  const std::size_t ny = static_cast<std::size_t>(dimensions[1]);
  for (int k = 0; k < dimensions[2]; ++k)
  {
    for (int j = 0; j < dimensions[1]; ++j)
    {
      const float* row = values + (static_cast<std::size_t>(k) * ny + j) * nx;
      for (int i = 0; i < dimensions[0]; ++i)
      {
        if (row[i] != 0.0f)
        {
          accessor.setValue(openvdb::Coord(i, j, k), row[i]);
        }
      }
    }
  }
  return FromGrid(grid, "", name, named, error, warning);
}

std::shared_ptr<const DensityGrid> DensityGrid::Placed(const double matrix[16], double scale) const
{
  std::shared_ptr<DensityGrid> placed(new DensityGrid(*this));
  placed->Scale = scale;
  if (matrix && InvertAffine(matrix, placed->InverseMatrix))
  {
    std::copy(matrix, matrix + 16, placed->Matrix);
  }
  else
  {
    Identity(placed->Matrix);
    Identity(placed->InverseMatrix);
  }
  return placed;
}

double DensityGrid::Sample(const Vec3& world) const
{
  const openvdb::FloatGrid& grid = *this->Shared->Grid;
  const openvdb::Vec3d index =
    grid.worldToIndex(Transform(this->InverseMatrix, openvdb::Vec3d(world[0], world[1], world[2])));
  // An unregistered accessor: cheap to make, safe to use from many threads at once.
  openvdb::tree::ValueAccessor<const openvdb::FloatTree, false> accessor(grid.tree());
  return this->Scale * openvdb::tools::BoxSampler::sample(accessor, index);
}

void DensityGrid::GetWorldBounds(double bounds[6]) const
{
  const openvdb::CoordBBox& box = this->Shared->ActiveBox;
  // Trilinear samples reach one voxel beyond the outermost active voxel centres.
  const openvdb::Vec3d lo = box.min().asVec3d() - openvdb::Vec3d(1.0);
  const openvdb::Vec3d hi = box.max().asVec3d() + openvdb::Vec3d(1.0);
  const double inf = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = inf;
    bounds[2 * a + 1] = -inf;
  }
  for (int corner = 0; corner < 8; ++corner)
  {
    const openvdb::Vec3d index(
      corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1], corner & 4 ? hi[2] : lo[2]);
    const openvdb::Vec3d world = Transform(this->Matrix, this->Shared->Grid->indexToWorld(index));
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = std::min(bounds[2 * a], world[a]);
      bounds[2 * a + 1] = std::max(bounds[2 * a + 1], world[a]);
    }
  }
}

double DensityGrid::GetMajorant() const
{
  return this->Shared->Maximum * this->Scale;
}

double DensityGrid::GetMinimum(const double worldBox[6]) const
{
  const Voxels& voxels = *this->Shared;
  if (!voxels.Dense)
  {
    return 0.0;
  }
  // Inside the centres' box, trilinear samples mix active values only. The box maps
  // to a parallelepiped in index space (linear transforms): inside iff its corners are.
  const openvdb::Vec3d lo = voxels.ActiveBox.min().asVec3d(), hi = voxels.ActiveBox.max().asVec3d();
  for (int corner = 0; corner < 8; ++corner)
  {
    const openvdb::Vec3d world(
      worldBox[corner & 1 ? 1 : 0], worldBox[corner & 2 ? 3 : 2], worldBox[corner & 4 ? 5 : 4]);
    const openvdb::Vec3d index = voxels.Grid->worldToIndex(Transform(this->InverseMatrix, world));
    for (int a = 0; a < 3; ++a)
    {
      if (!(index[a] >= lo[a] && index[a] <= hi[a]))
      {
        return 0.0;
      }
    }
  }
  return voxels.MinimumActive * this->Scale;
}

double DensityGrid::GetMeanDensity() const
{
  return this->Shared->Mean * this->Scale;
}

double DensityGrid::GetScale() const
{
  return this->Scale;
}

const double* DensityGrid::GetMatrix() const
{
  return this->Matrix;
}

std::uint64_t DensityGrid::GetContentHash() const
{
  return this->Shared->Hash;
}

std::size_t DensityGrid::GetNanoVDBBytes() const
{
  return static_cast<std::size_t>(this->Shared->Nano.size());
}

std::size_t DensityGrid::GetDenseBytes() const
{
  return static_cast<std::size_t>(this->Shared->ActiveBox.volume()) * sizeof(float);
}

const void* DensityGrid::GetNanoVDBData() const
{
  return this->Shared->Nano.data();
}

void DensityGrid::GetWorldToIndex(double matrix[16]) const
{
  // Both maps are affine: read the composition off the images of the origin and axes.
  const openvdb::FloatGrid& grid = *this->Shared->Grid;
  auto toIndex = [&](const openvdb::Vec3d& world)
  { return grid.worldToIndex(Transform(this->InverseMatrix, world)); };
  const openvdb::Vec3d origin = toIndex(openvdb::Vec3d(0.0));
  Identity(matrix);
  for (int c = 0; c < 3; ++c)
  {
    openvdb::Vec3d axis(0.0);
    axis[c] = 1.0;
    const openvdb::Vec3d column = toIndex(axis) - origin;
    for (int r = 0; r < 3; ++r)
    {
      matrix[4 * r + c] = column[r];
    }
  }
  for (int r = 0; r < 3; ++r)
  {
    matrix[4 * r + 3] = origin[r];
  }
}

std::int64_t DensityGrid::GetActiveVoxelCount() const
{
  return this->Shared->ActiveVoxels;
}

const std::string& DensityGrid::GetFileName() const
{
  return this->Shared->FileName;
}

const std::string& DensityGrid::GetGridName() const
{
  return this->Shared->GridName;
}
}
