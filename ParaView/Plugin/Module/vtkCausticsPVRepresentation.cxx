#include "vtkCausticsPVRepresentation.h"

#include "vtkCausticsMaterial.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPVLODActor.h"
#include "vtkPVView.h"
#include "vtkProperty.h"

#include <algorithm>

vtkStandardNewMacro(vtkCausticsPVRepresentation);

vtkCausticsPVRepresentation::vtkCausticsPVRepresentation() = default;

vtkCausticsPVRepresentation::~vtkCausticsPVRepresentation() = default;

void vtkCausticsPVRepresentation::SetCausticsRole(int role)
{
  role = std::min(static_cast<int>(REFRACTOR), std::max(static_cast<int>(AUTOMATIC), role));
  if (role != this->CausticsRole)
  {
    this->CausticsRole = role;
    this->ApplyCausticsMaterial();
    this->Modified();
  }
}

void vtkCausticsPVRepresentation::SetCausticsIOR(double ior)
{
  ior = std::min(4.0, std::max(1.0, ior));
  if (ior != this->CausticsIOR)
  {
    this->CausticsIOR = ior;
    this->ApplyCausticsMaterial();
    this->Modified();
  }
}

int vtkCausticsPVRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request_type, vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (request_type == vtkPVView::REQUEST_RENDER())
  {
    this->ApplyCausticsMaterial();
  }
  return this->Superclass::ProcessViewRequest(request_type, inInfo, outInfo);
}

void vtkCausticsPVRepresentation::ApplyCausticsMaterial()
{
  vtkActor* actor = this->GetActor();
  vtkProperty* property = actor ? actor->GetProperty() : nullptr;
  if (!property)
  {
    return;
  }
  // Keys are only touched when they differ: setting them modifies the actor.
  vtkInformation* keys = actor->GetPropertyKeys();
  const bool hasRole = keys && keys->Has(vtkCausticsMaterial::ROLE());
  if (this->CausticsRole == AUTOMATIC)
  {
    if (hasRole)
    {
      vtkCausticsMaterial::ClearRole(actor);
    }
  }
  else if (!hasRole || keys->Get(vtkCausticsMaterial::ROLE()) != this->CausticsRole)
  {
    vtkCausticsMaterial::SetRole(actor, this->CausticsRole);
  }
  if (this->CausticsRole == REFRACTOR)
  {
    if (!this->MadeGlass || property->GetBaseIOR() != this->CausticsIOR)
    {
      vtkCausticsMaterial::MakeGlass(property, this->CausticsIOR);
      this->MadeGlass = true;
    }
  }
  else if (this->MadeGlass)
  {
    property->GetInformation()->Remove(vtkCausticsMaterial::TRANSMISSION());
    this->MadeGlass = false;
  }
}

void vtkCausticsPVRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CausticsRole: " << this->CausticsRole << "\n";
  os << indent << "CausticsIOR: " << this->CausticsIOR << "\n";
}
