#include "vtkCausticsMedium.h"

#include "vtkInformation.h"
#include "vtkInformationObjectBaseKey.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkRenderer.h"

#include <cmath>

vtkStandardNewMacro(vtkCausticsMedium);
vtkInformationKeyMacro(vtkCausticsMedium, MEDIUM, ObjectBase);

void vtkCausticsMedium::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ScatteringCoefficient (1/m): " << this->ScatteringCoefficient[0] << " "
     << this->ScatteringCoefficient[1] << " " << this->ScatteringCoefficient[2] << "\n";
  os << indent << "AbsorptionCoefficient (1/m): " << this->AbsorptionCoefficient[0] << " "
     << this->AbsorptionCoefficient[1] << " " << this->AbsorptionCoefficient[2] << "\n";
  os << indent << "Anisotropy: " << this->Anisotropy << "\n";
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
  if (!ValidCoefficients(r, g, b))
  {
    vtkErrorMacro(<< "scattering coefficient (" << r << ", " << g << ", " << b
                  << ") must be finite and >= 0 (1/m); keeping the previous value");
    return;
  }
  if (r != this->ScatteringCoefficient[0] || g != this->ScatteringCoefficient[1] ||
    b != this->ScatteringCoefficient[2])
  {
    this->ScatteringCoefficient[0] = r;
    this->ScatteringCoefficient[1] = g;
    this->ScatteringCoefficient[2] = b;
    this->Modified();
  }
}

void vtkCausticsMedium::SetAbsorptionCoefficient(double r, double g, double b)
{
  if (!ValidCoefficients(r, g, b))
  {
    vtkErrorMacro(<< "absorption coefficient (" << r << ", " << g << ", " << b
                  << ") must be finite and >= 0 (1/m); keeping the previous value");
    return;
  }
  if (r != this->AbsorptionCoefficient[0] || g != this->AbsorptionCoefficient[1] ||
    b != this->AbsorptionCoefficient[2])
  {
    this->AbsorptionCoefficient[0] = r;
    this->AbsorptionCoefficient[1] = g;
    this->AbsorptionCoefficient[2] = b;
    this->Modified();
  }
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
