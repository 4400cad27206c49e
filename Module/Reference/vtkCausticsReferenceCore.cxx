#include "vtkCausticsReferenceCore.h"

#include "vtkCausticsDensityGrid.h"
#include "vtkSMPTools.h"

#include <embree3/rtcore.h>

#define GLM_ENABLE_EXPERIMENTAL // For glm::compMax (gtx)
#include <glm/glm.hpp>
#include <glm/gtx/component_wise.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <complex>
#include <exception>
#include <limits>
#include <mutex>
#include <new>
#include <sstream>
#include <thread>

namespace caustics
{
namespace
{
const double Pi = 3.14159265358979323846;
const double Infinity = std::numeric_limits<double>::infinity();

using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point from, Clock::time_point to)
{
  return std::chrono::duration<double>(to - from).count();
}

/** caustics::Vec3 (the scene's public type) to GLM and back, at the tracer's boundary. */
inline glm::dvec3 ToGlm(const Vec3& v)
{
  return glm::dvec3(v[0], v[1], v[2]);
}
inline Vec3 ToVec3(const glm::dvec3& v)
{
  return { { v.x, v.y, v.z } };
}

/**
 * Vertices, photon and beam records keep floats. (Not glm::make_vec3, which copies
 * through a temporary vec3 that the compiler keeps in memory: 5 % slower gathers.)
 */
glm::dvec3 FromFloat(const float* v)
{
  return glm::dvec3(v[0], v[1], v[2]);
}
void StoreFloat(const glm::dvec3& v, float* out)
{
  out[0] = static_cast<float>(v.x);
  out[1] = static_cast<float>(v.y);
  out[2] = static_cast<float>(v.z);
}

/** Adds an RGB flux to a statistics entry (which keeps the public Vec3). */
void Accumulate(Vec3& sum, const glm::dvec3& v)
{
  sum[0] += v.x;
  sum[1] += v.y;
  sum[2] += v.z;
}

/** Any unit vector perpendicular to unit w, and a third completing a right-handed basis. */
void Basis(const glm::dvec3& w, glm::dvec3& u, glm::dvec3& v)
{
  const glm::dvec3 helper = std::abs(w.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  u = glm::normalize(glm::cross(w, helper));
  v = glm::cross(w, u);
}

/**
 * Snell refraction of unit d about unit n facing it, eta = etaIncident / etaTransmitted;
 * false on total internal reflection. Not glm::refract: that one does not clamp
 * |cos| <= 1 against rounding and calls grazing TIR (sin^2 = 1) a refraction.
 */
bool RefractDirection(const glm::dvec3& d, const glm::dvec3& n, double eta, glm::dvec3& refracted)
{
  const double cosI = -glm::dot(d, n);
  const double sin2T = eta * eta * std::max(0.0, 1.0 - cosI * cosI);
  if (sin2T >= 1.0)
  {
    return false;
  }
  const double cosT = std::sqrt(1.0 - sin2T);
  refracted = glm::normalize(d * eta + n * (eta * cosI - cosT));
  return true;
}

/** Parameter range [t0, t1] of o + t d, t in [tmin, tmax], inside an axis-aligned box. */
bool ClipToBox(const double box[6], const glm::dvec3& o, const glm::dvec3& d, double tmin,
  double tmax, double& t0, double& t1)
{
  t0 = tmin;
  t1 = tmax;
  for (int axis = 0; axis < 3; ++axis)
  {
    const double lo = box[2 * axis], hi = box[2 * axis + 1];
    if (std::abs(d[axis]) < 1e-300)
    {
      if (o[axis] < lo || o[axis] > hi)
      {
        return false;
      }
      continue;
    }
    double ta = (lo - o[axis]) / d[axis], tb = (hi - o[axis]) / d[axis];
    if (ta > tb)
    {
      std::swap(ta, tb);
    }
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1)
    {
      return false;
    }
  }
  return true;
}

// --- Random numbers: counter-based, so that every photon/pixel has its own stream ---

std::uint64_t Mix64(std::uint64_t z)
{
  z ^= z >> 30;
  z *= 0xbf58476d1ce4e5b9ULL;
  z ^= z >> 27;
  z *= 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/** SplitMix64 stream keyed by (seed, a, b): results never depend on thread scheduling. */
class Random
{
public:
  Random(std::uint64_t seed, std::uint64_t a, std::uint64_t b)
    : State(Mix64(Mix64(seed ^ 0x6a09e667f3bcc909ULL) + a * 0x9e3779b97f4a7c15ULL) ^
        Mix64(b + 0xbb67ae8584caa73bULL))
  {
  }
  /** Uniform in [0, 1) with 53 random bits. */
  double Uniform()
  {
    this->State += 0x9e3779b97f4a7c15ULL;
    return static_cast<double>(Mix64(this->State) >> 11) * 0x1.0p-53;
  }

private:
  std::uint64_t State;
};

// --- Threads ---

/**
 * Runs work(item) for every item in [0, count) with vtkSMPTools, on the threads of
 * the enclosing vtkSMPTools::LocalScope. Results never depend on which thread runs an
 * item (each item owns its random stream and its output slot). Only the calling
 * thread reports progress (VTK observers are not thread-safe); it takes part in the
 * loop, so it sees the count of finished items grow. vtkSMPTools does not carry
 * exceptions out of every backend: the first one is kept, the remaining items are
 * skipped, and it is rethrown here.
 */
void ParallelFor(std::int64_t count, const std::function<void(std::int64_t)>& work,
  const std::function<void(double)>& progress)
{
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<std::int64_t> done(0);
  std::atomic<bool> failed(false);
  std::exception_ptr failure;
  std::mutex failureMutex;
  vtkSMPTools::For(0, count, 1,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType item = begin; item < end && !failed; ++item)
      {
        try
        {
          work(item);
        }
        catch (...)
        {
          std::lock_guard<std::mutex> lock(failureMutex);
          if (!failure)
          {
            failure = std::current_exception();
          }
          failed = true;
          return;
        }
        const std::int64_t finished = ++done;
        if (progress && std::this_thread::get_id() == caller)
        {
          progress(static_cast<double>(finished) / static_cast<double>(count));
        }
      }
    });
  if (failure)
  {
    std::rethrow_exception(failure);
  }
}

/** A ray hit with everything the tracer needs, in double precision. */
struct Hit
{
  double t = 0.0;
  int mesh = -1;
  unsigned int primitive = 0;
  glm::dvec3 position{ 0.0 };
  glm::dvec3 geometricNormal{ 0.0 }; ///< unit face normal, on the side the vertex normals point to
  glm::dvec3 shadingNormal{ 0.0 };   ///< unit interpolated vertex normal
};

/** How photons leave one light: a stratified grid over a rectangle, disk or cone. */
struct Emitter
{
  enum class Shape
  {
    None,
    Rectangle,
    Disk,
    Cone
  };
  Shape shape = Shape::None;
  const Light* light = nullptr;
  glm::dvec3 center{ 0.0 }; ///< rectangle/disk: centre on the emission plane; cone: the apex
  glm::dvec3 u{ 0.0 }, v{ 0.0 }, w{ 0.0 }; ///< w: travel direction (plane normal, cone axis)
  double halfU = 0.0, halfV = 0.0, radius = 0.0, cosMax = 1.0;
  std::int64_t nx = 0, ny = 0;
  double measure = 0.0;         ///< m^2 or sr
  glm::dvec3 photonFlux{ 0.0 }; ///< radiometric x measure / count (spot falloff applied per photon)
  std::int64_t Count() const { return this->nx * this->ny; }
};

/** One step of a photon path: where it is, where it goes, what it carries. */
struct Branch
{
  glm::dvec3 origin{ 0.0 }, direction{ 0.0 }, flux{ 0.0 }, firstHit{ 0.0 };
  int events = 0;
  int inside = -1; ///< mesh index of the refractor the segment runs in, -1 outside
};

/** What one chunk of photons produced; chunks are merged in order (determinism). */
struct ChunkResult
{
  bool beamPass = false; ///< volume photons: beams only; surface photons: deposits only
  std::vector<ReferencePhoton> photons;
  std::vector<ReferenceBeam> beams;
  ReferenceLightStatistics statistics;
  std::vector<Vec3> depositedByEvents;
};

/** Hash grid over the deposits for the surface kernel estimate. */
class PhotonGrid
{
public:
  struct Entry
  {
    float position[3];
    float normal[3];
    float flux[3];
  };

  void Build(const std::vector<ReferencePhoton>& photons, double cell)
  {
    this->Cell = cell;
    std::size_t buckets = 1;
    while (buckets < photons.size())
    {
      buckets <<= 1;
    }
    this->Mask = buckets - 1;
    this->Start.assign(buckets + 1, 0);
    std::vector<std::uint64_t> bucketOf(photons.size());
    for (std::size_t p = 0; p < photons.size(); ++p)
    {
      const float* x = photons[p].position;
      bucketOf[p] = this->Bucket(this->Coord(x[0]), this->Coord(x[1]), this->Coord(x[2]));
      ++this->Start[bucketOf[p] + 1];
    }
    for (std::size_t b = 0; b < buckets; ++b)
    {
      this->Start[b + 1] += this->Start[b];
    }
    // Stable counting sort: photons keep their (deterministic) order inside a bucket.
    std::vector<std::size_t> fill(this->Start.begin(), this->Start.end() - 1);
    this->Entries.resize(photons.size());
    for (std::size_t p = 0; p < photons.size(); ++p)
    {
      Entry& entry = this->Entries[fill[bucketOf[p]]++];
      std::copy(photons[p].position, photons[p].position + 3, entry.position);
      std::copy(photons[p].normal, photons[p].normal + 3, entry.normal);
      std::copy(photons[p].flux, photons[p].flux + 3, entry.flux);
    }
  }

  bool IsEmpty() const { return this->Entries.empty(); }

  /** Irradiance sum_p flux_p K2(|x - x_p|, r) over photons whose normal agrees with n. */
  glm::dvec3 Estimate(const glm::dvec3& x, const glm::dvec3& n, double r, double normalCosine) const
  {
    glm::dvec3 sum{ 0.0 };
    this->ForEachWithin(x, r,
      [&](const Entry& e, double d2)
      {
        if (glm::dot(FromFloat(e.normal), n) >= normalCosine)
        {
          sum += FromFloat(e.flux) * EpanechnikovKernel2D(d2, r);
        }
      });
    return sum;
  }

  /**
   * Flux (W) of the photons whose normal agrees with n, within `tolerance` of the plane
   * (x, n), that fall in the convex quadrilateral `corners` (in order, on that plane)
   * when projected onto it; `r` bounds the corners' distance from x.
   */
  glm::dvec3 FluxInQuad(const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3 corners[4],
    double r, double tolerance, double normalCosine) const
  {
    glm::dvec3 sum{ 0.0 };
    const double turn =
      glm::dot(glm::cross(corners[1] - corners[0], corners[2] - corners[1]), n) >= 0.0 ? 1.0 : -1.0;
    this->ForEachWithin(x, r,
      [&](const Entry& e, double)
      {
        const glm::dvec3 p = FromFloat(e.position);
        const double height = glm::dot(p - x, n);
        if (std::abs(height) > tolerance || glm::dot(FromFloat(e.normal), n) < normalCosine)
        {
          return;
        }
        const glm::dvec3 q = p - height * n;
        for (int k = 0; k < 4; ++k)
        {
          const glm::dvec3& a = corners[k];
          const glm::dvec3& b = corners[(k + 1) % 4];
          if (turn * glm::dot(glm::cross(b - a, q - a), n) < 0.0)
          {
            return;
          }
        }
        sum += FromFloat(e.flux);
      });
    return sum;
  }

  /** Calls visit(entry, squared distance) for every photon within r of x. */
  template <typename Visit>
  void ForEachWithin(const glm::dvec3& x, double r, const Visit& visit) const
  {
    if (this->Entries.empty() || !(r > 0.0))
    {
      return;
    }
    const double r2 = r * r;
    auto accumulate = [&](const Entry& e)
    {
      const glm::dvec3 d = FromFloat(e.position) - x;
      const double d2 = glm::dot(d, d);
      if (d2 < r2)
      {
        visit(e, d2);
      }
    };
    const std::int64_t lo[3] = { this->Coord(x.x - r), this->Coord(x.y - r), this->Coord(x.z - r) };
    const std::int64_t hi[3] = { this->Coord(x.x + r), this->Coord(x.y + r), this->Coord(x.z + r) };
    const double cells =
      double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) * double(hi[2] - lo[2] + 1);
    if (cells > 4096.0)
    {
      // A kernel much larger than the cells (grazing views): a linear scan is cheaper.
      for (const Entry& e : this->Entries)
      {
        accumulate(e);
      }
      return;
    }
    for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
    {
      for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
      {
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
        {
          const std::uint64_t bucket = this->Bucket(i, j, k);
          for (std::size_t p = this->Start[bucket]; p < this->Start[bucket + 1]; ++p)
          {
            const Entry& e = this->Entries[p];
            // Other cells share the bucket; count each photon in its own cell only.
            if (this->Coord(e.position[0]) == i && this->Coord(e.position[1]) == j &&
              this->Coord(e.position[2]) == k)
            {
              accumulate(e);
            }
          }
        }
      }
    }
  }

private:
  std::int64_t Coord(double x) const
  {
    return static_cast<std::int64_t>(std::floor(x / this->Cell));
  }
  std::uint64_t Bucket(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    const std::uint64_t h = static_cast<std::uint64_t>(i) * 0x9e3779b97f4a7c15ULL ^
      static_cast<std::uint64_t>(j) * 0xc2b2ae3d27d4eb4fULL ^
      static_cast<std::uint64_t>(k) * 0x165667b19e3779f9ULL;
    return Mix64(h) & this->Mask;
  }

  double Cell = 1.0;
  std::uint64_t Mask = 0;
  std::vector<std::size_t> Start;
  std::vector<Entry> Entries;
};

void EmbreeErrorCallback(void* userPtr, RTCError code, const char* message)
{
  auto* error = static_cast<std::string*>(userPtr);
  if (error->empty())
  {
    *error = "Embree error " + std::to_string(static_cast<int>(code)) + ": " +
      (message ? message : "(no message)");
  }
}

std::string Name(const SceneData& scene, std::size_t mesh)
{
  const std::string& name = scene.Meshes[mesh].name;
  return "mesh '" + (name.empty() ? "#" + std::to_string(mesh) : name) + "'";
}

bool IsFinite(const Vec3& v)
{
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

bool IsNonNegative(const Vec3& v)
{
  return IsFinite(v) && v[0] >= 0.0 && v[1] >= 0.0 && v[2] >= 0.0;
}
}

// ---------------------------------------------------------------------------------------
// Optics

double FresnelDielectric(double cosIncident, double etaIncident, double etaTransmitted)
{
  if (etaIncident == etaTransmitted)
  {
    return 0.0; // no interface (exactly, so that IOR 1 never spawns reflections)
  }
  const double cosI = std::min(1.0, std::abs(cosIncident));
  const double eta = etaIncident / etaTransmitted;
  const double sin2T = eta * eta * (1.0 - cosI * cosI);
  if (sin2T >= 1.0)
  {
    return 1.0;
  }
  const double cosT = std::sqrt(1.0 - sin2T);
  const double rs =
    (etaIncident * cosI - etaTransmitted * cosT) / (etaIncident * cosI + etaTransmitted * cosT);
  const double rp =
    (etaTransmitted * cosI - etaIncident * cosT) / (etaTransmitted * cosI + etaIncident * cosT);
  return 0.5 * (rs * rs + rp * rp);
}

double FresnelConductor(double cosIncident, double n, double k)
{
  // Amplitude coefficients with the complex index eta = n + ik and the complex
  // cosine of the transmitted angle (principal root: the wave decays inside).
  const double cosI = std::min(1.0, std::abs(cosIncident));
  const std::complex<double> eta(n, k);
  const std::complex<double> sin2T = (1.0 - cosI * cosI) / (eta * eta);
  const std::complex<double> cosT = std::sqrt(1.0 - sin2T);
  const std::complex<double> rParallel = (eta * cosI - cosT) / (eta * cosI + cosT);
  const std::complex<double> rPerpendicular = (cosI - eta * cosT) / (cosI + eta * cosT);
  const double r = 0.5 * (std::norm(rParallel) + std::norm(rPerpendicular));
  return std::isfinite(r) ? std::min(1.0, r) : 1.0;
}

Vec3 Reflect(const Vec3& d, const Vec3& n)
{
  // glm::reflect is d - n (n . d) 2: the same bits as d - (2 n . d) n (scaling by 2 is exact).
  return ToVec3(glm::reflect(ToGlm(d), ToGlm(n)));
}

bool Refract(const Vec3& d, const Vec3& n, double eta, Vec3& refracted)
{
  glm::dvec3 t;
  if (!RefractDirection(ToGlm(d), ToGlm(n), eta, t))
  {
    return false;
  }
  refracted = ToVec3(t);
  return true;
}

double HenyeyGreenstein(double cosTheta, double g)
{
  const double denominator = 1.0 + g * g - 2.0 * g * cosTheta;
  return (1.0 - g * g) / (4.0 * Pi * denominator * std::sqrt(denominator));
}

double EpanechnikovKernel2D(double distanceSquared, double radius)
{
  const double r2 = radius * radius;
  return distanceSquared < r2 ? 2.0 / (Pi * r2) * (1.0 - distanceSquared / r2) : 0.0;
}

double EpanechnikovKernel1D(double distance, double radius)
{
  const double h2 = radius * radius - distance * distance;
  if (!(h2 > 0.0))
  {
    return 0.0;
  }
  const double r2 = radius * radius;
  return 8.0 * h2 * std::sqrt(h2) / (3.0 * Pi * r2 * r2);
}

void ConcentricSquareToDisk(double u, double v, double& x, double& y)
{
  const double a = 2.0 * u - 1.0, b = 2.0 * v - 1.0;
  if (a == 0.0 && b == 0.0)
  {
    x = y = 0.0;
    return;
  }
  double r, phi;
  if (std::abs(a) > std::abs(b))
  {
    r = a;
    phi = 0.25 * Pi * (b / a);
  }
  else
  {
    r = b;
    phi = 0.5 * Pi - 0.25 * Pi * (a / b);
  }
  x = r * std::cos(phi);
  y = r * std::sin(phi);
}

void ReferenceImage::Resize(int w, int h)
{
  this->width = w;
  this->height = h;
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  for (auto* rgb : { &this->caustic, &this->direct, &this->airlight, &this->volumeCaustic,
         &this->transmittance, &this->position, &this->normal, &this->albedo })
  {
    rgb->assign(3 * n, 0.0f);
  }
  this->mask.assign(n, 0.0f);
  this->pixelArea.assign(n, 0.0f);
  this->specular.assign(3 * n, 0.0f);
  this->specularMask.assign(n, 0.0f);
}

// ---------------------------------------------------------------------------------------
// Validation

namespace
{
/** Array sizes, finite vertices and indices in range. */
std::string ValidateMeshArrays(const SceneData& scene, std::size_t m)
{
  const Mesh& mesh = scene.Meshes[m];
  if (mesh.positions.size() % 3 != 0 || mesh.normals.size() != mesh.positions.size())
  {
    return Name(scene, m) + " has " + std::to_string(mesh.positions.size()) +
      " position values and " + std::to_string(mesh.normals.size()) +
      " normal values; both must hold 3 per vertex";
  }
  if (mesh.indices.size() % 3 != 0)
  {
    return Name(scene, m) + " has " + std::to_string(mesh.indices.size()) +
      " indices, not a multiple of 3";
  }
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
  {
    if (!std::isfinite(mesh.positions[i]) || !std::isfinite(mesh.normals[i]))
    {
      return Name(scene, m) + ": vertex " + std::to_string(i / 3) + " has a non-finite " +
        (std::isfinite(mesh.positions[i]) ? "normal" : "position");
    }
  }
  const std::size_t vertices = mesh.positions.size() / 3;
  for (std::size_t i = 0; i < mesh.indices.size(); ++i)
  {
    if (mesh.indices[i] >= vertices)
    {
      return Name(scene, m) + ": triangle " + std::to_string(i / 3) + " refers to vertex " +
        std::to_string(mesh.indices[i]) + " of " + std::to_string(vertices);
    }
  }
  return std::string();
}

/** The role and the coefficients it uses. */
std::string ValidateMaterial(const SceneData& scene, std::size_t m)
{
  const Material& material = scene.Materials[scene.Meshes[m].material];
  const int role = static_cast<int>(material.role);
  if (role < 0 || role > 3)
  {
    return Name(scene, m) + " has an unknown role " + std::to_string(role);
  }
  if (!IsNonNegative(material.albedo))
  {
    return Name(scene, m) + ": albedo must be finite and >= 0";
  }
  if (material.role == Role::Refractor && !(std::isfinite(material.ior) && material.ior > 0.0))
  {
    return Name(scene, m) + ": index of refraction " + std::to_string(material.ior) +
      " must be finite and > 0";
  }
  if (material.role == Role::Refractor && !IsNonNegative(material.attenuation))
  {
    return Name(scene, m) + ": attenuation must be finite and >= 0 (1/m)";
  }
  if (material.role != Role::Reflector)
  {
    return std::string();
  }
  if (!IsNonNegative(material.metalN) || !IsNonNegative(material.metalK))
  {
    return Name(scene, m) + ": complex IOR n, k must be finite and >= 0";
  }
  for (int c = 0; c < 3; ++c)
  {
    if (material.metalN[c] + material.metalK[c] <= 0.0)
    {
      return Name(scene, m) + ": complex IOR n + ik is zero in channel " + std::to_string(c);
    }
  }
  return std::string();
}

std::string ValidateMeshes(const SceneData& scene)
{
  if (scene.Materials.size() != scene.Meshes.size())
  {
    return "the scene has " + std::to_string(scene.Meshes.size()) + " meshes but " +
      std::to_string(scene.Materials.size()) + " materials (one per mesh expected)";
  }
  for (std::size_t m = 0; m < scene.Meshes.size(); ++m)
  {
    const Mesh& mesh = scene.Meshes[m];
    if (mesh.material < 0 || mesh.material >= static_cast<int>(scene.Materials.size()))
    {
      return Name(scene, m) + " refers to material " + std::to_string(mesh.material) +
        ", which does not exist";
    }
    std::string problem = ValidateMeshArrays(scene, m);
    if (problem.empty())
    {
      problem = ValidateMaterial(scene, m);
    }
    if (!problem.empty())
    {
      return problem;
    }
  }
  return std::string();
}

std::string ValidateLight(const Light& light, std::size_t l)
{
  const std::string name = "light " + std::to_string(l);
  const int type = static_cast<int>(light.type);
  if (type < 0 || type > 2)
  {
    return name + " has an unknown type " + std::to_string(type);
  }
  if (!IsNonNegative(light.radiometric))
  {
    return name + ": radiometric value must be finite and >= 0 (W/m^2 or W/sr)";
  }
  if (!IsFinite(light.direction) || std::abs(glm::length(ToGlm(light.direction)) - 1.0) > 1e-6)
  {
    return name + ": direction must be a finite unit vector";
  }
  if (light.type != Light::Type::Directional && !IsFinite(light.position))
  {
    return name + ": position must be finite";
  }
  if (light.type == Light::Type::Spot &&
    !(light.cosOuter >= -1.0 && light.cosOuter <= 1.0 && light.cosInner >= -1.0 &&
      light.cosInner <= 1.0))
  {
    return name + ": spot cone cosines must lie in [-1, 1]";
  }
  return std::string();
}

std::string ValidateViewAndMedium(const SceneData& scene)
{
  const Camera& view = scene.View;
  if (view.width <= 0 || view.height <= 0)
  {
    return "camera image size " + std::to_string(view.width) + " x " + std::to_string(view.height) +
      " must be positive";
  }
  for (int i = 0; i < 16; ++i)
  {
    if (!std::isfinite(view.clipToWorld[i]) || !std::isfinite(view.worldToClip[i]))
    {
      return "camera transform has non-finite entries (degenerate camera?)";
    }
  }
  const Medium& medium = scene.Participating;
  if (!medium.enabled)
  {
    return std::string();
  }
  if (!IsNonNegative(medium.sigmaS) || !IsNonNegative(medium.sigmaA))
  {
    return "medium coefficients must be finite and >= 0 (1/m)";
  }
  if (!(std::abs(medium.g) < 1.0))
  {
    return "medium anisotropy g = " + std::to_string(medium.g) + " must lie in (-1, 1)";
  }
  return std::string();
}
}

std::string ValidateReferenceScene(const SceneData& scene)
{
  std::string problem = ValidateMeshes(scene);
  for (std::size_t l = 0; problem.empty() && l < scene.Lights.size(); ++l)
  {
    problem = ValidateLight(scene.Lights[l], l);
  }
  return problem.empty() ? ValidateViewAndMedium(scene) : problem;
}

/**
 * Residual ratio tracking's estimate of the transmittance along a ray, from its entry
 * into the medium (`start`) to distance s: the control extinction's exponential times
 * the residual's estimate, which is piecewise constant, changing at each tentative
 * collision.
 */
struct TransmittanceTrack
{
  double start = 0.0;
  glm::dvec3 control{ 0.0 };                        ///< 1/m, in closed form
  std::vector<double> at;                           ///< distances of the tentative collisions
  std::vector<glm::dvec3> value{ glm::dvec3(1.0) }; ///< value[k]: after k collisions
  glm::dvec3 At(double s) const
  {
    return glm::exp(control * -(s - start)) *
      value[std::upper_bound(at.begin(), at.end(), s) - at.begin()];
  }
};

// ---------------------------------------------------------------------------------------
// Tracer

struct ReferenceTracer::Internals
{
  const SceneData* Scene = nullptr;
  ReferenceSettings Settings;

  RTCDevice Device = nullptr;
  RTCScene Geometry = nullptr;
  std::string EmbreeError;

  double Bounds[6];         ///< every mesh taking part: also the medium's extent
  double SpecularBounds[6]; ///< reflectors and refractors
  bool HasSpecular = false;
  bool HasGeometry = false;
  double Epsilon = 1e-6; ///< ray offset off surfaces, m

  bool MediumOn = false;
  glm::dvec3 SigmaS{ 0.0 }, SigmaT{ 0.0 }; ///< per unit density
  double G = 0.0;
  /**
   * Heterogeneous medium: the density grid (null: homogeneous, closed forms); for
   * residual ratio tracking, the extinction of the grid's minimum density over the
   * medium (Control, 1/m, taken in closed form) and the majorant of the rest (1/m).
   * MediumBox is where the medium is: Bounds, cut to the grid's bounds with a grid.
   */
  std::shared_ptr<const DensityGrid> Density;
  /**
   * Independent tracks averaged per pixel for what one pixel sees through the medium
   * (its camera ray, its surface's shadow rays): a single track's estimate is very
   * noisy (0 or 1 in the channel of the majorant where the density is uniform), and
   * unlike the airlight's 256 shadow rays or the many beams it is not averaged by
   * anything else. 16 tracks: 4x less noise for a few density samples more per pixel.
   */
  static constexpr int TracksPerPixel = 16;
  double MinimumDensity = 0.0;
  glm::dvec3 Control{ 0.0 };
  double Majorant = 0.0;
  double MediumBox[6];

  std::vector<ReferencePhoton> Photons;
  std::vector<ReferenceBeam> Beams;

  /** Pixel rays and medium intervals of the view pass, reused by the volume pass. */
  std::vector<double> MediumStart, MediumEnd;
  /**
   * Per pixel, with a medium that fills the refractors: the absorption (1/m) of the
   * refractor the camera ray runs in up to its first surface (that surface seen from
   * its back side, as CameraPath decides), which the beams' light also crosses.
   */
  std::vector<glm::dvec3> CameraGlass;
  /** Per pixel, its camera ray's transmittance (heterogeneous medium only). */
  std::vector<TransmittanceTrack> CameraTracks;

  ProgressFunction Progress;
  double ProgressBase = 0.0, ProgressSpan = 1.0, LastReported = -1.0;

  ~Internals() { this->ReleaseEmbree(); }

  void ReleaseEmbree()
  {
    if (this->Geometry)
    {
      rtcReleaseScene(this->Geometry);
      this->Geometry = nullptr;
    }
    if (this->Device)
    {
      rtcReleaseDevice(this->Device);
      this->Device = nullptr;
    }
  }

  void ReportProgress(double stageFraction)
  {
    const double value = this->ProgressBase + this->ProgressSpan * stageFraction;
    if (this->Progress && (value - this->LastReported >= 0.01 || value >= 1.0))
    {
      this->LastReported = value;
      this->Progress(std::min(1.0, value));
    }
  }
  std::function<void(double)> Stage(double base, double span)
  {
    this->ProgressBase = base;
    this->ProgressSpan = span;
    return [this](double fraction) { this->ReportProgress(fraction); };
  }

  const Material& MaterialOf(int mesh) const
  {
    return this->Scene->Materials[this->Scene->Meshes[mesh].material];
  }

  // --- The render's steps ---

  /** Takes the scene and settings, and derives the bounds, the medium and the march step. */
  void Prepare(
    const SceneData& scene, const ReferenceSettings& settings, const ProgressFunction& progress)
  {
    this->Scene = &scene;
    this->Settings = settings;
    this->Progress = progress;
    this->LastReported = -1.0;
    this->ComputeBounds();
    const Medium& medium = scene.Participating;
    this->SigmaS = ToGlm(medium.sigmaS);
    this->SigmaT = ToGlm(medium.sigmaS) + ToGlm(medium.sigmaA);
    this->G = medium.g;
    this->MediumOn = medium.enabled && this->HasGeometry && glm::compMax(this->SigmaT) > 0.0;
    std::copy(this->Bounds, this->Bounds + 6, this->MediumBox);
    this->Density = this->MediumOn ? medium.density : nullptr;
    if (this->Density)
    {
      double grid[6];
      this->Density->GetWorldBounds(grid);
      for (int a = 0; a < 3; ++a)
      {
        this->MediumBox[2 * a] = std::max(this->MediumBox[2 * a], grid[2 * a]);
        this->MediumBox[2 * a + 1] = std::min(this->MediumBox[2 * a + 1], grid[2 * a + 1]);
        this->MediumOn = this->MediumOn && this->MediumBox[2 * a] < this->MediumBox[2 * a + 1];
      }
      this->MediumOn = this->MediumOn && this->Density->GetMajorant() > 0.0;
      this->MinimumDensity = this->Density->GetMinimum(this->MediumBox);
      this->Control = this->SigmaT * this->MinimumDensity;
      this->Majorant =
        glm::compMax(this->SigmaT) * (this->Density->GetMajorant() - this->MinimumDensity);
    }
    if (this->Settings.rayMarchStep <= 0.0)
    {
      const double* b = this->Bounds;
      const double size = this->HasGeometry
        ? std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
            (b[5] - b[4]) * (b[5] - b[4]))
        : 0.0;
      this->Settings.rayMarchStep = size > 0.0 ? size / 256.0 : 1.0;
    }
  }

  /**
   * Runs the stages on Settings.threads threads through a vtkSMPTools::LocalScope
   * (which changes vtkSMPTools' global thread count for its duration, so concurrent
   * renders with different counts are not supported); 0 keeps vtkSMPTools' own count
   * (all cores unless VTK_SMP_MAX_THREADS or vtkSMPTools::Initialize says otherwise).
   */
  void RunStages(ReferenceImage& image, ReferenceStatistics& statistics)
  {
    if (this->Settings.threads > 0)
    {
      vtkSMPTools::LocalScope(vtkSMPTools::Config{ this->Settings.threads },
        [&]() { this->TraceAndEstimate(image, statistics); });
    }
    else
    {
      this->TraceAndEstimate(image, statistics);
    }
  }

  /** Photon tracing, the view pass and the beam estimate, each timed. */
  void TraceAndEstimate(ReferenceImage& image, ReferenceStatistics& statistics)
  {
    const auto photonStart = Clock::now();
    this->Stage(0.0, 0.45);
    if (this->HasGeometry)
    {
      this->TracePhotons(statistics);
    }
    else
    {
      statistics.lights.assign(this->Scene->Lights.size(), ReferenceLightStatistics());
      statistics.depositedByEvents.assign(this->Settings.maxBounces + 1, Vec3{ { 0, 0, 0 } });
    }
    const auto viewStart = Clock::now();
    statistics.photonSeconds = Seconds(photonStart, viewStart);
    this->RenderView(image);
    const auto volumeStart = Clock::now();
    statistics.viewSeconds = Seconds(viewStart, volumeStart);
    this->RenderVolumeCaustics(image);
    statistics.volumeSeconds = Seconds(volumeStart, Clock::now());
    this->Stage(0.0, 1.0);
    this->ReportProgress(1.0);
  }

  /** Frees what only one render needs (the deposits and beams stay for GetPhotons()). */
  void Release()
  {
    this->ReleaseEmbree();
    std::vector<double>().swap(this->MediumStart);
    std::vector<glm::dvec3>().swap(this->CameraGlass);
    std::vector<double>().swap(this->MediumEnd);
    std::vector<TransmittanceTrack>().swap(this->CameraTracks);
    this->Density.reset();
    this->Scene = nullptr;
  }

  // --- Scene set-up ---

  void ComputeBounds()
  {
    const SceneData& scene = *this->Scene;
    for (int i = 0; i < 3; ++i)
    {
      this->Bounds[2 * i] = this->SpecularBounds[2 * i] = Infinity;
      this->Bounds[2 * i + 1] = this->SpecularBounds[2 * i + 1] = -Infinity;
    }
    this->HasSpecular = this->HasGeometry = false;
    double maxAbs = 0.0;
    for (std::size_t m = 0; m < scene.Meshes.size(); ++m)
    {
      const Mesh& mesh = scene.Meshes[m];
      const Role role = this->MaterialOf(static_cast<int>(m)).role;
      if (role == Role::None || mesh.indices.empty())
      {
        continue;
      }
      const bool specular = role == Role::Reflector || role == Role::Refractor;
      this->HasGeometry = true;
      this->HasSpecular = this->HasSpecular || specular;
      for (std::uint32_t index : mesh.indices)
      {
        for (int c = 0; c < 3; ++c)
        {
          const double x = mesh.positions[3 * index + c];
          this->Bounds[2 * c] = std::min(this->Bounds[2 * c], x);
          this->Bounds[2 * c + 1] = std::max(this->Bounds[2 * c + 1], x);
          if (specular)
          {
            this->SpecularBounds[2 * c] = std::min(this->SpecularBounds[2 * c], x);
            this->SpecularBounds[2 * c + 1] = std::max(this->SpecularBounds[2 * c + 1], x);
          }
          maxAbs = std::max(maxAbs, std::abs(x));
        }
      }
    }
    // Vertices are floats: 1e-5 of the largest coordinate is ~100 float ulps, well
    // above the rounding of a hit point, well below any feature worth rendering.
    this->Epsilon = 1e-5 * std::max(maxAbs, 1e-6);
  }

  bool BuildEmbree(std::string& error)
  {
    this->ReleaseEmbree();
    this->EmbreeError.clear();
    this->Device = rtcNewDevice(nullptr);
    if (!this->Device)
    {
      error = "Embree could not create a device (error " +
        std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")";
      return false;
    }
    rtcSetDeviceErrorFunction(this->Device, EmbreeErrorCallback, &this->EmbreeError);
    this->Geometry = rtcNewScene(this->Device);
    // Robust: watertight triangle tests, so photons cannot slip through the edges of
    // a closed refractor.
    rtcSetSceneFlags(this->Geometry, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(this->Geometry, RTC_BUILD_QUALITY_HIGH);
    const SceneData& scene = *this->Scene;
    for (std::size_t m = 0; m < scene.Meshes.size(); ++m)
    {
      const Mesh& mesh = scene.Meshes[m];
      if (this->MaterialOf(static_cast<int>(m)).role == Role::None || mesh.indices.empty())
      {
        continue;
      }
      RTCGeometry geometry = rtcNewGeometry(this->Device, RTC_GEOMETRY_TYPE_TRIANGLE);
      const std::size_t vertices = mesh.positions.size() / 3;
      auto* vertexBuffer = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices));
      auto* indexBuffer =
        static_cast<unsigned int*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
          RTC_FORMAT_UINT3, 3 * sizeof(unsigned int), mesh.TriangleCount()));
      if (!vertexBuffer || !indexBuffer)
      {
        rtcReleaseGeometry(geometry);
        error =
          "Embree could not allocate the buffers of " + Name(scene, m) + ": " + this->EmbreeError;
        return false;
      }
      std::copy(mesh.positions.begin(), mesh.positions.end(), vertexBuffer);
      std::copy(mesh.indices.begin(), mesh.indices.end(), indexBuffer);
      rtcCommitGeometry(geometry);
      rtcAttachGeometryByID(this->Geometry, geometry, static_cast<unsigned int>(m));
      rtcReleaseGeometry(geometry);
    }
    rtcCommitScene(this->Geometry);
    if (!this->EmbreeError.empty())
    {
      error = this->EmbreeError;
      return false;
    }
    return true;
  }

  // --- Ray queries ---

  /**
   * Embree asserts a valid ray (finite origin and direction, 0 <= tnear <= tfar): a
   * degenerate camera or a scene beyond float's range must be refused here, not abort.
   */
  static bool IsValidRay(const RTCRay& ray)
  {
    return std::isfinite(ray.org_x) && std::isfinite(ray.org_y) && std::isfinite(ray.org_z) &&
      std::isfinite(ray.dir_x) && std::isfinite(ray.dir_y) && std::isfinite(ray.dir_z) &&
      ray.tnear >= 0.0f && ray.tfar >= ray.tnear;
  }

  bool Intersect(const glm::dvec3& o, const glm::dvec3& d, double tfar, Hit& hit) const
  {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit query;
    query.ray.org_x = static_cast<float>(o.x);
    query.ray.org_y = static_cast<float>(o.y);
    query.ray.org_z = static_cast<float>(o.z);
    query.ray.dir_x = static_cast<float>(d.x);
    query.ray.dir_y = static_cast<float>(d.y);
    query.ray.dir_z = static_cast<float>(d.z);
    query.ray.tnear = 0.0f;
    query.ray.tfar = tfar >= std::numeric_limits<float>::max()
      ? std::numeric_limits<float>::infinity()
      : static_cast<float>(tfar);
    query.ray.time = 0.0f;
    query.ray.mask = 0xFFFFFFFFu;
    query.ray.id = 0;
    query.ray.flags = 0;
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    if (!IsValidRay(query.ray))
    {
      return false; // nothing is hit along no ray
    }
    rtcIntersect1(this->Geometry, &context, &query);
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID)
    {
      return false;
    }
    hit.t = query.ray.tfar;
    hit.mesh = static_cast<int>(query.hit.geomID);
    hit.primitive = query.hit.primID;
    const Mesh& mesh = this->Scene->Meshes[hit.mesh];
    const std::uint32_t* ids = &mesh.indices[3 * static_cast<std::size_t>(hit.primitive)];
    const glm::dvec3 a = FromFloat(&mesh.positions[3 * ids[0]]),
                     b = FromFloat(&mesh.positions[3 * ids[1]]),
                     c = FromFloat(&mesh.positions[3 * ids[2]]);
    const glm::dvec3 na = FromFloat(&mesh.normals[3 * ids[0]]),
                     nb = FromFloat(&mesh.normals[3 * ids[1]]),
                     nc = FromFloat(&mesh.normals[3 * ids[2]]);
    const double u = query.hit.u, v = query.hit.v, w = 1.0 - u - v;
    // The point from barycentrics in double lies on the triangle's plane (up to
    // double rounding), unlike o + t d in float.
    hit.position = a * w + b * u + c * v;
    // A zero-area triangle keeps a zero face normal (glm::normalize would make NaNs).
    const glm::dvec3 face = glm::cross(b - a, c - a);
    hit.geometricNormal = glm::dot(face, face) > 0.0 ? glm::normalize(face) : face;
    if (glm::dot(hit.geometricNormal, na + nb + nc) < 0.0)
    {
      hit.geometricNormal = -hit.geometricNormal;
    }
    const glm::dvec3 shading = na * w + nb * u + nc * v;
    const double length = glm::length(shading);
    hit.shadingNormal = length > 1e-12 ? shading * (1.0 / length) : hit.geometricNormal;
    if (glm::dot(hit.shadingNormal, hit.geometricNormal) <= 0.0)
    {
      hit.shadingNormal = hit.geometricNormal;
    }
    return true;
  }

  bool Occluded(const glm::dvec3& o, const glm::dvec3& d, double tnear, double tfar) const
  {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray;
    ray.org_x = static_cast<float>(o.x);
    ray.org_y = static_cast<float>(o.y);
    ray.org_z = static_cast<float>(o.z);
    ray.dir_x = static_cast<float>(d.x);
    ray.dir_y = static_cast<float>(d.y);
    ray.dir_z = static_cast<float>(d.z);
    ray.tnear = static_cast<float>(tnear);
    ray.tfar = tfar >= std::numeric_limits<float>::max() ? std::numeric_limits<float>::infinity()
                                                         : static_cast<float>(tfar);
    ray.time = 0.0f;
    ray.mask = 0xFFFFFFFFu;
    ray.id = 0;
    ray.flags = 0;
    if (!IsValidRay(ray))
    {
      return true; // no light travels along no ray
    }
    rtcOccluded1(this->Geometry, &context, &ray);
    return ray.tfar < 0.0f;
  }

  /**
   * Origin of a ray leaving a surface point: Epsilon off the surface on the side the
   * ray leaves towards. It moves along the ray itself, so that the ray's line still
   * passes through the point (an offset along the normal would shift it sideways by
   * Epsilon); only rays within ~0.6 degrees of the surface are also lifted off it.
   */
  glm::dvec3 Offset(
    const glm::dvec3& position, const glm::dvec3& normal, const glm::dvec3& direction) const
  {
    const double cosine = glm::dot(direction, normal);
    const double along = this->Epsilon / std::max(std::abs(cosine), 0.01);
    glm::dvec3 origin = position + direction * along;
    const double lift = this->Epsilon - along * std::abs(cosine);
    if (lift > 0.0)
    {
      origin += normal * (cosine >= 0.0 ? lift : -lift);
    }
    return origin;
  }

  /**
   * Medium transmittance along o + t d for t in [0, length] (the medium fills
   * MediumBox): in closed form when homogeneous, else the mean of `tracks`
   * estimates by residual ratio tracking.
   */
  glm::dvec3 Transmittance(
    const glm::dvec3& o, const glm::dvec3& d, double length, Random& random, int tracks) const
  {
    double t0, t1;
    if (!this->MediumOn || !ClipToBox(this->MediumBox, o, d, 0.0, length, t0, t1) || t1 <= t0)
    {
      return glm::dvec3(1, 1, 1);
    }
    if (this->Density)
    {
      glm::dvec3 residual(0.0);
      for (int k = 0; k < tracks; ++k)
      {
        residual += this->TrackResidual(o, d, t0, t1, random, [](double, const glm::dvec3&) {});
      }
      return glm::exp(this->Control * -(t1 - t0)) * (residual / static_cast<double>(tracks));
    }
    return glm::exp(this->SigmaT * -(t1 - t0));
  }

  /**
   * Residual ratio tracking (Novak, Selle and Jarosz 2014, "Residual ratio tracking
   * for estimating attenuation in participating media") over [t0, t1] of o + t d in
   * the heterogeneous medium. The extinction splits into the control, sigma_t x the
   * grid's minimum density over the medium, whose transmittance
   * exp(-Control (t1 - t0)) the caller takes in closed form, and the residual
   * sigma_t x (density - minimum), estimated here: tentative collisions at the rate of
   * its majorant, each multiplying the estimate by 1 - residual(x) / majorant per
   * channel; `visit(t, estimate)` after each. Unbiased for any majorant >= the
   * residual. Ratio rather than delta tracking: delta tracking's estimate is 0 or 1,
   * ratio tracking's weights vary smoothly, per RGB channel with one set of
   * collisions, for far less noise at the same cost (one density sample per
   * collision); the control makes a constant density exact (no collision at all).
   * Stops early once every channel is 0.
   */
  template <typename Visit>
  glm::dvec3 TrackResidual(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1,
    Random& random, Visit&& visit) const
  {
    glm::dvec3 estimate(1.0);
    if (!(this->Majorant > 0.0))
    {
      return estimate;
    }
    for (double t = t0;;)
    {
      t -= std::log(1.0 - random.Uniform()) / this->Majorant;
      if (!(t < t1))
      {
        return estimate;
      }
      const double residual = this->DensityAt(o + d * t) - this->MinimumDensity;
      estimate *= glm::dvec3(1.0) - this->SigmaT * (residual / this->Majorant);
      visit(t, estimate);
      if (!(glm::compMax(estimate) > 0.0))
      {
        return estimate;
      }
    }
  }

  /** Density at x (heterogeneous medium only). */
  double DensityAt(const glm::dvec3& x) const { return this->Density->Sample(ToVec3(x)); }

  /** Scattering coefficient at x, 1/m: sigma_s, times the density when there is a grid. */
  glm::dvec3 ScatteringAt(const glm::dvec3& x) const
  {
    return this->Density ? this->SigmaS * this->DensityAt(x) : this->SigmaS;
  }

  /**
   * Transmittance from the camera ray's entry into the medium (at sa) to distance s:
   * closed form, or the pixel's ratio-tracked `track` in a heterogeneous medium.
   */
  glm::dvec3 ToCamera(const TransmittanceTrack* track, double s, double sa) const
  {
    return track ? track->At(s) : glm::exp(this->SigmaT * -(s - sa));
  }

  // --- Photon emission ---

  /**
   * The domain photons of one light are aimed at: the sphere bounding the specular
   * objects, with a 1% margin so that rounding never trims the silhouette.
   */
  struct Target
  {
    glm::dvec3 center{ 0.0 };
    double margin = 0.0; ///< added to the specular box on every side
    double radius = 0.0; ///< of the sphere, margin included
  };

  Emitter MakeEmitter(const Light& light, std::int64_t requested) const
  {
    Emitter e;
    e.light = &light;
    if (!this->HasSpecular || requested <= 0 || glm::compMax(ToGlm(light.radiometric)) <= 0.0)
    {
      return e;
    }
    const double* sb = this->SpecularBounds;
    Target target;
    target.center = glm::dvec3(0.5 * (sb[0] + sb[1]), 0.5 * (sb[2] + sb[3]), 0.5 * (sb[4] + sb[5]));
    const glm::dvec3 half(0.5 * (sb[1] - sb[0]), 0.5 * (sb[3] - sb[2]), 0.5 * (sb[5] - sb[4]));
    target.margin = 0.01 * glm::length(half) + this->Epsilon;
    target.radius = glm::length(half) + target.margin;
    if (light.type == Light::Type::Directional)
    {
      this->AimParallel(e, target, requested);
    }
    else
    {
      AimCone(e, target, requested);
    }
    if (!(e.measure > 0.0))
    {
      e.shape = Emitter::Shape::None;
      e.nx = e.ny = 0;
      return e;
    }
    e.photonFlux = ToGlm(light.radiometric) * (e.measure / static_cast<double>(e.Count()));
    return e;
  }

  /**
   * Directional light: the rectangle covering the projection of the (margin-expanded)
   * specular box, or the disk covering the target sphere, whichever is smaller, on a
   * plane before every mesh.
   */
  void AimParallel(Emitter& e, const Target& target, std::int64_t requested) const
  {
    e.w = glm::normalize(ToGlm(e.light->direction));
    Basis(e.w, e.u, e.v);
    double lo[2], hi[2];
    this->ProjectSpecularBox(e, target, lo, hi);
    const double rectangle = (hi[0] - lo[0]) * (hi[1] - lo[1]);
    const double disk = Pi * target.radius * target.radius;
    const double reach = this->SceneReach(target.center) + (target.radius + this->Epsilon);
    if (rectangle <= disk)
    {
      e.shape = Emitter::Shape::Rectangle;
      e.halfU = 0.5 * (hi[0] - lo[0]);
      e.halfV = 0.5 * (hi[1] - lo[1]);
      e.center =
        target.center + e.u * (0.5 * (lo[0] + hi[0])) + e.v * (0.5 * (lo[1] + hi[1])) - e.w * reach;
      e.measure = rectangle;
      // Strata about square: nx / ny follows the rectangle's aspect ratio.
      const double aspect = e.halfV > 0.0 ? e.halfU / e.halfV : 1.0;
      e.nx = std::max<std::int64_t>(
        1, std::min<std::int64_t>(requested, std::llround(std::sqrt(requested * aspect))));
      e.ny = std::max<std::int64_t>(1, requested / e.nx);
    }
    else
    {
      e.shape = Emitter::Shape::Disk;
      e.radius = target.radius;
      e.center = target.center - e.w * reach;
      e.measure = disk;
      e.nx = e.ny =
        std::max<std::int64_t>(1, static_cast<std::int64_t>(std::sqrt(double(requested))));
    }
  }

  /** Extent [lo, hi] of the margin-expanded specular box along e.u and e.v. */
  void ProjectSpecularBox(const Emitter& e, const Target& target, double lo[2], double hi[2]) const
  {
    const double* sb = this->SpecularBounds;
    const double margin = target.margin;
    lo[0] = lo[1] = Infinity;
    hi[0] = hi[1] = -Infinity;
    for (int corner = 0; corner < 8; ++corner)
    {
      const glm::dvec3 p(corner & 1 ? sb[1] + margin : sb[0] - margin,
        corner & 2 ? sb[3] + margin : sb[2] - margin, corner & 4 ? sb[5] + margin : sb[4] - margin);
      const double pu = glm::dot(p - target.center, e.u), pv = glm::dot(p - target.center, e.v);
      lo[0] = std::min(lo[0], pu);
      hi[0] = std::max(hi[0], pu);
      lo[1] = std::min(lo[1], pv);
      hi[1] = std::max(hi[1], pv);
    }
  }

  /** Largest distance from `center` to a corner of the whole scene's bounds. */
  double SceneReach(const glm::dvec3& center) const
  {
    double reach = 0.0;
    for (int corner = 0; corner < 8; ++corner)
    {
      const glm::dvec3 p(this->Bounds[corner & 1 ? 1 : 0], this->Bounds[corner & 2 ? 3 : 2],
        this->Bounds[corner & 4 ? 5 : 4]);
      reach = std::max(reach, glm::length(p - center));
    }
    return reach;
  }

  /**
   * Point and spot lights: the cap subtending the target sphere (every direction from
   * inside it), or the spot's outer cone when that is narrower (no wasted photons).
   */
  static void AimCone(Emitter& e, const Target& target, std::int64_t requested)
  {
    const Light& light = *e.light;
    e.shape = Emitter::Shape::Cone;
    e.center = ToGlm(light.position);
    const glm::dvec3 toCenter = target.center - e.center;
    const double distance = glm::length(toCenter);
    glm::dvec3 axis = distance > 0.0 ? toCenter * (1.0 / distance) : ToGlm(light.direction);
    double cosMax = -1.0;
    if (distance > target.radius)
    {
      cosMax = std::sqrt(1.0 - (target.radius / distance) * (target.radius / distance));
    }
    if (light.type == Light::Type::Spot && light.cosOuter > cosMax)
    {
      axis = ToGlm(light.direction);
      cosMax = light.cosOuter;
    }
    e.w = glm::normalize(axis);
    Basis(e.w, e.u, e.v);
    e.cosMax = cosMax;
    e.measure = 2.0 * Pi * (1.0 - cosMax);
    e.nx = e.ny =
      std::max<std::int64_t>(1, static_cast<std::int64_t>(std::sqrt(double(requested))));
  }

  /** Photon `index`: a jittered sample in its stratum. */
  Branch Emit(const Emitter& e, std::int64_t index, Random& random) const
  {
    Branch b;
    const double su = (static_cast<double>(index % e.nx) + random.Uniform()) / e.nx;
    const double sv = (static_cast<double>(index / e.nx) + random.Uniform()) / e.ny;
    b.flux = e.photonFlux;
    switch (e.shape)
    {
      case Emitter::Shape::Rectangle:
        b.origin =
          e.center + e.u * (e.halfU * (2.0 * su - 1.0)) + e.v * (e.halfV * (2.0 * sv - 1.0));
        b.direction = e.w;
        break;
      case Emitter::Shape::Disk:
      {
        double x, y;
        ConcentricSquareToDisk(su, sv, x, y);
        b.origin = e.center + e.u * (e.radius * x) + e.v * (e.radius * y);
        b.direction = e.w;
        break;
      }
      case Emitter::Shape::Cone:
      {
        // Disk to cap, equal-area: cos(theta) = 1 - rho^2 (1 - cosMax).
        double x, y;
        ConcentricSquareToDisk(su, sv, x, y);
        const double rho2 = x * x + y * y, rho = std::sqrt(rho2);
        const double cosTheta = 1.0 - rho2 * (1.0 - e.cosMax);
        const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
        glm::dvec3 d = e.w * cosTheta;
        if (rho > 0.0)
        {
          d += (e.u * x + e.v * y) * (sinTheta / rho);
        }
        b.origin = e.center;
        b.direction = glm::normalize(d);
        b.flux = b.flux * e.light->SpotFactor(glm::dot(b.direction, ToGlm(e.light->direction)));
        break;
      }
      case Emitter::Shape::None:
        break;
    }
    return b;
  }

  // --- Photon tracing ---

  /** Largest ratio of the branch's flux to the photon's emitted flux over channels. */
  static double Weight(const glm::dvec3& flux, const glm::dvec3& emitted)
  {
    double w = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      if (emitted[c] > 0.0)
      {
        w = std::max(w, flux[c] / emitted[c]);
      }
    }
    return w;
  }

  /** Russian roulette below the threshold (unbiased); false when the branch dies. */
  bool Survives(glm::dvec3& flux, const glm::dvec3& emitted, Random& random, ChunkResult& out) const
  {
    const double w = Weight(flux, emitted);
    const double threshold = this->Settings.rouletteThreshold;
    if (w >= threshold)
    {
      return true;
    }
    if (!(w > 0.0))
    {
      return false;
    }
    const double q = w / threshold;
    if (random.Uniform() < q)
    {
      const glm::dvec3 boosted = flux * (1.0 / q);
      Accumulate(out.statistics.roulette, flux - boosted);
      flux = boosted;
      return true;
    }
    Accumulate(out.statistics.roulette, flux);
    return false;
  }

  void Deposit(const Branch& s, const Hit& hit, int lightIndex, ChunkResult& out) const
  {
    ReferencePhoton photon;
    StoreFloat(hit.position, photon.position);
    const glm::dvec3 facing =
      glm::dot(s.direction, hit.geometricNormal) < 0.0 ? hit.geometricNormal : -hit.geometricNormal;
    StoreFloat(facing, photon.normal);
    StoreFloat(s.direction, photon.direction);
    StoreFloat(s.flux, photon.flux);
    StoreFloat(s.firstHit, photon.firstHit);
    photon.mesh = static_cast<std::uint32_t>(hit.mesh);
    photon.light = static_cast<std::uint16_t>(lightIndex);
    photon.events = static_cast<std::uint8_t>(s.events);
    out.photons.push_back(photon);
    Accumulate(out.statistics.deposited, s.flux);
    ++out.statistics.photonsDeposited;
    Accumulate(out.depositedByEvents[s.events], s.flux);
  }

  /**
   * Follows one branch until it is absorbed, escapes, is deposited, or splits at a
   * dielectric (its children go on `stack`).
   */
  void FollowBranch(Branch s, const glm::dvec3& emitted, int lightIndex, Random& random,
    std::vector<Branch>& stack, ChunkResult& out) const
  {
    for (;;)
    {
      Hit hit;
      const bool found = this->Intersect(s.origin, s.direction, Infinity, hit);
      if (!found && s.inside >= 0)
      {
        Accumulate(out.statistics.escaped, s.flux); // an open refractor mesh
        return;
      }
      this->Attenuate(s, found ? hit.t : Infinity, random, out);
      if (!found)
      {
        Accumulate(out.statistics.escaped, s.flux);
        return;
      }
      const Material& material = this->MaterialOf(hit.mesh);
      if (material.role == Role::Receiver)
      {
        if (s.events == 0)
        {
          Accumulate(out.statistics.direct, s.flux);
        }
        else if (!out.beamPass)
        {
          this->Deposit(s, hit, lightIndex, out);
        }
        return;
      }
      if (s.events >= this->Settings.maxBounces)
      {
        Accumulate(out.statistics.bounceLimit, s.flux);
        return;
      }
      ++s.events;
      if (s.events == 1)
      {
        s.firstHit = hit.position;
      }
      if (material.role != Role::Reflector)
      {
        this->SplitAtDielectric(s, hit, material, emitted, random, stack, out);
        return;
      }
      if (!this->ReflectOffConductor(s, hit, material, emitted, random, out))
      {
        return;
      }
    }
  }

  /**
   * Losses along the segment of length `length` just travelled: Beer-Lambert inside
   * a refractor, extinction in the medium (which also records the segment as a beam
   * in the beam pass) in air, and inside refractors when the medium fills them.
   */
  void Attenuate(Branch& s, double length, Random& random, ChunkResult& out) const
  {
    // The refractor's own absorption, 1/m (0 in air).
    const glm::dvec3 glass =
      s.inside >= 0 ? ToGlm(this->MaterialOf(s.inside).attenuation) : glm::dvec3(0.0);
    if (s.inside < 0 || this->Scene->Participating.fillsRefractors)
    {
      this->Extinguish(s, length, glass, random, out);
    }
    if (glm::compMax(glass) > 0.0)
    {
      Absorb(s, s.flux * glm::exp(glass * -length), out);
    }
  }

  /**
   * The medium's extinction along the segment (before the refractor's absorption
   * `glass`, which the caller takes after it), recording the beams in the beam pass:
   * each beam's flux at its start has lost the refractor's share up to there, and
   * decays by it along the beam (ReferenceBeam::attenuation).
   */
  void Extinguish(
    Branch& s, double length, const glm::dvec3& glass, Random& random, ChunkResult& out) const
  {
    double t0, t1;
    if (!this->MediumOn ||
      !ClipToBox(this->MediumBox, s.origin, s.direction, 0.0, length, t0, t1) || !(t1 > t0))
    {
      return;
    }
    const bool beams = out.beamPass && s.events > 0;
    if (!this->Density)
    {
      if (beams)
      {
        out.beams.push_back(MakeBeam(s, s.flux * glm::exp(glass * -t0), t0, t1, glass));
      }
      Absorb(s, s.flux * glm::exp(this->SigmaT * -(t1 - t0)), out);
      return;
    }
    // The residual's estimate is constant between tentative collisions: the segment
    // becomes one beam per piece, whose flux decays along it by the control (and the
    // refractor's absorption) only.
    double from = t0;
    glm::dvec3 flux = s.flux;
    auto piece = [&](double to)
    {
      if (beams && glm::compMax(flux) > 0.0)
      {
        out.beams.push_back(MakeBeam(s, flux * glm::exp(glass * -from), from, to, glass));
      }
    };
    const glm::dvec3 residual = this->TrackResidual(s.origin, s.direction, t0, t1, random,
      [&](double t, const glm::dvec3& estimate)
      {
        piece(t);
        from = t;
        flux = s.flux * glm::exp(this->Control * -(t - t0)) * estimate;
      });
    piece(t1);
    Absorb(s, s.flux * glm::exp(this->Control * -(t1 - t0)) * residual, out);
  }

  /** The branch keeps `kept` of its flux; the rest counts as absorbed. */
  static void Absorb(Branch& s, const glm::dvec3& kept, ChunkResult& out)
  {
    Accumulate(out.statistics.absorbed, s.flux - kept);
    s.flux = kept;
  }

  /**
   * The part [t0, t1] of a branch's segment that lies in the medium, with `flux` at t0,
   * inside a refractor absorbing `glass` (1/m; 0 in air).
   */
  static ReferenceBeam MakeBeam(
    const Branch& s, const glm::dvec3& flux, double t0, double t1, const glm::dvec3& glass)
  {
    ReferenceBeam beam;
    StoreFloat(s.origin + s.direction * t0, beam.start);
    StoreFloat(s.direction, beam.direction);
    beam.length = static_cast<float>(t1 - t0);
    StoreFloat(flux, beam.flux);
    StoreFloat(glass, beam.attenuation);
    return beam;
  }

  /**
   * The hit's face and shading normals turned to the side the ray arrives from; true
   * when that is the front (the side the vertex normals point to).
   */
  static bool FacingNormals(
    const glm::dvec3& direction, const Hit& hit, glm::dvec3& ng, glm::dvec3& ns)
  {
    const bool front = glm::dot(direction, hit.geometricNormal) < 0.0;
    ng = front ? hit.geometricNormal : -hit.geometricNormal;
    ns = front ? hit.shadingNormal : -hit.shadingNormal;
    return front;
  }

  /**
   * Conductor: mirror reflection weighted by the complex-index Fresnel reflectance per
   * channel. False when Russian roulette ends the branch.
   */
  bool ReflectOffConductor(Branch& s, const Hit& hit, const Material& material,
    const glm::dvec3& emitted, Random& random, ChunkResult& out) const
  {
    glm::dvec3 ng, n;
    FacingNormals(s.direction, hit, ng, n);
    glm::dvec3 r = glm::reflect(s.direction, n);
    // Interpolated normals can send the ray into the surface: fall back on the face.
    if (glm::dot(s.direction, n) >= 0.0 || glm::dot(r, ng) <= 0.0)
    {
      n = ng;
      r = glm::reflect(s.direction, n);
    }
    const double cosI = -glm::dot(s.direction, n);
    glm::dvec3 fresnel{ 0.0 };
    for (int c = 0; c < 3; ++c)
    {
      fresnel[c] = FresnelConductor(cosI, material.metalN[c], material.metalK[c]);
    }
    Absorb(s, s.flux * fresnel, out);
    s.origin = this->Offset(hit.position, ng, r);
    s.direction = r;
    return this->Survives(s.flux, emitted, random, out);
  }

  /**
   * Fresnel reflectance and the reflected and refracted directions of d on normal n
   * (shading or face), from index etaI into etaT. True when both directions leave on
   * their proper side of the actual (flat) face ng.
   */
  static bool ScatterDielectric(const glm::dvec3& d, const glm::dvec3& n, const glm::dvec3& ng,
    double etaI, double etaT, double& reflectance, glm::dvec3& reflected, glm::dvec3& refracted)
  {
    reflectance = FresnelDielectric(-glm::dot(d, n), etaI, etaT);
    reflected = glm::reflect(d, n);
    if (!(reflectance < 1.0 && RefractDirection(d, n, etaI / etaT, refracted)))
    {
      reflectance = 1.0;
    }
    return glm::dot(d, n) < 0.0 && glm::dot(reflected, ng) > 0.0 &&
      (reflectance >= 1.0 || glm::dot(refracted, ng) < 0.0);
  }

  /**
   * Dielectric: the branch splits into its reflected (flux x R) and refracted (flux x
   * (1 - R)) children, which go on `stack` unless Russian roulette ends them.
   */
  void SplitAtDielectric(const Branch& s, const Hit& hit, const Material& material,
    const glm::dvec3& emitted, Random& random, std::vector<Branch>& stack, ChunkResult& out) const
  {
    glm::dvec3 ng, ns;
    const bool front = FacingNormals(s.direction, hit, ng, ns);
    // Entering when the ray meets the outward face normal head-on.
    const double etaI = front ? 1.0 : material.ior;
    const double etaT = front ? material.ior : 1.0;
    double reflectance;
    glm::dvec3 reflected{ 0.0 }, refracted{ 0.0 };
    if (!ScatterDielectric(s.direction, ns, ng, etaI, etaT, reflectance, reflected, refracted))
    {
      ScatterDielectric(s.direction, ng, ng, etaI, etaT, reflectance, reflected, refracted);
    }
    Branch children[2];
    int count = 0;
    if (reflectance > 0.0)
    {
      children[count++] = this->Child(
        s, s.flux * reflectance, reflected, hit.position, ng, front ? s.inside : hit.mesh);
    }
    if (reflectance < 1.0)
    {
      children[count++] = this->Child(
        s, s.flux * (1.0 - reflectance), refracted, hit.position, ng, front ? hit.mesh : -1);
    }
    for (int i = 0; i < count; ++i)
    {
      if (this->Survives(children[i].flux, emitted, random, out))
      {
        stack.push_back(children[i]);
      }
    }
  }

  /** A branch leaving `position` along `direction` with `flux`, inside refractor `inside`. */
  Branch Child(const Branch& parent, const glm::dvec3& flux, const glm::dvec3& direction,
    const glm::dvec3& position, const glm::dvec3& ng, int inside) const
  {
    Branch child = parent;
    child.flux = flux;
    child.direction = direction;
    child.origin = this->Offset(position, ng, direction);
    child.inside = inside;
    return child;
  }

  void TraceChunk(const Emitter& emitter, int lightIndex, std::int64_t begin, std::int64_t end,
    ChunkResult& out) const
  {
    out.depositedByEvents.assign(this->Settings.maxBounces + 1, Vec3{ { 0, 0, 0 } });
    // Volume photons draw from other streams than surface photons: independent sets.
    const std::uint64_t stream =
      static_cast<std::uint64_t>(lightIndex) + (out.beamPass ? (std::uint64_t(1) << 32) : 0);
    std::vector<Branch> stack;
    for (std::int64_t index = begin; index < end; ++index)
    {
      Random random(this->Settings.seed, stream, static_cast<std::uint64_t>(index));
      const Branch start = this->Emit(emitter, index, random);
      Accumulate(out.statistics.emitted, start.flux);
      if (!(glm::compMax(start.flux) > 0.0))
      {
        continue;
      }
      stack.clear();
      stack.push_back(start);
      while (!stack.empty())
      {
        const Branch branch = stack.back();
        stack.pop_back();
        this->FollowBranch(branch, start.flux, lightIndex, random, stack, out);
      }
    }
  }

  /**
   * Traces one light's photons in chunks on all threads and merges the chunks in
   * order. Surface photons add their deposits and statistics; volume photons (an
   * independent set, only with a medium) add their beams.
   */
  void TraceLight(int light, const Emitter& emitter, bool beamPass, ReferenceStatistics& statistics,
    const std::function<void(double)>& progress)
  {
    const std::int64_t chunkSize = 2048;
    const std::int64_t chunks = (emitter.Count() + chunkSize - 1) / chunkSize;
    std::vector<ChunkResult> results(static_cast<std::size_t>(chunks));
    ParallelFor(
      chunks,
      [&](std::int64_t chunk)
      {
        results[chunk].beamPass = beamPass;
        this->TraceChunk(emitter, light, chunk * chunkSize,
          std::min(emitter.Count(), (chunk + 1) * chunkSize), results[chunk]);
      },
      progress);
    for (ChunkResult& chunk : results)
    {
      this->MergeChunk(chunk, statistics.lights[light], statistics);
    }
  }

  /** Moves one chunk's records into the tracer and adds up its statistics. */
  void MergeChunk(
    ChunkResult& chunk, ReferenceLightStatistics& total, ReferenceStatistics& statistics)
  {
    this->Beams.insert(this->Beams.end(), chunk.beams.begin(), chunk.beams.end());
    std::vector<ReferenceBeam>().swap(chunk.beams); // free as we go
    if (chunk.beamPass)
    {
      return;
    }
    this->Photons.insert(this->Photons.end(), chunk.photons.begin(), chunk.photons.end());
    std::vector<ReferencePhoton>().swap(chunk.photons);
    const ReferenceLightStatistics& s = chunk.statistics;
    total.photonsDeposited += s.photonsDeposited;
    Accumulate(total.emitted, ToGlm(s.emitted));
    Accumulate(total.direct, ToGlm(s.direct));
    Accumulate(total.deposited, ToGlm(s.deposited));
    Accumulate(total.escaped, ToGlm(s.escaped));
    Accumulate(total.absorbed, ToGlm(s.absorbed));
    Accumulate(total.bounceLimit, ToGlm(s.bounceLimit));
    Accumulate(total.roulette, ToGlm(s.roulette));
    for (std::size_t k = 0; k < chunk.depositedByEvents.size(); ++k)
    {
      Accumulate(statistics.depositedByEvents[k], ToGlm(chunk.depositedByEvents[k]));
    }
  }

  void TracePhotons(ReferenceStatistics& statistics)
  {
    const SceneData& scene = *this->Scene;
    const int lights = static_cast<int>(scene.Lights.size());
    statistics.lights.assign(lights, ReferenceLightStatistics());
    statistics.depositedByEvents.assign(this->Settings.maxBounces + 1, Vec3{ { 0, 0, 0 } });
    for (int l = 0; l < lights; ++l)
    {
      const Emitter emitter = this->MakeEmitter(scene.Lights[l], this->Settings.photonsPerLight);
      statistics.lights[l].emissionMeasure = emitter.measure;
      statistics.lights[l].photonsEmitted = emitter.Count();
      if (emitter.shape == Emitter::Shape::None)
      {
        continue;
      }
      this->TraceLight(l, emitter, false, statistics,
        [&](double fraction) { this->ReportProgress((l + 0.8 * fraction) / lights); });
      if (this->MediumOn)
      {
        const Emitter volume =
          this->MakeEmitter(scene.Lights[l], this->Settings.volumePhotonsPerLight);
        this->TraceLight(l, volume, true, statistics,
          [&](double fraction) { this->ReportProgress((l + 0.8 + 0.2 * fraction) / lights); });
      }
    }
    statistics.beams = static_cast<std::int64_t>(this->Beams.size());
  }

  // --- Camera view ---

  /** Length of pixel ray (i, j) from its near-plane origin to the far plane. */
  double FarDistance(double i, double j, const glm::dvec3& origin) const
  {
    const Camera& view = this->Scene->View;
    const double ndcX = 2.0 * (i + 0.5) / view.width - 1.0;
    const double ndcY = 2.0 * (j + 0.5) / view.height - 1.0;
    const double clip[4] = { ndcX, ndcY, 1.0, 1.0 };
    double world[4];
    for (int r = 0; r < 4; ++r)
    {
      world[r] = view.clipToWorld[4 * r] * clip[0] + view.clipToWorld[4 * r + 1] * clip[1] +
        view.clipToWorld[4 * r + 2] * clip[2] + view.clipToWorld[4 * r + 3] * clip[3];
    }
    const glm::dvec3 far(world[0] / world[3], world[1] / world[3], world[2] / world[3]);
    const double distance = glm::length(far - origin);
    return std::isfinite(distance) ? distance : Infinity;
  }

  void PixelRay(double i, double j, glm::dvec3& origin, glm::dvec3& direction) const
  {
    Vec3 o, d;
    this->Scene->View.PixelRay(i, j, o, d);
    origin = ToGlm(o);
    direction = ToGlm(d);
  }

  /**
   * Pixel (i, j)'s footprint on the plane (x, n): where its corner rays meet it, in
   * order around the pixel. False where one misses it (a grazing view).
   */
  bool FootprintCorners(
    int i, int j, const glm::dvec3& x, const glm::dvec3& n, glm::dvec3 corners[4]) const
  {
    const double offsets[4][2] = { { -0.5, -0.5 }, { 0.5, -0.5 }, { 0.5, 0.5 }, { -0.5, 0.5 } };
    bool valid = true;
    for (int c = 0; c < 4 && valid; ++c)
    {
      glm::dvec3 o{ 0.0 }, d{ 0.0 };
      this->PixelRay(i + offsets[c][0], j + offsets[c][1], o, d);
      const double denominator = glm::dot(d, n);
      const double t = glm::dot(x - o, n) / denominator;
      valid = std::abs(denominator) > 1e-9 && t > 0.0 && std::isfinite(t);
      corners[c] = o + d * t;
    }
    return valid;
  }

  /** Receiver area seen by pixel (i, j) around x: its corner rays on the tangent plane. */
  double PixelArea(int i, int j, const glm::dvec3& x, const glm::dvec3& n, double distance) const
  {
    glm::dvec3 corners[4];
    const bool valid = this->FootprintCorners(i, j, x, n, corners);
    double area =
      valid ? 0.5 * glm::length(glm::cross(corners[2] - corners[0], corners[3] - corners[1])) : 0.0;
    if (!(area > 0.0) || !std::isfinite(area))
    {
      // A corner ray misses the tangent plane (grazing view): use the pixel's
      // spread at this distance over the obliquity instead.
      glm::dvec3 o0, d0, o1, d1;
      this->PixelRay(i, j, o0, d0);
      this->PixelRay(i + 1, j, o1, d1);
      const double spread = glm::length((o1 - o0) + (d1 - d0) * distance);
      area = spread * spread / std::max(std::abs(glm::dot(d0, n)), 1e-3);
    }
    return area;
  }

  /**
   * Unshadowed light arriving at x from one light: the direction towards it, its
   * distance (infinite for directional lights) and the irradiance on a surface facing
   * it (E, or I x spot falloff / d^2). False when none arrives.
   */
  static bool Incident(const Light& light, const glm::dvec3& x, glm::dvec3& toLight,
    double& distance, glm::dvec3& incident)
  {
    incident = ToGlm(light.radiometric);
    distance = Infinity;
    if (light.type == Light::Type::Directional)
    {
      toLight = -ToGlm(light.direction);
    }
    else
    {
      const glm::dvec3 offset = ToGlm(light.position) - x;
      distance = glm::length(offset);
      if (!(distance > 0.0))
      {
        return false;
      }
      toLight = offset * (1.0 / distance);
      incident = incident *
        (light.SpotFactor(-glm::dot(toLight, ToGlm(light.direction))) / (distance * distance));
    }
    return glm::compMax(incident) > 0.0;
  }

  /** Shadowed irradiance at a surface point from every light, no specular event. */
  glm::dvec3 DirectIrradiance(
    const glm::dvec3& x, const glm::dvec3& ng, const glm::dvec3& ns, Random& random) const
  {
    glm::dvec3 total{ 0.0 };
    for (const Light& light : this->Scene->Lights)
    {
      glm::dvec3 toLight{ 0.0 }, incident{ 0.0 };
      double distance;
      if (!Incident(light, x, toLight, distance, incident))
      {
        continue;
      }
      const double cosine = glm::dot(ns, toLight);
      if (cosine <= 0.0 || glm::dot(ng, toLight) <= 0.0)
      {
        continue;
      }
      const glm::dvec3 origin = this->Offset(x, ng, toLight);
      const double reach = std::isfinite(distance)
        ? glm::length(ToGlm(light.position) - origin) - this->Epsilon
        : Infinity;
      if (reach <= 0.0 || this->Occluded(origin, toLight, 0.0, reach))
      {
        continue;
      }
      total +=
        incident * this->Transmittance(origin, toLight, reach, random, TracksPerPixel) * cosine;
    }
    return total;
  }

  /**
   * Single-scattered direct light along the camera ray, ray-marched with shadow rays;
   * `track`: the ray's transmittance in a heterogeneous medium (else null).
   */
  glm::dvec3 Airlight(const glm::dvec3& o, const glm::dvec3& v, double t0, double t1,
    const TransmittanceTrack* track, Random& random) const
  {
    glm::dvec3 radiance{ 0.0 };
    const double step = this->Settings.rayMarchStep;
    const std::int64_t steps = std::max<std::int64_t>(1, std::llround(std::ceil((t1 - t0) / step)));
    const double delta = (t1 - t0) / static_cast<double>(steps);
    for (std::int64_t k = 0; k < steps; ++k)
    {
      // One jittered sample per stratum: unbiased, no banding.
      const double s = t0 + (static_cast<double>(k) + random.Uniform()) * delta;
      const glm::dvec3 x = o + v * s;
      const glm::dvec3 scattering = this->ScatteringAt(x);
      if (this->Density && !(glm::compMax(scattering) > 0.0))
      {
        continue; // no density here: no shadow rays
      }
      const glm::dvec3 toCamera = this->ToCamera(track, s, t0);
      for (const Light& light : this->Scene->Lights)
      {
        glm::dvec3 toLight{ 0.0 }, incident{ 0.0 };
        double distance;
        if (!Incident(light, x, toLight, distance, incident) ||
          this->Occluded(x, toLight, this->Epsilon, distance))
        {
          continue;
        }
        // Light travels along -toLight, leaves towards the camera along -v.
        const double phase = HenyeyGreenstein(glm::dot(toLight, v), this->G);
        // One track per step: the march's steps average them.
        radiance += scattering * incident * this->Transmittance(x, toLight, distance, random, 1) *
          toCamera * (phase * delta);
      }
    }
    return radiance;
  }

  /**
   * Pass 1: visibility, geometry buffers, direct light, airlight; pass 2: the caustic
   * gather at the receiver pixels.
   */
  void RenderView(ReferenceImage& image)
  {
    const Camera& view = this->Scene->View;
    const std::size_t pixels = static_cast<std::size_t>(view.width) * view.height;
    image.Resize(view.width, view.height);
    this->MediumStart.assign(pixels, 0.0);
    this->MediumEnd.assign(pixels, 0.0);
    const bool filled = this->MediumOn && this->Scene->Participating.fillsRefractors;
    this->CameraGlass.assign(filled ? pixels : 0, glm::dvec3(0.0));
    this->CameraTracks.assign(this->Density ? pixels : 0, TransmittanceTrack());
    std::vector<double> radii(pixels, 0.0);
    std::vector<Hit> hits(pixels);
    ParallelFor(
      view.height,
      [&](std::int64_t row)
      {
        for (int i = 0; i < view.width; ++i)
        {
          this->ShadePixel(i, static_cast<int>(row), hits, radii, image);
        }
      },
      this->Stage(0.45, 0.35));
    PhotonGrid grid;
    double cell = 0.0;
    if (!this->Photons.empty() && GridCell(radii, cell))
    {
      grid.Build(this->Photons, cell);
    }
    this->GatherCaustics(grid, hits, radii, image);
    this->ShadeSpecularPixels(grid, hits, radii, image);
  }

  /** Pixel (i, j): its first visible surface, what lies there, and the medium before it. */
  void ShadePixel(
    int i, int j, std::vector<Hit>& hits, std::vector<double>& radii, ReferenceImage& image)
  {
    const std::size_t id = static_cast<std::size_t>(j) * this->Scene->View.width + i;
    glm::dvec3 o{ 0.0 }, v{ 0.0 };
    this->PixelRay(i, j, o, v);
    const double far = this->FarDistance(i, j, o);
    Hit& hit = hits[id];
    const bool found = this->FirstVisibleSurface(o, v, far, hit);
    if (found && !this->CameraGlass.empty() &&
      this->MaterialOf(hit.mesh).role == Role::Refractor &&
      glm::dot(v, hit.geometricNormal) > 0.0)
    {
      this->CameraGlass[id] = ToGlm(this->MaterialOf(hit.mesh).attenuation);
    }
    if (found)
    {
      this->ShadeSurface(i, j, id, v, hit, radii[id], image);
    }
    this->ShadeMedium(id, o, v, found ? hit.t : far, image);
  }

  /**
   * The camera ray's first surface within `far`. Optionally it looks through
   * refractors, unbent, as the GPU's opaque G-buffer does.
   */
  bool FirstVisibleSurface(const glm::dvec3& o, const glm::dvec3& v, double far, Hit& hit) const
  {
    hit.mesh = -1;
    bool found = this->HasGeometry && this->Intersect(o, v, far, hit);
    while (found && !this->Settings.cameraSeesRefractors &&
      this->MaterialOf(hit.mesh).role == Role::Refractor)
    {
      const glm::dvec3 next = this->Offset(hit.position, hit.geometricNormal, v);
      const double skipped = glm::length(next - o);
      found = this->Intersect(next, v, far - skipped, hit);
      hit.t += found ? skipped : 0.0;
    }
    return found;
  }

  /**
   * Geometry buffers of a visible surface (its normals turned to the camera), and on a
   * receiver its albedo, pixel area, kernel radius and direct irradiance.
   */
  void ShadeSurface(int i, int j, std::size_t id, const glm::dvec3& v, Hit& hit, double& radius,
    ReferenceImage& image) const
  {
    glm::dvec3 ng, ns;
    FacingNormals(v, hit, ng, ns);
    StoreFloat(hit.position, &image.position[3 * id]);
    StoreFloat(ns, &image.normal[3 * id]);
    const Material& material = this->MaterialOf(hit.mesh);
    if (material.role != Role::Receiver)
    {
      // Glass or a mirror: pass 3 follows the camera's paths from it
      // (ShadeSpecularPixels); the pixel's footprint there sizes their caustic kernel.
      // The hit keeps its own normals: they tell CameraPath whether the camera ray
      // enters the glass or leaves it (a camera inside the glass sees the way out
      // first; turned to the camera, every first hit looked like an entry from air).
      image.specularMask[id] = 1.0f;
      radius = -this->Settings.kernelRadiusPixels *
        std::sqrt(this->PixelArea(i, j, hit.position, ng, hit.t));
      return;
    }
    hit.geometricNormal = ng;
    hit.shadingNormal = ns;
    image.mask[id] = 1.0f;
    StoreFloat(ToGlm(material.albedo), &image.albedo[3 * id]);
    const double area = this->PixelArea(i, j, hit.position, hit.geometricNormal, hit.t);
    image.pixelArea[id] = static_cast<float>(area);
    radius = this->Settings.kernelRadius > 0.0
      ? this->Settings.kernelRadius
      : this->Settings.kernelRadiusPixels * std::sqrt(area);
    // Its own stream: ratio tracking towards the lights in a heterogeneous medium.
    Random random(this->Settings.seed ^ 0x5bd1e995ULL, 0x9e37ULL + id, 2);
    StoreFloat(this->DirectIrradiance(hit.position, hit.geometricNormal, hit.shadingNormal, random),
      &image.direct[3 * id]);
  }

  /**
   * Transmittance to the camera and airlight along the camera ray's part [0, end]
   * inside the medium; the interval is kept for the beam estimate.
   */
  void ShadeMedium(
    std::size_t id, const glm::dvec3& o, const glm::dvec3& v, double end, ReferenceImage& image)
  {
    glm::dvec3 transmittance(1, 1, 1);
    double t0, t1;
    if (this->MediumOn && ClipToBox(this->MediumBox, o, v, 0.0, end, t0, t1) && t1 > t0)
    {
      this->MediumStart[id] = t0;
      this->MediumEnd[id] = t1;
      Random random(this->Settings.seed ^ 0x5bd1e995ULL, 0x9e37ULL + id, 1);
      const TransmittanceTrack* track = nullptr;
      if (this->Density)
      {
        // Tracked once per pixel: the airlight and every beam read it.
        TransmittanceTrack& camera = this->CameraTracks[id];
        this->TrackCameraRay(o, v, t0, t1, random, camera);
        track = &camera;
        transmittance = camera.At(t1);
      }
      else
      {
        transmittance = glm::exp(this->SigmaT * -(t1 - t0));
      }
      StoreFloat(this->Airlight(o, v, t0, t1, track, random), &image.airlight[3 * id]);
    }
    StoreFloat(transmittance, &image.transmittance[3 * id]);
  }

  /**
   * The mean of TracksPerPixel residual ratio tracks along the camera ray's part
   * [t0, t1] in the medium, as one piecewise-constant track: each track's changes,
   * divided by their count, merged in order of distance.
   */
  void TrackCameraRay(const glm::dvec3& o, const glm::dvec3& v, double t0, double t1,
    Random& random, TransmittanceTrack& camera) const
  {
    camera.start = t0;
    camera.control = this->Control;
    std::vector<std::pair<double, glm::dvec3>> changes;
    for (int k = 0; k < TracksPerPixel; ++k)
    {
      glm::dvec3 previous(1.0);
      this->TrackResidual(o, v, t0, t1, random,
        [&](double t, const glm::dvec3& estimate)
        {
          changes.emplace_back(t, (estimate - previous) / static_cast<double>(TracksPerPixel));
          previous = estimate;
        });
    }
    std::sort(changes.begin(), changes.end(),
      [](const std::pair<double, glm::dvec3>& a, const std::pair<double, glm::dvec3>& b)
      { return a.first < b.first; });
    glm::dvec3 mean(1.0);
    for (const auto& change : changes)
    {
      mean += change.second;
      camera.at.push_back(change.first);
      camera.value.push_back(mean);
    }
  }

  /**
   * The photons' irradiance at x on a receiver with normal n, kernel radius r: the
   * photon grid's estimate divided by the share of its kernel that lies on receivers
   * (KernelCoverage), so that it does not fall off where the receiver ends.
   */
  glm::dvec3 CausticEstimate(
    const PhotonGrid& grid, const glm::dvec3& x, const glm::dvec3& n, double r) const
  {
    const glm::dvec3 sum = grid.Estimate(x, n, r, this->Settings.kernelNormalCosine);
    const bool lit = sum.x > 0.0 || sum.y > 0.0 || sum.z > 0.0;
    return lit ? sum * (1.0 / this->KernelCoverage(x, n, r)) : sum;
  }

  /**
   * The photons' irradiance averaged over pixel (i, j)'s footprint on the receiver at x
   * (normal n; its corner rays on the tangent plane): the flux landing in it over its
   * area, with no kernel (Settings.pixelFootprint). Where a corner ray misses the
   * plane (a grazing view), the kernel estimate of radius r.
   */
  glm::dvec3 FootprintEstimate(
    const PhotonGrid& grid, int i, int j, const glm::dvec3& x, const glm::dvec3& n, double r) const
  {
    glm::dvec3 corners[4];
    if (!this->FootprintCorners(i, j, x, n, corners))
    {
      return this->CausticEstimate(grid, x, n, r);
    }
    const double area =
      0.5 * glm::length(glm::cross(corners[2] - corners[0], corners[3] - corners[1]));
    double reach = 0.0;
    for (const glm::dvec3& corner : corners)
    {
      reach = std::max(reach, glm::length(corner - x));
    }
    if (!(area > 0.0) || !std::isfinite(area) || !std::isfinite(reach))
    {
      return this->CausticEstimate(grid, x, n, r);
    }
    // Photons on the pixel's own surface: within half the footprint's mean side of its
    // plane (the kernel estimate's ball allows its whole radius).
    return grid.FluxInQuad(x, n, corners, 1.0001 * reach, 0.5 * std::sqrt(area),
             this->Settings.kernelNormalCosine) *
      (1.0 / area);
  }

  /**
   * The share of the gather kernel (radius r about x on a receiver with normal n)
   * that lies on receivers the estimate takes photons from, at least 1/4. A kernel
   * across a receiver's end (a floor meeting a wall, a table's edge, the pool's floor
   * along its walls) holds photons from its covered part only, and the estimate,
   * normalized for the whole disc, fell off towards the end: the pool's floor read
   * 1 to 3 % low along its walls. Probed by short rays along -n through fixed points
   * of the disc: first eight on its rim, which is all that a kernel far from any end
   * needs; else 36 points (a 6 x 6 grid mapped to the disc), weighted by the kernel.
   */
  double KernelCoverage(const glm::dvec3& x, const glm::dvec3& n, double r) const
  {
    glm::dvec3 e1, e2;
    Basis(n, e1, e2);
    bool rimCovered = true;
    for (int k = 0; k < 8 && rimCovered; ++k)
    {
      const double angle = k * (Pi / 4.0);
      rimCovered = this->ReceiverUnder(
        x + 0.85 * r * (std::cos(angle) * e1 + std::sin(angle) * e2), n, r);
    }
    if (rimCovered)
    {
      return 1.0;
    }
    const int side = 6;
    double covered = 0.0, total = 0.0;
    for (int j = 0; j < side; ++j)
    {
      for (int i = 0; i < side; ++i)
      {
        double u, v;
        ConcentricSquareToDisk((i + 0.5) / side, (j + 0.5) / side, u, v);
        const double weight = 1.0 - (u * u + v * v);
        total += weight;
        covered += this->ReceiverUnder(x + r * (u * e1 + v * e2), n, r) ? weight : 0.0;
      }
    }
    return std::max(covered / total, 0.25);
  }

  /**
   * Whether a receiver passes within r/2 of point y of a kernel's disc (normal n),
   * with a normal the photon estimate accepts: the first such surface along a ray
   * from r/2 above y down to r/2 below it (glass and other surfaces in between are
   * passed through).
   */
  bool ReceiverUnder(const glm::dvec3& y, const glm::dvec3& n, double r) const
  {
    const double h = 0.5 * r;
    glm::dvec3 origin = y + h * n;
    double left = 2.0 * h;
    for (int crossings = 0; crossings < 8 && left > 0.0; ++crossings)
    {
      Hit hit;
      if (!this->Intersect(origin, -n, left, hit))
      {
        return false;
      }
      if (this->MaterialOf(hit.mesh).role == Role::Receiver &&
        std::abs(glm::dot(hit.geometricNormal, n)) >= this->Settings.kernelNormalCosine)
      {
        return true;
      }
      const double step = hit.t + this->Epsilon;
      origin -= step * n;
      left -= step;
    }
    return false;
  }

  /**
   * Pass 2: caustic irradiance from the deposits at every receiver pixel. Grid cells of
   * the median kernel radius keep most queries to 27 cells.
   */
  void GatherCaustics(const PhotonGrid& grid, const std::vector<Hit>& hits,
    const std::vector<double>& radii, ReferenceImage& image)
  {
    if (grid.IsEmpty())
    {
      return;
    }
    const int width = this->Scene->View.width;
    ParallelFor(
      this->Scene->View.height,
      [&](std::int64_t row)
      {
        for (int i = 0; i < width; ++i)
        {
          const std::size_t id = static_cast<std::size_t>(row) * width + i;
          if (image.mask[id] == 0.0f || !(radii[id] > 0.0) || !std::isfinite(radii[id]))
          {
            continue;
          }
          const Hit& hit = hits[id];
          StoreFloat(this->Settings.pixelFootprint
              ? this->FootprintEstimate(
                  grid, i, static_cast<int>(row), hit.position, hit.geometricNormal, radii[id])
              : this->CausticEstimate(grid, hit.position, hit.geometricNormal, radii[id]),
            &image.caustic[3 * id]);
        }
      },
      this->Stage(0.8, 0.05));
  }

  /**
   * Pass 3: what the camera sees on glass and mirrors, in display units (VTK's
   * Lambertian convention: albedo x irradiance), averaged over `specularSamples`
   * camera paths per pixel whose first visible surface is specular (radii < 0 mark
   * them, |radius| the caustic kernel's radius there).
   */
  void ShadeSpecularPixels(const PhotonGrid& grid, const std::vector<Hit>& hits,
    const std::vector<double>& radii, ReferenceImage& image)
  {
    const int samples = this->Settings.specularSamples;
    const int width = this->Scene->View.width;
    if (samples <= 0)
    {
      std::fill(image.specularMask.begin(), image.specularMask.end(), 0.0f);
      return;
    }
    ParallelFor(
      this->Scene->View.height,
      [&](std::int64_t row)
      {
        for (int i = 0; i < width; ++i)
        {
          const std::size_t id = static_cast<std::size_t>(row) * width + i;
          if (image.specularMask[id] == 0.0f)
          {
            continue;
          }
          glm::dvec3 o{ 0.0 }, v{ 0.0 };
          this->PixelRay(i, static_cast<int>(row), o, v);
          // The camera ray's length to its first surface, from the eye (a parallel
          // view: from the near plane).
          const Camera& view = this->Scene->View;
          const double fromEye = view.parallel
            ? hits[id].t
            : glm::distance(ToGlm(view.position), hits[id].position);
          Random random(this->Settings.seed ^ 0x27d4eb2fULL, 0x85ebULL + id, 3);
          glm::dvec3 sum{ 0.0 };
          for (int k = 0; k < samples; ++k)
          {
            sum += this->CameraPath(v, hits[id], fromEye, grid, -radii[id], random);
          }
          StoreFloat(sum * (1.0 / samples), &image.specular[3 * id]);
        }
      },
      this->Stage(0.85, 0.05));
  }

  /**
   * One camera path leaving along v from the specular surface `hit`: at a dielectric
   * it reflects with probability R (Fresnel) and refracts otherwise, which keeps the
   * estimate unbiased with weight 1; a mirror reflects, weighted by its conductor
   * Fresnel reflectance; Beer-Lambert inside glass. It ends on a receiver, with
   * albedo x (direct + caustic irradiance there, the caustic from the photons with
   * kernel radius `radius`), or leaving the scene, with the background; black after
   * maxBounces events. The medium in air is not applied. A first surface that is a
   * refractor seen from its back side means the eye is in that refractor (as the GPU's
   * camera view decides): its absorption over the `fromEye` metres the ray crossed.
   */
  glm::dvec3 CameraPath(glm::dvec3 v, Hit hit, double fromEye, const PhotonGrid& grid,
    double radius, Random& random) const
  {
    glm::dvec3 throughput{ 1.0 };
    int inside = -1;
    if (this->MaterialOf(hit.mesh).role == Role::Refractor &&
      glm::dot(v, hit.geometricNormal) > 0.0)
    {
      throughput *= glm::exp(ToGlm(this->MaterialOf(hit.mesh).attenuation) * -fromEye);
    }
    for (int event = 0; event <= this->Settings.maxBounces; ++event)
    {
      const Material& material = this->MaterialOf(hit.mesh);
      glm::dvec3 ng, ns;
      const bool front = FacingNormals(v, hit, ng, ns);
      if (material.role == Role::Receiver)
      {
        const glm::dvec3 caustic = grid.IsEmpty()
          ? glm::dvec3(0.0)
          : this->CausticEstimate(grid, hit.position, ng, radius);
        return throughput * ToGlm(material.albedo) *
          (this->DirectIrradiance(hit.position, ng, ns, random) + caustic);
      }
      glm::dvec3 next{ 0.0 };
      if (material.role == Role::Reflector)
      {
        glm::dvec3 n = ns;
        next = glm::reflect(v, n);
        if (glm::dot(v, n) >= 0.0 || glm::dot(next, ng) <= 0.0)
        {
          n = ng; // an interpolated normal that sends the ray into the surface
          next = glm::reflect(v, n);
        }
        const double cosI = -glm::dot(v, n);
        for (int c = 0; c < 3; ++c)
        {
          throughput[c] *= FresnelConductor(cosI, material.metalN[c], material.metalK[c]);
        }
      }
      else
      {
        const double etaI = front ? 1.0 : material.ior;
        const double etaT = front ? material.ior : 1.0;
        double reflectance;
        glm::dvec3 reflected{ 0.0 }, refracted{ 0.0 };
        if (!ScatterDielectric(v, ns, ng, etaI, etaT, reflectance, reflected, refracted))
        {
          ScatterDielectric(v, ng, ng, etaI, etaT, reflectance, reflected, refracted);
        }
        if (random.Uniform() < reflectance)
        {
          next = reflected;
        }
        else
        {
          next = refracted;
          inside = front ? hit.mesh : -1;
        }
      }
      Hit following;
      if (!this->Intersect(this->Offset(hit.position, ng, next), next, Infinity, following))
      {
        return inside >= 0 ? glm::dvec3(0.0) : throughput * ToGlm(this->Settings.background);
      }
      if (inside >= 0)
      {
        throughput *= glm::exp(ToGlm(this->MaterialOf(inside).attenuation) * -following.t);
      }
      v = next;
      hit = following;
    }
    return glm::dvec3(0.0);
  }

  /** Median of the positive finite values; false when there is none. */
  /**
   * The photon grid's cell: the median kernel radius of the receivers the camera sees,
   * or, when it sees none (a view filled by a mirror or glass), of the specular pixels'
   * camera paths (stored negated), whose caustic would otherwise be lost.
   */
  static bool GridCell(const std::vector<double>& radii, double& cell)
  {
    if (MedianPositive(radii, cell))
    {
      return true;
    }
    std::vector<double> specular(radii.size());
    std::transform(radii.begin(), radii.end(), specular.begin(), [](double r) { return -r; });
    return MedianPositive(specular, cell);
  }

  static bool MedianPositive(const std::vector<double>& values, double& median)
  {
    std::vector<double> positive;
    for (double r : values)
    {
      if (r > 0.0 && std::isfinite(r))
      {
        positive.push_back(r);
      }
    }
    if (positive.empty())
    {
      return false;
    }
    std::nth_element(positive.begin(), positive.begin() + positive.size() / 2, positive.end());
    median = positive[positive.size() / 2];
    return true;
  }

  // --- Volume caustics: beam radiance estimate ---

  /** Beam ends in continuous pixel coordinates, clipped to the near plane. */
  bool ProjectBeam(const ReferenceBeam& beam, double p[2][2]) const
  {
    const Camera& view = this->Scene->View;
    const glm::dvec3 a = FromFloat(beam.start);
    const glm::dvec3 b = a + FromFloat(beam.direction) * static_cast<double>(beam.length);
    double clip[2][4];
    for (int e = 0; e < 2; ++e)
    {
      const glm::dvec3& x = e == 0 ? a : b;
      for (int r = 0; r < 4; ++r)
      {
        clip[e][r] = view.worldToClip[4 * r] * x.x + view.worldToClip[4 * r + 1] * x.y +
          view.worldToClip[4 * r + 2] * x.z + view.worldToClip[4 * r + 3];
      }
    }
    // Near plane in clip space: z + w >= 0.
    const double f0 = clip[0][2] + clip[0][3], f1 = clip[1][2] + clip[1][3];
    if (f0 < 0.0 && f1 < 0.0)
    {
      return false;
    }
    if (f0 < 0.0 || f1 < 0.0)
    {
      const double t = f0 / (f0 - f1);
      const int moved = f0 < 0.0 ? 0 : 1;
      for (int r = 0; r < 4; ++r)
      {
        clip[moved][r] = clip[0][r] + t * (clip[1][r] - clip[0][r]);
      }
    }
    for (int e = 0; e < 2; ++e)
    {
      const double w = clip[e][3];
      if (!(w > 0.0))
      {
        return false;
      }
      p[e][0] = (clip[e][0] / w * 0.5 + 0.5) * view.width;
      p[e][1] = (clip[e][1] / w * 0.5 + 0.5) * view.height;
    }
    return std::isfinite(p[0][0] + p[0][1] + p[1][0] + p[1][1]);
  }

  /**
   * Screen tiles of 16 x 16 pixels, each listing the beams (indices into the current
   * batch) whose kernel may reach it.
   */
  struct BeamTiles
  {
    static const int Size = 16;
    int tilesX = 0, tilesY = 0;
    double reach = 0.0; ///< pixels: how far from its projected line a beam's kernel reaches
    std::vector<std::array<double, 4>> projected; ///< per beam of the batch: its ends, pixels
    std::vector<std::vector<std::uint32_t>> lists;

    BeamTiles(int width, int height, double kernelPixels)
      : tilesX((width + Size - 1) / Size)
      , tilesY((height + Size - 1) / Size)
      // c pixel footprints, plus slack for the footprint varying across a pixel in
      // perspective.
      , reach(1.1 * kernelPixels + 1.5)
    {
    }

    /** Lists beam `index`, projected to pixel coordinates p, in the tiles it reaches. */
    void Add(std::uint32_t index, const double p[2][2])
    {
      this->projected[index] = { { p[0][0], p[0][1], p[1][0], p[1][1] } };
      const double reach = this->reach;
      const double lo[2] = { std::min(p[0][0], p[1][0]) - reach,
        std::min(p[0][1], p[1][1]) - reach };
      const double hi[2] = { std::max(p[0][0], p[1][0]) + reach,
        std::max(p[0][1], p[1][1]) + reach };
      const int tx0 = std::max(0, static_cast<int>(std::floor(lo[0] / Size)));
      const int ty0 = std::max(0, static_cast<int>(std::floor(lo[1] / Size)));
      const int tx1 = std::min(this->tilesX - 1, static_cast<int>(std::floor(hi[0] / Size)));
      const int ty1 = std::min(this->tilesY - 1, static_cast<int>(std::floor(hi[1] / Size)));
      const double sx = p[1][0] - p[0][0], sy = p[1][1] - p[0][1];
      const double length2 = sx * sx + sy * sy;
      const double tileHalfDiagonal = Size * 0.5 * std::sqrt(2.0);
      for (int ty = ty0; ty <= ty1; ++ty)
      {
        for (int tx = tx0; tx <= tx1; ++tx)
        {
          // Distance from the tile centre to the projected segment.
          const double cx = (tx + 0.5) * Size, cy = (ty + 0.5) * Size;
          double t = length2 > 0.0 ? ((cx - p[0][0]) * sx + (cy - p[0][1]) * sy) / length2 : 0.0;
          t = std::min(1.0, std::max(0.0, t));
          const double dx = p[0][0] + t * sx - cx, dy = p[0][1] + t * sy - cy;
          if (dx * dx + dy * dy <= (tileHalfDiagonal + reach) * (tileHalfDiagonal + reach))
          {
            this->lists[static_cast<std::size_t>(ty) * this->tilesX + tx].push_back(index);
          }
        }
      }
    }
  };

  /**
   * Beams are binned to screen tiles in batches (bounded memory); tiles are then
   * shaded in parallel, each pixel summing its beams in index order (deterministic).
   */
  void RenderVolumeCaustics(ReferenceImage& image)
  {
    if (!this->MediumOn || this->Beams.empty())
    {
      return;
    }
    const Camera& view = this->Scene->View;
    BeamTiles tiles(view.width, view.height, this->Settings.volumeKernelRadiusPixels);
    std::vector<double> accumulated(3 * static_cast<std::size_t>(view.width) * view.height, 0.0);
    const std::size_t batch = std::size_t(1) << 20;
    for (std::size_t first = 0; first < this->Beams.size(); first += batch)
    {
      const std::size_t last = std::min(this->Beams.size(), first + batch);
      this->BinBeams(first, last, tiles);
      ParallelFor(
        static_cast<std::int64_t>(tiles.lists.size()),
        [&](std::int64_t tile)
        {
          const std::vector<std::uint32_t>& list = tiles.lists[tile];
          if (!list.empty())
          {
            this->ShadeTile(static_cast<int>(tile % tiles.tilesX) * BeamTiles::Size,
              static_cast<int>(tile / tiles.tilesX) * BeamTiles::Size, BeamTiles::Size, list,
              tiles.projected, first, tiles.reach, accumulated);
          }
        },
        this->Stage(0.85 + 0.15 * double(first) / this->Beams.size(),
          0.15 * double(last - first) / this->Beams.size()));
    }
    for (std::size_t k = 0; k < accumulated.size(); ++k)
    {
      image.volumeCaustic[k] = static_cast<float>(accumulated[k]);
    }
  }

  /** Projects the beams [first, last) and lists them in the tiles they reach. */
  void BinBeams(std::size_t first, std::size_t last, BeamTiles& tiles) const
  {
    tiles.projected.assign(last - first, std::array<double, 4>());
    tiles.lists.assign(static_cast<std::size_t>(tiles.tilesX) * tiles.tilesY, {});
    for (std::size_t b = first; b < last; ++b)
    {
      double p[2][2];
      if (this->ProjectBeam(this->Beams[b], p))
      {
        tiles.Add(static_cast<std::uint32_t>(b - first), p);
      }
    }
  }

  /** A pixel's camera ray in a tile, its spread to the next pixel, and its beam sum. */
  struct TileRay
  {
    glm::dvec3 origin{ 0.0 }, direction{ 0.0 }, spreadOrigin{ 0.0 }, spreadDirection{ 0.0 },
      sum{ 0.0 };
    double start = 0.0, end = 0.0;             ///< the ray's part in the medium
    const TransmittanceTrack* track = nullptr; ///< heterogeneous medium: its transmittance
    glm::dvec3 glass{ 0.0 }; ///< the absorption of the refractor it runs in (CameraGlass)
    double eyeToOrigin = 0.0; ///< m from the eye to `origin` on the near plane (perspective)
  };

  /** The camera rays of pixels [x0, x1) x [y0, y1), rows of tileSize. */
  void SetUpTileRays(int x0, int y0, int x1, int y1, int tileSize, std::vector<TileRay>& rays) const
  {
    const int width = this->Scene->View.width;
    rays.assign(static_cast<std::size_t>(tileSize) * tileSize, TileRay());
    for (int j = y0; j < y1; ++j)
    {
      for (int i = x0; i < x1; ++i)
      {
        TileRay& pixel = rays[(j - y0) * tileSize + (i - x0)];
        const std::size_t id = static_cast<std::size_t>(j) * width + i;
        pixel.start = this->MediumStart[id];
        pixel.end = this->MediumEnd[id];
        pixel.track = this->CameraTracks.empty() ? nullptr : &this->CameraTracks[id];
        pixel.glass = this->CameraGlass.empty() ? glm::dvec3(0.0) : this->CameraGlass[id];
        glm::dvec3 o1, v1;
        this->PixelRay(i, j, pixel.origin, pixel.direction);
        this->PixelRay(i + (i + 1 < width ? 1 : -1), j, o1, v1);
        pixel.spreadOrigin = o1 - pixel.origin;
        pixel.spreadDirection = v1 - pixel.direction;
        const Camera& view = this->Scene->View;
        pixel.eyeToOrigin =
          view.parallel ? 0.0 : glm::distance(pixel.origin, ToGlm(view.position));
      }
    }
  }

  /**
   * Beam radiance estimate for the pixels of one tile. Each beam is rasterized: per
   * pixel row, only the pixels whose centre lies within `reach` of the beam's
   * projected line get the exact 3D evaluation.
   */
  void ShadeTile(int x0, int y0, int tileSize, const std::vector<std::uint32_t>& list,
    const std::vector<std::array<double, 4>>& projected, std::size_t first, double reach,
    std::vector<double>& accumulated) const
  {
    const Camera& view = this->Scene->View;
    const int width = view.width;
    const int x1 = std::min(view.width, x0 + tileSize), y1 = std::min(view.height, y0 + tileSize);
    std::vector<TileRay> pixels;
    this->SetUpTileRays(x0, y0, x1, y1, tileSize, pixels);
    const double c = this->Settings.volumeKernelRadiusPixels;
    for (std::uint32_t index : list)
    {
      const ReferenceBeam& beam = this->Beams[first + index];
      const auto& p = projected[index];
      const double sx = p[2] - p[0], sy = p[3] - p[1];
      const double length = std::sqrt(sx * sx + sy * sy);
      // Unit normal of the projected line (beams seen end-on: a disk around the point).
      const double nx = length > 1e-9 ? -sy / length : 0.0, ny = length > 1e-9 ? sx / length : 0.0;
      const double offset = -(nx * p[0] + ny * p[1]);
      const double xMin = std::min(p[0], p[2]) - reach, xMax = std::max(p[0], p[2]) + reach;
      const double yMin = std::min(p[1], p[3]) - reach, yMax = std::max(p[1], p[3]) + reach;
      for (int j = std::max(y0, static_cast<int>(std::ceil(yMin - 0.5))); j < y1 && j + 0.5 <= yMax;
           ++j)
      {
        const double y = j + 0.5;
        double lo = xMin, hi = xMax;
        if (std::abs(nx) > 1e-12)
        {
          const double a = (-reach - ny * y - offset) / nx, b = (reach - ny * y - offset) / nx;
          lo = std::max(lo, std::min(a, b));
          hi = std::min(hi, std::max(a, b));
        }
        else if (length > 1e-9 && std::abs(ny * y + offset) > reach)
        {
          continue;
        }
        for (int i = std::max(x0, static_cast<int>(std::ceil(lo - 0.5))); i < x1 && i + 0.5 <= hi;
             ++i)
        {
          TileRay& pixel = pixels[(j - y0) * tileSize + (i - x0)];
          if (pixel.end > pixel.start)
          {
            pixel.sum += this->BeamContribution(beam, pixel, c);
          }
        }
      }
    }
    for (int j = y0; j < y1; ++j)
    {
      for (int i = x0; i < x1; ++i)
      {
        const glm::dvec3& sum = pixels[(j - y0) * tileSize + (i - x0)].sum;
        const std::size_t id = static_cast<std::size_t>(j) * width + i;
        accumulated[3 * id] += sum.x;
        accumulated[3 * id + 1] += sum.y;
        accumulated[3 * id + 2] += sum.z;
      }
    }
  }

  /**
   * In-scattered radiance from one beam along a pixel's camera ray, over the ray's part
   * in the medium: the 2D kernel around the beam integrated exactly along the ray,
   * K1(d) / sin(alpha), with d the distance between the two lines and alpha their
   * angle; flux, density and transmittances are taken at the closest approach.
   */
  glm::dvec3 BeamContribution(const ReferenceBeam& beam, const TileRay& ray, double pixels) const
  {
    const glm::dvec3 &o = ray.origin, &v = ray.direction;
    const double sa = ray.start, sb = ray.end;
    const glm::dvec3 p = FromFloat(beam.start), b = FromFloat(beam.direction);
    const double length = beam.length;
    const glm::dvec3 w0 = o - p;
    const double a = glm::dot(v, b), d = glm::dot(v, w0), e = glm::dot(b, w0);
    const double sin2 = 1.0 - a * a;
    double s, t, along;
    if (sin2 > 1e-8)
    {
      s = (a * e - d) / sin2;
      t = (e - a * d) / sin2;
      along = Infinity;
    }
    else
    {
      // Nearly parallel: the kernel covers the overlapping length of the beam.
      t = 0.5 * length;
      s = glm::dot(p + b * t - o, v);
      along = length;
    }
    if (t < 0.0 || t > length || s < sa || s > sb)
    {
      return glm::dvec3(0.0);
    }
    const glm::dvec3 gap = (o + v * s) - (p + b * t);
    const double d2 = glm::dot(gap, gap);
    const glm::dvec3 spread = ray.spreadOrigin + ray.spreadDirection * s;
    const double radius2 = pixels * pixels * glm::dot(spread, spread);
    if (!(d2 < radius2))
    {
      return glm::dvec3(0.0);
    }
    const double radius = std::sqrt(radius2);
    const double acrossRay =
      sin2 > 1e-8 ? EpanechnikovKernel1D(std::sqrt(d2), radius) / std::sqrt(sin2) : Infinity;
    const double kernel = std::min(acrossRay, EpanechnikovKernel2D(d2, radius) * along);
    const double phase = HenyeyGreenstein(-a, this->G); // beam along b, out along -v
    // A refractor's own absorption along the beam, and along the camera ray from the
    // eye when the eye is in it (0 in air).
    const glm::dvec3 glass =
      glm::exp(FromFloat(beam.attenuation) * -t - ray.glass * (ray.eyeToOrigin + s));
    if (ray.track)
    {
      // Heterogeneous: the piece's flux decays by the control along it (the residual
      // is tracked into its flux); the camera side is the pixel's track.
      return this->ScatteringAt(p + b * t) * FromFloat(beam.flux) * glm::exp(this->Control * -t) *
        ray.track->At(s) * glass * (phase * kernel);
    }
    const glm::dvec3 decay = glm::exp(this->SigmaT * -(t + (s - sa)));
    return this->SigmaS * FromFloat(beam.flux) * decay * glass * (phase * kernel);
  }
};

ReferenceTracer::ReferenceTracer()
  : Internal(new Internals)
{
}

ReferenceTracer::~ReferenceTracer() = default;

const std::vector<ReferencePhoton>& ReferenceTracer::GetPhotons() const
{
  return this->Internal->Photons;
}

const std::vector<ReferenceBeam>& ReferenceTracer::GetBeams() const
{
  return this->Internal->Beams;
}

void ReferenceTracer::ReleasePhotons()
{
  std::vector<ReferencePhoton>().swap(this->Internal->Photons);
  std::vector<ReferenceBeam>().swap(this->Internal->Beams);
}

bool ReferenceTracer::Render(const SceneData& scene, const ReferenceSettings& settings,
  ReferenceImage& image, ReferenceStatistics& statistics, const ProgressFunction& progress,
  std::string& error)
{
  const auto start = Clock::now();
  Internals& in = *this->Internal;
  this->ReleasePhotons();
  statistics = ReferenceStatistics();
  error = ValidateReferenceScene(scene);
  if (!error.empty())
  {
    return false;
  }
  in.Prepare(scene, settings, progress);
  bool ok = false;
  try
  {
    if (!in.HasGeometry || in.BuildEmbree(error))
    {
      in.RunStages(image, statistics);
      ok = true;
    }
  }
  catch (const std::bad_alloc&)
  {
    error = "out of memory (reduce the photon count or the image size)";
  }
  catch (const std::exception& e)
  {
    error = std::string("reference render failed: ") + e.what();
  }
  in.Release();
  if (!ok)
  {
    this->ReleasePhotons();
    return false;
  }
  statistics.totalSeconds = Seconds(start, Clock::now());
  return true;
}
}
