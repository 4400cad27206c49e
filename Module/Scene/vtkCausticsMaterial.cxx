#include "vtkCausticsMaterial.h"

#include "vtkActor.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleKey.h"
#include "vtkInformationDoubleVectorKey.h"
#include "vtkInformationIntegerKey.h"
#include "vtkInformationStringKey.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkProperty.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkCausticsMaterial);

vtkInformationKeyMacro(vtkCausticsMaterial, ROLE, Integer);
vtkInformationKeyMacro(vtkCausticsMaterial, NAME, String);
vtkInformationKeyMacro(vtkCausticsMaterial, TRANSMISSION, Double);
vtkInformationKeyRestrictedMacro(vtkCausticsMaterial, METAL_N, DoubleVector, 3);
vtkInformationKeyRestrictedMacro(vtkCausticsMaterial, METAL_K, DoubleVector, 3);
vtkInformationKeyRestrictedMacro(vtkCausticsMaterial, ATTENUATION, DoubleVector, 3);

void vtkCausticsMaterial::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Keys: ROLE (actor), TRANSMISSION, METAL_N, METAL_K, ATTENUATION (property)\n";
}

namespace
{
vtkInformation* PropertyInformation(vtkProperty* property)
{
  if (!property->GetInformation())
  {
    vtkNew<vtkInformation> info;
    property->SetInformation(info);
  }
  return property->GetInformation();
}
}

namespace
{
vtkInformation* ActorKeys(vtkActor* actor)
{
  if (!actor->GetPropertyKeys())
  {
    vtkNew<vtkInformation> keys;
    actor->SetPropertyKeys(keys);
  }
  return actor->GetPropertyKeys();
}
}

void vtkCausticsMaterial::SetRole(vtkActor* actor, int role)
{
  if (!actor)
  {
    return;
  }
  if (role < ROLE_NONE || role > ROLE_REFRACTOR)
  {
    vtkGenericWarningMacro(<< "vtkCausticsMaterial::SetRole: role " << role
                           << " is not one of 0 (none), 1 (receiver), 2 (reflector), 3 "
                              "(refractor); ignored");
    return;
  }
  ActorKeys(actor)->Set(ROLE(), role);
  actor->Modified();
}

void vtkCausticsMaterial::SetName(vtkActor* actor, const std::string& name)
{
  if (actor)
  {
    ActorKeys(actor)->Set(NAME(), name.c_str());
  }
}

std::string vtkCausticsMaterial::GetName(vtkActor* actor)
{
  if (actor && actor->GetPropertyKeys() && actor->GetPropertyKeys()->Has(NAME()))
  {
    return actor->GetPropertyKeys()->Get(NAME());
  }
  return std::string();
}

void vtkCausticsMaterial::ClearRole(vtkActor* actor)
{
  if (actor && actor->GetPropertyKeys())
  {
    actor->GetPropertyKeys()->Remove(ROLE());
    actor->Modified();
  }
}

void vtkCausticsMaterial::SetTransmission(vtkProperty* property, double transmission)
{
  PropertyInformation(property)->Set(TRANSMISSION(), std::min(1.0, std::max(0.0, transmission)));
  property->Modified();
}

void vtkCausticsMaterial::SetComplexIOR(vtkProperty* property, const double n[3], const double k[3])
{
  PropertyInformation(property)->Set(METAL_N(), n, 3);
  PropertyInformation(property)->Set(METAL_K(), k, 3);
  property->Modified();
}

void vtkCausticsMaterial::SetAttenuation(vtkProperty* property, const double perMetre[3])
{
  PropertyInformation(property)->Set(ATTENUATION(), perMetre, 3);
  property->Modified();
}

void vtkCausticsMaterial::MakeGlass(vtkProperty* property, double ior)
{
  property->SetInterpolationToPBR();
  property->SetBaseIOR(ior);
  property->SetMetallic(0.0);
  property->SetRoughness(0.0);
  vtkCausticsMaterial::SetTransmission(property, 1.0);
}

void vtkCausticsMaterial::MakeMirror(vtkProperty* property, const double n[3], const double k[3])
{
  property->SetInterpolationToPBR();
  property->SetMetallic(1.0);
  property->SetRoughness(0.0);
  vtkCausticsMaterial::SetComplexIOR(property, n, k);
}

void vtkCausticsMaterial::ComplexIORFromReflectance(const double f0[3], double n[3], double k[3])
{
  for (int c = 0; c < 3; ++c)
  {
    const double r = std::min(0.99, std::max(0.0, f0[c]));
    const double g = r; // edge tint
    const double sqrtR = std::sqrt(r);
    const double nMin = (1.0 - r) / (1.0 + r);
    const double nMax = (1.0 + sqrtR) / (1.0 - sqrtR);
    n[c] = g * nMin + (1.0 - g) * nMax;
    const double k2 = (r * (n[c] + 1.0) * (n[c] + 1.0) - (n[c] - 1.0) * (n[c] - 1.0)) / (1.0 - r);
    k[c] = std::sqrt(std::max(0.0, k2));
  }
}

const char* vtkCausticsMaterial::GetRoleName(int role)
{
  return caustics::RoleName(static_cast<caustics::Role>(role));
}

namespace
{
/**
 * What the actor does to light, from its keys and property alone: the part of
 * Describe() that Classify() needs (the render pass asks it for every actor
 * before each frame, so it reads no more than it must).
 */
caustics::Role RoleOf(vtkActor* actor, vtkProperty* property, double roughnessCutoff)
{
  vtkInformation* keys = actor->GetPropertyKeys();
  if (keys && keys->Has(vtkCausticsMaterial::ROLE()))
  {
    const int role = keys->Get(vtkCausticsMaterial::ROLE());
    return (role >= vtkCausticsMaterial::ROLE_NONE && role <= vtkCausticsMaterial::ROLE_REFRACTOR)
      ? static_cast<caustics::Role>(role)
      : caustics::Role::Receiver;
  }
  vtkInformation* info = property->GetInformation();
  const double transmission = info && info->Has(vtkCausticsMaterial::TRANSMISSION())
    ? info->Get(vtkCausticsMaterial::TRANSMISSION())
    : 0.0;
  if (transmission > 0.0)
  {
    return caustics::Role::Refractor;
  }
  if (property->GetInterpolation() == VTK_PBR && property->GetMetallic() >= 0.5 &&
    property->GetRoughness() < roughnessCutoff)
  {
    return caustics::Role::Reflector;
  }
  return property->GetOpacity() < 1.0 ? caustics::Role::None : caustics::Role::Receiver;
}
}

int vtkCausticsMaterial::Classify(vtkActor* actor, double roughnessCutoff)
{
  vtkProperty* property = actor ? actor->GetProperty() : nullptr;
  return static_cast<int>(property ? RoleOf(actor, property, roughnessCutoff) : caustics::Role::None);
}

caustics::Material vtkCausticsMaterial::Describe(vtkActor* actor, double roughnessCutoff)
{
  caustics::Material material;
  vtkProperty* property = actor ? actor->GetProperty() : nullptr;
  if (!property)
  {
    material.role = caustics::Role::None;
    return material;
  }
  vtkInformation* info = property->GetInformation();
  const double* color = property->GetColor();
  for (int c = 0; c < 3; ++c)
  {
    material.albedo[c] = std::min(1.0, std::max(0.0, color[c] * property->GetDiffuse()));
  }
  material.ior = property->GetBaseIOR();
  material.roughness = property->GetRoughness();
  if (info && info->Has(ATTENUATION()))
  {
    const double* a = info->Get(ATTENUATION());
    material.attenuation = { { std::max(0.0, a[0]), std::max(0.0, a[1]), std::max(0.0, a[2]) } };
  }
  const bool isPBR = property->GetInterpolation() == VTK_PBR;

  // Conductor parameters: explicit (n, k), else from the base colour.
  if (info && info->Has(METAL_N()) && info->Has(METAL_K()))
  {
    const double* n = info->Get(METAL_N());
    const double* k = info->Get(METAL_K());
    material.metalN = { { n[0], n[1], n[2] } };
    material.metalK = { { k[0], k[1], k[2] } };
  }
  else if (isPBR)
  {
    double n[3], k[3];
    vtkCausticsMaterial::ComplexIORFromReflectance(color, n, k);
    material.metalN = { { n[0], n[1], n[2] } };
    material.metalK = { { k[0], k[1], k[2] } };
  }

  material.role = RoleOf(actor, property, roughnessCutoff);
  return material;
}
