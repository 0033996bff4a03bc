#pragma once
// Every field of the scene's structs, by name, for code that must see all of them rather than
// a hand-picked few (the resume fingerprint, pipeline/settings_fingerprint.cpp). visit_fields(x, f)
// calls f("name", x.name) once per data member, in declaration order.
//
// A field added to a struct in config/scene_desc.h must be added here too:
// tests/config/test_scene_fields.cpp counts each struct's members and fails otherwise.
#include "config/scene_desc.h"

namespace sl {

template <class F> void visit_fields(const CameraDesc& c, F&& f) {
    f("position", c.position); f("look_at", c.look_at); f("up", c.up); f("vfov_deg", c.vfov_deg);
    f("width", c.width); f("height", c.height);
}

template <class F> void visit_fields(const MaterialDesc& m, F&& f) {
    f("name", m.name); f("type", m.type); f("albedo", m.albedo); f("reflectance", m.reflectance);
    f("ior", m.ior); f("roughness", m.roughness); f("complex_ior", m.complex_ior); f("eta", m.eta); f("k", m.k);
    f("metallic", m.metallic); f("specular", m.specular); f("specular_color", m.specular_color);
    f("transmission", m.transmission); f("metallic_roughness_texture", m.metallic_roughness_texture);
    f("principled", m.principled);
    f("albedo_texture", m.albedo_texture); f("emission", m.emission);
    f("emission_texture", m.emission_texture); f("normal_texture", m.normal_texture);
    f("normal_scale", m.normal_scale); f("double_sided", m.double_sided);
}

template <class F> void visit_fields(const TextureDesc& t, F&& f) {
    f("file", t.file); f("srgb", t.srgb); f("wrap_s", t.wrap_s); f("wrap_t", t.wrap_t); f("image", t.image);
}

template <class F> void visit_fields(const ShapeDesc& s, F&& f) {
    f("type", s.type); f("material", s.material); f("corner", s.corner); f("edge1", s.edge1);
    f("edge2", s.edge2); f("min", s.min); f("max", s.max); f("center", s.center); f("radius", s.radius);
    f("file", s.file); f("translate", s.translate); f("scale", s.scale); f("rotate_deg", s.rotate_deg);
    f("mesh", s.mesh); f("instances", s.instances); f("light_units", s.light_units); f("principled", s.principled);
    f("first_light", s.first_light);
    f("light_count", s.light_count);
}

template <class F> void visit_fields(const LightDesc& l, F&& f) {
    f("type", l.type); f("position", l.position); f("corner", l.corner); f("edge1", l.edge1);
    f("edge2", l.edge2); f("direction", l.direction); f("power", l.power); f("radiance", l.radiance);
    f("cone_deg", l.cone_deg); f("radius", l.radius); f("irradiance", l.irradiance);
    f("angle_deg", l.angle_deg);
}

template <class F> void visit_fields(const MediumDesc& m, F&& f) {
    f("present", m.present); f("sigma_a", m.sigma_a); f("sigma_s", m.sigma_s); f("g", m.g);
    f("has_bounds", m.has_bounds); f("bounds_min", m.bounds_min); f("bounds_max", m.bounds_max);
}

template <class F> void visit_fields(const TimeDesc& t, F&& f) {
    f("start_ns", t.start_ns); f("end_ns", t.end_ns); f("frames", t.frames); f("fps", t.fps);
}

template <class F> void visit_fields(const EmissionDesc& e, F&& f) {
    f("mode", e.mode); f("width_ns", e.width_ns); f("width_frames", e.width_frames);
}

template <class F> void visit_fields(const RenderDesc& r, F&& f) {
    f("passes", r.passes); f("photons_per_pass", r.photons_per_pass); f("max_depth", r.max_depth);
    f("radius", r.radius); f("alpha", r.alpha); f("camera_tof", r.camera_tof); f("seed", r.seed);
    f("ambient", r.ambient);
}

template <class F> void visit_fields(const SceneDesc& s, F&& f) {
    f("source", s.source); f("meters_per_unit", s.meters_per_unit); f("camera", s.camera);
    f("materials", s.materials); f("shapes", s.shapes); f("lights", s.lights); f("textures", s.textures);
    f("imports_resolved", s.imports_resolved); f("imported_camera", s.imported_camera);
    f("medium", s.medium); f("time", s.time); f("emission", s.emission); f("render", s.render);
    f("input_files", s.input_files);
}

}  // namespace sl
