// Receiver-oriented, energy-normalized photon splat (000_54cf099eeccf42d9.txt §3.1,
// Eq. 1, normalized): the pixel's surface point x (from the target view's
// G-buffer) receives flux x K(d), where d is the distance from the photon to x
// measured in the photon's tangent plane and K is the Epanechnikov kernel
// K(d) = 2 / (pi r^2) (1 - d^2 / r^2), whose integral over the plane is 1: each
// photon deposits exactly its flux (W), so the sum is irradiance in W/m^2.
// Points off the photon's plane (another surface) or facing away are skipped.
// Alpha: the deposit's luminance signed by its photon's half set (CausticsDeposit),
// summed into the difference of the two halves' estimates.
uniform sampler2D targetPosition; // xyz world, w = material (-1: no surface)
uniform sampler2D targetNormal;   // xyz normal as modelled, w = role
uniform float planeTolerance;     // allowed distance off the tangent plane, in radii
uniform float normalTolerance;    // minimum cosine between the two normals

flat in vec3 splatCentre;
flat in vec3 splatNormal;
flat in vec3 splatFlux;
flat in float splatRadius;
flat in float splatHalfSet;

layout(location = 0) out vec4 outIrradiance;
#ifdef CAUSTICS_KERNEL_RADII
// The kernels' radius at this pixel, as sums weighted by what each deposits (its
// luminance): the disc whose share on the receiver vtkCausticsPhotonSplatEndsFS
// divides by.
layout(location = 1) out vec2 outKernelRadii;
#endif

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 position = texelFetch(targetPosition, pixel, 0);
  vec4 normalRole = texelFetch(targetNormal, pixel, 0);
  if (position.w < 0.0 || int(normalRole.w + 0.5) != ROLE_RECEIVER ||
    dot(normalRole.xyz, splatNormal) < normalTolerance)
  {
    discard;
  }
  vec3 v = position.xyz - splatCentre;
  float height = dot(v, splatNormal);
  float r2 = splatRadius * splatRadius;
  float d2 = dot(v, v) - height * height;
  if (abs(height) > planeTolerance * splatRadius || d2 >= r2)
  {
    discard;
  }
  float kernel = 2.0 / (CAUSTICS_PI * r2) * (1.0 - d2 / r2);
  outIrradiance = CausticsDeposit(splatFlux * kernel, splatHalfSet);
#ifdef CAUSTICS_KERNEL_RADII
  float weight = CausticsLuminance(splatFlux * kernel);
  outKernelRadii = vec2(weight, weight * splatRadius);
#endif
}
