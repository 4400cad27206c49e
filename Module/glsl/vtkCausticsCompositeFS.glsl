// Adds caustic light to VTK's image. VTK shades a Lambertian surface as
// albedo x intensity x cos, i.e. pi x radiance for irradiance in W/m^2, so the
// caustic term in the same display units is albedo x caustic irradiance.
// It is added only where the caustics G-buffer's receiver is what VTK drew
// (same depth), so props drawn by VTK alone are never painted over. A technique
// may replace VTK's colour where its own colour has alpha 1 (e.g. refractors
// seen through traced refraction), and add volume radiance (pi x, like surfaces).
// VTK shades receivers without shadows: where reflectors and refractors block the
// light (which they pass on as the caustic), that part of VTK's diffuse shading is
// taken off first (specularShadow, per unit albedo).
in vec2 texCoord;

uniform sampler2D delegateColor;
uniform sampler2D delegateDepth;
uniform sampler2D gNormal;  // w = role
uniform sampler2D gAlbedo;
uniform sampler2D gDepth;
uniform sampler2D causticIrradiance;
uniform sampler2D volumeRadiance;
uniform sampler2D techniqueColor;
uniform sampler2D specularShadow;
uniform int hasSpecularShadow;
uniform int hasCaustics;
uniform int hasVolume;
uniform int hasTechniqueColor;
uniform float depthTolerance;

layout(location = 0) out vec4 outColor;

void main()
{
  vec4 color = texture(delegateColor, texCoord);
  float depth = texture(delegateDepth, texCoord).r;
  if (hasTechniqueColor != 0)
  {
    vec4 replacement = texture(techniqueColor, texCoord);
    if (replacement.a >= 1.0)
    {
      color.rgb = replacement.rgb;
    }
  }
  if (hasCaustics != 0)
  {
    int role = int(texture(gNormal, texCoord).w + 0.5);
    float surfaceDepth = texture(gDepth, texCoord).r;
    if (role == ROLE_RECEIVER && abs(surfaceDepth - depth) <= depthTolerance)
    {
      vec3 albedo = texture(gAlbedo, texCoord).rgb;
      if (hasSpecularShadow != 0)
      {
        color.rgb = max(color.rgb - albedo * texture(specularShadow, texCoord).rgb, vec3(0.0));
      }
      vec3 irradiance = texture(causticIrradiance, texCoord).rgb;
      color.rgb += albedo * max(irradiance, vec3(0.0));
    }
  }
  if (hasVolume != 0)
  {
    color.rgb += CAUSTICS_PI * texture(volumeRadiance, texCoord).rgb;
  }
  outColor = color;
  gl_FragDepth = depth;
}
