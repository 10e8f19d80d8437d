// Schlick's Fresnel reflectance (twin of traced_effects::trace::fresnel_schlick): what the
// ray casting buffer and the combination weigh reflected against refracted light with, and
// what a renderer's lighting weighs the mirror and glass parts with, so that both agree.

// Schlick's Fresnel reflectance for a dielectric of index `ior` seen at cosine `c`.
fn fresnel_schlick(c: f32, ior: f32) -> f32 {
    let r0 = (ior - 1.0) / (ior + 1.0);
    let f0 = r0 * r0;
    return f0 + (1.0 - f0) * pow(1.0 - clamp(c, 0.0, 1.0), 5.0);
}
