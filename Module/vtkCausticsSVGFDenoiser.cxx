#include "vtkCausticsSVGFDenoiser.h"

#include "vtkActor.h"
#include "vtkDataObject.h"
#include "vtkCausticsBindings.h"
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkTextureObject.h"
#include "vtkWeakPointer.h"
#include "vtk_glew.h"

#include "vtkCausticsSVGFAtrousCS.h"
#include "vtkCausticsSVGFCommon.h"
#include "vtkCausticsSVGFReprojectCS.h"
#include "vtkCausticsSVGFTemporalCS.h"
#include "vtkCausticsSVGFVarianceCS.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkCausticsSVGFDenoiser);

namespace
{
// The steps' programs, in the order Denoise() runs them.
enum Program
{
  REPROJECT = 0, // history at this frame's pixels
  TEMPORAL = 1,  // colour and moments accumulated
  VARIANCE = 2,  // luminance variance
  DEVIATION = 3, // a-trous: blurred deviation of luminance
  NORMALIZE = 4, // a-trous: first Sinkhorn step of the weights' balance
  BALANCE = 5,   // a-trous: second Sinkhorn step
  ATROUS = 6,    // a-trous: one wavelet iteration with the balanced weights
  PROGRAMS = 7
};

constexpr unsigned int LocalSize = 16; // the shaders' local_size_x/y

void BindImage(unsigned int unit, vtkTextureObject* texture, unsigned int access,
  unsigned int format = GL_RGBA32F)
{
  glBindImageTexture(unit, texture->GetHandle(), 0, GL_FALSE, 0, access, format);
}

void CopyTexture(vtkTextureObject* from, vtkTextureObject* to, int width, int height)
{
  glCopyImageSubData(from->GetHandle(), GL_TEXTURE_2D, 0, 0, 0, 0, to->GetHandle(), GL_TEXTURE_2D,
    0, 0, 0, 0, width, height, 1);
}

void Barrier()
{
  // Image stores, then image loads, copies or texture fetches (the composite).
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

/** One entry of the reprojection's motion table (SVGFMotion in the shader, std430). */
struct MeshMotion
{
  float PreviousFromCurrent[16]; // column-major, world to world
  float PreviousIndex[4];        // x: the mesh's index last frame, -1: no history
};
static_assert(sizeof(MeshMotion) == 80, "the shader's SVGFMotion");

/**
 * Where an actor's mesh was in a frame: its model-to-world matrix (the actor's
 * composed with its assemblies'), three of the mesh's world vertices (which check
 * that the matrix moved them: a deformed mesh moves otherwise) and the mesh's index.
 */
struct Placement
{
  vtkWeakPointer<vtkActor> Actor; // null once the actor is gone (its address may be reused)
  std::array<double, 16> Matrix;  // model to world, row-major
  std::array<std::array<double, 3>, 3> Samples; // world vertices: first, middle, last
  std::size_t Vertices = 0;
  vtkMTimeType InputTime = 0; // of the mapper and its input: a change is a new shape
  int Index = -1;

  Placement() = default;
  Placement(const caustics::Mesh& mesh, int index)
    : Actor(mesh.actor)
    , Vertices(mesh.positions.size() / 3)
    , Index(index)
  {
    this->Matrix = mesh.modelToWorld;
    if (vtkMapper* mapper = mesh.actor->GetMapper())
    {
      vtkDataObject* input = mapper->GetInputDataObject(0, 0);
      this->InputTime = std::max(mapper->GetMTime(), input ? input->GetMTime() : 0);
    }
    const std::size_t at[3] = { 0, this->Vertices / 2, this->Vertices - 1 };
    for (int i = 0; i < 3; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        this->Samples[i][c] = mesh.positions[3 * at[i] + c];
      }
    }
  }
};

/** An actor's meshes by occurrence (one actor may appear on several assembly paths). */
using PlacementKey = std::pair<const vtkActor*, int>;

/** A rigid (affine) motion, row-major: this frame's world position to the last frame's. */
using Motion = std::array<double, 16>;
const Motion Still = { { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 } };

/** `m` applied to the point or (w = 0) direction `x`, row `r`. */
double Apply(const Motion& m, const double x[3], double w, int r)
{
  return m[4 * r] * x[0] + m[4 * r + 1] * x[1] + m[4 * r + 2] * x[2] + m[4 * r + 3] * w;
}

/** Whether `a` and `b` agree within float rounding of coordinates of size `scale`. */
bool Near(const double a[3], const double b[3], double scale)
{
  for (int r = 0; r < 3; ++r)
  {
    if (!(std::abs(a[r] - b[r]) <= 1e-5 * (1.0 + scale)))
    {
      return false;
    }
  }
  return true;
}

/**
 * The motion of a mesh from the last frame to this one: previous x inverse(current)
 * of the model-to-world matrices. False when the mapper or its input changed (a new
 * shape), the matrix cannot be inverted or the motion does not take this frame's
 * sample vertices to the last frame's: then the mesh moved otherwise (deformed).
 */
bool MeshMotionOf(const Placement& previous, const Placement& current, Motion& motion)
{
  double inverse[16];
  if (previous.Vertices != current.Vertices || previous.InputTime != current.InputTime ||
    !(std::abs(vtkMatrix4x4::Determinant(current.Matrix.data())) > 1e-300))
  {
    return false;
  }
  vtkMatrix4x4::Invert(current.Matrix.data(), inverse);
  vtkMatrix4x4::Multiply4x4(previous.Matrix.data(), inverse, motion.data());
  for (int i = 0; i < 3; ++i)
  {
    const double* x = current.Samples[i].data();
    const double moved[3] = { Apply(motion, x, 1, 0), Apply(motion, x, 1, 1),
      Apply(motion, x, 1, 2) };
    const double scale = std::max({ std::abs(x[0]), std::abs(x[1]), std::abs(x[2]) });
    if (!Near(moved, previous.Samples[i].data(), scale))
    {
      return false;
    }
  }
  return std::all_of(motion.begin(), motion.end(), [](double v) { return std::isfinite(v); });
}

/** Whether two motions agree (within float rounding at the scale of their translations). */
bool SameMotion(const Motion& a, const Motion& b)
{
  const double scale = std::max({ std::abs(a[3]), std::abs(a[7]), std::abs(a[11]) });
  for (int i = 0; i < 16; ++i)
  {
    if (!(std::abs(a[i] - b[i]) <= 1e-5 * (1.0 + (i % 4 == 3 ? scale : 0.0))))
    {
      return false;
    }
  }
  return true;
}

/** Whether the lights made `motion` (positions and directions, as rigid parts of the scene). */
bool LightsMadeMotion(const std::vector<caustics::Light>& previous,
  const std::vector<caustics::Light>& current, const Motion& motion)
{
  if (previous.size() != current.size())
  {
    return false;
  }
  for (std::size_t i = 0; i < current.size(); ++i)
  {
    const caustics::Light& a = previous[i];
    const caustics::Light& b = current[i];
    const double d[3] = { Apply(motion, b.direction.data(), 0, 0),
      Apply(motion, b.direction.data(), 0, 1), Apply(motion, b.direction.data(), 0, 2) };
    const double norm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double unit[3] = { d[0] / norm, d[1] / norm, d[2] / norm };
    const double x[3] = { Apply(motion, b.position.data(), 1, 0),
      Apply(motion, b.position.data(), 1, 1), Apply(motion, b.position.data(), 1, 2) };
    const double scale =
      std::max({ std::abs(b.position[0]), std::abs(b.position[1]), std::abs(b.position[2]) });
    const bool positional = b.type != caustics::Light::Type::Directional;
    const bool aimed = b.type != caustics::Light::Type::Point;
    if (a.type != b.type || (aimed && (!(norm > 0.0) || !Near(unit, a.direction.data(), 0.0))) ||
      (positional && !Near(x, a.position.data(), scale)))
    {
      return false;
    }
  }
  return true;
}

/**
 * The one rigid motion that what lights the receivers made (every reflector and
 * refractor, with a known motion, and every light), in `light`; false if it made none.
 */
bool LightMotion(const caustics::SceneData& scene, const std::vector<Motion>& motions,
  const std::vector<char>& known, const std::vector<caustics::Light>& previousLights,
  Motion& light)
{
  bool first = true;
  for (std::size_t i = 0; i < scene.Meshes.size(); ++i)
  {
    if (scene.Materials[scene.Meshes[i].material].role != caustics::Role::Receiver)
    {
      if (!known[i] || (!first && !SameMotion(motions[i], light)))
      {
        return false;
      }
      light = motions[i];
      first = false;
    }
  }
  return !first && LightsMadeMotion(previousLights, scene.Lights, light);
}
}

struct vtkCausticsSVGFDenoiser::Internals
{
  vtkNew<vtkCausticsShaderProgram> Programs[PROGRAMS];
  vtkNew<vtkTextureObject> Raw;                // the input as it came (W/m^2)
  vtkNew<vtkTextureObject> HistoryColor;       // rgb W/m^2
  vtkNew<vtkTextureObject> HistoryMoments;     // m1, m2, frames
  vtkNew<vtkTextureObject> ReprojectedColor;   // the history at this frame's pixels
  vtkNew<vtkTextureObject> ReprojectedMoments; //
  vtkNew<vtkTextureObject> Filter[2];          // rgb W/m^2, a: variance (ping-pong)
  vtkNew<vtkTextureObject> Deviation;          // R32F: blurred deviation of luminance
  vtkNew<vtkTextureObject> Balance[2];         // R32F: the a-trous weights' balance
  vtkNew<vtkTextureObject> PreviousPosition;   // the last frame's G-buffer
  vtkNew<vtkTextureObject> PreviousNormal;     //
  vtkNew<vtkTextureObject> Counts;             // R32UI 2 x 1: receivers, reprojected
  caustics::gl::StorageBuffer Motion;          // MeshMotion per mesh of this frame
  std::vector<MeshMotion> MotionTable;         // its contents, kept to reuse the memory
  std::map<PlacementKey, Placement> Previous;  // the last denoised frame's actors
  std::map<PlacementKey, Placement> Current;   // this frame's, the next one's Previous
  std::vector<caustics::Light> PreviousLights; // the last denoised frame's lights
  std::vector<caustics::Light> CurrentLights;  //
  float PreviousWorldToClip[16] = {};
  bool Released = true; // nothing allocated, or all released
};

vtkCausticsSVGFDenoiser::vtkCausticsSVGFDenoiser()
  : Internal(new Internals)
{
  const char* names[PROGRAMS] = { "SVGF reproject", "SVGF temporal", "SVGF variance",
    "SVGF a-trous deviation", "SVGF a-trous normalize", "SVGF a-trous balance", "SVGF a-trous" };
  const char* sources[PROGRAMS] = { vtkCausticsSVGFReprojectCS, vtkCausticsSVGFTemporalCS,
    vtkCausticsSVGFVarianceCS, vtkCausticsSVGFAtrousCS, vtkCausticsSVGFAtrousCS,
    vtkCausticsSVGFAtrousCS, vtkCausticsSVGFAtrousCS };
  for (int i = 0; i < PROGRAMS; ++i)
  {
    auto& program = this->Internal->Programs[i];
    program->SetName(names[i]);
    program->SetComputeSource((std::string(vtkCausticsSVGFCommon) + sources[i]).c_str());
    program->SetDefine("CAUSTICS_NO_MATERIALS", 1);
    if (i >= DEVIATION)
    {
      program->SetDefine("SVGF_ATROUS_STAGE", i - DEVIATION); // the shader's stages, in order
    }
  }
}

vtkCausticsSVGFDenoiser::~vtkCausticsSVGFDenoiser()
{
  if (!this->Internal->Released)
  {
    vtkErrorMacro(<< "destroyed with graphics resources not released: call "
                     "ReleaseGraphicsResources() first");
  }
}

void vtkCausticsSVGFDenoiser::ResetHistory()
{
  this->HasHistory = false;
}

vtkTextureObject* vtkCausticsSVGFDenoiser::GetRawTexture()
{
  return this->Internal->Raw;
}

bool vtkCausticsSVGFDenoiser::Denoise(const Inputs& in)
{
  if (!in.Window || !in.Irradiance || !in.GBuffer || !in.Camera || in.Width < 1 || in.Height < 1)
  {
    return false;
  }
  if (this->EnsureTextures(in))
  {
    this->HasHistory = false; // a new size: nothing of the last frame lines up
  }
  this->FramesSinceReset = this->HasHistory ? this->FramesSinceReset : 0;
  // The light on the receivers changed unless nothing did or the whole scene, lights
  // included, made one rigid motion (which the reprojection follows). Without a history
  // nothing lit otherwise can linger: the light field counts as still.
  const bool rigid = this->FollowActors(in);
  const bool changed = in.OpticsChanged || (in.LightChanged && !rigid);
  const int still = 1 << 30;
  const int sinceChange = changed ? 0 : std::min(this->FramesSinceLightChanged + 1, still);
  this->FramesSinceLightChanged = this->HasHistory ? sinceChange : still;
  CopyTexture(in.Irradiance, this->Internal->Raw, in.Width, in.Height);
  const bool ok = this->Reproject(in) && this->Accumulate(in) && this->EstimateVariance(in) &&
    this->FilterAtrous(in);
  if (!ok)
  {
    CopyTexture(this->Internal->Raw, in.Irradiance, in.Width, in.Height);
    this->HasHistory = false;
    return false;
  }
  this->KeepForNextFrame(in);
  return true;
}

bool vtkCausticsSVGFDenoiser::EnsureTextures(const Inputs& in)
{
  auto& s = *this->Internal;
  s.Released = false;
  const int w = in.Width, h = in.Height;
  vtkTextureObject* colour[] = { s.Raw, s.HistoryColor, s.HistoryMoments, s.ReprojectedColor,
    s.ReprojectedMoments, s.Filter[0], s.Filter[1], s.PreviousPosition };
  bool resized = false;
  for (vtkTextureObject* texture : colour)
  {
    resized |= caustics::gl::EnsureTexture(texture, in.Window, w, h, GL_RGBA32F);
  }
  resized |= caustics::gl::EnsureTexture(s.PreviousNormal, in.Window, w, h, GL_RGBA16F);
  for (vtkTextureObject* texture : { s.Deviation.Get(), s.Balance[0].Get(), s.Balance[1].Get() })
  {
    resized |= caustics::gl::EnsureTexture(texture, in.Window, w, h, GL_R32F);
  }
  caustics::gl::EnsureTexture(s.Counts, in.Window, 2, 1, GL_R32UI);
  return resized;
}

void vtkCausticsSVGFDenoiser::SetCommonUniforms(const Inputs& in, int index)
{
  vtkCausticsShaderProgram* program = this->Internal->Programs[index];
  const caustics::Camera& camera = *in.Camera;
  program->SetUniform2i("size", in.Width, in.Height);
  program->SetUniform3f("eye", static_cast<float>(camera.position[0]),
    static_cast<float>(camera.position[1]), static_cast<float>(camera.position[2]));
  const double pi = std::acos(-1.0);
  const double angle = 2.0 * std::tan(0.5 * camera.viewAngle * pi / 180.0) / in.Height;
  program->SetUniformf("pixelAngle", camera.parallel ? 0.0f : static_cast<float>(angle));
  program->SetUniformf("pixelSize",
    camera.parallel ? static_cast<float>(2.0 * camera.parallelScale / in.Height) : 0.0f);
  program->SetUniformf("sigmaDepth", static_cast<float>(this->Settings.SigmaDepth));
  program->SetUniformf("sigmaNormal", static_cast<float>(this->Settings.SigmaNormal));
  BindImage(0, in.GBuffer->GetPositionTexture(), GL_READ_ONLY);
  BindImage(1, in.GBuffer->GetNormalTexture(), GL_READ_ONLY, GL_RGBA16F);
}

bool vtkCausticsSVGFDenoiser::FollowActors(const Inputs& in)
{
  auto& s = *this->Internal;
  const std::size_t meshes = in.Scene ? in.Scene->Meshes.size() : 0;
  // Each mesh's own motion since the last frame (known: its actor's matrices moved it).
  s.Current.clear();
  std::vector<int> previousIndex(meshes, -1); // -1: a new actor, no history
  std::vector<Motion> motions(meshes, Still);
  std::vector<char> known(meshes, 0);
  for (std::size_t i = 0; i < meshes; ++i)
  {
    const caustics::Mesh& mesh = in.Scene->Meshes[i];
    if (!mesh.actor || mesh.positions.empty())
    {
      continue;
    }
    int occurrence = 0; // the n-th mesh of this actor in the snapshot's order
    while (s.Current.count({ mesh.actor, occurrence }))
    {
      ++occurrence;
    }
    const Placement& now = s.Current[{ mesh.actor, occurrence }] =
      Placement(mesh, static_cast<int>(i));
    auto previous = s.Previous.find({ mesh.actor, occurrence });
    if (previous != s.Previous.end() && previous->second.Actor == mesh.actor)
    {
      previousIndex[i] = previous->second.Index;
      known[i] = MeshMotionOf(previous->second, now, motions[i]);
    }
  }
  // Did what lights the receivers (specular meshes and lights) move as one rigid body?
  Motion light = Still;
  const bool lightMoved =
    meshes > 0 && LightMotion(*in.Scene, motions, known, s.PreviousLights, light);
  bool rigid = lightMoved; // every mesh, receivers too, made the lights' motion
  // A receiver follows its own motion where its light made the same one; otherwise its
  // caustic stays where it was in the world (or moves with the casters, which the
  // colour test of the accumulation sees), and the reprojection takes it as still.
  s.MotionTable.assign(std::max<std::size_t>(meshes, 1), MeshMotion{});
  for (std::size_t i = 0; i < s.MotionTable.size(); ++i)
  {
    const bool follow = i < meshes && known[i] && lightMoved && SameMotion(motions[i], light);
    rigid = rigid && (i >= meshes || follow);
    caustics::gl::ToColumnMajor(
      follow ? motions[i].data() : Still.data(), s.MotionTable[i].PreviousFromCurrent);
    s.MotionTable[i].PreviousIndex[0] = i < meshes ? static_cast<float>(previousIndex[i]) : -1.0f;
  }
  s.CurrentLights = in.Scene ? in.Scene->Lights : std::vector<caustics::Light>();
  const std::size_t bytes = s.MotionTable.size() * sizeof(MeshMotion);
  s.Motion.Allocate(bytes);
  s.Motion.Write(0, bytes, s.MotionTable.data());
  return rigid;
}

bool vtkCausticsSVGFDenoiser::Reproject(const Inputs& in)
{
  auto& s = *this->Internal;
  vtkCausticsShaderProgram* program = s.Programs[REPROJECT];
  if (!program->Bind(in.Window))
  {
    return false;
  }
  const unsigned int zero = 0;
  glClearTexImage(s.Counts->GetHandle(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  this->SetCommonUniforms(in, REPROJECT);
  BindImage(2, s.PreviousPosition, GL_READ_ONLY);
  BindImage(3, s.PreviousNormal, GL_READ_ONLY, GL_RGBA16F);
  BindImage(4, s.HistoryColor, GL_READ_ONLY);
  BindImage(5, s.HistoryMoments, GL_READ_ONLY);
  BindImage(6, s.ReprojectedColor, GL_WRITE_ONLY);
  BindImage(7, s.ReprojectedMoments, GL_WRITE_ONLY);
  BindImage(8, s.Counts, GL_READ_WRITE, GL_R32UI);
  program->SetUniformMatrix4("previousWorldToClip", s.PreviousWorldToClip);
  program->SetUniformi("meshCount", in.Scene ? static_cast<int>(in.Scene->Meshes.size()) : 0);
  s.Motion.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SVGF_MOTION_BINDING);
  program->SetUniformi("hasHistory", this->HasHistory ? 1 : 0);
  program->SetUniformf("depthTolerance", static_cast<float>(this->Settings.DepthTolerance));
  program->SetUniformf("normalTolerance", static_cast<float>(this->Settings.NormalTolerance));
  program->DispatchCovering2D(in.Width, in.Height, LocalSize, LocalSize);
  Barrier();
  program->Unbind(in.Window);
  return true;
}

bool vtkCausticsSVGFDenoiser::Accumulate(const Inputs& in)
{
  auto& s = *this->Internal;
  vtkCausticsShaderProgram* program = s.Programs[TEMPORAL];
  if (!program->Bind(in.Window))
  {
    return false;
  }
  this->SetCommonUniforms(in, TEMPORAL);
  BindImage(2, in.Irradiance, GL_READ_ONLY);
  BindImage(3, s.ReprojectedColor, GL_READ_ONLY);
  BindImage(4, s.ReprojectedMoments, GL_READ_ONLY);
  BindImage(5, s.Filter[0], GL_WRITE_ONLY);
  BindImage(6, s.HistoryMoments, GL_WRITE_ONLY);
  BindImage(7, s.Counts, GL_READ_ONLY, GL_R32UI);
  const caustics::DenoiserSettings& settings = this->Settings;
  program->SetUniformf("temporalAlpha", static_cast<float>(settings.TemporalAlpha));
  program->SetUniformf("momentsAlpha", static_cast<float>(settings.MomentsAlpha));
  program->SetUniformf("maximumFrames", static_cast<float>(settings.MaximumHistoryLength));
  // Light moves over the receivers only when what lights them changes: only a history
  // older than the last change can hold light that is gone (see the shader).
  program->SetUniformf("rejectSigmas", static_cast<float>(settings.HistoryRejectionSigmas));
  program->SetUniformf(
    "framesSinceLightChanged", static_cast<float>(this->FramesSinceLightChanged));
  program->SetUniformf("minimumFraction", static_cast<float>(settings.MinimumReprojectedFraction));
  program->DispatchCovering2D(in.Width, in.Height, LocalSize, LocalSize);
  Barrier();
  program->Unbind(in.Window);
  return true;
}

bool vtkCausticsSVGFDenoiser::EstimateVariance(const Inputs& in)
{
  auto& s = *this->Internal;
  vtkCausticsShaderProgram* program = s.Programs[VARIANCE];
  if (!program->Bind(in.Window))
  {
    return false;
  }
  this->SetCommonUniforms(in, VARIANCE);
  BindImage(2, s.HistoryMoments, GL_READ_ONLY);
  BindImage(3, s.Filter[0], GL_READ_WRITE);
  program->SetUniformf("spatialFrames", static_cast<float>(this->Settings.SpatialVarianceFrames));
  program->SetUniformi(
    "photonVariance", in.PhotonVariance && this->Settings.PhotonVariance ? 1 : 0);
  program->DispatchCovering2D(in.Width, in.Height, LocalSize, LocalSize);
  Barrier();
  program->Unbind(in.Window);
  return true;
}

bool vtkCausticsSVGFDenoiser::FilterAtrous(const Inputs& in)
{
  auto& s = *this->Internal;
  const int iterations = this->Settings.AtrousIterations;
  const int keep = std::min(this->Settings.HistoryIteration, iterations);
  if (keep == 0)
  {
    CopyTexture(s.Filter[0], s.HistoryColor, in.Width, in.Height);
  }
  if (iterations == 0)
  {
    CopyTexture(s.Filter[0], in.Irradiance, in.Width, in.Height);
    Barrier();
    return true;
  }
  for (int i = 0; i < iterations; ++i)
  {
    // The last iteration writes the result where the input was.
    vtkTextureObject* source = s.Filter[i % 2];
    vtkTextureObject* destination = i + 1 == iterations ? in.Irradiance : s.Filter[(i + 1) % 2];
    if (!this->AtrousStage(in, DEVIATION, i, source, s.Deviation) ||
      !this->AtrousStage(in, NORMALIZE, i, source, s.Balance[0]) ||
      !this->AtrousStage(in, BALANCE, i, source, s.Balance[1]) ||
      !this->AtrousStage(in, ATROUS, i, source, destination))
    {
      return false;
    }
    if (i + 1 == keep)
    {
      CopyTexture(destination, s.HistoryColor, in.Width, in.Height);
    }
  }
  return true;
}

bool vtkCausticsSVGFDenoiser::AtrousStage(
  const Inputs& in, int stage, int iteration, vtkTextureObject* source, vtkTextureObject* output)
{
  auto& s = *this->Internal;
  vtkCausticsShaderProgram* program = s.Programs[stage];
  if (!program->Bind(in.Window))
  {
    return false;
  }
  this->SetCommonUniforms(in, stage);
  program->SetUniformf("sigmaLuminance", static_cast<float>(this->Settings.SigmaLuminance));
  program->SetUniformi("stepSize", 1 << iteration);
  BindImage(2, source, GL_READ_ONLY);
  BindImage(3, output, GL_WRITE_ONLY, stage == ATROUS ? GL_RGBA32F : GL_R32F);
  BindImage(4, s.Deviation, GL_READ_ONLY, GL_R32F);
  BindImage(5, s.Balance[stage == ATROUS ? 1 : 0], GL_READ_ONLY, GL_R32F); // the last step's
  program->DispatchCovering2D(in.Width, in.Height, LocalSize, LocalSize);
  Barrier();
  program->Unbind(in.Window);
  return true;
}

void vtkCausticsSVGFDenoiser::KeepForNextFrame(const Inputs& in)
{
  auto& s = *this->Internal;
  CopyTexture(in.GBuffer->GetPositionTexture(), s.PreviousPosition, in.Width, in.Height);
  CopyTexture(in.GBuffer->GetNormalTexture(), s.PreviousNormal, in.Width, in.Height);
  caustics::gl::ToColumnMajor(in.Camera->worldToClip, s.PreviousWorldToClip);
  std::swap(s.Previous, s.Current);
  std::swap(s.PreviousLights, s.CurrentLights);
  Barrier();
  this->HasHistory = true;
  this->FramesSinceReset = std::min(this->FramesSinceReset + 1, 1 << 30);
}

void vtkCausticsSVGFDenoiser::ReleaseGraphicsResources(vtkWindow* w)
{
  auto& s = *this->Internal;
  for (auto& program : s.Programs)
  {
    program->ReleaseGraphicsResources(w);
  }
  vtkTextureObject* textures[] = { s.Raw, s.HistoryColor, s.HistoryMoments, s.ReprojectedColor,
    s.ReprojectedMoments, s.Filter[0], s.Filter[1], s.Deviation, s.Balance[0], s.Balance[1],
    s.PreviousPosition, s.PreviousNormal, s.Counts };
  for (vtkTextureObject* texture : textures)
  {
    texture->ReleaseGraphicsResources(w);
  }
  s.Motion.Release();
  s.Previous.clear();
  s.Current.clear();
  s.PreviousLights.clear();
  s.Released = true;
  this->HasHistory = false;
  this->FramesSinceReset = 0;
}

void vtkCausticsSVGFDenoiser::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const caustics::DenoiserSettings& s = this->Settings;
  os << indent << "TemporalAlpha: " << s.TemporalAlpha << "\n";
  os << indent << "MomentsAlpha: " << s.MomentsAlpha << "\n";
  os << indent << "MaximumHistoryLength: " << s.MaximumHistoryLength << "\n";
  os << indent << "SpatialVarianceFrames: " << s.SpatialVarianceFrames << "\n";
  os << indent << "PhotonVariance: " << (s.PhotonVariance ? "On" : "Off") << "\n";
  os << indent << "AtrousIterations: " << s.AtrousIterations << "\n";
  os << indent << "HistoryIteration: " << s.HistoryIteration << "\n";
  os << indent << "SigmaDepth: " << s.SigmaDepth << "\n";
  os << indent << "SigmaNormal: " << s.SigmaNormal << "\n";
  os << indent << "SigmaLuminance: " << s.SigmaLuminance << "\n";
  os << indent << "HistoryRejectionSigmas: " << s.HistoryRejectionSigmas << "\n";
  os << indent << "DepthTolerance: " << s.DepthTolerance << "\n";
  os << indent << "NormalTolerance: " << s.NormalTolerance << "\n";
  os << indent << "MinimumReprojectedFraction: " << s.MinimumReprojectedFraction << "\n";
  os << indent << "HasHistory: " << this->HasHistory << "\n";
  os << indent << "FramesSinceReset: " << this->FramesSinceReset << "\n";
  os << indent << "FramesSinceLightChanged: " << this->FramesSinceLightChanged << "\n";
  os << indent << "Actors followed: " << this->Internal->Previous.size() << "\n";
}
