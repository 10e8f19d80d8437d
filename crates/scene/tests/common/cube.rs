//! The pieces of hand-written glTF files the tests share (the `scene` tests and, by path,
//! the `app` tests): base64 for data URIs and a unit cube's buffer.

/// Standard base64 with padding, for `data:` URIs.
pub fn base64(data: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in data.chunks(3) {
        let b = [c[0], *c.get(1).unwrap_or(&0), *c.get(2).unwrap_or(&0)];
        let n = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for k in 0..4 {
            if k <= c.len() {
                s.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// A unit cube centred on the origin: 24 vertices with flat normals, 36 u16 indices; the
/// buffer (positions, normals, indices).
pub fn cube_buffer() -> Vec<u8> {
    let (mut pos, mut nrm, mut idx) = (Vec::new(), Vec::new(), Vec::<u16>::new());
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let mut n = [0.0f32; 3];
            n[axis] = sign;
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let base = pos.len() as u16;
            for (a, b) in [(-1.0f32, -1.0f32), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                let mut p = [0.0f32; 3];
                p[axis] = 0.5 * sign;
                p[u] = 0.5 * a * sign;
                p[v] = 0.5 * b;
                pos.push(p);
                nrm.push(n);
            }
            idx.extend([0, 1, 2, 0, 2, 3].map(|i| base + i));
        }
    }
    let mut buf = Vec::new();
    for f in pos.iter().flatten().chain(nrm.iter().flatten()) {
        buf.extend_from_slice(&f.to_le_bytes());
    }
    for i in &idx {
        buf.extend_from_slice(&i.to_le_bytes());
    }
    buf
}

/// Byte offsets of [`cube_buffer`]'s positions, normals and indices.
pub const CUBE_VIEWS: [usize; 3] = [0, 24 * 12, 48 * 12];
