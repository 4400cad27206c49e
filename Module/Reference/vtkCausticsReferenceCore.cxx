#include "vtkCausticsReferenceCore.h"

#include <embree3/rtcore.h>

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

/** Small double-precision vector for the tracer's maths (also used for RGB). */
struct V3
{
  double x = 0.0, y = 0.0, z = 0.0;
  V3() = default;
  V3(double a, double b, double c)
    : x(a)
    , y(b)
    , z(c)
  {
  }
  explicit V3(const Vec3& v)
    : x(v[0])
    , y(v[1])
    , z(v[2])
  {
  }
  explicit V3(const float* v)
    : x(v[0])
    , y(v[1])
    , z(v[2])
  {
  }
  double operator[](int i) const { return i == 0 ? this->x : (i == 1 ? this->y : this->z); }
  Vec3 ToVec3() const { return { { this->x, this->y, this->z } }; }
  void ToFloat(float* out) const
  {
    out[0] = static_cast<float>(this->x);
    out[1] = static_cast<float>(this->y);
    out[2] = static_cast<float>(this->z);
  }
};

V3 operator+(const V3& a, const V3& b)
{
  return { a.x + b.x, a.y + b.y, a.z + b.z };
}
V3 operator-(const V3& a, const V3& b)
{
  return { a.x - b.x, a.y - b.y, a.z - b.z };
}
V3 operator-(const V3& a)
{
  return { -a.x, -a.y, -a.z };
}
V3 operator*(const V3& a, double s)
{
  return { a.x * s, a.y * s, a.z * s };
}
V3 operator*(const V3& a, const V3& b) // per channel
{
  return { a.x * b.x, a.y * b.y, a.z * b.z };
}
V3& operator+=(V3& a, const V3& b)
{
  a.x += b.x;
  a.y += b.y;
  a.z += b.z;
  return a;
}
double Dot(const V3& a, const V3& b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
V3 Cross(const V3& a, const V3& b)
{
  return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
}
double Length(const V3& a)
{
  return std::sqrt(Dot(a, a));
}
V3 Normalize(const V3& a)
{
  const double length = Length(a);
  return length > 0.0 ? a * (1.0 / length) : a;
}
double MaxComponent(const V3& a)
{
  return std::max(a.x, std::max(a.y, a.z));
}
V3 Exp(const V3& a)
{
  return { std::exp(a.x), std::exp(a.y), std::exp(a.z) };
}
bool IsFinite(const V3& a)
{
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
Vec3& operator+=(Vec3& a, const V3& b)
{
  a[0] += b.x;
  a[1] += b.y;
  a[2] += b.z;
  return a;
}
Vec3& operator+=(Vec3& a, const Vec3& b)
{
  a[0] += b[0];
  a[1] += b[1];
  a[2] += b[2];
  return a;
}

/** Any unit vector perpendicular to unit w, and a third completing a right-handed basis. */
void Basis(const V3& w, V3& u, V3& v)
{
  const V3 helper = std::abs(w.x) < 0.6 ? V3(1, 0, 0) : V3(0, 1, 0);
  u = Normalize(Cross(w, helper));
  v = Cross(w, u);
}

/** Parameter range [t0, t1] of o + t d, t in [tmin, tmax], inside an axis-aligned box. */
bool ClipToBox(
  const double box[6], const V3& o, const V3& d, double tmin, double tmax, double& t0, double& t1)
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
 * Runs work(item) for every item in [0, count) on `threads` threads. The calling
 * thread takes part and is the only one that reports progress (VTK observers are
 * not thread-safe). An exception in any worker stops the loop and is rethrown.
 */
void ParallelFor(std::int64_t count, int threads, const std::function<void(std::int64_t)>& work,
  const std::function<void(double)>& progress)
{
  std::atomic<std::int64_t> next(0), done(0);
  std::atomic<bool> failed(false);
  std::exception_ptr failure;
  std::mutex failureMutex;
  auto run = [&](bool reporter)
  {
    for (;;)
    {
      if (failed)
      {
        return;
      }
      const std::int64_t item = next++;
      if (item >= count)
      {
        return;
      }
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
      if (reporter && progress)
      {
        progress(static_cast<double>(finished) / static_cast<double>(count));
      }
    }
  };
  std::vector<std::thread> pool;
  const std::int64_t helpers = std::min<std::int64_t>(threads, count) - 1;
  try
  {
    for (std::int64_t t = 0; t < helpers; ++t)
    {
      pool.emplace_back(run, false);
    }
  }
  catch (...)
  {
    failed = true;
    for (auto& thread : pool)
    {
      thread.join();
    }
    throw;
  }
  run(true);
  for (auto& thread : pool)
  {
    thread.join();
  }
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
  V3 position;
  V3 geometricNormal; ///< unit face normal, on the side the vertex normals point to
  V3 shadingNormal;   ///< unit interpolated vertex normal
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
  V3 center;  ///< rectangle/disk: centre on the emission plane; cone: the apex
  V3 u, v, w; ///< w: travel direction (plane normal, cone axis)
  double halfU = 0.0, halfV = 0.0, radius = 0.0, cosMax = 1.0;
  std::int64_t nx = 0, ny = 0;
  double measure = 0.0; ///< m^2 or sr
  V3 photonFlux;        ///< radiometric x measure / count (spot falloff applied per photon)
  std::int64_t Count() const { return this->nx * this->ny; }
};

/** One step of a photon path: where it is, where it goes, what it carries. */
struct Branch
{
  V3 origin, direction, flux, firstHit;
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

  /** Irradiance sum_p flux_p K2(|x - x_p|, r) over photons whose normal agrees with n. */
  V3 Estimate(const V3& x, const V3& n, double r, double normalCosine) const
  {
    V3 sum;
    if (this->Entries.empty() || !(r > 0.0))
    {
      return sum;
    }
    const double r2 = r * r;
    auto accumulate = [&](const Entry& e)
    {
      const V3 d = V3(e.position) - x;
      const double d2 = Dot(d, d);
      if (d2 >= r2 || Dot(V3(e.normal), n) < normalCosine)
      {
        return;
      }
      const double k = EpanechnikovKernel2D(d2, r);
      sum += V3(e.flux) * k;
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
      return sum;
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
    return sum;
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
  const double c = 2.0 * (d[0] * n[0] + d[1] * n[1] + d[2] * n[2]);
  return { { d[0] - c * n[0], d[1] - c * n[1], d[2] - c * n[2] } };
}

bool Refract(const Vec3& d, const Vec3& n, double eta, Vec3& refracted)
{
  const double cosI = -(d[0] * n[0] + d[1] * n[1] + d[2] * n[2]);
  const double sin2T = eta * eta * std::max(0.0, 1.0 - cosI * cosI);
  if (sin2T >= 1.0)
  {
    return false;
  }
  const double cosT = std::sqrt(1.0 - sin2T);
  const double c = eta * cosI - cosT;
  V3 t(eta * d[0] + c * n[0], eta * d[1] + c * n[1], eta * d[2] + c * n[2]);
  refracted = Normalize(t).ToVec3();
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
}

// ---------------------------------------------------------------------------------------
// Validation

std::string ValidateReferenceScene(const SceneData& scene)
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
    const Material& material = scene.Materials[mesh.material];
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
    if (material.role == Role::Reflector)
    {
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
    }
  }
  for (std::size_t l = 0; l < scene.Lights.size(); ++l)
  {
    const Light& light = scene.Lights[l];
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
    const V3 direction(light.direction);
    if (!IsFinite(direction) || std::abs(Length(direction) - 1.0) > 1e-6)
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
  }
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
  if (medium.enabled)
  {
    if (!IsNonNegative(medium.sigmaS) || !IsNonNegative(medium.sigmaA))
    {
      return "medium coefficients must be finite and >= 0 (1/m)";
    }
    if (!(std::abs(medium.g) < 1.0))
    {
      return "medium anisotropy g = " + std::to_string(medium.g) + " must lie in (-1, 1)";
    }
  }
  return std::string();
}

// ---------------------------------------------------------------------------------------
// Tracer

struct ReferenceTracer::Internals
{
  const SceneData* Scene = nullptr;
  ReferenceSettings Settings;
  int Threads = 1;

  RTCDevice Device = nullptr;
  RTCScene Geometry = nullptr;
  std::string EmbreeError;

  double Bounds[6];         ///< every mesh taking part: also the medium's extent
  double SpecularBounds[6]; ///< reflectors and refractors
  bool HasSpecular = false;
  bool HasGeometry = false;
  double Epsilon = 1e-6; ///< ray offset off surfaces, m

  bool MediumOn = false;
  V3 SigmaS, SigmaT;
  double G = 0.0;

  std::vector<ReferencePhoton> Photons;
  std::vector<ReferenceBeam> Beams;

  /** Pixel rays and medium intervals of the view pass, reused by the volume pass. */
  std::vector<double> MediumStart, MediumEnd;

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

  bool Intersect(const V3& o, const V3& d, double tfar, Hit& hit) const
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
    const V3 a(&mesh.positions[3 * ids[0]]), b(&mesh.positions[3 * ids[1]]),
      c(&mesh.positions[3 * ids[2]]);
    const V3 na(&mesh.normals[3 * ids[0]]), nb(&mesh.normals[3 * ids[1]]),
      nc(&mesh.normals[3 * ids[2]]);
    const double u = query.hit.u, v = query.hit.v, w = 1.0 - u - v;
    // The point from barycentrics in double lies on the triangle's plane (up to
    // double rounding), unlike o + t d in float.
    hit.position = a * w + b * u + c * v;
    hit.geometricNormal = Normalize(Cross(b - a, c - a));
    if (Dot(hit.geometricNormal, na + nb + nc) < 0.0)
    {
      hit.geometricNormal = -hit.geometricNormal;
    }
    const V3 shading = na * w + nb * u + nc * v;
    const double length = Length(shading);
    hit.shadingNormal = length > 1e-12 ? shading * (1.0 / length) : hit.geometricNormal;
    if (Dot(hit.shadingNormal, hit.geometricNormal) <= 0.0)
    {
      hit.shadingNormal = hit.geometricNormal;
    }
    return true;
  }

  bool Occluded(const V3& o, const V3& d, double tnear, double tfar) const
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
    rtcOccluded1(this->Geometry, &context, &ray);
    return ray.tfar < 0.0f;
  }

  /**
   * Origin of a ray leaving a surface point: Epsilon off the surface on the side the
   * ray leaves towards. It moves along the ray itself, so that the ray's line still
   * passes through the point (an offset along the normal would shift it sideways by
   * Epsilon); only rays within ~0.6 degrees of the surface are also lifted off it.
   */
  V3 Offset(const V3& position, const V3& normal, const V3& direction) const
  {
    const double cosine = Dot(direction, normal);
    const double along = this->Epsilon / std::max(std::abs(cosine), 0.01);
    V3 origin = position + direction * along;
    const double lift = this->Epsilon - along * std::abs(cosine);
    if (lift > 0.0)
    {
      origin += normal * (cosine >= 0.0 ? lift : -lift);
    }
    return origin;
  }

  /** Medium transmittance along o + t d for t in [0, length] (the medium fills Bounds). */
  V3 Transmittance(const V3& o, const V3& d, double length) const
  {
    double t0, t1;
    if (!this->MediumOn || !ClipToBox(this->Bounds, o, d, 0.0, length, t0, t1) || t1 <= t0)
    {
      return V3(1, 1, 1);
    }
    return Exp(this->SigmaT * -(t1 - t0));
  }

  // --- Photon emission ---

  Emitter MakeEmitter(const Light& light, std::int64_t requested) const
  {
    Emitter e;
    e.light = &light;
    if (!this->HasSpecular || requested <= 0 || MaxComponent(V3(light.radiometric)) <= 0.0)
    {
      return e;
    }
    // Bounding sphere of the specular objects, with a 1% margin so that rounding
    // never trims the silhouette.
    const double* sb = this->SpecularBounds;
    const V3 c(0.5 * (sb[0] + sb[1]), 0.5 * (sb[2] + sb[3]), 0.5 * (sb[4] + sb[5]));
    const V3 half(0.5 * (sb[1] - sb[0]), 0.5 * (sb[3] - sb[2]), 0.5 * (sb[5] - sb[4]));
    const double margin = 0.01 * Length(half) + this->Epsilon;
    const double radius = Length(half) + margin;

    if (light.type == Light::Type::Directional)
    {
      e.w = Normalize(V3(light.direction));
      Basis(e.w, e.u, e.v);
      // Rectangle covering the projection of the (margin-expanded) box, or the disk
      // covering the bounding sphere: whichever is smaller.
      double lo[2] = { Infinity, Infinity }, hi[2] = { -Infinity, -Infinity };
      for (int corner = 0; corner < 8; ++corner)
      {
        const V3 p(corner & 1 ? sb[1] + margin : sb[0] - margin,
          corner & 2 ? sb[3] + margin : sb[2] - margin,
          corner & 4 ? sb[5] + margin : sb[4] - margin);
        const double pu = Dot(p - c, e.u), pv = Dot(p - c, e.v);
        lo[0] = std::min(lo[0], pu);
        hi[0] = std::max(hi[0], pu);
        lo[1] = std::min(lo[1], pv);
        hi[1] = std::max(hi[1], pv);
      }
      const double rectangle = (hi[0] - lo[0]) * (hi[1] - lo[1]);
      const double disk = Pi * radius * radius;
      // The emission plane lies before every mesh (the whole scene's bounds).
      double reach = 0.0;
      for (int corner = 0; corner < 8; ++corner)
      {
        const V3 p(this->Bounds[corner & 1 ? 1 : 0], this->Bounds[corner & 2 ? 3 : 2],
          this->Bounds[corner & 4 ? 5 : 4]);
        reach = std::max(reach, Length(p - c));
      }
      reach += radius + this->Epsilon;
      if (rectangle <= disk)
      {
        e.shape = Emitter::Shape::Rectangle;
        e.halfU = 0.5 * (hi[0] - lo[0]);
        e.halfV = 0.5 * (hi[1] - lo[1]);
        e.center = c + e.u * (0.5 * (lo[0] + hi[0])) + e.v * (0.5 * (lo[1] + hi[1])) - e.w * reach;
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
        e.radius = radius;
        e.center = c - e.w * reach;
        e.measure = disk;
        e.nx = e.ny =
          std::max<std::int64_t>(1, static_cast<std::int64_t>(std::sqrt(double(requested))));
      }
    }
    else
    {
      e.shape = Emitter::Shape::Cone;
      e.center = V3(light.position);
      const V3 toCenter = c - e.center;
      const double distance = Length(toCenter);
      // Cap subtending the bounding sphere, or every direction from inside it.
      V3 axis = distance > 0.0 ? toCenter * (1.0 / distance) : V3(light.direction);
      double cosMax = -1.0;
      if (distance > radius)
      {
        cosMax = std::sqrt(1.0 - (radius / distance) * (radius / distance));
      }
      // A spot cone narrower than that cap is the better domain (no wasted photons).
      if (light.type == Light::Type::Spot && light.cosOuter > cosMax)
      {
        axis = V3(light.direction);
        cosMax = light.cosOuter;
      }
      e.w = Normalize(axis);
      Basis(e.w, e.u, e.v);
      e.cosMax = cosMax;
      e.measure = 2.0 * Pi * (1.0 - cosMax);
      e.nx = e.ny =
        std::max<std::int64_t>(1, static_cast<std::int64_t>(std::sqrt(double(requested))));
    }
    if (!(e.measure > 0.0))
    {
      e.shape = Emitter::Shape::None;
      e.nx = e.ny = 0;
      return e;
    }
    e.photonFlux = V3(light.radiometric) * (e.measure / static_cast<double>(e.Count()));
    return e;
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
        V3 d = e.w * cosTheta;
        if (rho > 0.0)
        {
          d += (e.u * x + e.v * y) * (sinTheta / rho);
        }
        b.origin = e.center;
        b.direction = Normalize(d);
        b.flux = b.flux * e.light->SpotFactor(Dot(b.direction, V3(e.light->direction)));
        break;
      }
      case Emitter::Shape::None:
        break;
    }
    return b;
  }

  // --- Photon tracing ---

  /** Largest ratio of the branch's flux to the photon's emitted flux over channels. */
  static double Weight(const V3& flux, const V3& emitted)
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
  bool Survives(V3& flux, const V3& emitted, Random& random, ChunkResult& out) const
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
      const V3 boosted = flux * (1.0 / q);
      out.statistics.roulette += flux - boosted;
      flux = boosted;
      return true;
    }
    out.statistics.roulette += flux;
    return false;
  }

  void Deposit(const Branch& s, const Hit& hit, int lightIndex, ChunkResult& out) const
  {
    ReferencePhoton photon;
    hit.position.ToFloat(photon.position);
    const V3 facing =
      Dot(s.direction, hit.geometricNormal) < 0.0 ? hit.geometricNormal : -hit.geometricNormal;
    facing.ToFloat(photon.normal);
    s.direction.ToFloat(photon.direction);
    s.flux.ToFloat(photon.flux);
    s.firstHit.ToFloat(photon.firstHit);
    photon.mesh = static_cast<std::uint32_t>(hit.mesh);
    photon.light = static_cast<std::uint16_t>(lightIndex);
    photon.events = static_cast<std::uint8_t>(s.events);
    out.photons.push_back(photon);
    out.statistics.deposited += s.flux;
    ++out.statistics.photonsDeposited;
    out.depositedByEvents[s.events] += s.flux;
  }

  /**
   * Follows one branch until it is absorbed, escapes, is deposited, or splits at a
   * dielectric (its children go on `stack`).
   */
  void FollowBranch(Branch s, const V3& emitted, int lightIndex, Random& random,
    std::vector<Branch>& stack, ChunkResult& out) const
  {
    const int maxBounces = this->Settings.maxBounces;
    for (;;)
    {
      Hit hit;
      const bool found = this->Intersect(s.origin, s.direction, Infinity, hit);
      const double length = found ? hit.t : Infinity;
      if (s.inside >= 0)
      {
        if (!found)
        {
          out.statistics.escaped += s.flux; // an open refractor mesh
          return;
        }
        const V3 attenuation(this->MaterialOf(s.inside).attenuation);
        if (MaxComponent(attenuation) > 0.0)
        {
          const V3 kept = s.flux * Exp(attenuation * -length);
          out.statistics.absorbed += s.flux - kept;
          s.flux = kept;
        }
      }
      else if (this->MediumOn)
      {
        double t0, t1;
        if (ClipToBox(this->Bounds, s.origin, s.direction, 0.0, length, t0, t1) && t1 > t0)
        {
          if (out.beamPass && s.events > 0)
          {
            ReferenceBeam beam;
            (s.origin + s.direction * t0).ToFloat(beam.start);
            s.direction.ToFloat(beam.direction);
            beam.length = static_cast<float>(t1 - t0);
            s.flux.ToFloat(beam.flux);
            out.beams.push_back(beam);
          }
          const V3 kept = s.flux * Exp(this->SigmaT * -(t1 - t0));
          out.statistics.absorbed += s.flux - kept;
          s.flux = kept;
        }
      }
      if (!found)
      {
        out.statistics.escaped += s.flux;
        return;
      }
      const Material& material = this->MaterialOf(hit.mesh);
      if (material.role == Role::Receiver)
      {
        if (s.events == 0)
        {
          out.statistics.direct += s.flux;
        }
        else if (!out.beamPass)
        {
          this->Deposit(s, hit, lightIndex, out);
        }
        return;
      }
      if (s.events >= maxBounces)
      {
        out.statistics.bounceLimit += s.flux;
        return;
      }
      ++s.events;
      if (s.events == 1)
      {
        s.firstHit = hit.position;
      }
      // Normals on the side the ray arrives from.
      const bool front = Dot(s.direction, hit.geometricNormal) < 0.0;
      const V3 ng = front ? hit.geometricNormal : -hit.geometricNormal;
      const V3 ns = front ? hit.shadingNormal : -hit.shadingNormal;

      if (material.role == Role::Reflector)
      {
        V3 n = ns;
        V3 r(Reflect(s.direction.ToVec3(), n.ToVec3()));
        // Interpolated normals can send the ray into the surface: fall back on the face.
        if (Dot(s.direction, n) >= 0.0 || Dot(r, ng) <= 0.0)
        {
          n = ng;
          r = V3(Reflect(s.direction.ToVec3(), n.ToVec3()));
        }
        const double cosI = -Dot(s.direction, n);
        V3 fresnel;
        for (int c = 0; c < 3; ++c)
        {
          (c == 0 ? fresnel.x : (c == 1 ? fresnel.y : fresnel.z)) =
            FresnelConductor(cosI, material.metalN[c], material.metalK[c]);
        }
        const V3 kept = s.flux * fresnel;
        out.statistics.absorbed += s.flux - kept;
        s.flux = kept;
        s.origin = this->Offset(hit.position, ng, r);
        s.direction = r;
        if (!this->Survives(s.flux, emitted, random, out))
        {
          return;
        }
        continue;
      }

      // Dielectric: entering when the ray meets the outward face normal head-on.
      const double etaI = front ? 1.0 : material.ior;
      const double etaT = front ? material.ior : 1.0;
      auto scatter = [&](const V3& n, double& reflectance, V3& reflected, V3& refracted)
      {
        reflectance = FresnelDielectric(-Dot(s.direction, n), etaI, etaT);
        reflected = V3(Reflect(s.direction.ToVec3(), n.ToVec3()));
        Vec3 t;
        if (reflectance < 1.0 && Refract(s.direction.ToVec3(), n.ToVec3(), etaI / etaT, t))
        {
          refracted = V3(t);
        }
        else
        {
          reflectance = 1.0;
        }
        // Valid when both leave on their proper side of the actual (flat) surface.
        return Dot(s.direction, n) < 0.0 && Dot(reflected, ng) > 0.0 &&
          (reflectance >= 1.0 || Dot(refracted, ng) < 0.0);
      };
      double reflectance;
      V3 reflected, refracted;
      if (!scatter(ns, reflectance, reflected, refracted))
      {
        scatter(ng, reflectance, reflected, refracted);
      }
      Branch children[2];
      int count = 0;
      if (reflectance > 0.0)
      {
        Branch& child = children[count++];
        child = s;
        child.flux = s.flux * reflectance;
        child.direction = reflected;
        child.origin = this->Offset(hit.position, ng, reflected);
        child.inside = front ? s.inside : hit.mesh;
      }
      if (reflectance < 1.0)
      {
        Branch& child = children[count++];
        child = s;
        child.flux = s.flux * (1.0 - reflectance);
        child.direction = refracted;
        child.origin = this->Offset(hit.position, ng, refracted);
        child.inside = front ? hit.mesh : -1;
      }
      for (int i = 0; i < count; ++i)
      {
        if (this->Survives(children[i].flux, emitted, random, out))
        {
          stack.push_back(children[i]);
        }
      }
      return;
    }
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
      out.statistics.emitted += start.flux;
      if (!(MaxComponent(start.flux) > 0.0))
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
      chunks, this->Threads,
      [&](std::int64_t chunk)
      {
        results[chunk].beamPass = beamPass;
        this->TraceChunk(emitter, light, chunk * chunkSize,
          std::min(emitter.Count(), (chunk + 1) * chunkSize), results[chunk]);
      },
      progress);
    ReferenceLightStatistics& total = statistics.lights[light];
    for (ChunkResult& chunk : results)
    {
      this->Beams.insert(this->Beams.end(), chunk.beams.begin(), chunk.beams.end());
      std::vector<ReferenceBeam>().swap(chunk.beams); // free as we go
      if (beamPass)
      {
        continue;
      }
      this->Photons.insert(this->Photons.end(), chunk.photons.begin(), chunk.photons.end());
      std::vector<ReferencePhoton>().swap(chunk.photons);
      const ReferenceLightStatistics& s = chunk.statistics;
      total.photonsDeposited += s.photonsDeposited;
      total.emitted += s.emitted;
      total.direct += s.direct;
      total.deposited += s.deposited;
      total.escaped += s.escaped;
      total.absorbed += s.absorbed;
      total.bounceLimit += s.bounceLimit;
      total.roulette += s.roulette;
      for (std::size_t k = 0; k < chunk.depositedByEvents.size(); ++k)
      {
        statistics.depositedByEvents[k] += chunk.depositedByEvents[k];
      }
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
  double FarDistance(double i, double j, const V3& origin) const
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
    const V3 far(world[0] / world[3], world[1] / world[3], world[2] / world[3]);
    const double distance = Length(far - origin);
    return std::isfinite(distance) ? distance : Infinity;
  }

  void PixelRay(double i, double j, V3& origin, V3& direction) const
  {
    Vec3 o, d;
    this->Scene->View.PixelRay(i, j, o, d);
    origin = V3(o);
    direction = V3(d);
  }

  /** Receiver area seen by pixel (i, j) around x: its corner rays on the tangent plane. */
  double PixelArea(int i, int j, const V3& x, const V3& n, double distance) const
  {
    V3 corners[4];
    const double offsets[4][2] = { { -0.5, -0.5 }, { 0.5, -0.5 }, { 0.5, 0.5 }, { -0.5, 0.5 } };
    bool valid = true;
    for (int c = 0; c < 4 && valid; ++c)
    {
      V3 o, d;
      this->PixelRay(i + offsets[c][0], j + offsets[c][1], o, d);
      const double denominator = Dot(d, n);
      const double t = Dot(x - o, n) / denominator;
      valid = std::abs(denominator) > 1e-9 && t > 0.0 && std::isfinite(t);
      corners[c] = o + d * t;
    }
    double area =
      valid ? 0.5 * Length(Cross(corners[2] - corners[0], corners[3] - corners[1])) : 0.0;
    if (!(area > 0.0) || !std::isfinite(area))
    {
      // A corner ray misses the tangent plane (grazing view): use the pixel's
      // spread at this distance over the obliquity instead.
      V3 o0, d0, o1, d1;
      this->PixelRay(i, j, o0, d0);
      this->PixelRay(i + 1, j, o1, d1);
      const double spread = Length((o1 - o0) + (d1 - d0) * distance);
      area = spread * spread / std::max(std::abs(Dot(d0, n)), 1e-3);
    }
    return area;
  }

  /**
   * Unshadowed light arriving at x from one light: the direction towards it, its
   * distance (infinite for directional lights) and the irradiance on a surface facing
   * it (E, or I x spot falloff / d^2). False when none arrives.
   */
  static bool Incident(const Light& light, const V3& x, V3& toLight, double& distance, V3& incident)
  {
    incident = V3(light.radiometric);
    distance = Infinity;
    if (light.type == Light::Type::Directional)
    {
      toLight = -V3(light.direction);
    }
    else
    {
      const V3 offset = V3(light.position) - x;
      distance = Length(offset);
      if (!(distance > 0.0))
      {
        return false;
      }
      toLight = offset * (1.0 / distance);
      incident =
        incident * (light.SpotFactor(-Dot(toLight, V3(light.direction))) / (distance * distance));
    }
    return MaxComponent(incident) > 0.0;
  }

  /** Shadowed irradiance at a surface point from every light, no specular event. */
  V3 DirectIrradiance(const V3& x, const V3& ng, const V3& ns) const
  {
    V3 total;
    for (const Light& light : this->Scene->Lights)
    {
      V3 toLight, incident;
      double distance;
      if (!Incident(light, x, toLight, distance, incident))
      {
        continue;
      }
      const double cosine = Dot(ns, toLight);
      if (cosine <= 0.0 || Dot(ng, toLight) <= 0.0)
      {
        continue;
      }
      const V3 origin = this->Offset(x, ng, toLight);
      const double reach =
        std::isfinite(distance) ? Length(V3(light.position) - origin) - this->Epsilon : Infinity;
      if (reach <= 0.0 || this->Occluded(origin, toLight, 0.0, reach))
      {
        continue;
      }
      total += incident * this->Transmittance(origin, toLight, reach) * cosine;
    }
    return total;
  }

  /** Single-scattered direct light along the camera ray, ray-marched with shadow rays. */
  V3 Airlight(const V3& o, const V3& v, double t0, double t1, Random& random) const
  {
    V3 radiance;
    const double step = this->Settings.rayMarchStep;
    const std::int64_t steps = std::max<std::int64_t>(1, std::llround(std::ceil((t1 - t0) / step)));
    const double delta = (t1 - t0) / static_cast<double>(steps);
    for (std::int64_t k = 0; k < steps; ++k)
    {
      // One jittered sample per stratum: unbiased, no banding.
      const double s = t0 + (static_cast<double>(k) + random.Uniform()) * delta;
      const V3 x = o + v * s;
      const V3 toCamera = Exp(this->SigmaT * -(s - t0));
      for (const Light& light : this->Scene->Lights)
      {
        V3 toLight, incident;
        double distance;
        if (!Incident(light, x, toLight, distance, incident) ||
          this->Occluded(x, toLight, this->Epsilon, distance))
        {
          continue;
        }
        // Light travels along -toLight, leaves towards the camera along -v.
        const double phase = HenyeyGreenstein(Dot(toLight, v), this->G);
        radiance += this->SigmaS * incident * this->Transmittance(x, toLight, distance) * toCamera *
          (phase * delta);
      }
    }
    return radiance;
  }

  void RenderView(ReferenceImage& image)
  {
    const Camera& view = this->Scene->View;
    const int width = view.width, height = view.height;
    image.Resize(width, height);
    this->MediumStart.assign(static_cast<std::size_t>(width) * height, 0.0);
    this->MediumEnd.assign(static_cast<std::size_t>(width) * height, 0.0);
    std::vector<double> radii(static_cast<std::size_t>(width) * height, 0.0);
    std::vector<Hit> hits(static_cast<std::size_t>(width) * height);

    // Pass 1: visibility, geometry buffers, direct light, airlight.
    ParallelFor(
      height, this->Threads,
      [&](std::int64_t row)
      {
        const int j = static_cast<int>(row);
        for (int i = 0; i < width; ++i)
        {
          const std::size_t id = static_cast<std::size_t>(j) * width + i;
          V3 o, v;
          this->PixelRay(i, j, o, v);
          const double far = this->FarDistance(i, j, o);
          Hit& hit = hits[id];
          hit.mesh = -1;
          bool found = this->HasGeometry && this->Intersect(o, v, far, hit);
          // Optionally look through refractors, unbent, as the GPU's opaque G-buffer does.
          while (found && !this->Settings.cameraSeesRefractors &&
            this->MaterialOf(hit.mesh).role == Role::Refractor)
          {
            const V3 next = this->Offset(hit.position, hit.geometricNormal, v);
            const double skipped = Length(next - o);
            found = this->Intersect(next, v, far - skipped, hit);
            hit.t += found ? skipped : 0.0;
          }
          const double end = found ? hit.t : far;
          if (found)
          {
            const bool front = Dot(v, hit.geometricNormal) < 0.0;
            hit.geometricNormal = front ? hit.geometricNormal : -hit.geometricNormal;
            hit.shadingNormal = front ? hit.shadingNormal : -hit.shadingNormal;
            hit.position.ToFloat(&image.position[3 * id]);
            hit.shadingNormal.ToFloat(&image.normal[3 * id]);
            const Material& material = this->MaterialOf(hit.mesh);
            if (material.role == Role::Receiver)
            {
              image.mask[id] = 1.0f;
              V3(material.albedo).ToFloat(&image.albedo[3 * id]);
              const double area = this->PixelArea(i, j, hit.position, hit.geometricNormal, hit.t);
              image.pixelArea[id] = static_cast<float>(area);
              radii[id] = this->Settings.kernelRadius > 0.0
                ? this->Settings.kernelRadius
                : this->Settings.kernelRadiusPixels * std::sqrt(area);
              this->DirectIrradiance(hit.position, hit.geometricNormal, hit.shadingNormal)
                .ToFloat(&image.direct[3 * id]);
            }
          }
          V3 transmittance(1, 1, 1);
          double t0, t1;
          if (this->MediumOn && ClipToBox(this->Bounds, o, v, 0.0, end, t0, t1) && t1 > t0)
          {
            transmittance = Exp(this->SigmaT * -(t1 - t0));
            this->MediumStart[id] = t0;
            this->MediumEnd[id] = t1;
            Random random(this->Settings.seed ^ 0x5bd1e995ULL, 0x9e37ULL + id, 1);
            this->Airlight(o, v, t0, t1, random).ToFloat(&image.airlight[3 * id]);
          }
          transmittance.ToFloat(&image.transmittance[3 * id]);
        }
      },
      this->Stage(0.45, 0.35));

    // Pass 2: caustic irradiance from the deposits. Cells of the median radius keep
    // most queries to 27 cells.
    if (this->Photons.empty())
    {
      return;
    }
    std::vector<double> positive;
    for (double r : radii)
    {
      if (r > 0.0 && std::isfinite(r))
      {
        positive.push_back(r);
      }
    }
    if (positive.empty())
    {
      return;
    }
    std::nth_element(positive.begin(), positive.begin() + positive.size() / 2, positive.end());
    PhotonGrid grid;
    grid.Build(this->Photons, positive[positive.size() / 2]);
    ParallelFor(
      height, this->Threads,
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
          grid
            .Estimate(
              hit.position, hit.geometricNormal, radii[id], this->Settings.kernelNormalCosine)
            .ToFloat(&image.caustic[3 * id]);
        }
      },
      this->Stage(0.8, 0.05));
  }

  // --- Volume caustics: beam radiance estimate ---

  /** Beam ends in continuous pixel coordinates, clipped to the near plane. */
  bool ProjectBeam(const ReferenceBeam& beam, double p[2][2]) const
  {
    const Camera& view = this->Scene->View;
    const V3 a(beam.start);
    const V3 b = a + V3(beam.direction) * beam.length;
    double clip[2][4];
    for (int e = 0; e < 2; ++e)
    {
      const V3& x = e == 0 ? a : b;
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

  void RenderVolumeCaustics(ReferenceImage& image)
  {
    if (!this->MediumOn || this->Beams.empty())
    {
      return;
    }
    const Camera& view = this->Scene->View;
    const int width = view.width, height = view.height;
    const int tileSize = 16;
    const int tilesX = (width + tileSize - 1) / tileSize;
    const int tilesY = (height + tileSize - 1) / tileSize;
    const double c = this->Settings.volumeKernelRadiusPixels;
    // Reach of a beam's kernel on screen, in pixels: c pixel footprints, plus slack
    // for the footprint varying across a pixel in perspective.
    const double reach = 1.1 * c + 1.5;
    const double tileHalfDiagonal = tileSize * 0.5 * std::sqrt(2.0);
    std::vector<double> accumulated(3 * static_cast<std::size_t>(width) * height, 0.0);

    // Beams are binned to screen tiles in batches (bounded memory); tiles are then
    // shaded in parallel, each pixel summing its beams in index order (deterministic).
    const std::size_t batch = std::size_t(1) << 20;
    for (std::size_t first = 0; first < this->Beams.size(); first += batch)
    {
      const std::size_t last = std::min(this->Beams.size(), first + batch);
      std::vector<std::vector<std::uint32_t>> tiles(static_cast<std::size_t>(tilesX) * tilesY);
      std::vector<std::array<double, 4>> projected(last - first);
      for (std::size_t b = first; b < last; ++b)
      {
        double p[2][2];
        if (!this->ProjectBeam(this->Beams[b], p))
        {
          continue;
        }
        projected[b - first] = { { p[0][0], p[0][1], p[1][0], p[1][1] } };
        const double lo[2] = { std::min(p[0][0], p[1][0]) - reach,
          std::min(p[0][1], p[1][1]) - reach };
        const double hi[2] = { std::max(p[0][0], p[1][0]) + reach,
          std::max(p[0][1], p[1][1]) + reach };
        const int tx0 = std::max(0, static_cast<int>(std::floor(lo[0] / tileSize)));
        const int ty0 = std::max(0, static_cast<int>(std::floor(lo[1] / tileSize)));
        const int tx1 = std::min(tilesX - 1, static_cast<int>(std::floor(hi[0] / tileSize)));
        const int ty1 = std::min(tilesY - 1, static_cast<int>(std::floor(hi[1] / tileSize)));
        const double sx = p[1][0] - p[0][0], sy = p[1][1] - p[0][1];
        const double length2 = sx * sx + sy * sy;
        for (int ty = ty0; ty <= ty1; ++ty)
        {
          for (int tx = tx0; tx <= tx1; ++tx)
          {
            // Distance from the tile centre to the projected segment.
            const double cx = (tx + 0.5) * tileSize, cy = (ty + 0.5) * tileSize;
            double t = length2 > 0.0 ? ((cx - p[0][0]) * sx + (cy - p[0][1]) * sy) / length2 : 0.0;
            t = std::min(1.0, std::max(0.0, t));
            const double dx = p[0][0] + t * sx - cx, dy = p[0][1] + t * sy - cy;
            if (dx * dx + dy * dy <= (tileHalfDiagonal + reach) * (tileHalfDiagonal + reach))
            {
              tiles[static_cast<std::size_t>(ty) * tilesX + tx].push_back(
                static_cast<std::uint32_t>(b - first));
            }
          }
        }
      }
      ParallelFor(
        static_cast<std::int64_t>(tiles.size()), this->Threads,
        [&](std::int64_t tile)
        {
          const std::vector<std::uint32_t>& list = tiles[tile];
          if (!list.empty())
          {
            this->ShadeTile(static_cast<int>(tile % tilesX) * tileSize,
              static_cast<int>(tile / tilesX) * tileSize, tileSize, list, projected, first, reach,
              accumulated);
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
    struct PixelRayData
    {
      V3 origin, direction, spreadOrigin, spreadDirection, sum;
      double start = 0.0, end = 0.0;
    };
    std::vector<PixelRayData> pixels(static_cast<std::size_t>(tileSize) * tileSize);
    for (int j = y0; j < y1; ++j)
    {
      for (int i = x0; i < x1; ++i)
      {
        PixelRayData& pixel = pixels[(j - y0) * tileSize + (i - x0)];
        const std::size_t id = static_cast<std::size_t>(j) * width + i;
        pixel.start = this->MediumStart[id];
        pixel.end = this->MediumEnd[id];
        V3 o1, v1;
        this->PixelRay(i, j, pixel.origin, pixel.direction);
        this->PixelRay(i + (i + 1 < width ? 1 : -1), j, o1, v1);
        pixel.spreadOrigin = o1 - pixel.origin;
        pixel.spreadDirection = v1 - pixel.direction;
      }
    }
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
          PixelRayData& pixel = pixels[(j - y0) * tileSize + (i - x0)];
          if (pixel.end > pixel.start)
          {
            pixel.sum += this->BeamContribution(beam, pixel.origin, pixel.direction, pixel.start,
              pixel.end, pixel.spreadOrigin, pixel.spreadDirection, c);
          }
        }
      }
    }
    for (int j = y0; j < y1; ++j)
    {
      for (int i = x0; i < x1; ++i)
      {
        const V3& sum = pixels[(j - y0) * tileSize + (i - x0)].sum;
        const std::size_t id = static_cast<std::size_t>(j) * width + i;
        accumulated[3 * id] += sum.x;
        accumulated[3 * id + 1] += sum.y;
        accumulated[3 * id + 2] += sum.z;
      }
    }
  }

  /**
   * In-scattered radiance from one beam along a camera ray, over [sa, sb]: the 2D
   * kernel around the beam integrated exactly along the ray, K1(d) / sin(alpha),
   * with d the distance between the two lines and alpha their angle; flux and
   * transmittances are taken at the closest approach.
   */
  V3 BeamContribution(const ReferenceBeam& beam, const V3& o, const V3& v, double sa, double sb,
    const V3& spreadOrigin, const V3& spreadDirection, double pixels) const
  {
    const V3 p(beam.start), b(beam.direction);
    const double length = beam.length;
    const V3 w0 = o - p;
    const double a = Dot(v, b), d = Dot(v, w0), e = Dot(b, w0);
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
      s = Dot(p + b * t - o, v);
      along = length;
    }
    if (t < 0.0 || t > length || s < sa || s > sb)
    {
      return V3();
    }
    const V3 gap = (o + v * s) - (p + b * t);
    const double d2 = Dot(gap, gap);
    const V3 spread = spreadOrigin + spreadDirection * s;
    const double radius2 = pixels * pixels * Dot(spread, spread);
    if (!(d2 < radius2))
    {
      return V3();
    }
    const double radius = std::sqrt(radius2);
    const double acrossRay =
      sin2 > 1e-8 ? EpanechnikovKernel1D(std::sqrt(d2), radius) / std::sqrt(sin2) : Infinity;
    const double kernel = std::min(acrossRay, EpanechnikovKernel2D(d2, radius) * along);
    const double phase = HenyeyGreenstein(-a, this->G); // beam along b, out along -v
    const V3 decay = Exp(this->SigmaT * -(t + (s - sa)));
    return this->SigmaS * V3(beam.flux) * decay * (phase * kernel);
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
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto seconds = [](Clock::time_point a, Clock::time_point b)
  { return std::chrono::duration<double>(b - a).count(); };
  Internals& in = *this->Internal;
  this->ReleasePhotons();
  statistics = ReferenceStatistics();
  error = ValidateReferenceScene(scene);
  if (!error.empty())
  {
    return false;
  }
  in.Scene = &scene;
  in.Settings = settings;
  in.Threads = settings.threads > 0
    ? settings.threads
    : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  in.Progress = progress;
  in.LastReported = -1.0;
  in.ComputeBounds();
  const Medium& medium = scene.Participating;
  in.SigmaS = V3(medium.sigmaS);
  in.SigmaT = V3(medium.sigmaS) + V3(medium.sigmaA);
  in.G = medium.g;
  in.MediumOn = medium.enabled && in.HasGeometry && MaxComponent(in.SigmaT) > 0.0;
  if (in.Settings.rayMarchStep <= 0.0)
  {
    const double* b = in.Bounds;
    const double size = in.HasGeometry
      ? std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
          (b[5] - b[4]) * (b[5] - b[4]))
      : 0.0;
    in.Settings.rayMarchStep = size > 0.0 ? size / 256.0 : 1.0;
  }

  bool ok = true;
  try
  {
    if (in.HasGeometry && !in.BuildEmbree(error))
    {
      ok = false;
    }
    if (ok)
    {
      const auto photonStart = Clock::now();
      in.Stage(0.0, 0.45);
      if (in.HasGeometry)
      {
        in.TracePhotons(statistics);
      }
      else
      {
        statistics.lights.assign(scene.Lights.size(), ReferenceLightStatistics());
        statistics.depositedByEvents.assign(settings.maxBounces + 1, Vec3{ { 0, 0, 0 } });
      }
      const auto viewStart = Clock::now();
      statistics.photonSeconds = seconds(photonStart, viewStart);
      in.RenderView(image);
      const auto volumeStart = Clock::now();
      statistics.viewSeconds = seconds(viewStart, volumeStart);
      in.RenderVolumeCaustics(image);
      statistics.volumeSeconds = seconds(volumeStart, Clock::now());
      in.Stage(0.0, 1.0);
      in.ReportProgress(1.0);
    }
  }
  catch (const std::bad_alloc&)
  {
    error = "out of memory (reduce the photon count or the image size)";
    ok = false;
  }
  catch (const std::exception& e)
  {
    error = std::string("reference render failed: ") + e.what();
    ok = false;
  }
  in.ReleaseEmbree();
  std::vector<double>().swap(in.MediumStart);
  std::vector<double>().swap(in.MediumEnd);
  in.Scene = nullptr;
  if (!ok)
  {
    this->ReleasePhotons();
    return false;
  }
  statistics.totalSeconds = seconds(start, Clock::now());
  return true;
}
}
