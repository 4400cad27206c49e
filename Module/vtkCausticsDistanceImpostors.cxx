#include "vtkCausticsDistanceImpostors.h"

#include "vtkCausticsBindings.h" // CAUSTICS_IMPOSTOR_CAUSTIC_IMAGE
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsScreenSpaceUtilities.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkCausticsTimings.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsCausticStoreCS.h"       // the store's fill (shared by the techniques)
#include "vtkCausticsImpostorCausticAreaCS.h" // the store's coarse cells
#include "vtkCausticsImpostorCommon.h"        // Hit() over the cube maps
#include "vtkCausticsImpostorShadeCS.h"
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsPhotonBufferCommon.h"    // AllFinite
#include "vtkCausticsPhotonGrid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

vtkStandardNewMacro(vtkCausticsDistanceImpostors);

namespace
{
constexpr int Faces = 6;
// The caustic store covers maps 0-2 (18 layers per channel, as the shaders index
// it): photons land on receivers, which only the environment maps (0 and 2) show.
constexpr int CausticMaps = 3;
// The store's coarse level (glsl/vtkCausticsImpostorCommon.glsl): cells of
// CoarseCell^2 texels, each channel's faces tiled 8 x 8 in CoarseLayers more layers.
constexpr int CoarseCell = 8;
constexpr int CoarseLayers = 2;

// Forward and up axes of the six faces (+x, -x, +y, -y, +z, -z), the GL cube order.
constexpr double FaceAxes[Faces][2][3] = {
  { { 1, 0, 0 }, { 0, -1, 0 } },
  { { -1, 0, 0 }, { 0, -1, 0 } },
  { { 0, 1, 0 }, { 0, 0, 1 } },
  { { 0, -1, 0 }, { 0, 0, -1 } },
  { { 0, 0, 1 }, { 0, -1, 0 } },
  { { 0, 0, -1 }, { 0, -1, 0 } },
};

/**
 * Column-major clip matrix of face `face` (a 90-degree frustum, near/far in m) for
 * points relative to the reference point: P x V, V the face's rotation.
 */
std::array<float, 16> FaceRotation(int face, double nearPlane, double farPlane)
{
  const double* f = FaceAxes[face][0];
  const double* up = FaceAxes[face][1];
  const double s[3] = { f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2],
    f[0] * up[1] - f[1] * up[0] };
  const double u[3] = { s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2],
    s[0] * f[1] - s[1] * f[0] };
  const double a = -(farPlane + nearPlane) / (farPlane - nearPlane);
  const double b = -2.0 * farPlane * nearPlane / (farPlane - nearPlane);
  // Rows of P x V: (s, 0), (u, 0), (a (-f), b), (f, 0).
  std::array<float, 16> m{};
  for (int c = 0; c < 3; ++c)
  {
    m[4 * c + 0] = static_cast<float>(s[c]);
    m[4 * c + 1] = static_cast<float>(u[c]);
    m[4 * c + 2] = static_cast<float>(-a * f[c]);
    m[4 * c + 3] = static_cast<float>(f[c]);
  }
  m[14] = static_cast<float>(b);
  return m;
}

/** The same with the translation to a reference point: world to the face's clip space. */
std::array<float, 16> FaceWorldToClip(const std::array<float, 16>& rotation, const double c[3])
{
  std::array<float, 16> m = rotation;
  for (int r = 0; r < 4; ++r)
  {
    m[12 + r] -= static_cast<float>(
      rotation[r] * c[0] + rotation[4 + r] * c[1] + rotation[8 + r] * c[2]);
  }
  return m;
}

/** Roles each map draws, its reference group (the roles whose box centre is the point). */
constexpr int MapRoles[vtkCausticsDistanceImpostors::NUMBER_OF_MAPS] = {
  vtkCausticsSceneGeometry::RoleBit(1) | vtkCausticsSceneGeometry::RoleBit(2),
  vtkCausticsSceneGeometry::RoleBit(3),
  vtkCausticsSceneGeometry::RoleBit(1) | vtkCausticsSceneGeometry::RoleBit(3),
  vtkCausticsSceneGeometry::RoleBit(2),
};
constexpr caustics::Role MapGroup[vtkCausticsDistanceImpostors::NUMBER_OF_MAPS] = {
  caustics::Role::Refractor, caustics::Role::Refractor, caustics::Role::Reflector,
  caustics::Role::Reflector
};

/** Whether a mesh's material has the given role. */
bool HasRole(const caustics::SceneData& scene, const caustics::Mesh& mesh, caustics::Role role)
{
  return caustics::MeshRole(scene, mesh) == role;
}
}

struct vtkCausticsDistanceImpostors::Internals
{
  vtkNew<vtkCausticsGBuffer> Face; // one face at a time, copied into the arrays
  caustics::ssp::Texture Position; // RGBA32F, layer 6 map + face: world xyz, w = material
  caustics::ssp::Texture Normal;   // RGBA16F: normal as modelled, w = role
  caustics::ssp::Texture Radiance; // RGBA32F: receivers' albedo x direct irradiance
  caustics::ssp::Texture Caustic;  // R32I, 4 x 18 layers: caustic flux per texel (fixed
                                   // point), then the deposits per texel; 2 more: the
                                   // same per coarse cell
  caustics::ssp::Texture CausticArea; // R32F, a layer per store face: receiver area per
                                      // coarse cell, m^2 (made with the maps)
  vtkNew<vtkCausticsShaderProgram> Shade;
  vtkNew<vtkCausticsShaderProgram> Store; // glsl/vtkCausticsCausticStoreCS.glsl
  vtkNew<vtkCausticsShaderProgram> Area;  // glsl/vtkCausticsImpostorCausticAreaCS.glsl
  std::array<std::array<float, 16>, Faces> Rotation{};
  double Centre[NUMBER_OF_MAPS][3] = {};
  double Reach[NUMBER_OF_MAPS] = {}; // longest ray segment a search needs, m
  // The box of the meshes each map draws: a ray that misses it meets nothing there.
  double Content[NUMBER_OF_MAPS][6] = {};
  bool Made[NUMBER_OF_MAPS] = {};
  double ReflectorWinding = 0.0; // of the reflectors at their reference point
  // What the maps were made from: (version, material, role) per mesh, the lights'
  // parameters and the materials' albedos, and the resolution.
  std::vector<std::tuple<unsigned long, int, int>> Key;
  std::vector<double> LightKey;
  int KeyResolution = 0;
  bool KeySelf = false; // ReflectorBounces > 0
  // The shadow maps the radiance was shaded with (compared only; null: none).
  const vtkCausticsLightBuffers* ShadedWith = nullptr;
  bool Shadowed = false;

  caustics::StageSteps Steps; // "<prefix>faces", "<prefix>shading", "<prefix>caustic cells"
};

vtkCausticsDistanceImpostors::vtkCausticsDistanceImpostors()
  : Internal(new Internals)
{
  this->Internal->Face->AlbedoOff(); // the arrays take positions and normals
  this->Internal->Shade->SetName("distance impostor shading");
  this->Internal->Shade->SetComputeSource(vtkCausticsImpostorShadeCS);
  this->Internal->Store->SetName("caustic store");
  const std::string store = std::string(vtkCausticsPhotonBufferCommon) +
    vtkCausticsImpostorCommon + vtkCausticsCausticStoreCS;
  this->Internal->Store->SetComputeSource(store.c_str());
  this->Internal->Area->SetName("caustic store areas");
  const std::string area = std::string(vtkCausticsPhotonBufferCommon) +
    vtkCausticsImpostorCommon + vtkCausticsImpostorCausticAreaCS;
  this->Internal->Area->SetComputeSource(area.c_str());
}

vtkCausticsDistanceImpostors::~vtkCausticsDistanceImpostors()
{
  if (this->Internal->Position.Handle)
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): GL objects leaked");
  }
}

bool vtkCausticsDistanceImpostors::Update(vtkOpenGLRenderWindow* renWin,
  vtkCausticsSceneGeometry* geometry, const caustics::SceneData& scene,
  vtkCausticsLightBuffers* shadowMaps)
{
  auto& maps = *this->Internal;
  const bool shadowsChanged =
    shadowMaps != maps.ShadedWith || (shadowMaps && !shadowMaps->GetLastRenderReused());
  if (!this->SceneChanged(scene))
  {
    if (!shadowsChanged)
    {
      return true;
    }
    // The maps stand; only the lights' shadows moved (or came, or went).
    const bool ok = this->ShadeMaps(renWin, geometry, scene, shadowMaps);
    if (!ok)
    {
      maps.Key.clear(); // try again next frame
    }
    return ok;
  }
  this->ChooseReferencePoints(scene);
  auto& in = *this->Internal;
  const int r = this->Resolution;
  // The arrays end with the last map made: the shaders read a map's layers only
  // where impostorValid says it exists, so the ball lens (refractor maps alone)
  // holds and shades 12 layers, not 24: at 256 texels, 31 MB less to allocate (12
  // layers of position RGBA32F, normal RGBA16F and radiance RGBA32F).
  const int layers = this->GetNumberOfLayers();
  in.Position.Ensure(r, r, layers, GL_RGBA32F);
  in.Normal.Ensure(r, r, layers, GL_RGBA16F);
  in.Radiance.Ensure(r, r, layers, GL_RGBA32F);
  if (in.Caustic.Ensure(r, r, 4 * CausticMaps * Faces + CoarseLayers, GL_R32I))
  {
    const int zero = 0;
    glClearTexImage(in.Caustic.Handle, 0, GL_RED_INTEGER, GL_INT, &zero);
  }
  this->CausticUnit = 0.0; // the store was made for other maps
  bool ok = in.Steps.Timed("faces",
    [&]
    {
      bool made = true;
      for (int map = 0; map < NUMBER_OF_MAPS && made; ++map)
      {
        made = !in.Made[map] || this->RenderMap(renWin, geometry, map);
      }
      return made;
    });
  ok = ok &&
    in.Steps.Timed(
      "shading", [&] { return this->ShadeMaps(renWin, geometry, scene, shadowMaps); }) &&
    in.Steps.Timed("caustic cells", [&] { return this->MeasureCausticCells(renWin); });
  ++this->MapRenders;
  if (!ok)
  {
    in.Key.clear(); // try again next frame
    std::fill(in.Made, in.Made + NUMBER_OF_MAPS, false);
  }
  return ok;
}

void vtkCausticsDistanceImpostors::SetTimings(vtkCausticsTimings* timings, const char* stagePrefix)
{
  this->Internal->Steps.Timings = timings;
  this->Internal->Steps.Prefix = stagePrefix ? stagePrefix : "";
}

int vtkCausticsDistanceImpostors::GetNumberOfLayers() const
{
  const auto& in = *this->Internal;
  int maps = 1; // an array of one map's layers even when none is made
  for (int map = 0; map < NUMBER_OF_MAPS; ++map)
  {
    maps = in.Made[map] ? map + 1 : maps;
  }
  return maps * Faces;
}

bool vtkCausticsDistanceImpostors::SceneChanged(const caustics::SceneData& scene)
{
  auto& in = *this->Internal;
  std::vector<std::tuple<unsigned long, int, int>> key = caustics::MeshKey(scene);
  std::vector<double> lights;
  for (const caustics::Light& light : scene.Lights)
  {
    lights.push_back(static_cast<double>(light.type));
    lights.insert(lights.end(), light.position.begin(), light.position.end());
    lights.insert(lights.end(), light.direction.begin(), light.direction.end());
    lights.insert(lights.end(), light.radiometric.begin(), light.radiometric.end());
    lights.push_back(light.cosOuter);
    lights.push_back(light.cosInner);
  }
  for (const caustics::Material& material : scene.Materials)
  {
    lights.insert(lights.end(), material.albedo.begin(), material.albedo.end());
  }
  const bool self = this->ReflectorBounces > 0;
  if (key == in.Key && lights == in.LightKey && this->Resolution == in.KeyResolution &&
    self == in.KeySelf && in.Position.Handle)
  {
    return false;
  }
  in.Key = std::move(key);
  in.LightKey = std::move(lights);
  in.KeyResolution = this->Resolution;
  in.KeySelf = self;
  return true;
}

void vtkCausticsDistanceImpostors::ChooseReferencePoints(const caustics::SceneData& scene)
{
  auto& in = *this->Internal;
  const double diagonal = std::max(scene.Scale(), 1e-6);
  in.ReflectorWinding = 0.0;
  for (int map = 0; map < NUMBER_OF_MAPS; ++map)
  {
    double box[6] = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
    for (const caustics::Mesh& mesh : scene.Meshes)
    {
      if (HasRole(scene, mesh, MapGroup[map]))
      {
        caustics::GrowBounds(mesh, box);
      }
    }
    in.Made[map] = box[0] <= box[1] && box[2] <= box[3] && box[4] <= box[5];
    double content[6] = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
    for (const caustics::Mesh& mesh : scene.Meshes)
    {
      const int role = static_cast<int>(caustics::MeshRole(scene, mesh));
      if (MapRoles[map] & vtkCausticsSceneGeometry::RoleBit(role))
      {
        caustics::GrowBounds(mesh, content);
      }
    }
    const bool drawsSomething = content[0] <= content[1];
    for (int k = 0; k < 6; ++k)
    {
      in.Content[map][k] = drawsSomething ? content[k] : (k % 2 ? -1.0 : 1.0); // min > max: none
    }
    double groupDiagonal = 0.0;
    double thinnest = 1e300;
    for (int a = 0; a < 3 && in.Made[map]; ++a)
    {
      in.Centre[map][a] = 0.5 * (box[2 * a] + box[2 * a + 1]);
      groupDiagonal += (box[2 * a + 1] - box[2 * a]) * (box[2 * a + 1] - box[2 * a]);
      thinnest = std::min(thinnest, box[2 * a + 1] - box[2 * a]);
    }
    groupDiagonal = std::sqrt(groupDiagonal);
    // A ray inside a refractor, or from a mirror to a mirror, crosses at most the
    // group's box; otherwise, the scene.
    in.Reach[map] = map == REFRACTOR_SURFACE || map == REFLECTOR_SURFACE ? groupDiagonal : diagonal;
    if (map == REFLECTOR_SURFACE && in.Made[map])
    {
      // The mirrors see themselves only from outside the mirror solid (winding
      // number under 1/2) and only if they are not all in one plane.
      in.ReflectorWinding = WindingNumber(scene, static_cast<int>(MapGroup[map]), in.Centre[map]);
      in.Made[map] = this->ReflectorBounces > 0 && in.ReflectorWinding < 0.5 &&
        thinnest > 1e-3 * groupDiagonal;
    }
  }
  // One frustum for every map: from a thousandth of a millimetre-scale object to
  // beyond the scene seen from any point in it.
  for (int face = 0; face < Faces; ++face)
  {
    in.Rotation[face] = FaceRotation(face, 1e-5 * diagonal, 4.0 * diagonal);
  }
}

double vtkCausticsDistanceImpostors::WindingNumber(
  const caustics::SceneData& scene, int role, const double point[3])
{
  double sum = 0.0;
  for (const caustics::Mesh& mesh : scene.Meshes)
  {
    if (HasRole(scene, mesh, static_cast<caustics::Role>(role)))
    {
      sum += caustics::WindingNumber(mesh, point);
    }
  }
  return sum;
}

bool vtkCausticsDistanceImpostors::RenderMap(
  vtkOpenGLRenderWindow* renWin, vtkCausticsSceneGeometry* geometry, int map)
{
  auto& in = *this->Internal;
  const int r = this->Resolution;
  for (int face = 0; face < Faces; ++face)
  {
    const std::array<float, 16> worldToClip = FaceWorldToClip(in.Rotation[face], in.Centre[map]);
    if (!in.Face->Render(renWin, geometry, worldToClip.data(), r, r, MapRoles[map]))
    {
      return false;
    }
    const int layer = map * Faces + face;
    glCopyImageSubData(in.Face->GetPositionTexture()->GetHandle(), GL_TEXTURE_2D, 0, 0, 0, 0,
      in.Position.Handle, GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer, r, r, 1);
    glCopyImageSubData(in.Face->GetNormalTexture()->GetHandle(), GL_TEXTURE_2D, 0, 0, 0, 0,
      in.Normal.Handle, GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer, r, r, 1);
  }
  return true;
}

bool vtkCausticsDistanceImpostors::ShadeMaps(vtkOpenGLRenderWindow* renWin,
  vtkCausticsSceneGeometry* geometry, const caustics::SceneData& scene,
  vtkCausticsLightBuffers* shadowMaps)
{
  auto& in = *this->Internal;
  in.ShadedWith = nullptr;
  in.Shadowed = false;
  vtkCausticsShaderProgram* p = in.Shade;
  if (!p->Bind(renWin))
  {
    return false;
  }
  constexpr int maxLights = 8;
  const int lights = std::min(static_cast<int>(scene.Lights.size()), maxLights);
  if (static_cast<int>(scene.Lights.size()) > maxLights)
  {
    vtkWarningMacro(<< "distance impostors shade with the first " << maxLights << " of "
                    << scene.Lights.size() << " lights");
  }
  // Shadows only when every light shaded has its shadow map.
  const bool shadowed = shadowMaps && shadowMaps->GetNumberOfLights() >= lights;
  {
    caustics::ssp::TextureUnits units(renWin);
    p->SetUniformi("impostorPosition", units.Bind(in.Position.Handle));
    p->SetUniformi("impostorNormal", units.Bind(in.Normal.Handle));
    for (int map = 0; map < NUMBER_OF_MAPS; ++map)
    {
      const double* c = in.Centre[map];
      p->SetUniform3f(("impostorCentre[" + std::to_string(map) + "]").c_str(),
        static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]));
    }
    geometry->BindMaterials();
    glBindImageTexture(0, in.Radiance.Handle, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
    const unsigned int groups = static_cast<unsigned int>((this->Resolution + 7) / 8);
    // One dispatch per light, each adding to the last (a light's shadow map is one
    // texture pair); without lights one that clears.
    for (int i = 0; i < std::max(lights, 1); ++i)
    {
      p->SetUniformi("accumulate", i > 0 ? 1 : 0);
      p->SetUniformi("lightOn", i < lights ? 1 : 0);
      p->SetUniformi("shadowed", shadowed ? 1 : 0);
      // The shadow samplers always name 2D textures (GL refuses two sampler types on
      // one unit): the light's shadow map, or unread, the face target's.
      const bool lit = shadowed && i < lights;
      vtkCausticsGBuffer* shadowSource = lit ? shadowMaps->GetGBuffer(i) : in.Face.GetPointer();
      p->SetUniformi("shadowPosition", units.Bind(shadowSource->GetPositionTexture()));
      p->SetUniformi("shadowNormal", units.Bind(shadowSource->GetNormalTexture()));
      if (i < lights)
      {
        const caustics::Light& light = scene.Lights[i];
        const caustics::Vec3* origin = &light.position;
        if (shadowed)
        {
          const caustics::LightView& view = shadowMaps->GetView(i);
          float matrix[16];
          caustics::gl::ToColumnMajor(view.worldToClip, matrix);
          p->SetUniformMatrix4("lightWorldToClip", matrix);
          vtkTextureObject* shadowMap = shadowMaps->GetGBuffer(i)->GetPositionTexture();
          const int resolution = std::max(static_cast<int>(shadowMap->GetWidth()), 1);
          p->SetUniformf("texelWorldSize", static_cast<float>(view.TexelWidth(resolution)));
          // Directional lights measure distance along the axis from the view's eye.
          if (light.type == caustics::Light::Type::Directional)
          {
            origin = &view.eye;
          }
        }
        p->SetUniformi("lightType", static_cast<int>(light.type));
        const auto set3 = [&](const char* name, const caustics::Vec3& v) {
          p->SetUniform3f(name, static_cast<float>(v[0]), static_cast<float>(v[1]),
            static_cast<float>(v[2]));
        };
        set3("lightOrigin", *origin);
        set3("lightDirection", light.direction);
        set3("lightRadiometric", light.radiometric);
        p->SetUniformf("lightCosOuter", static_cast<float>(light.cosOuter));
        p->SetUniformf("lightCosInner", static_cast<float>(light.cosInner));
      }
      p->Dispatch(groups, groups, static_cast<unsigned int>(in.Position.Layers));
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  p->Unbind(renWin);
  in.ShadedWith = shadowMaps;
  in.Shadowed = shadowed;
  return true;
}

bool vtkCausticsDistanceImpostors::GetRadianceShadowed() const
{
  return this->Internal->Shadowed;
}

bool vtkCausticsDistanceImpostors::MeasureCausticCells(vtkOpenGLRenderWindow* renWin)
{
  auto& in = *this->Internal;
  const int cells = this->Resolution / CoarseCell;
  const int layers = std::min(in.Position.Layers, CausticMaps * Faces);
  in.CausticArea.Ensure(cells, cells, CausticMaps * Faces, GL_R32F);
  const float zero = 0.0f;
  glClearTexImage(in.CausticArea.Handle, 0, GL_RED, GL_FLOAT, &zero);
  vtkCausticsShaderProgram* p = in.Area;
  if (!p->Bind(renWin))
  {
    return false;
  }
  {
    caustics::ssp::TextureUnits units(renWin);
    this->SetUniforms(p, units);
    glBindImageTexture(0, in.CausticArea.Handle, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
    const unsigned int groups = static_cast<unsigned int>((cells + 7) / 8);
    p->Dispatch(groups, groups, static_cast<unsigned int>(layers));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  p->Unbind(renWin);
  return true;
}

void vtkCausticsDistanceImpostors::SetUniforms(
  vtkCausticsShaderProgram* program, caustics::ssp::TextureUnits& units)
{
  auto& in = *this->Internal;
  if (!in.Position.Handle)
  {
    vtkErrorMacro(<< "SetUniforms() before Update(): the maps do not exist");
    return;
  }
  program->SetUniformi("impostorPosition", units.Bind(in.Position.Handle));
  program->SetUniformi("impostorNormal", units.Bind(in.Normal.Handle));
  program->SetUniformi("impostorRadiance", units.Bind(in.Radiance.Handle));
  program->SetUniformi("impostorResolution", this->Resolution);
  program->SetUniformf("impostorCausticUnit", static_cast<float>(this->CausticUnit));
  program->SetUniformi("impostorCausticRadius", this->CausticRadius);
  program->SetUniformi("impostorCausticSamples", this->CausticSamples);
  program->SetUniformi("impostorCausticCoarseSamples", this->CausticCoarseSamples);
  program->SetUniformi("impostorCausticCells", in.CausticArea.Handle ? in.CausticArea.Width : 0);
  program->SetUniformi("impostorCausticArea",
    units.Bind(in.CausticArea.Handle ? in.CausticArea.Handle : in.Position.Handle));
  if (this->CausticUnit > 0.0)
  {
    this->BindCausticImage();
  }
  program->SetUniformi("impostorLinearSteps", this->LinearSteps);
  program->SetUniformi("impostorSecantSteps", this->SecantSteps);
  program->SetUniformi("impostorReflectorBounces", this->ReflectorBounces);
  for (int face = 0; face < Faces; ++face)
  {
    const std::string name = "impostorFaceRotation[" + std::to_string(face) + "]";
    program->SetUniformMatrix4(name.c_str(), in.Rotation[face].data());
  }
  for (int map = 0; map < NUMBER_OF_MAPS; ++map)
  {
    const std::string index = "[" + std::to_string(map) + "]";
    const double* c = in.Centre[map];
    program->SetUniform3f(("impostorCentre" + index).c_str(), static_cast<float>(c[0]),
      static_cast<float>(c[1]), static_cast<float>(c[2]));
    program->SetUniformf(("impostorReach" + index).c_str(), static_cast<float>(in.Reach[map]));
    program->SetUniformi(("impostorValid" + index).c_str(), in.Made[map] ? 1 : 0);
    const double* box = in.Content[map];
    program->SetUniform3f(("impostorContentMin" + index).c_str(), static_cast<float>(box[0]),
      static_cast<float>(box[2]), static_cast<float>(box[4]));
    program->SetUniform3f(("impostorContentMax" + index).c_str(), static_cast<float>(box[1]),
      static_cast<float>(box[3]), static_cast<float>(box[5]));
  }
}

void vtkCausticsDistanceImpostors::SetAbsentUniforms(
  vtkCausticsShaderProgram* program, int fallbackArrayUnit)
{
  program->SetUniformi("impostorPosition", fallbackArrayUnit);
  program->SetUniformi("impostorNormal", fallbackArrayUnit);
  program->SetUniformi("impostorRadiance", fallbackArrayUnit);
  program->SetUniformf("impostorCausticUnit", 0.0f);
  program->SetUniformi("impostorCausticArea", fallbackArrayUnit);
  program->SetUniformi("impostorCausticCells", 0);
  for (int map = 0; map < NUMBER_OF_MAPS; ++map)
  {
    program->SetUniformi(("impostorValid[" + std::to_string(map) + "]").c_str(), 0);
  }
}

void vtkCausticsDistanceImpostors::BeginCaustic(double unit)
{
  auto& in = *this->Internal;
  if (!in.Caustic.Handle)
  {
    vtkErrorMacro(<< "BeginCaustic() before Update(): the maps do not exist");
    return;
  }
  const int zero = 0;
  glClearTexImage(in.Caustic.Handle, 0, GL_RED_INTEGER, GL_INT, &zero);
  this->CausticUnit = unit > 0.0 && std::isfinite(unit) ? unit : 0.0;
}

void vtkCausticsDistanceImpostors::ResetCaustic()
{
  this->CausticUnit = 0.0;
}

bool vtkCausticsDistanceImpostors::OpenCaustic(double maximumPhotonFlux)
{
  if (!(this->CausticUnit > 0.0) && this->Internal->Caustic.Handle)
  {
    // Fixed point of the store: 1/4096 of the frame's first light's largest photon.
    this->BeginCaustic(maximumPhotonFlux / 3.0 / 4096.0);
  }
  return this->CausticUnit > 0.0;
}

bool vtkCausticsDistanceImpostors::StoreCaustic(vtkOpenGLRenderWindow* renWin,
  const caustics::PhotonRecords& landed, int width, int height, double maximumPhotonFlux,
  vtkCausticsLightBuffers* lightBuffers, int light, const caustics::SceneData& scene,
  bool shadow)
{
  auto& in = *this->Internal;
  if (!in.Caustic.Handle || !landed.IsSet() || !lightBuffers || light < 0 ||
    light >= static_cast<int>(scene.Lights.size()) || !lightBuffers->GetView(light).valid)
  {
    return true; // no maps, photons or light: nothing to store
  }
  if (!this->OpenCaustic(maximumPhotonFlux))
  {
    return true;
  }
  vtkCausticsShaderProgram* p = in.Store;
  if (!p->Bind(renWin))
  {
    return false;
  }
  const caustics::LightView& view = lightBuffers->GetView(light);
  const caustics::Light& source = scene.Lights[light];
  const int resolution =
    shadow ? lightBuffers->GetGBuffer(light)->GetPositionTexture()->GetWidth() : 0;
  {
    caustics::ssp::TextureUnits units(renWin);
    p->SetUniformi("landedPosition", units.Bind(landed.Position));
    p->SetUniformi("landedFlux", units.Bind(landed.Flux));
    p->SetUniform2i("landedGrid", width, height);
    vtkCausticsGBuffer* seen = lightBuffers->GetGBuffer(light);
    p->SetUniformi("lightPosition", units.Bind(seen->GetPositionTexture()));
    p->SetUniformi("lightNormal", units.Bind(seen->GetNormalTexture()));
    p->SetUniformi("lightFlux", units.Bind(lightBuffers->GetFluxTexture(light)));
    p->SetUniformi("lightResolution", resolution);
    p->SetUniformi("lightType", static_cast<int>(source.type));
    p->SetUniform3f("lightOrigin", static_cast<float>(source.position[0]),
      static_cast<float>(source.position[1]), static_cast<float>(source.position[2]));
    p->SetUniform3f("lightAxis", static_cast<float>(view.axis[0]),
      static_cast<float>(view.axis[1]), static_cast<float>(view.axis[2]));
    const double* b = scene.Bounds;
    p->SetUniform3f("boundsMin", static_cast<float>(b[0]), static_cast<float>(b[2]),
      static_cast<float>(b[4]));
    p->SetUniform3f("boundsMax", static_cast<float>(b[1]), static_cast<float>(b[3]),
      static_cast<float>(b[5]));
    p->SetUniformf("tolerance", static_cast<float>(1e-5 * scene.Scale()));
    this->SetUniforms(p, units);
    p->DispatchCovering2D(std::max(width, resolution), std::max(height, resolution), 8, 8);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
  p->Unbind(renWin);
  glBindImageTexture(CAUSTICS_IMPOSTOR_CAUSTIC_IMAGE, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32I);
  return true;
}

void vtkCausticsDistanceImpostors::BindCausticImage() const
{
  glBindImageTexture(CAUSTICS_IMPOSTOR_CAUSTIC_IMAGE, this->Internal->Caustic.Handle, 0, GL_TRUE,
    0, GL_READ_WRITE, GL_R32I);
}

double vtkCausticsDistanceImpostors::GetReflectorWinding() const
{
  return this->Internal->ReflectorWinding;
}

bool vtkCausticsDistanceImpostors::HasMap(int map) const
{
  return map >= 0 && map < NUMBER_OF_MAPS && this->Internal->Position.Handle &&
    this->Internal->Made[map];
}

void vtkCausticsDistanceImpostors::GetReferencePoint(int map, double point[3]) const
{
  const int m = std::min(std::max(map, 0), NUMBER_OF_MAPS - 1);
  std::copy(this->Internal->Centre[m], this->Internal->Centre[m] + 3, point);
}

void vtkCausticsDistanceImpostors::ReleaseGraphicsResources(vtkWindow* win)
{
  auto& in = *this->Internal;
  in.Face->ReleaseGraphicsResources(win);
  in.Position.Release();
  in.Normal.Release();
  in.Radiance.Release();
  in.Caustic.Release();
  in.CausticArea.Release();
  in.Area->ReleaseGraphicsResources(win);
  in.Store->ReleaseGraphicsResources(win);
  this->CausticUnit = 0.0;
  in.Shade->ReleaseGraphicsResources(win);
  in.Key.clear();
  std::fill(in.Made, in.Made + NUMBER_OF_MAPS, false);
}

void vtkCausticsDistanceImpostors::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "LinearSteps: " << this->LinearSteps << "\n";
  os << indent << "SecantSteps: " << this->SecantSteps << "\n";
  os << indent << "ReflectorBounces: " << this->ReflectorBounces << "\n";
  os << indent << "MapRenders: " << this->MapRenders << "\n";
  os << indent << "ReflectorWinding: " << this->Internal->ReflectorWinding << "\n";
  os << indent << "CausticRadius: " << this->CausticRadius << " texels\n";
  os << indent << "CausticSamples: " << this->CausticSamples << "\n";
  os << indent << "CausticCoarseSamples: " << this->CausticCoarseSamples << "\n";
  os << indent << "CausticUnit: " << this->CausticUnit << " W per count\n";
  for (int map = 0; map < NUMBER_OF_MAPS; ++map)
  {
    const double* c = this->Internal->Centre[map];
    os << indent << "Map " << map << ": " << (this->HasMap(map) ? "made" : "absent")
       << ", reference point (" << c[0] << ", " << c[1] << ", " << c[2] << ")\n";
  }
}
