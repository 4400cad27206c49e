// Optics shared by the photon stages and the screen-space refraction (prepended
// by the stages that need them, after vtkCausticsCommon.glsl). Exact Fresnel
// equations, as the CPU reference uses: unpolarized dielectric reflectance, and
// conductor reflectance with complex IOR n + ik per channel
// (004_4da4b323b51d1415.txt §3). Every stage meets a specular surface through
// CausticsSurfaceInteraction or, where it knows the two indices itself,
// CausticsDielectric; absorption is CausticsTransmittance.

// Unpolarized dielectric reflectance for cosine of incidence cosI (>= 0) going
// from index n1 to n2; 1 under total internal reflection.
float FresnelDielectric(float cosI, float n1, float n2)
{
  float eta = n1 / n2;
  float sin2T = eta * eta * max(0.0, 1.0 - cosI * cosI);
  if (sin2T >= 1.0)
  {
    return 1.0;
  }
  float cosT = sqrt(1.0 - sin2T);
  float rs = (n1 * cosI - n2 * cosT) / (n1 * cosI + n2 * cosT);
  float rp = (n2 * cosI - n1 * cosT) / (n2 * cosI + n1 * cosT);
  return 0.5 * (rs * rs + rp * rp);
}

// Unpolarized conductor reflectance for cosine of incidence cosI, complex IOR n + ik
// (relative to the outside medium, air).
vec3 FresnelConductor(float cosI, vec3 n, vec3 k)
{
  float c2 = cosI * cosI;
  float s2 = max(0.0, 1.0 - c2);
  vec3 n2k2 = n * n - k * k;
  vec3 t0 = n2k2 - vec3(s2);
  vec3 a2b2 = sqrt(max(t0 * t0 + 4.0 * n * n * k * k, vec3(0.0)));
  vec3 a = sqrt(max(0.5 * (a2b2 + t0), vec3(0.0)));
  vec3 t1 = a2b2 + vec3(c2);
  vec3 t2 = 2.0 * cosI * a;
  vec3 rs = (t1 - t2) / max(t1 + t2, vec3(1e-20));
  vec3 t3 = c2 * a2b2 + vec3(s2 * s2);
  vec3 t4 = t2 * s2;
  vec3 rp = rs * (t3 - t4) / max(t3 + t4, vec3(1e-20));
  return clamp(0.5 * (rs + rp), 0.0, 1.0);
}

// Refraction of unit direction d at unit normal n facing against d (dot(d, n) < 0),
// eta = n1 / n2. Returns false under total internal reflection.
bool RefractDirection(vec3 d, vec3 n, float eta, out vec3 t)
{
  float cosI = -dot(d, n);
  float sin2T = eta * eta * max(0.0, 1.0 - cosI * cosI);
  if (sin2T >= 1.0)
  {
    t = reflect(d, n);
    return false;
  }
  t = normalize(eta * d + (eta * cosI - sqrt(1.0 - sin2T)) * n);
  return true;
}

// A dielectric interface met by the unit direction d: facing is the unit normal
// on d's side, cosI the cosine of incidence, n1 the index d travels in and n2 the
// index beyond. Gives the exact Fresnel reflectance and both directions; false
// under total internal reflection (then refracted = reflected).
bool CausticsDielectric(vec3 d, vec3 facing, float cosI, float n1, float n2,
  out float reflectance, out vec3 reflected, out vec3 refracted)
{
  reflectance = FresnelDielectric(cosI, n1, n2);
  reflected = reflect(d, facing);
  return RefractDirection(d, facing, n1 / n2, refracted);
}

// What a specular surface does to a photon: both outgoing directions and the
// flux weight of each. The caller decides what to follow (emission keeps both
// branches of a refractor, a photon each; the screen-space transfer follows one,
// reflected with probability R) and applies the weight to its flux.
struct CausticsInteraction
{
  bool entering;        // d arrived on the side the normal points to (from outside)
  bool transmits;       // a refractor, and no total internal reflection
  vec3 reflected;       // mirror direction
  vec3 refracted;       // transmitted direction (= reflected where !transmits)
  vec3 reflectedWeight; // conductor Fresnel per channel, or the dielectric's R
  vec3 refractedWeight; // 1 - R (0 for a conductor)
};

// The photon with unit direction d meets the surface with unit shading normal n
// (as modelled, either side) and material (its role given separately, as the
// caller knows it): ROLE_REFLECTOR is a conductor (complex IOR metalN + i metalK,
// reflected only); otherwise a dielectric of index max(IOR, 1) inside and
// outsideIor around it, entered or left depending on the side d arrives on.
CausticsInteraction CausticsSurfaceInteraction(
  vec3 d, vec3 n, CausticsMaterial material, int role, float outsideIor)
{
  CausticsInteraction s;
  s.entering = dot(d, n) < 0.0;
  vec3 facing = s.entering ? n : -n;
  float cosI = clamp(-dot(d, facing), 0.0, 1.0);
  if (role == ROLE_REFLECTOR)
  {
    s.transmits = false;
    s.reflected = reflect(d, facing);
    s.refracted = s.reflected;
    s.reflectedWeight = FresnelConductor(cosI, material.metalN.rgb, material.metalK.rgb);
    s.refractedWeight = vec3(0.0);
    return s;
  }
  float ior = max(material.params.x, 1.0);
  float n1 = s.entering ? outsideIor : ior;
  float n2 = s.entering ? ior : outsideIor;
  float reflectance;
  s.transmits = CausticsDielectric(d, facing, cosI, n1, n2, reflectance, s.reflected, s.refracted);
  s.reflectedWeight = vec3(reflectance);
  s.refractedWeight = vec3(1.0 - reflectance);
  return s;
}

// The normal a photon's interaction at a traced triangle takes (glass and mirrors traced
// as triangles, vtkCausticsSpecularTrace.glsl), as the reference's rules and the camera
// view's (ScatterDielectric): the face (`geometric`, on the side of the interpolated
// normal) decides which side d arrives on, and the interpolated normal `shading`
// shades, unless it takes the other side or would send a direction out on the wrong
// side of the face (a grazing ray at a coarse facet); then the face's own.
vec3 CausticsTriangleNormal(vec3 d, vec3 shading, vec3 geometric, CausticsMaterial material, int role)
{
  bool entering = dot(d, geometric) < 0.0;
  vec3 face = entering ? geometric : -geometric; // towards where d comes from
  CausticsInteraction s = CausticsSurfaceInteraction(d, shading, material, role, 1.0);
  bool fine = s.entering == entering && dot(s.reflected, face) > 0.0 &&
    (!s.transmits || role != ROLE_REFRACTOR || dot(s.refracted, face) < 0.0);
  return fine ? shading : geometric;
}

// A photon's specular event followed as one branch (Russian roulette): reflection
// or refraction, chosen by the uniform number u with its share of the exact Fresnel
// weights, the flux divided by that probability so that the estimate stays
// unbiased. `inside` follows the refractor's side; a surface that passes nothing
// leaves the flux at 0.
void CausticsScatterOneBranchBy(float u, vec3 n, CausticsMaterial material, int role,
  inout vec3 d, inout vec3 flux, inout bool inside)
{
  CausticsInteraction s = CausticsSurfaceInteraction(d, n, material, role, 1.0);
  float reflected = CausticsChannelSum(s.reflectedWeight);
  float refracted =
    s.transmits && role == ROLE_REFRACTOR ? CausticsChannelSum(s.refractedWeight) : 0.0;
  float total = reflected + refracted;
  if (!(total > 0.0))
  {
    flux = vec3(0.0);
    return;
  }
  bool reflect = u * total < reflected;
  float probability = (reflect ? reflected : refracted) / total;
  flux *= (reflect ? s.reflectedWeight : s.refractedWeight) / probability;
  d = reflect ? s.reflected : s.refracted;
  if (role == ROLE_REFRACTOR)
  {
    inside = reflect ? inside : s.entering;
  }
}

// The same with the photon's own random stream.
void CausticsScatterOneBranch(vec3 n, CausticsMaterial material, int role, inout vec3 d,
  inout vec3 flux, inout bool inside, inout uint rng)
{
  CausticsScatterOneBranchBy(CausticsRandom(rng), n, material, role, d, flux, inside);
}
