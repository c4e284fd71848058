#pragma once
// The Mitsuba 3 plugins surfscatter supports, one factory per plugin and one plugin per file (bsdfs/, emitters/,
// shapes/, textures/, filters/, sensors/, films/, integrators/), each documented at the top of its file: what it
// supports and how it differs from Mitsuba. The XML loader (xml_loader.cpp) maps plugin names to these factories;
// docs/RENDERER.md tables the whole subset.
#include <string>

#include "surfscatter/render/camera.hpp"
#include "surfscatter/render/emitter.hpp"
#include "surfscatter/render/filter.hpp"
#include "surfscatter/render/properties.hpp"
#include "surfscatter/render/scene.hpp"
#include "surfscatter/render/shape.hpp"

namespace surfscatter::render::plugins {

// BSDFs (bsdfs/).
MaterialPtr diffuse(Properties& props);
MaterialPtr conductor(Properties& props);
MaterialPtr roughconductor(Properties& props);
MaterialPtr dielectric(Properties& props);
MaterialPtr thindielectric(Properties& props);
MaterialPtr roughdielectric(Properties& props);
MaterialPtr plastic(Properties& props);
MaterialPtr roughplastic(Properties& props);
MaterialPtr twosided(Properties& props);
MaterialPtr blendbsdf(Properties& props);
MaterialPtr mask(Properties& props);
MaterialPtr bumpmap(Properties& props);
MaterialPtr normalmap(Properties& props);
MaterialPtr measured(Properties& props);  // RGL measured BSDF files (bsdfs/measured.cpp)
// surfscatter's scattering models (bsdfs/scattering_models.cpp): `type` is ghs, ghs_ssa, ggx_stats or two_scale.
MaterialPtr scattering_model(Properties& props, const std::string& type);

// Emitters (emitters/). `area` is read by the shape that carries it: its radiance spectrum.
EmitterPtr point(Properties& props);
EmitterPtr spot(Properties& props);
EmitterPtr directional(Properties& props);
EmitterPtr constant(Properties& props);
EmitterPtr envmap(Properties& props);
SpectrumPtr area(Properties& props);

// Shapes (shapes/): the geometry in world space; the loader attaches the BSDF and area emitter.
ShapeGeometry obj(Properties& props);
ShapeGeometry ply(Properties& props);
ShapeGeometry serialized(Properties& props);
ShapeGeometry rectangle(Properties& props);
ShapeGeometry disk(Properties& props);
ShapeGeometry cube(Properties& props);
ShapeGeometry sphere(Properties& props);
ShapeGeometry cylinder(Properties& props);

// Textures (textures/).
TexturePtr bitmap(Properties& props);
TexturePtr checkerboard(Properties& props);

// Reconstruction filters (filters/), and the profiles shared between files.
FilterPtr box(Properties& props);
FilterPtr tent(Properties& props);
FilterPtr gaussian(Properties& props);
FilterPtr mitchell(Properties& props);
FilterPtr catmullrom(Properties& props);
FilterPtr lanczos(Properties& props);
double box_profile(double x, const double* params);
double gaussian_profile(double x, const double* params);
double mitchell_netravali_profile(double x, const double* params);  // params: B, C

// Sensors (sensors/): the film's size decides the field of view's axes.
CameraSettings perspective(Properties& props, int film_width, int film_height);
CameraSettings thinlens(Properties& props, int film_width, int film_height);
// The field of view shared by both (Mitsuba's parse_fov: fov + fov_axis, or focal_length in 35 mm equivalent).
void read_field_of_view(Properties& props, CameraSettings& camera, int film_width, int film_height);

// Film (films/); its nested rfilter is built by the loader and passed in.
FilmSettings hdrfilm(Properties& props, FilterPtr filter);

// Integrators (integrators/).
IntegratorSettings path(Properties& props);
IntegratorSettings direct(Properties& props);

}  // namespace surfscatter::render::plugins
