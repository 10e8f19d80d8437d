// Alpha-tested casters: group 1 of a shadow pass's masked pipeline binds one material's mask
// (crates/shadows/src/gpu/mask.rs `AlphaMask`). A fragment whose mask alpha is below the
// cutoff is a hole: it casts no shadow and reflects nothing into the RSM.

@group(1) @binding(0) var mask_texture: texture_2d<f32>;
@group(1) @binding(1) var mask_sampler: sampler;
// x: the cutoff; yzw unused.
@group(1) @binding(2) var<uniform> mask_cutoff: vec4<f32>;

fn mask_is_hole(uv: vec2<f32>) -> bool {
    return textureSample(mask_texture, mask_sampler, uv).a < mask_cutoff.x;
}
