/**
 * @class   vtkCausticsPVRepresentation
 * @brief   ParaView's surface representation whose actor has a caustics role.
 *
 * The "Caustics Surface" representation type of the plugin: a surface
 * (vtkGeometryRepresentationWithFaces, every Surface property shared) whose actor
 * carries the vtkCausticsMaterial keys the caustics passes read:
 * 1. CausticsRole: AUTOMATIC (the rules of vtkCausticsMaterial: an opaque
 *    diffuse surface is a receiver), NONE, RECEIVER, REFLECTOR or REFRACTOR;
 * 2. a refractor is made glass (vtkCausticsMaterial::MakeGlass) with CausticsIOR;
 *    leaving REFRACTOR removes the transmission this class set;
 * 3. the keys are set again before each render if ParaView changed the
 *    property's IOR (its own "BaseIOR" property).
 * The keys live on the actor of the process that renders it, so the role holds
 * on every rank that has a piece of the data.
 */
#ifndef vtkCausticsPVRepresentation_h
#define vtkCausticsPVRepresentation_h

#include "vtkCausticsParaViewModule.h" // For export macro
#include "vtkGeometryRepresentationWithFaces.h"

class VTKCAUSTICSPARAVIEW_EXPORT vtkCausticsPVRepresentation
  : public vtkGeometryRepresentationWithFaces
{
public:
  static vtkCausticsPVRepresentation* New();
  vtkTypeMacro(vtkCausticsPVRepresentation, vtkGeometryRepresentationWithFaces);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** CausticsRole values: AUTOMATIC, then vtkCausticsMaterial::RoleType's numbers. */
  enum CausticsRoleType
  {
    AUTOMATIC = -1,
    NONE = 0,
    RECEIVER = 1,
    REFLECTOR = 2,
    REFRACTOR = 3
  };

  ///@{
  /** The actor's caustics role (CausticsRoleType). Default AUTOMATIC. */
  void SetCausticsRole(int role);
  vtkGetMacro(CausticsRole, int);
  ///@}

  ///@{
  /** Index of refraction of a refractor, in [1, 4]. Default 1.5 (glass). */
  void SetCausticsIOR(double ior);
  vtkGetMacro(CausticsIOR, double);
  ///@}

  int ProcessViewRequest(vtkInformationRequestKey* request_type, vtkInformation* inInfo,
    vtkInformation* outInfo) override;

protected:
  vtkCausticsPVRepresentation();
  ~vtkCausticsPVRepresentation() override;

private:
  vtkCausticsPVRepresentation(const vtkCausticsPVRepresentation&) = delete;
  void operator=(const vtkCausticsPVRepresentation&) = delete;

  /** Steps 1 to 3 of the class description, on the actor and its property. */
  void ApplyCausticsMaterial();

  int CausticsRole = AUTOMATIC;
  double CausticsIOR = 1.5;
  bool MadeGlass = false; ///< whether this class set the property's transmission
};

#endif
