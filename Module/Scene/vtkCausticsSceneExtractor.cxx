#include "vtkCausticsSceneExtractor.h"

#include "vtkActor.h"
#include "vtkAssemblyNode.h"
#include "vtkAssemblyPath.h"
#include "vtkCamera.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsMedium.h"
#include "vtkCellArray.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleKey.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkProp.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

vtkStandardNewMacro(vtkCausticsSceneExtractor);
vtkInformationKeyMacro(vtkCausticsSceneExtractor, INNER_CONE_ANGLE, Double);

namespace
{
/** What is known of an actor's geometry; the geometry itself lives in the scene. */
struct CachedMesh
{
  vtkMTimeType inputTime = 0;
  vtkMTimeType mapperTime = 0;
  double matrix[16];
  unsigned long version = 0;
  vtkIdType dropped = 0;
  vtkIdType repaired = 0;
  bool seen = false;
};

unsigned long NextVersion()
{
  static unsigned long version = 0;
  return ++version;
}

/** Appends the polygons of one polydata, transformed to world space, to a mesh. */
void AppendPolyData(
  vtkPolyData* input, vtkMatrix4x4* matrix, CachedMesh& cache, caustics::Mesh& mesh)
{
  if (!input || input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0)
  {
    return;
  }
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(input);
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  vtkSmartPointer<vtkPolyData> surface;
  if (input->GetPointData()->GetNormals())
  {
    triangles->Update();
    surface = triangles->GetOutput();
  }
  else
  {
    // Smooth normals with sharp edges (> 30 degrees) split, as VTK's own
    // vtkPolyDataNormals defaults; a box gets flat faces, a sphere smooth ones.
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputConnection(triangles->GetOutputPort());
    normals->ComputePointNormalsOn();
    normals->SplittingOn();
    normals->ConsistencyOff();
    normals->AutoOrientNormalsOff();
    normals->Update();
    surface = normals->GetOutput();
  }
  vtkPoints* points = surface->GetPoints();
  vtkDataArray* pointNormals = surface->GetPointData()->GetNormals();
  if (!points)
  {
    return;
  }

  double normalMatrix[16];
  {
    // Normals transform with the inverse transpose of the upper 3x3.
    vtkNew<vtkMatrix4x4> inverse;
    vtkMatrix4x4::Invert(matrix->GetData(), inverse->GetData());
    vtkMatrix4x4::Transpose(inverse->GetData(), normalMatrix);
  }

  const std::uint32_t base = static_cast<std::uint32_t>(mesh.positions.size() / 3);
  const vtkIdType numPoints = points->GetNumberOfPoints();
  std::vector<char> validNormal(numPoints, 1);
  for (vtkIdType i = 0; i < numPoints; ++i)
  {
    double p[4] = { 0, 0, 0, 1 };
    points->GetPoint(i, p);
    double w[4];
    matrix->MultiplyPoint(p, w);
    for (int c = 0; c < 3; ++c)
    {
      mesh.positions.push_back(static_cast<float>(w[c] / w[3]));
    }
    double n[4] = { 0, 0, 0, 0 };
    if (pointNormals)
    {
      pointNormals->GetTuple(i, n);
    }
    double wn[4];
    vtkMatrix4x4::MultiplyPoint(normalMatrix, n, wn);
    const double length = vtkMath::Norm(wn);
    if (!(length > 1e-20) || !std::isfinite(length))
    {
      validNormal[i] = 0;
      wn[0] = wn[1] = 0;
      wn[2] = 1;
    }
    else
    {
      for (int c = 0; c < 3; ++c)
      {
        wn[c] /= length;
      }
    }
    for (int c = 0; c < 3; ++c)
    {
      mesh.normals.push_back(static_cast<float>(wn[c]));
    }
  }

  vtkCellArray* polys = surface->GetPolys();
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  std::vector<char> normalFixed(numPoints, 0);
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    if (npts != 3)
    {
      continue;
    }
    const float* a = &mesh.positions[3 * (base + ids[0])];
    const float* b = &mesh.positions[3 * (base + ids[1])];
    const float* c = &mesh.positions[3 * (base + ids[2])];
    bool finite = true;
    for (int k = 0; k < 3; ++k)
    {
      finite = finite && std::isfinite(a[k]) && std::isfinite(b[k]) && std::isfinite(c[k]);
    }
    if (!finite)
    {
      ++cache.dropped;
      continue;
    }
    const double e1[3] = { double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2] };
    const double e2[3] = { double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2] };
    double faceNormal[3];
    vtkMath::Cross(e1, e2, faceNormal);
    const double twiceArea = vtkMath::Norm(faceNormal);
    const double edgeScale = std::max(vtkMath::Dot(e1, e1), vtkMath::Dot(e2, e2));
    // Zero area relative to the triangle's own size (scale-free, float precision).
    if (!(twiceArea > 1e-12 * edgeScale) || edgeScale == 0.0)
    {
      ++cache.dropped;
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      faceNormal[k] /= twiceArea;
    }
    for (int v = 0; v < 3; ++v)
    {
      const vtkIdType id = ids[v];
      if (!validNormal[id] && !normalFixed[id])
      {
        float* n = &mesh.normals[3 * (base + id)];
        for (int k = 0; k < 3; ++k)
        {
          n[k] = static_cast<float>(faceNormal[k]);
        }
        normalFixed[id] = 1;
        ++cache.repaired;
      }
      mesh.indices.push_back(base + static_cast<std::uint32_t>(id));
    }
  }
}

caustics::Vec3 Normalized(const double v[3])
{
  const double length = vtkMath::Norm(v);
  if (!(length > 0.0) || !std::isfinite(length))
  {
    return { { 0.0, 0.0, -1.0 } };
  }
  return { { v[0] / length, v[1] / length, v[2] / length } };
}
}

struct vtkCausticsSceneExtractor::Internals
{
  caustics::SceneData Scene;
  std::map<vtkActor*, CachedMesh> Cache;
  std::map<vtkActor*, caustics::Mesh> Empty; // actors with no triangles, kept to skip re-extraction
};

vtkCausticsSceneExtractor::vtkCausticsSceneExtractor()
  : Internal(new Internals)
{
}

vtkCausticsSceneExtractor::~vtkCausticsSceneExtractor() = default;

void vtkCausticsSceneExtractor::ClearCache()
{
  this->Internal->Cache.clear();
  this->Internal->Empty.clear();
  this->Internal->Scene.Meshes.clear();
}

const caustics::SceneData& vtkCausticsSceneExtractor::GetScene() const
{
  return this->Internal->Scene;
}

int vtkCausticsSceneExtractor::GetNumberOfMeshes() const
{
  return static_cast<int>(this->Internal->Scene.Meshes.size());
}

int vtkCausticsSceneExtractor::GetNumberOfLights() const
{
  return static_cast<int>(this->Internal->Scene.Lights.size());
}

vtkIdType vtkCausticsSceneExtractor::GetNumberOfTriangles() const
{
  vtkIdType count = 0;
  for (const auto& mesh : this->Internal->Scene.Meshes)
  {
    count += static_cast<vtkIdType>(mesh.TriangleCount());
  }
  return count;
}

int vtkCausticsSceneExtractor::GetNumberOfMeshesWithRole(int role) const
{
  int count = 0;
  for (const auto& material : this->Internal->Scene.Materials)
  {
    count += static_cast<int>(material.role) == role ? 1 : 0;
  }
  return count;
}

vtkIdType vtkCausticsSceneExtractor::GetNumberOfDroppedTriangles() const
{
  vtkIdType count = 0;
  for (const auto& entry : this->Internal->Cache)
  {
    count += entry.second.seen ? entry.second.dropped : 0;
  }
  return count;
}

vtkIdType vtkCausticsSceneExtractor::GetNumberOfRepairedNormals() const
{
  vtkIdType count = 0;
  for (const auto& entry : this->Internal->Cache)
  {
    count += entry.second.seen ? entry.second.repaired : 0;
  }
  return count;
}

bool vtkCausticsSceneExtractor::Update(vtkRenderer* renderer, int width, int height)
{
  if (!renderer || !renderer->GetActiveCamera())
  {
    vtkErrorMacro(<< "Update needs a renderer with an active camera");
    return false;
  }
  if (width <= 0 || height <= 0)
  {
    vtkErrorMacro(<< "image size " << width << " x " << height << " must be positive");
    return false;
  }
  auto& scene = this->Internal->Scene;
  // Unchanged meshes move from the previous snapshot into the new one (no copy).
  std::map<vtkActor*, caustics::Mesh> previous;
  for (auto& mesh : scene.Meshes)
  {
    vtkActor* key = mesh.actor;
    previous.emplace(key, std::move(mesh));
  }
  for (auto& entry : this->Internal->Empty)
  {
    previous.emplace(entry.first, std::move(entry.second));
  }
  this->Internal->Empty.clear();
  scene.Meshes.clear();
  scene.Materials.clear();
  scene.Lights.clear();
  for (auto& entry : this->Internal->Cache)
  {
    entry.second.seen = false;
  }

  // 1-3: geometry and materials.
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator propIt;
  props->InitTraversal(propIt);
  int actorIndex = 0;
  while (vtkProp* prop = props->GetNextProp(propIt))
  {
    if (!prop->GetVisibility())
    {
      continue;
    }
    prop->InitPathTraversal();
    while (vtkAssemblyPath* path = prop->GetNextPath())
    {
      vtkActor* actor = vtkActor::SafeDownCast(path->GetLastNode()->GetViewProp());
      vtkMatrix4x4* matrix = path->GetLastNode()->GetMatrix();
      if (!actor || !actor->GetVisibility() || !actor->GetMapper() || !matrix)
      {
        continue;
      }
      ++actorIndex;
      const caustics::Material material =
        vtkCausticsMaterial::Describe(actor, this->RoughnessCutoff);
      if (material.role == caustics::Role::None)
      {
        continue;
      }
      vtkMapper* mapper = actor->GetMapper();
      mapper->Update();
      vtkDataObject* input = mapper->GetInputDataObject(0, 0);
      if (!input)
      {
        continue;
      }
      CachedMesh& cache = this->Internal->Cache[actor];
      auto reusable = previous.find(actor);
      const bool changed = cache.version == 0 || reusable == previous.end() ||
        reusable->second.version != cache.version || cache.inputTime != input->GetMTime() ||
        cache.mapperTime != mapper->GetMTime() ||
        !std::equal(cache.matrix, cache.matrix + 16, matrix->GetData());
      caustics::Mesh mesh;
      if (!changed)
      {
        mesh = std::move(reusable->second);
      }
      else
      {
        cache.inputTime = input->GetMTime();
        cache.mapperTime = mapper->GetMTime();
        std::copy(matrix->GetData(), matrix->GetData() + 16, cache.matrix);
        cache.dropped = cache.repaired = 0;
        mesh.actor = actor;
        mesh.name = vtkCausticsMaterial::GetName(actor);
        if (mesh.name.empty())
        {
          mesh.name = "actor " + std::to_string(actorIndex);
        }
        if (auto* polyData = vtkPolyData::SafeDownCast(input))
        {
          AppendPolyData(polyData, matrix, cache, mesh);
        }
        else if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
        {
          vtkSmartPointer<vtkCompositeDataIterator> it;
          it.TakeReference(composite->NewIterator());
          for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
          {
            AppendPolyData(
              vtkPolyData::SafeDownCast(it->GetCurrentDataObject()), matrix, cache, mesh);
          }
        }
        else
        {
          vtkWarningMacro(<< mesh.name << ": mapper input is a " << input->GetClassName()
                          << ", not polygonal data; it takes no part in caustics");
        }
        if (cache.dropped > 0 || cache.repaired > 0)
        {
          vtkWarningMacro(<< mesh.name << ": dropped " << cache.dropped
                          << " triangle(s) with NaN/Inf vertices or zero area, replaced "
                          << cache.repaired << " invalid vertex normal(s) by face normals");
        }
        mesh.version = cache.version = NextVersion();
      }
      cache.seen = true;
      if (mesh.indices.empty())
      {
        // Keep it for the next update so an empty actor is not re-extracted each frame.
        this->Internal->Empty[actor] = std::move(mesh);
        continue;
      }
      mesh.material = static_cast<int>(scene.Materials.size());
      scene.Meshes.push_back(std::move(mesh));
      scene.Materials.push_back(material);
    }
  }
  // Forget actors that left the scene (their pointers may be reused).
  for (auto it = this->Internal->Cache.begin(); it != this->Internal->Cache.end();)
  {
    it = it->second.seen ? std::next(it) : this->Internal->Cache.erase(it);
  }

  // Bounds.
  double all[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  double specular[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  scene.HasSpecular = false;
  for (const auto& mesh : scene.Meshes)
  {
    const auto role = scene.Materials[mesh.material].role;
    const bool isSpecular = role == caustics::Role::Reflector || role == caustics::Role::Refractor;
    scene.HasSpecular = scene.HasSpecular || isSpecular;
    for (std::uint32_t index : mesh.indices)
    {
      for (int c = 0; c < 3; ++c)
      {
        const double v = mesh.positions[3 * index + c];
        all[2 * c] = std::min(all[2 * c], v);
        all[2 * c + 1] = std::max(all[2 * c + 1], v);
        if (isSpecular)
        {
          specular[2 * c] = std::min(specular[2 * c], v);
          specular[2 * c + 1] = std::max(specular[2 * c + 1], v);
        }
      }
    }
  }
  for (int i = 0; i < 6; ++i)
  {
    scene.Bounds[i] = scene.Meshes.empty() ? 0.0 : all[i];
    scene.SpecularBounds[i] = scene.HasSpecular ? specular[i] : 0.0;
  }

  // 4: lights.
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkLightCollection* lights = renderer->GetLights();
  vtkCollectionSimpleIterator lightIt;
  lights->InitTraversal(lightIt);
  while (vtkLight* vtklight = lights->GetNextLight(lightIt))
  {
    if (!vtklight->GetSwitch() || !(vtklight->GetIntensity() > 0.0))
    {
      continue;
    }
    double position[3], focal[3];
    if (vtklight->LightTypeIsHeadlight())
    {
      camera->GetPosition(position);
      camera->GetFocalPoint(focal);
    }
    else if (vtklight->LightTypeIsCameraLight())
    {
      vtkNew<vtkMatrix4x4> lightToWorld;
      lightToWorld->DeepCopy(camera->GetCameraLightTransformMatrix());
      double p[4] = { 0, 0, 0, 1 }, f[4] = { 0, 0, 0, 1 }, out[4];
      vtklight->GetPosition(p);
      vtklight->GetFocalPoint(f);
      lightToWorld->MultiplyPoint(p, out);
      std::copy(out, out + 3, position);
      lightToWorld->MultiplyPoint(f, out);
      std::copy(out, out + 3, focal);
    }
    else
    {
      vtklight->GetTransformedPosition(position);
      vtklight->GetTransformedFocalPoint(focal);
    }
    caustics::Light light;
    const double axis[3] = { focal[0] - position[0], focal[1] - position[1],
      focal[2] - position[2] };
    light.direction = Normalized(axis);
    light.position = { { position[0], position[1], position[2] } };
    const double* color = vtklight->GetDiffuseColor();
    for (int c = 0; c < 3; ++c)
    {
      light.radiometric[c] = std::max(0.0, vtklight->GetIntensity() * color[c]);
    }
    if (!vtklight->GetPositional())
    {
      light.type = caustics::Light::Type::Directional;
    }
    else if (vtklight->GetConeAngle() < 90.0)
    {
      light.type = caustics::Light::Type::Spot;
      const double outer = std::max(0.0, vtklight->GetConeAngle());
      double inner = 0.0;
      if (vtklight->GetInformation() && vtklight->GetInformation()->Has(INNER_CONE_ANGLE()))
      {
        inner = std::min(outer, std::max(0.0, vtklight->GetInformation()->Get(INNER_CONE_ANGLE())));
      }
      light.cosOuter = std::cos(vtkMath::RadiansFromDegrees(outer));
      light.cosInner = std::cos(vtkMath::RadiansFromDegrees(inner));
    }
    else
    {
      light.type = caustics::Light::Type::Point;
    }
    const bool finite = std::isfinite(light.position[0]) && std::isfinite(light.position[1]) &&
      std::isfinite(light.position[2]) && std::isfinite(light.radiometric[0]) &&
      std::isfinite(light.radiometric[1]) && std::isfinite(light.radiometric[2]);
    if (!finite)
    {
      vtkWarningMacro(<< "a light with a non-finite position or intensity was skipped");
      continue;
    }
    scene.Lights.push_back(light);
  }

  // 5: camera and medium.
  auto& view = scene.View;
  view.width = width;
  view.height = height;
  camera->GetPosition(view.position.data());
  camera->GetFocalPoint(view.focalPoint.data());
  camera->GetViewUp(view.viewUp.data());
  view.viewAngle = camera->GetViewAngle();
  view.parallel = camera->GetParallelProjection() != 0;
  view.parallelScale = camera->GetParallelScale();
  camera->GetClippingRange(view.clippingRange);
  vtkMatrix4x4* worldToClip =
    camera->GetCompositeProjectionTransformMatrix(static_cast<double>(width) / height, -1.0, 1.0);
  std::copy(worldToClip->GetData(), worldToClip->GetData() + 16, view.worldToClip);
  vtkMatrix4x4::Invert(view.worldToClip, view.clipToWorld);

  scene.Participating = caustics::Medium();
  if (vtkCausticsMedium* medium = vtkCausticsMedium::GetFrom(renderer))
  {
    scene.Participating.enabled = medium->IsScattering();
    for (int c = 0; c < 3; ++c)
    {
      scene.Participating.sigmaS[c] = medium->GetScatteringCoefficient()[c];
      scene.Participating.sigmaA[c] = medium->GetAbsorptionCoefficient()[c];
    }
    scene.Participating.g = medium->GetAnisotropy();
  }
  return true;
}

void vtkCausticsSceneExtractor::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RoughnessCutoff: " << this->RoughnessCutoff << "\n";
  os << indent << "Meshes: " << this->GetNumberOfMeshes() << " (receivers "
     << this->GetNumberOfMeshesWithRole(vtkCausticsMaterial::ROLE_RECEIVER) << ", reflectors "
     << this->GetNumberOfMeshesWithRole(vtkCausticsMaterial::ROLE_REFLECTOR) << ", refractors "
     << this->GetNumberOfMeshesWithRole(vtkCausticsMaterial::ROLE_REFRACTOR) << ")\n";
  os << indent << "Triangles: " << this->GetNumberOfTriangles() << "\n";
  os << indent << "Lights: " << this->GetNumberOfLights() << "\n";
  os << indent << "DroppedTriangles: " << this->GetNumberOfDroppedTriangles() << "\n";
  os << indent << "RepairedNormals: " << this->GetNumberOfRepairedNormals() << "\n";
}
