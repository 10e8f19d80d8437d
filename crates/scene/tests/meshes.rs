//! Mesh clean-up: degenerate triangles dropped and counted, zero-length normals recomputed,
//! out-of-range indices and non-finite vertices rejected, tangent frames orthonormal.

mod common;

use glam::{Vec2, Vec3};
use proptest::prelude::*;
use scene::{LoadErrorKind, MaterialId, Mesh, MeshData};

fn grid(n: u32) -> MeshData {
    let mut d = MeshData::default();
    for j in 0..=n {
        for i in 0..=n {
            d.positions.push(Vec3::new(i as f32, 0.0, -(j as f32)));
        }
    }
    d.uvs = Some(d.positions.iter().map(|p| Vec2::new(p.x, -p.z)).collect());
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            d.indices.extend_from_slice(&[a, a + 1, a + n + 2, a, a + n + 2, a + n + 1]);
        }
    }
    d
}

#[test]
fn index_out_of_range_and_nan_are_typed_errors() {
    let mut d = grid(2);
    d.indices[4] = 99;
    assert_eq!(
        Mesh::build("m", d, MaterialId(0)).unwrap_err(),
        LoadErrorKind::IndexOutOfRange { index: 99, vertex_count: 9 }
    );
    let mut d = grid(2);
    d.positions[5].y = f32::NAN;
    assert_eq!(
        Mesh::build("m", d, MaterialId(0)).unwrap_err(),
        LoadErrorKind::NonFinite { attribute: "position", vertex: 5 }
    );
    let mut d = grid(1);
    d.indices.pop();
    assert!(matches!(Mesh::build("m", d, MaterialId(0)), Err(LoadErrorKind::Inconsistent(_))));
}

#[test]
fn an_empty_mesh_is_valid() {
    let (m, c) = Mesh::build("empty", MeshData::default(), MaterialId(0)).unwrap();
    m.validate(1).unwrap();
    assert_eq!((m.triangle_count(), c.degenerate_dropped), (0, 0));
    assert!(m.local_bounds().is_empty());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(common::cases(64)))]

    /// Inject degenerate triangles (repeated indices, collinear points) and zero/NaN normals:
    /// exactly those triangles are dropped, exactly those normals recomputed, and the
    /// recomputed normals of a flat grid are the face normal (+Y).
    #[test]
    fn degenerates_dropped_and_zero_normals_recomputed(
        n in 1u32..6,
        degenerate in prop::collection::vec((any::<u32>(), 0u8..3), 0..5),
        zero in prop::collection::vec(any::<u32>(), 0..6),
        explicit_normals in any::<bool>(),
    ) {
        let mut d = grid(n);
        let real = d.indices.len() / 3;
        let nv = d.positions.len() as u32;
        for &(v, kind) in &degenerate {
            let v = v % nv;
            match kind {
                0 => d.indices.extend_from_slice(&[v, v, (v + 1) % nv]),
                1 => d.indices.extend_from_slice(&[v, v, v]),
                // Collinear: three distinct points along the first row (zero area).
                _ if n >= 2 => d.indices.extend_from_slice(&[0, 1, 2]),
                _ => d.indices.extend_from_slice(&[0, 0, 1]),
            }
        }
        let mut bad = std::collections::BTreeSet::new();
        if explicit_normals {
            let mut normals = vec![Vec3::Y; d.positions.len()];
            for (k, &z) in zero.iter().enumerate() {
                let i = (z % nv) as usize;
                normals[i] = if k % 2 == 0 { Vec3::ZERO } else { Vec3::NAN };
                bad.insert(i);
            }
            d.normals = Some(normals);
        }
        let expected_dropped = d.indices.len() / 3 - real;
        let (m, c) = Mesh::build("g", d, MaterialId(0)).unwrap();
        m.validate(1).unwrap();
        prop_assert_eq!(c.degenerate_dropped, expected_dropped);
        prop_assert_eq!(m.triangle_count(), real);
        let expected_recomputed = if explicit_normals { bad.len() } else { m.vertex_count() };
        prop_assert_eq!(c.normals_recomputed, expected_recomputed);
        for (nrm, t) in m.normals.iter().zip(&m.tangents) {
            prop_assert!((*nrm - Vec3::Y).length() < 1e-5, "normal {}", nrm);
            prop_assert!(nrm.dot(t.truncate()).abs() < 1e-5);
            // UV u grows along +X: the tangent is +X.
            prop_assert!((t.truncate() - Vec3::X).length() < 1e-5);
        }
    }
}
