// Sun visibility in overlapped shadow maps (thesis 6.3.1): maps centred on the camera,
// smallest first, that cover points the view's cascades miss (those seen only in reflections
// and refractions). The WGSL twin of crates/shadows/src/csm_lookup.rs (`osm_visibility`).
// Include after pcss.inc.wgsl and csm.inc.wgsl: the maps are CsmCascade blocks, provided as
// the cascades are (csm_count, csm_cascade, and pcss_depth reading layer `csm_layer`).

// Visibility (1 lit) of world point p with unit geometry normal gn: the first map that holds
// the point; lit outside every map.
fn osm_visibility(p: vec3<f32>, gn: vec3<f32>) -> f32 {
    let count = csm_count();
    for (var c = 0; c < count; c = c + 1) {
        let cs = csm_cascade(c);
        var r: PcssReceiver;
        if csm_receiver(cs, p, gn, &r) {
            csm_layer = c;
            return pcss_soft(cs.pcss, r);
        }
    }
    return 1.0;
}
