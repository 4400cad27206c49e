// Shared by every caustics shader (prepended after #version, the defines and the
// binding table vtkCausticsBindings.h).
// Layouts and constants here must match the host side (vtkCausticsSceneGeometry,
// vtkCausticsSceneData.h).

const float CAUSTICS_PI = 3.14159265358979323846;

// Material roles (caustics::Role).
const int ROLE_NONE = 0;
const int ROLE_RECEIVER = 1;
const int ROLE_REFLECTOR = 2;
const int ROLE_REFRACTOR = 3;

// Spot falloff of glTF KHR_lights_punctual, as caustics::Light::SpotFactor: 1
// inside the inner cone, 0 outside the outer cone, a squared linear ramp in
// cos(angle) between.
float CausticsSpotFactor(float cosAngle, float cosOuter, float cosInner)
{
  if (cosAngle <= cosOuter)
  {
    return 0.0;
  }
  float range = cosInner - cosOuter;
  if (range <= 1e-12)
  {
    return 1.0;
  }
  float t = min(1.0, (cosAngle - cosOuter) / range);
  return t * t;
}

// The photon record (caustics::PhotonRecords, vtkCausticsPhotonGrid.h): three
// RGBA32F planes, one texel per photon of the emitter's grid.
//              emitted (after the first specular event)   landed on a receiver
//   position   xyz m; w: 0 none, 1 into air, 2 inside      xyz m; w: path length from the light (m), > 0
//   direction  xyz unit direction; w: texel measure        xyz receiver normal as modelled; w: |N.D|
//   flux       rgb W; a: specular events so far (1)        rgb W; a: texel measure
// The measure is m^2 across a directional light's beam, sr from a point or spot
// light; a directional light's path length starts at its view's eye plane. The
// kernel radius (m) a reconstruction gives a landed photon is an R32F texture
// beside them.

// Beer-Lambert: the fraction of the flux left after distance (m) through a
// medium of attenuation (or extinction) coefficients sigma (1/m).
vec3 CausticsTransmittance(vec3 sigma, float distance)
{
  return exp(-sigma * distance);
}

// Clips o + t d, t in [t0, t1], to an axis-aligned box; false if it misses.
bool CausticsClipToBox(vec3 o, vec3 d, vec3 boxMin, vec3 boxMax, inout float t0, inout float t1)
{
  for (int a = 0; a < 3; ++a)
  {
    if (abs(d[a]) < 1e-20)
    {
      if (o[a] < boxMin[a] || o[a] > boxMax[a])
      {
        return false;
      }
      continue;
    }
    float ta = (boxMin[a] - o[a]) / d[a];
    float tb = (boxMax[a] - o[a]) / d[a];
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
  }
  return t0 < t1;
}

// The participating medium (caustics::Medium): homogeneous, filling the scene's
// bounding box but not the refractors, as in the reference renderer. Set from the
// host by caustics::gl::SetMediumUniforms.
uniform int causticsMediumOn;
uniform vec3 causticsSigmaT;     // extinction, 1/m
uniform vec3 causticsMediumLow;  // the scene's bounds (m)
uniform vec3 causticsMediumHigh;

// The medium's transmittance along o + t d, t in [t0, t1] (d need not be unit: the
// distance is (t1 - t0) |d|); 1 without a medium or outside its box.
vec3 CausticsMediumTransmittance(vec3 o, vec3 d, float t0, float t1)
{
  if (causticsMediumOn == 0 ||
    !CausticsClipToBox(o, d, causticsMediumLow, causticsMediumHigh, t0, t1))
  {
    return vec3(1.0);
  }
  return CausticsTransmittance(causticsSigmaT, (t1 - t0) * length(d));
}

// One entry per mesh (vtkCausticsSceneGeometry::UploadMaterials).
struct CausticsMaterial
{
  vec4 albedoRole;  // rgb: diffuse albedo, a: role
  vec4 params;      // x: IOR, y: roughness
  vec4 metalN;      // rgb: real part of the complex IOR (reflectors)
  vec4 metalK;      // rgb: imaginary part
  vec4 attenuation; // rgb: Beer-Lambert absorption inside refractors, 1/m
};

#ifndef CAUSTICS_NO_MATERIALS
layout(std430, binding = CAUSTICS_MATERIAL_BINDING) readonly buffer CausticsMaterials
{
  CausticsMaterial causticsMaterials[];
};
#endif
