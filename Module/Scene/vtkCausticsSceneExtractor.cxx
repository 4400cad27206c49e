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

/**
 * The polygons of `input` as triangles with point normals: its own, or smooth
 * normals with sharp edges (> 30 degrees) split, as VTK's own vtkPolyDataNormals
 * defaults; a box gets flat faces, a sphere smooth ones. Only the points, polygons,
 * strips and normals are used: other point arrays, and normals that do not cover
 * every point, are left out, as the filters would read past an array shorter than
 * the points (a glTF with an empty normal array did; found by fuzzing).
 */
vtkSmartPointer<vtkPolyData> TriangulatedSurface(vtkPolyData* input)
{
  vtkNew<vtkPolyData> geometry;
  geometry->SetPoints(input->GetPoints());
  geometry->SetPolys(input->GetPolys());
  geometry->SetStrips(input->GetStrips());
  vtkDataArray* given = input->GetPointData()->GetNormals();
  const bool haveNormals = given && given->GetNumberOfComponents() == 3 &&
    given->GetNumberOfTuples() >= input->GetNumberOfPoints();
  if (haveNormals)
  {
    geometry->GetPointData()->SetNormals(given);
  }
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(geometry);
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  if (haveNormals)
  {
    triangles->Update();
    return triangles->GetOutput();
  }
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(triangles->GetOutputPort());
  normals->ComputePointNormalsOn();
  normals->SplittingOn();
  normals->ConsistencyOff();
  normals->AutoOrientNormalsOff();
  normals->Update();
  return normals->GetOutput();
}

/**
 * Appends the points and their normals, transformed to world space. Returns, per
 * point, whether its normal was valid (a zero or non-finite one is replaced by +z
 * here, and by a face normal in AppendTriangles).
 */
std::vector<char> AppendPoints(
  vtkPoints* points, vtkDataArray* pointNormals, vtkMatrix4x4* matrix, caustics::Mesh& mesh)
{
  double normalMatrix[16];
  {
    // Normals transform with the inverse transpose of the upper 3x3.
    vtkNew<vtkMatrix4x4> inverse;
    vtkMatrix4x4::Invert(matrix->GetData(), inverse->GetData());
    vtkMatrix4x4::Transpose(inverse->GetData(), normalMatrix);
  }
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
  return validNormal;
}

/**
 * The unit normal of triangle abc, or false for a triangle to drop: a NaN/Inf
 * vertex, or zero area relative to the triangle's own size (scale-free, float
 * precision).
 */
bool FaceNormal(const float* a, const float* b, const float* c, double faceNormal[3])
{
  bool finite = true;
  for (int k = 0; k < 3; ++k)
  {
    finite = finite && std::isfinite(a[k]) && std::isfinite(b[k]) && std::isfinite(c[k]);
  }
  if (!finite)
  {
    return false;
  }
  const double e1[3] = { double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2] };
  const double e2[3] = { double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2] };
  vtkMath::Cross(e1, e2, faceNormal);
  const double twiceArea = vtkMath::Norm(faceNormal);
  const double edgeScale = std::max(vtkMath::Dot(e1, e1), vtkMath::Dot(e2, e2));
  if (!(twiceArea > 1e-12 * edgeScale) || edgeScale == 0.0)
  {
    return false;
  }
  for (int k = 0; k < 3; ++k)
  {
    faceNormal[k] /= twiceArea;
  }
  return true;
}

/**
 * Appends the triangles of `polys` (point ids from `base`), dropping degenerate
 * ones, and gives each invalid point normal the normal of its first kept face.
 */
void AppendTriangles(vtkCellArray* polys, std::uint32_t base, const std::vector<char>& validNormal,
  CachedMesh& cache, caustics::Mesh& mesh)
{
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  std::vector<char> normalFixed(validNormal.size(), 0);
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    if (npts != 3)
    {
      continue;
    }
    double faceNormal[3];
    if (!FaceNormal(&mesh.positions[3 * (base + ids[0])], &mesh.positions[3 * (base + ids[1])],
          &mesh.positions[3 * (base + ids[2])], faceNormal))
    {
      ++cache.dropped;
      continue;
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

/** Appends the polygons of one polydata, transformed to world space, to a mesh. */
void AppendPolyData(
  vtkPolyData* input, vtkMatrix4x4* matrix, CachedMesh& cache, caustics::Mesh& mesh)
{
  if (!input || input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0)
  {
    return;
  }
  vtkSmartPointer<vtkPolyData> surface = TriangulatedSurface(input);
  vtkPoints* points = surface->GetPoints();
  if (!points)
  {
    return;
  }
  const std::uint32_t base = static_cast<std::uint32_t>(mesh.positions.size() / 3);
  const std::vector<char> validNormal =
    AppendPoints(points, surface->GetPointData()->GetNormals(), matrix, mesh);
  AppendTriangles(surface->GetPolys(), base, validNormal, cache, mesh);
}

/**
 * Appends the polygons of a polydata or of every block of a composite dataset.
 * Returns false for any other data (it takes no part in caustics).
 */
bool AppendDataObject(
  vtkDataObject* input, vtkMatrix4x4* matrix, CachedMesh& cache, caustics::Mesh& mesh)
{
  if (auto* polyData = vtkPolyData::SafeDownCast(input))
  {
    AppendPolyData(polyData, matrix, cache, mesh);
    return true;
  }
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      AppendPolyData(vtkPolyData::SafeDownCast(it->GetCurrentDataObject()), matrix, cache, mesh);
    }
    return true;
  }
  return false;
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

/** Bounds of all meshes and of the specular ones (zero where there are none). */
void ComputeBounds(caustics::SceneData& scene)
{
  double all[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  double specular[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  scene.HasSpecular = false;
  scene.RefractorChord = 0.0;
  for (const auto& mesh : scene.Meshes)
  {
    const auto role = scene.Materials[mesh.material].role;
    const bool isSpecular = role == caustics::Role::Reflector || role == caustics::Role::Refractor;
    scene.HasSpecular = scene.HasSpecular || isSpecular;
    double own[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
      VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
    for (std::uint32_t index : mesh.indices)
    {
      for (int c = 0; c < 3; ++c)
      {
        const double v = mesh.positions[3 * index + c];
        own[2 * c] = std::min(own[2 * c], v);
        own[2 * c + 1] = std::max(own[2 * c + 1], v);
      }
    }
    if (mesh.indices.empty())
    {
      continue;
    }
    for (int c = 0; c < 3; ++c)
    {
      all[2 * c] = std::min(all[2 * c], own[2 * c]);
      all[2 * c + 1] = std::max(all[2 * c + 1], own[2 * c + 1]);
      if (isSpecular)
      {
        specular[2 * c] = std::min(specular[2 * c], own[2 * c]);
        specular[2 * c + 1] = std::max(specular[2 * c + 1], own[2 * c + 1]);
      }
    }
    if (role == caustics::Role::Refractor)
    {
      const double dx = own[1] - own[0], dy = own[3] - own[2], dz = own[5] - own[4];
      scene.RefractorChord = std::max(scene.RefractorChord, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
  }
  for (int i = 0; i < 6; ++i)
  {
    scene.Bounds[i] = scene.Meshes.empty() ? 0.0 : all[i];
    scene.SpecularBounds[i] = scene.HasSpecular ? specular[i] : 0.0;
  }
}

/** A light's world position and focal point: headlights and camera lights follow the camera. */
void LightFrame(vtkLight* vtklight, vtkCamera* camera, double position[3], double focal[3])
{
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
}

/** Directional, spot (cone under 90 degrees, inner cone from INNER_CONE_ANGLE) or point. */
void SetLightType(vtkLight* vtklight, vtkInformationDoubleKey* innerConeKey, caustics::Light& light)
{
  if (!vtklight->GetPositional())
  {
    light.type = caustics::Light::Type::Directional;
  }
  else if (vtklight->GetConeAngle() < 90.0)
  {
    light.type = caustics::Light::Type::Spot;
    const double outer = std::max(0.0, vtklight->GetConeAngle());
    double inner = 0.0;
    if (vtklight->GetInformation() && vtklight->GetInformation()->Has(innerConeKey))
    {
      inner = std::min(outer, std::max(0.0, vtklight->GetInformation()->Get(innerConeKey)));
    }
    light.cosOuter = std::cos(vtkMath::RadiansFromDegrees(outer));
    light.cosInner = std::cos(vtkMath::RadiansFromDegrees(inner));
  }
  else
  {
    light.type = caustics::Light::Type::Point;
  }
}

/** The caustics light of a VTK light seen with `camera`. */
caustics::Light DescribeLight(
  vtkLight* vtklight, vtkCamera* camera, vtkInformationDoubleKey* innerConeKey)
{
  double position[3], focal[3];
  LightFrame(vtklight, camera, position, focal);
  caustics::Light light;
  const double axis[3] = { focal[0] - position[0], focal[1] - position[1], focal[2] - position[2] };
  light.direction = Normalized(axis);
  light.position = { { position[0], position[1], position[2] } };
  const double* color = vtklight->GetDiffuseColor();
  for (int c = 0; c < 3; ++c)
  {
    light.radiometric[c] = std::max(0.0, vtklight->GetIntensity() * color[c]);
  }
  SetLightType(vtklight, innerConeKey, light);
  const double* attenuation = vtklight->GetAttenuationValues();
  light.shadingAttenuation = { { attenuation[0], attenuation[1], attenuation[2] } };
  light.shadingExponent = vtklight->GetExponent();
  light.shadingConeAngle = vtklight->GetConeAngle();
  return light;
}

bool IsFinite(const caustics::Light& light)
{
  return std::isfinite(light.position[0]) && std::isfinite(light.position[1]) &&
    std::isfinite(light.position[2]) && std::isfinite(light.radiometric[0]) &&
    std::isfinite(light.radiometric[1]) && std::isfinite(light.radiometric[2]);
}

/** The camera's view of a width x height image. */
void DescribeView(vtkCamera* camera, int width, int height, caustics::Camera& view)
{
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
}

/** The renderer's participating medium (vtkCausticsMedium), disabled without one. */
caustics::Medium DescribeMedium(vtkRenderer* renderer)
{
  caustics::Medium participating;
  if (vtkCausticsMedium* medium = vtkCausticsMedium::GetFrom(renderer))
  {
    // Absorption alone dims light too (it was ignored until some scattering was set).
    participating.enabled = medium->IsAttenuating();
    for (int c = 0; c < 3; ++c)
    {
      participating.sigmaS[c] = medium->GetScatteringCoefficient()[c];
      participating.sigmaA[c] = medium->GetAbsorptionCoefficient()[c];
    }
    participating.g = medium->GetAnisotropy();
    participating.fillsRefractors = medium->GetFillsRefractors();
    participating.density = medium->GetDensity();
  }
  return participating;
}
}

struct vtkCausticsSceneExtractor::Internals
{
  caustics::SceneData Scene;
  std::map<vtkActor*, CachedMesh> Cache;
  std::map<vtkActor*, caustics::Mesh> Empty; // actors with no triangles, kept to skip re-extraction
  vtkCausticsSceneExtractor* Owner = nullptr; // warnings are its own

  using MeshMap = std::map<vtkActor*, caustics::Mesh>;
  MeshMap TakeMeshes();
  void AddActors(vtkRenderer* renderer, double roughnessCutoff, MeshMap& previous);
  void AddActor(vtkActor* actor, vtkMatrix4x4* matrix, int actorIndex, double roughnessCutoff,
    MeshMap& previous);
  caustics::Mesh ExtractMesh(
    vtkActor* actor, vtkDataObject* input, vtkMatrix4x4* matrix, int actorIndex, CachedMesh& cache);
  void ForgetDepartedActors();
  void AddLights(vtkRenderer* renderer);
};

/**
 * Empties the snapshot for a new one. Its meshes, and the empty ones, are handed
 * back by actor so that unchanged meshes move into the new snapshot (no copy).
 */
vtkCausticsSceneExtractor::Internals::MeshMap vtkCausticsSceneExtractor::Internals::TakeMeshes()
{
  MeshMap previous;
  for (auto& mesh : this->Scene.Meshes)
  {
    vtkActor* key = mesh.actor;
    previous.emplace(key, std::move(mesh));
  }
  for (auto& entry : this->Empty)
  {
    previous.emplace(entry.first, std::move(entry.second));
  }
  this->Empty.clear();
  this->Scene.Meshes.clear();
  this->Scene.Materials.clear();
  this->Scene.Lights.clear();
  for (auto& entry : this->Cache)
  {
    entry.second.seen = false;
  }
  return previous;
}

/** Steps 1-3: every visible actor of every assembly path, with its world matrix. */
void vtkCausticsSceneExtractor::Internals::AddActors(
  vtkRenderer* renderer, double roughnessCutoff, MeshMap& previous)
{
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
      this->AddActor(actor, matrix, ++actorIndex, roughnessCutoff, previous);
    }
  }
}

/**
 * Adds an actor of a caustics role with its material, re-extracting its mesh only
 * when its input, mapper or matrix changed since the previous snapshot.
 */
void vtkCausticsSceneExtractor::Internals::AddActor(
  vtkActor* actor, vtkMatrix4x4* matrix, int actorIndex, double roughnessCutoff, MeshMap& previous)
{
  const caustics::Material material = vtkCausticsMaterial::Describe(actor, roughnessCutoff);
  if (material.role == caustics::Role::None)
  {
    return;
  }
  vtkMapper* mapper = actor->GetMapper();
  mapper->Update();
  vtkDataObject* input = mapper->GetInputDataObject(0, 0);
  if (!input)
  {
    return;
  }
  CachedMesh& cache = this->Cache[actor];
  auto reusable = previous.find(actor);
  const bool changed = cache.version == 0 || reusable == previous.end() ||
    reusable->second.version != cache.version || cache.inputTime != input->GetMTime() ||
    cache.mapperTime != mapper->GetMTime() ||
    !std::equal(cache.matrix, cache.matrix + 16, matrix->GetData());
  caustics::Mesh mesh = changed ? this->ExtractMesh(actor, input, matrix, actorIndex, cache)
                                : std::move(reusable->second);
  cache.seen = true;
  if (mesh.indices.empty())
  {
    // Keep it for the next update so an empty actor is not re-extracted each frame.
    this->Empty[actor] = std::move(mesh);
    return;
  }
  mesh.material = static_cast<int>(this->Scene.Materials.size());
  this->Scene.Meshes.push_back(std::move(mesh));
  this->Scene.Materials.push_back(material);
}

/** The actor's triangles in world space, with a new version; the cache records why. */
caustics::Mesh vtkCausticsSceneExtractor::Internals::ExtractMesh(
  vtkActor* actor, vtkDataObject* input, vtkMatrix4x4* matrix, int actorIndex, CachedMesh& cache)
{
  cache.inputTime = input->GetMTime();
  cache.mapperTime = actor->GetMapper()->GetMTime();
  std::copy(matrix->GetData(), matrix->GetData() + 16, cache.matrix);
  cache.dropped = cache.repaired = 0;
  caustics::Mesh mesh;
  mesh.actor = actor;
  std::copy(matrix->GetData(), matrix->GetData() + 16, mesh.modelToWorld.begin());
  mesh.name = vtkCausticsMaterial::GetName(actor);
  if (mesh.name.empty())
  {
    mesh.name = "actor " + std::to_string(actorIndex);
  }
  if (!AppendDataObject(input, matrix, cache, mesh))
  {
    vtkWarningWithObjectMacro(this->Owner, << mesh.name << ": mapper input is a "
                                           << input->GetClassName()
                                           << ", not polygonal data; it takes no part in caustics");
  }
  if (cache.dropped > 0 || cache.repaired > 0)
  {
    vtkWarningWithObjectMacro(
      this->Owner, << mesh.name << ": dropped " << cache.dropped
                   << " triangle(s) with NaN/Inf vertices or zero area, replaced " << cache.repaired
                   << " invalid vertex normal(s) by face normals");
  }
  mesh.version = cache.version = NextVersion();
  return mesh;
}

/** Forgets actors that left the scene (their pointers may be reused). */
void vtkCausticsSceneExtractor::Internals::ForgetDepartedActors()
{
  for (auto it = this->Cache.begin(); it != this->Cache.end();)
  {
    it = it->second.seen ? std::next(it) : this->Cache.erase(it);
  }
}

/** Step 4: the lights that are on and bright, skipping non-finite ones. */
void vtkCausticsSceneExtractor::Internals::AddLights(vtkRenderer* renderer)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkLightCollection* lights = renderer->GetLights();
  vtkCollectionSimpleIterator lightIt;
  lights->InitTraversal(lightIt);
  while (vtkLight* vtklight = lights->GetNextLight(lightIt))
  {
    // A NaN intensity fails "> 0" too: test finiteness first, so it is reported.
    if (!vtklight->GetSwitch() ||
      (std::isfinite(vtklight->GetIntensity()) && !(vtklight->GetIntensity() > 0.0)))
    {
      continue;
    }
    const caustics::Light light = DescribeLight(vtklight, camera, INNER_CONE_ANGLE());
    if (!IsFinite(light) || !std::isfinite(vtklight->GetIntensity()))
    {
      vtkWarningWithObjectMacro(
        this->Owner, << "a light with a non-finite position or intensity was skipped");
      continue;
    }
    this->Scene.Lights.push_back(light);
  }
}

vtkCausticsSceneExtractor::vtkCausticsSceneExtractor()
  : Internal(new Internals)
{
  this->Internal->Owner = this;
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
  auto& in = *this->Internal;
  Internals::MeshMap previous = in.TakeMeshes();
  in.AddActors(renderer, this->RoughnessCutoff, previous);
  in.ForgetDepartedActors();
  ComputeBounds(in.Scene);
  in.AddLights(renderer);
  DescribeView(renderer->GetActiveCamera(), width, height, in.Scene.View);
  in.Scene.Participating = DescribeMedium(renderer);
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
