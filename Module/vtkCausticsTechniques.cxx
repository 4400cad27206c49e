#include "vtkCausticsTechniques.h"

#include "vtkCausticsCascadedPhotonPass.h"
#include "vtkCausticsDeviceLimits.h"
#include "vtkCausticsHierarchicalCausticMapPass.h"
#include "vtkCausticsPhotonFocus.h"
#include "vtkCausticsImpostorPhotonPass.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>

vtkStandardNewMacro(vtkCausticsTechniques);

namespace
{
struct Entry
{
  std::string Name;
  std::string Description;
  std::function<vtkSmartPointer<vtkCausticsRenderPass>()> Make;
};

std::vector<Entry>& Entries()
{
  static std::vector<Entry> entries = {
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
    { "cascaded",
      "photons sampled from the light buffers, marched in the light's view, then the camera's "
      "(Meenrattanakorn and Lambers, docs/technique-cascaded.md)",
      [] { return vtkSmartPointer<vtkCausticsCascadedPhotonPass>::New(); } },
    { "impostors",
      "photons traced against distance impostors, cube maps of the specular objects and their "
      "surroundings (Szirmay-Kalos et al. 2005, docs/technique-distance-impostors.md)",
      [] { return vtkSmartPointer<vtkCausticsImpostorPhotonPass>::New(); } },
  };
  return entries;
}

/**
 * Whether the mesh is closed: every edge is shared by exactly two triangles.
 * Vertices are welded by position first (glTF and smoothed meshes split them at
 * seams), at a millionth of the mesh's size.
 */
bool IsClosed(const caustics::Mesh& mesh)
{
  const std::size_t vertices = mesh.positions.size() / 3;
  if (mesh.indices.empty() || vertices == 0)
  {
    return false;
  }
  float low[3] = { mesh.positions[0], mesh.positions[1], mesh.positions[2] };
  float high[3] = { low[0], low[1], low[2] };
  for (std::size_t v = 0; v < vertices; ++v)
  {
    for (int k = 0; k < 3; ++k)
    {
      low[k] = std::min(low[k], mesh.positions[3 * v + k]);
      high[k] = std::max(high[k], mesh.positions[3 * v + k]);
    }
  }
  const double cell =
    1e-6 * std::max({ high[0] - low[0], high[1] - low[1], high[2] - low[2], 1e-30f });
  std::map<std::array<long long, 3>, std::uint32_t> welded;
  std::vector<std::uint32_t> id(vertices);
  for (std::size_t v = 0; v < vertices; ++v)
  {
    std::array<long long, 3> key;
    for (int k = 0; k < 3; ++k)
    {
      key[k] = std::llround((mesh.positions[3 * v + k] - low[k]) / cell);
    }
    id[v] = welded.emplace(key, static_cast<std::uint32_t>(welded.size())).first->second;
  }
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
  {
    for (int e = 0; e < 3; ++e)
    {
      const std::uint32_t a = id[mesh.indices[t + e]], b = id[mesh.indices[t + (e + 1) % 3]];
      if (a != b)
      {
        ++edges[{ std::min(a, b), std::max(a, b) }];
      }
    }
  }
  return std::all_of(edges.begin(), edges.end(), [](const auto& edge) { return edge.second == 2; });
}

bool IsRegistered(const std::string& name)
{
  const std::vector<Entry>& entries = Entries();
  return std::any_of(
    entries.begin(), entries.end(), [&name](const Entry& entry) { return entry.Name == name; });
}


/**
 * Whether a closed mesh is convex: no vertex lies outside the plane of a face (by
 * more than 1e-4 of the mesh's size), tested on up to 256 faces spread over it.
 */
bool IsConvex(const caustics::Mesh& mesh)
{
  const std::size_t vertices = mesh.positions.size() / 3, faces = mesh.indices.size() / 3;
  if (vertices == 0 || faces == 0)
  {
    return false;
  }
  auto point = [&mesh](std::size_t v)
  {
    return std::array<double, 3>{ mesh.positions[3 * v], mesh.positions[3 * v + 1],
      mesh.positions[3 * v + 2] };
  };
  std::array<double, 3> low = point(0), high = low;
  for (std::size_t v = 0; v < vertices; ++v)
  {
    const auto p = point(v);
    for (int k = 0; k < 3; ++k)
    {
      low[k] = std::min(low[k], p[k]);
      high[k] = std::max(high[k], p[k]);
    }
  }
  const double tolerance =
    1e-4 * std::max({ high[0] - low[0], high[1] - low[1], high[2] - low[2] });
  const std::size_t stride = std::max<std::size_t>(faces / 256, 1);
  for (std::size_t f = 0; f < faces; f += stride)
  {
    const auto a = point(mesh.indices[3 * f]), b = point(mesh.indices[3 * f + 1]),
               c = point(mesh.indices[3 * f + 2]);
    const std::array<double, 3> u{ b[0] - a[0], b[1] - a[1], b[2] - a[2] },
      w{ c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    std::array<double, 3> n{ u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
      u[0] * w[1] - u[1] * w[0] };
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(length > 0.0))
    {
      continue; // a degenerate face has no plane
    }
    // Vertices on both sides of the plane (whichever way the face winds): concave.
    bool above = false, below = false;
    for (std::size_t v = 0; v < vertices && !(above && below); ++v)
    {
      const auto p = point(v);
      const double height =
        (n[0] * (p[0] - a[0]) + n[1] * (p[1] - a[1]) + n[2] * (p[2] - a[2])) / length;
      above = above || height > tolerance;
      below = below || height < -tolerance;
    }
    if (above && below)
    {
      return false;
    }
  }
  return true;
}
}

void vtkCausticsTechniques::Register(const std::string& name, const std::string& description,
  std::function<vtkSmartPointer<vtkCausticsRenderPass>()> make)
{
  std::vector<Entry>& entries = Entries();
  const auto found = std::find_if(
    entries.begin(), entries.end(), [&name](const Entry& entry) { return entry.Name == name; });
  if (found != entries.end())
  {
    found->Description = description;
    found->Make = std::move(make);
    return;
  }
  entries.push_back({ name, description, std::move(make) });
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
  // Without a scene (GetBestNameFor() chooses per scene): screen-space, the one
  // that handles every feature (mirrors, any open glass; docs/benchmarks.md).
  return "screen-space";
}

std::string vtkCausticsTechniques::GetBestNameFor(vtkRenderer* renderer)
{
  vtkNew<vtkCausticsSceneExtractor> extractor;
  if (!renderer || !extractor->Update(renderer, 64, 64))
  {
    return GetBestName();
  }
  const caustics::SceneData& scene = extractor->GetScene();
  const caustics::Medium& medium = scene.Participating;
  // In a scattering medium the GPU techniques draw their volume caustics through the
  // same stage (smoke-lens, 256² photons: relative L2 0.218-0.219 each, caustic maps
  // 2.3x faster than screen-space), so the surface decides among them as without it.
  // The CPU technique's volume caustic is not measured against them: not chosen there.
  const bool scatters =
    medium.enabled && medium.sigmaS[0] + medium.sigmaS[1] + medium.sigmaS[2] > 0.0;
  // Without a GPU (llvmpipe), the CPU technique where it measured better in less
  // time (docs/benchmarks.md, "Which technique is best"): mirrors, open water and
  // concave glass; a convex refractor alone keeps caustic maps.
  const bool software = !scatters && IsRegistered("cpu-progressive") &&
    caustics::gl::IsSoftwareOpenGL(renderer->GetRenderWindow());
  bool refractor = false;
  for (const caustics::Mesh& mesh : scene.Meshes)
  {
    const caustics::Role role = scene.Materials[mesh.material].role;
    if (software &&
      (role == caustics::Role::Reflector ||
        (role == caustics::Role::Refractor && (!IsClosed(mesh) || !IsConvex(mesh)))))
    {
      return "cpu-progressive";
    }
    // Mirrors (the ring: 19.9 % against the caustic maps' 23.0 %) and open refractors
    // that are not a sheet (a glass hemisphere beside the ball lens: 0.96 % against
    // 30.7 %): screen-space. An open sheet such as a water surface over a walled pool
    // takes the caustic maps since their hidden receivers' map (the pool: 4.4 % in
    // 261 ms against 9.4 % in 344 ms; the exact water sheet: 5.2, 19.3, 24.2 %
    // against 6.9, 37.2, 26.3 % with the sun at 90, 60 and 30 degrees).
    if (role == caustics::Role::Reflector ||
      (role == caustics::Role::Refractor && !IsClosed(mesh) && !caustics::IsSheet(mesh)))
    {
      return "screen-space";
    }
    refractor = refractor || role == caustics::Role::Refractor;
  }
  // A view much larger than its refractors: the caustic map, which covers what
  // the camera sees, loses the caustic's detail first.
  if (refractor &&
    caustics::VisibleOverSpecular(scene) > vtkCausticsHierarchicalCausticMapPass::SCENE_SCALE_LIMIT)
  {
    return "screen-space";
  }
  // Closed refractors and open sheets alone (the ball lens: 1.8 % against 5.1 %,
  // 3.3x faster; the bunny: 8.8 % against 28.7 %, impostors 19.6 %; open water as
  // above): caustic maps.
  return refractor ? "caustic-maps" : GetBestName();
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
