#include "vtkCausticsMedium.h"

#include "vtkCausticsDensityGrid.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationObjectBaseKey.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkCausticsMedium);
vtkInformationKeyMacro(vtkCausticsMedium, MEDIUM, ObjectBase);

vtkCausticsMedium::vtkCausticsMedium() = default;

vtkCausticsMedium::~vtkCausticsMedium()
{
  this->SetDensityMatrix(nullptr);
}

void vtkCausticsMedium::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ScatteringCoefficient (1/m): " << this->ScatteringCoefficient[0] << " "
     << this->ScatteringCoefficient[1] << " " << this->ScatteringCoefficient[2] << "\n";
  os << indent << "AbsorptionCoefficient (1/m): " << this->AbsorptionCoefficient[0] << " "
     << this->AbsorptionCoefficient[1] << " " << this->AbsorptionCoefficient[2] << "\n";
  os << indent << "Anisotropy: " << this->Anisotropy << "\n";
  os << indent << "FillsRefractors: " << this->FillsRefractors << "\n";
  os << indent << "Density: ";
  if (this->LoadedDensity)
  {
    const caustics::DensityGrid& grid = *this->LoadedDensity;
    os << "grid '" << grid.GetGridName() << "' of " << grid.GetFileName() << " ("
       << grid.GetActiveVoxelCount() << " active voxels, mean " << grid.GetMeanDensity() << ", max "
       << grid.GetMajorant() << ", NanoVDB " << grid.GetNanoVDBBytes() << " bytes, dense "
       << grid.GetDenseBytes() << " bytes)\n";
  }
  else
  {
    os << "none (homogeneous, density 1)\n";
  }
  os << indent << "DensityScale: " << this->DensityScale << "\n";
  os << indent << "DensityMatrix: " << this->DensityMatrix << "\n";
  if (this->DensityMatrix)
  {
    this->DensityMatrix->PrintSelf(os, indent.GetNextIndent());
  }
}

namespace
{
bool ValidCoefficients(double r, double g, double b)
{
  for (double v : { r, g, b })
  {
    if (!std::isfinite(v) || v < 0.0)
    {
      return false;
    }
  }
  return true;
}
}

void vtkCausticsMedium::SetScatteringCoefficient(double r, double g, double b)
{
  this->SetCoefficient("scattering", this->ScatteringCoefficient, r, g, b);
}

void vtkCausticsMedium::SetAbsorptionCoefficient(double r, double g, double b)
{
  this->SetCoefficient("absorption", this->AbsorptionCoefficient, r, g, b);
}

void vtkCausticsMedium::SetCoefficient(
  const char* what, double (&coefficient)[3], double r, double g, double b)
{
  if (!ValidCoefficients(r, g, b))
  {
    vtkErrorMacro(<< what << " coefficient (" << r << ", " << g << ", " << b
                  << ") must be finite and >= 0 (1/m); keeping the previous value");
    return;
  }
  if (r != coefficient[0] || g != coefficient[1] || b != coefficient[2])
  {
    coefficient[0] = r;
    coefficient[1] = g;
    coefficient[2] = b;
    this->Modified();
  }
}

bool vtkCausticsMedium::LoadDensity(const char* vdbFile, const char* gridName)
{
  std::string warning;
  this->LastError.clear();
  auto grid = vdbFile && *vdbFile && gridName && *gridName
    ? caustics::DensityGrid::Load(vdbFile, gridName, this->LastError, warning)
    : nullptr;
  if (!grid)
  {
    if (this->LastError.empty())
    {
      this->LastError = "LoadDensity needs a VDB file name and a grid name";
    }
    vtkErrorMacro(<< this->LastError << "; keeping the previous density");
    return false;
  }
  if (!warning.empty())
  {
    vtkWarningMacro(<< warning);
  }
  this->LoadedDensity = grid;
  this->PlacedDensity.reset();
  this->Modified();
  return true;
}

bool vtkCausticsMedium::SetDensityData(vtkImageData* image, const char* arrayName)
{
  this->LastError.clear();
  vtkDataArray* array = nullptr;
  if (!image)
  {
    this->LastError = "SetDensityData needs an image";
  }
  else
  {
    array = arrayName && *arrayName ? image->GetPointData()->GetArray(arrayName)
                                    : image->GetPointData()->GetScalars();
    if (!array)
    {
      this->LastError = arrayName && *arrayName
        ? "SetDensityData: the image has no numeric point array '" + std::string(arrayName) + "'"
        : std::string("SetDensityData: the image has no point scalars");
    }
    else if (array->GetNumberOfTuples() != image->GetNumberOfPoints())
    {
      this->LastError = "SetDensityData: the array has " +
        std::to_string(array->GetNumberOfTuples()) + " values for " +
        std::to_string(image->GetNumberOfPoints()) + " points";
    }
  }
  std::shared_ptr<const caustics::DensityGrid> grid;
  std::string warning;
  if (this->LastError.empty())
  {
    int dimensions[3];
    image->GetDimensions(dimensions);
    double volume = 1.0;
    for (int d : dimensions)
    {
      volume *= std::max(d, 0);
    }
    if (volume > caustics::DensityGrid::MaximumDenseVoxels)
    {
      this->LastError = "SetDensityData: the image has more than 2^28 points";
    }
    else
    {
      const vtkIdType count = array->GetNumberOfTuples();
      std::vector<float> values(static_cast<std::size_t>(count));
      for (vtkIdType i = 0; i < count; ++i)
      {
        values[static_cast<std::size_t>(i)] = static_cast<float>(array->GetComponent(i, 0));
      }
      // Array index (i, j, k) to world, as vtkImageData places points (origin, spacing,
      // direction; the extent may start anywhere): read off the images of the first
      // point and its three neighbours.
      int extent[6];
      image->GetExtent(extent);
      double first[3], indexToWorld[16] = { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1 };
      image->TransformIndexToPhysicalPoint(extent[0], extent[2], extent[4], first);
      for (int axis = 0; axis < 3; ++axis)
      {
        int next[3] = { extent[0], extent[2], extent[4] };
        ++next[axis];
        double point[3];
        image->TransformIndexToPhysicalPoint(next, point);
        for (int r = 0; r < 3; ++r)
        {
          indexToWorld[4 * r + axis] = point[r] - first[r];
        }
      }
      for (int r = 0; r < 3; ++r)
      {
        indexToWorld[4 * r + 3] = first[r];
      }
      const std::string name =
        std::string("vtkImageData:") + (array->GetName() ? array->GetName() : "scalars");
      grid = caustics::DensityGrid::FromDense(
        values.data(), dimensions, indexToWorld, name, this->LastError, warning);
    }
  }
  if (!grid)
  {
    vtkErrorMacro(<< this->LastError << "; keeping the previous density");
    return false;
  }
  if (!warning.empty())
  {
    vtkWarningMacro(<< warning);
  }
  this->LoadedDensity = grid;
  this->PlacedDensity.reset();
  this->Modified();
  return true;
}

void vtkCausticsMedium::RemoveDensity()
{
  if (this->LoadedDensity)
  {
    this->LoadedDensity.reset();
    this->PlacedDensity.reset();
    this->Modified();
  }
}

bool vtkCausticsMedium::HasDensity() const
{
  return this->LoadedDensity != nullptr;
}

const char* vtkCausticsMedium::GetDensityFileName() const
{
  return this->LoadedDensity ? this->LoadedDensity->GetFileName().c_str() : "";
}

const char* vtkCausticsMedium::GetDensityGridName() const
{
  return this->LoadedDensity ? this->LoadedDensity->GetGridName().c_str() : "";
}

void vtkCausticsMedium::SetDensityScale(double scale)
{
  if (!std::isfinite(scale) || scale < 0.0 || scale > caustics::DensityGrid::MaximumScale)
  {
    vtkErrorMacro(<< "density scale " << scale << " must be finite, >= 0 and <= "
                  << caustics::DensityGrid::MaximumScale << "; keeping the previous value");
    return;
  }
  if (scale != this->DensityScale)
  {
    this->DensityScale = scale;
    this->Modified();
  }
}

void vtkCausticsMedium::SetDensityMatrix(vtkMatrix4x4* matrix)
{
  if (matrix == this->DensityMatrix)
  {
    return;
  }
  if (matrix)
  {
    matrix->Register(this);
  }
  if (this->DensityMatrix)
  {
    this->DensityMatrix->UnRegister(this);
  }
  this->DensityMatrix = matrix;
  this->Modified();
}

vtkMTimeType vtkCausticsMedium::GetMTime()
{
  vtkMTimeType time = this->Superclass::GetMTime();
  return this->DensityMatrix ? std::max(time, this->DensityMatrix->GetMTime()) : time;
}

std::shared_ptr<const caustics::DensityGrid> vtkCausticsMedium::GetDensity()
{
  if (!this->LoadedDensity)
  {
    return nullptr;
  }
  // Placing is cheap (the voxels are shared) but snapshots compare grids by pointer:
  // the same placement keeps the same object.
  const vtkMTimeType time = this->GetMTime();
  if (!this->PlacedDensity || time != this->PlacedTime)
  {
    const double* m = this->DensityMatrix ? this->DensityMatrix->GetData() : nullptr;
    const bool invertible = !m ||
      (m[12] == 0.0 && m[13] == 0.0 && m[14] == 0.0 && m[15] == 1.0 &&
        std::isfinite(this->DensityMatrix->Determinant()) &&
        this->DensityMatrix->Determinant() != 0.0);
    if (!invertible)
    {
      vtkWarningMacro(<< "the density matrix is not an invertible affine transform; the grid is "
                         "placed without it");
    }
    this->PlacedDensity = this->LoadedDensity->Placed(
      invertible && this->DensityMatrix ? this->DensityMatrix->GetData() : nullptr,
      this->DensityScale);
    this->PlacedTime = time;
  }
  return this->PlacedDensity;
}

bool vtkCausticsMedium::IsScattering() const
{
  for (double s : this->ScatteringCoefficient)
  {
    if (s > 0.0 && std::isfinite(s))
    {
      return true;
    }
  }
  return false;
}

bool vtkCausticsMedium::IsAttenuating() const
{
  for (int c = 0; c < 3; ++c)
  {
    const double extinction = this->ScatteringCoefficient[c] + this->AbsorptionCoefficient[c];
    if (extinction > 0.0 && std::isfinite(extinction))
    {
      return true;
    }
  }
  return false;
}

void vtkCausticsMedium::AttachTo(vtkRenderer* renderer, vtkCausticsMedium* medium)
{
  if (!renderer)
  {
    return;
  }
  if (!renderer->GetInformation())
  {
    vtkNew<vtkInformation> info;
    renderer->SetInformation(info);
  }
  if (medium)
  {
    renderer->GetInformation()->Set(MEDIUM(), medium);
  }
  else
  {
    renderer->GetInformation()->Remove(MEDIUM());
  }
  renderer->Modified();
}

vtkCausticsMedium* vtkCausticsMedium::GetFrom(vtkRenderer* renderer)
{
  if (!renderer || !renderer->GetInformation())
  {
    return nullptr;
  }
  return vtkCausticsMedium::SafeDownCast(renderer->GetInformation()->Get(MEDIUM()));
}
