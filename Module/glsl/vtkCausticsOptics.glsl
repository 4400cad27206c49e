// Optics shared by the photon stages (inserted where CAUSTICS_OPTICS is defined).
// Exact Fresnel equations, as the CPU reference uses: unpolarized dielectric
// reflectance, and conductor reflectance with complex IOR n + ik per channel
// (004_4da4b323b51d1415.txt §3).

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
