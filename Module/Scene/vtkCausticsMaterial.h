/**
 * @class   vtkCausticsMaterial
 * @brief   How an actor takes part in caustics: receiver, reflector or refractor.
 *
 * Caustics need more than vtkProperty says, so the extra material parameters
 * ride on VTK information keys:
 * - on the actor's property keys (vtkProp::GetPropertyKeys): ROLE, an explicit
 *   override of the classification;
 * - on the vtkProperty's information: TRANSMISSION (glTF
 *   KHR_materials_transmission), METAL_N / METAL_K (complex IOR of a conductor,
 *   per RGB channel) and ATTENUATION (Beer-Lambert absorption of a dielectric, 1/m).
 *
 * Classification (Describe), in order:
 * 1. ROLE set on the actor: used as is.
 * 2. TRANSMISSION > 0: refractor with IOR vtkProperty::GetBaseIOR().
 * 3. PBR interpolation, Metallic >= 0.5 and Roughness < RoughnessCutoff (0.3 by
 *    default, as 002_97e66a5090de9b07.txt §3.1): reflector. Without METAL_N/K, its
 *    complex IOR is derived from the base colour (the normal-incidence
 *    reflectance F0) with Gulbrandsen's (2014) mapping, edge tint = F0.
 * 4. Opacity < 1 without TRANSMISSION: none (VTK blends it; caustics ignore it).
 * 5. Otherwise: diffuse receiver with albedo = Color * Diffuse.
 */
#ifndef vtkCausticsMaterial_h
#define vtkCausticsMaterial_h

#include "vtkObject.h"
#include "vtkCausticsSceneModule.h" // For export macro

#include "vtkCausticsSceneData.h" // For caustics::Material

#include <string> // For std::string

class vtkActor;
class vtkInformationDoubleKey;
class vtkInformationDoubleVectorKey;
class vtkInformationIntegerKey;
class vtkInformationStringKey;
class vtkProperty;

class VTKCAUSTICSSCENE_EXPORT vtkCausticsMaterial : public vtkObject
{
public:
  static vtkCausticsMaterial* New();
  vtkTypeMacro(vtkCausticsMaterial, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Values of the ROLE key (same numbers as caustics::Role). */
  enum RoleType
  {
    ROLE_NONE = 0,
    ROLE_RECEIVER = 1,
    ROLE_REFLECTOR = 2,
    ROLE_REFRACTOR = 3
  };

  /** Explicit role of an actor, set on vtkProp::GetPropertyKeys(). */
  static vtkInformationIntegerKey* ROLE();
  /** A name for messages and the CLI (e.g. the glTF mesh name), on the actor's property keys. */
  static vtkInformationStringKey* NAME();
  /** glTF KHR_materials_transmission factor in [0, 1], on vtkProperty::GetInformation(). */
  static vtkInformationDoubleKey* TRANSMISSION();
  /** Real part n of a conductor's complex IOR, 3 values (RGB), on the property's information. */
  static vtkInformationDoubleVectorKey* METAL_N();
  /** Imaginary part k of a conductor's complex IOR, 3 values (RGB). */
  static vtkInformationDoubleVectorKey* METAL_K();
  /** Absorption coefficient of a dielectric in 1/m, 3 values (RGB). */
  static vtkInformationDoubleVectorKey* ATTENUATION();

  ///@{
  /** Convenience setters for the keys above. */
  static void SetRole(vtkActor* actor, int role);
  static void ClearRole(vtkActor* actor);
  static void SetName(vtkActor* actor, const std::string& name);
  static std::string GetName(vtkActor* actor);
  static void SetTransmission(vtkProperty* property, double transmission);
  static void SetComplexIOR(vtkProperty* property, const double n[3], const double k[3]);
  static void SetAttenuation(vtkProperty* property, const double perMetre[3]);
  ///@}

  /** Turns a glass-like property into a refractor with the given IOR (transmission 1). */
  static void MakeGlass(vtkProperty* property, double ior);
  /** Turns a property into a polished conductor with the given complex IOR. */
  static void MakeMirror(vtkProperty* property, const double n[3], const double k[3]);

  /**
   * Complex IOR (n, k) whose normal-incidence reflectance is f0 per channel, with edge
   * tint equal to f0 (Gulbrandsen 2014, "Artist Friendly Metallic Fresnel").
   */
  static void ComplexIORFromReflectance(const double f0[3], double n[3], double k[3]);

  /** Role name as used in messages and the CLI ("receiver", ...). */
  static const char* GetRoleName(int role);

  /** Classifies an actor (rules in the class description) and reads its parameters. */
  static int Classify(vtkActor* actor, double roughnessCutoff = 0.3);

#ifndef __VTK_WRAP__
  /** Classification plus every parameter the caustics stages need. */
  static caustics::Material Describe(vtkActor* actor, double roughnessCutoff = 0.3);
#endif

protected:
  vtkCausticsMaterial() = default;
  ~vtkCausticsMaterial() override = default;

private:
  vtkCausticsMaterial(const vtkCausticsMaterial&) = delete;
  void operator=(const vtkCausticsMaterial&) = delete;
};

#endif
