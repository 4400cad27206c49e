/**
 * The part of the specular actors a light's photons are worth emitting towards: the
 * surfaces whose light can reach what the camera sees.
 *
 * The light buffers emit one photon per texel of a frustum aimed at a box of specular
 * surfaces (caustics::LightView). Aimed at every specular actor, a camera framing a
 * small part of a large water surface (zoomed in on its caustic) gets few of the
 * photons: most land outside the view, and the caustic it shows is coarse and blurred.
 * PhotonFocusBounds() narrows the box to the specular triangles whose reflected or
 * refracted light can reach the region the camera sees, that region taken as the
 * scene's bounds cut by the camera's clip volume (caustics::VisibleBounds) and
 * widened by where the camera's own rays go after reflecting or refracting at those
 * surfaces (a floor seen through water, a wall seen in a mirror).
 *
 * The test follows one specular event per path, so it narrows only the meshes where a
 * path meets one: a sheet (normals within 45 degrees of their mean: water, a flat or
 * gently curved mirror; a closed or strongly curved surface sends light on to itself)
 * that no other specular mesh's light can reach (light arriving from another mesh comes
 * from directions its cones do not follow). Such a sheet keeps the triangles whose light
 * can reach what the camera sees or another specular mesh; every other specular mesh
 * counts whole, and the box holds them all. Where the camera's rays, reflected or
 * refracted at a sheet in view, can meet another specular mesh, or where the camera
 * sees a closed or curved one, every receiver counts as seen. Nothing narrows with a
 * participating medium (volume caustics are seen along the photons' paths, not only
 * where they land), where the camera sees nothing, or where no light reaches what it
 * sees: the box is then SceneData::SpecularBounds.
 *
 * Each triangle's outgoing directions (the vertex normals' reflection and refraction
 * of the incoming light) are bounded by a cone around their mean, widened by a tenth
 * and half a degree for the interpolated normals between vertices; a triangle
 * is kept when that cone, started from anywhere on the triangle, can meet the region.
 * So the box only ever holds more than the exact answer. A CPU pass over the specular
 * meshes' triangles (a few ms for 10^5 triangles; with several meshes each sheet
 * triangle is also tested against every other mesh, and past 2 * 10^6 such tests the box
 * is SceneData::SpecularBounds); callers keep its result while the camera, the light
 * and the meshes stay.
 */
#ifndef vtkCausticsPhotonFocus_h
#define vtkCausticsPhotonFocus_h

namespace caustics
{
struct Mesh;
struct SceneData;

/**
 * The box (xmin, xmax, ymin, ymax, zmin, zmax) of the specular surfaces whose light
 * from light `index` can reach what the camera sees (above). True when it is
 * narrower than scene.SpecularBounds, false when it is that box (`box` is set either
 * way; to scene.Bounds without specular actors).
 */
bool PhotonFocusBounds(const SceneData& scene, int index, double box[6]);

/**
 * Whether the mesh is a sheet as the focus tells them: every (vertex or face) normal
 * within 45 degrees of their mean. A water surface or a gently curved mirror is; a
 * closed or strongly curved surface, which a ray can meet twice, is not.
 */
bool IsSheet(const Mesh& mesh);
}

#endif
