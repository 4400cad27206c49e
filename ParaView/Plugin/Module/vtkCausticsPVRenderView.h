/**
 * @class   vtkCausticsPVRenderView
 * @brief   ParaView's render view with a caustics pass as its geometry pass.
 *
 * What the plugin's "Caustics Render View" proxy creates on every process that
 * renders (the client in built-in mode; each pvserver or pvbatch rank). It is a
 * vtkPVRenderView in every respect but one: the pass that renders the geometry,
 * which ParaView wraps in its camera pass (and, in parallel, in IceT's compositing),
 * is a vtkCausticsRenderPass of the chosen technique:
 * 1. SetCausticsTechnique / SetPhotonGridSide only record the request;
 * 2. before each render (Render()), a changed technique releases the old pass's
 *    GPU resources and makes the new one (vtkCausticsTechniques::Create), which
 *    vtkPVSynchronizedRenderer::SetRenderPass installs; "off" installs none
 *    (ParaView's default pass);
 * 3. the photon grid side is passed on as the pass's light-buffer resolution.
 * Actors take part as the caustics rules classify them (vtkCausticsMaterial);
 * the "Caustics Surface" representation (vtkCausticsPVRepresentation) sets a
 * role explicitly. Each process traces photons against the geometry it renders
 * only (docs/paraview.md).
 */
#ifndef vtkCausticsPVRenderView_h
#define vtkCausticsPVRenderView_h

#include "vtkCausticsParaViewModule.h" // For export macro
#include "vtkPVRenderView.h"

#include "vtkSmartPointer.h" // For the pass

#include <string> // For the technique's name

class vtkCausticsRenderPass;

class VTKCAUSTICSPARAVIEW_EXPORT vtkCausticsPVRenderView : public vtkPVRenderView
{
public:
  static vtkCausticsPVRenderView* New();
  vtkTypeMacro(vtkCausticsPVRenderView, vtkPVRenderView);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The technique, by vtkCausticsTechniques name ("screen-space", "caustic-maps",
   * "best", "none") or "off" for ParaView's own pass. An unknown name is reported
   * and leaves the view on ParaView's pass. Default "best".
   */
  void SetCausticsTechnique(const char* name);
  const char* GetCausticsTechnique() const { return this->Technique.c_str(); }
  ///@}

  ///@{
  /**
   * Photons per light along each side of the light's photon grid (the pass's
   * light-buffer resolution): side x side photons per light, in [1, 8192]. Default 256.
   */
  void SetPhotonGridSide(int side);
  vtkGetMacro(PhotonGridSide, int);
  ///@}

  /** The pass of the last render; nullptr with "off" or before the first render. */
  vtkCausticsRenderPass* GetCausticsPass();

protected:
  vtkCausticsPVRenderView();
  ~vtkCausticsPVRenderView() override;

  /** Installs the requested pass, then renders as vtkPVRenderView does. */
  void Render(bool interactive, bool skip_rendering) override;

private:
  vtkCausticsPVRenderView(const vtkCausticsPVRenderView&) = delete;
  void operator=(const vtkCausticsPVRenderView&) = delete;

  void UpdateCausticsPass();

  std::string Technique = "best";
  std::string InstalledTechnique; ///< the pass's technique; empty: none installed
  int PhotonGridSide = 256;
  vtkSmartPointer<vtkCausticsRenderPass> Pass;
};

#endif
