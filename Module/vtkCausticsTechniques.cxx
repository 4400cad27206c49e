#include "vtkCausticsTechniques.h"

#include "vtkCausticsHierarchicalCausticMapPass.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
#include "vtkObjectFactory.h"

#include <functional>
#include <sstream>

vtkStandardNewMacro(vtkCausticsTechniques);

namespace
{
struct Entry
{
  const char* Name;
  const char* Description;
  std::function<vtkSmartPointer<vtkCausticsRenderPass>()> Make;
};

const std::vector<Entry>& Entries()
{
  static const std::vector<Entry> entries = {
    { "none", "VTK's own shading plus the shared caustics buffers (no caustic light)",
      [] { return vtkSmartPointer<vtkCausticsRenderPass>::New(); } },
    { "screen-space",
      "photons traced as lines against a layered depth image, with screen-space refraction "
      "and god-rays (Kruger et al. 2006, docs/technique-screen-space.md)",
      [] { return vtkSmartPointer<vtkCausticsScreenSpacePhotonPass>::New(); } },
    { "caustic-maps",
      "photon buffers from the lights gathered hierarchically into multi-resolution caustic "
      "maps (Wyman 2008, docs/technique-caustic-maps.md)",
      [] { return vtkSmartPointer<vtkCausticsHierarchicalCausticMapPass>::New(); } },
  };
  return entries;
}
}

std::vector<std::string> vtkCausticsTechniques::GetNames()
{
  std::vector<std::string> names;
  for (const Entry& entry : Entries())
  {
    names.emplace_back(entry.Name);
  }
  return names;
}

std::string vtkCausticsTechniques::GetBestName()
{
  // Chosen from docs/benchmarks.md (caustics-bench, default settings, 256^2 photons
  // and image): screen-space has the lower error against the ground truth on the
  // pool and the ring (9 % and 20 %, against 20 % and 41 %), caustic-maps on the ball
  // lens and the bunny (1.9 % and 11 %, against 5.1 % and 29 %), faster there too.
  // The tie goes to screen-space because only it shows the refractors refracting
  // the scene (screen-space refraction), which the final picture of every built-in
  // scene needs.
  return "screen-space";
}

vtkSmartPointer<vtkCausticsRenderPass> vtkCausticsTechniques::Create(const std::string& name)
{
  const std::string wanted = name == "best" ? GetBestName() : name;
  for (const Entry& entry : Entries())
  {
    if (wanted == entry.Name)
    {
      return entry.Make();
    }
  }
  return nullptr;
}

vtkCausticsRenderPass* vtkCausticsTechniques::NewPass(const std::string& name)
{
  vtkSmartPointer<vtkCausticsRenderPass> pass = vtkCausticsTechniques::Create(name);
  if (pass)
  {
    pass->Register(nullptr); // the reference handed to the caller
  }
  return pass;
}

std::string vtkCausticsTechniques::Describe()
{
  std::ostringstream text;
  for (const Entry& entry : Entries())
  {
    text << "  " << entry.Name << ": " << entry.Description << "\n";
  }
  text << "  best: " << GetBestName() << "\n";
  return text.str();
}

void vtkCausticsTechniques::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Techniques:\n" << Describe();
}
