#include "vtkCausticsTechniques.h"

#include "vtkCausticsRenderPass.h"
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
  return Entries().back().Name;
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
